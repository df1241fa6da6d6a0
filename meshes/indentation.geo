// Rigid sphere indentation (Hertz): a quarter of an elastic block under the sphere, refined near the contact.
//
// The block is [0,L]x[0,L]x[0,H]; the sphere touches its top face z = H at the corner (0,0,H), which lies on
// both symmetry planes x = 0 and y = 0. The mesh size is h within the distance rf of that corner (the contact
// radius a = sqrt(R d) should be a few h and below rf), grows linearly to hc at the distance rf + rg, and is
// hc beyond. Physical surfaces (face selectors of the scene): top (z = H), bottom (z = 0), sym_x (x = 0),
// sym_y (y = 0), side_x (x = L), side_y (y = L); physical volume: block.
//
// Mesh (from the repository root):  gmsh -3 meshes/indentation.geo -setnumber h 0.02 -o indentation.msh
// scripts/bench-hertz.py sets h (and the other parameters) this way; petsc-options/indentation.opts is the scene.
SetFactory("OpenCASCADE");

DefineConstant[
  L  = {20.0, Name "Parameters/L: block width (quarter)"},
  H  = {20.0, Name "Parameters/H: block height"},
  h  = {0.02, Name "Parameters/h: mesh size at the contact"},
  hc = {2.0,  Name "Parameters/hc: mesh size far from the contact"},
  rf = {0.25, Name "Parameters/rf: radius of the finely meshed region"},
  rg = {10.0, Name "Parameters/rg: distance over which the size grows from h to hc"}
];

Box(1) = {0, 0, 0, L, L, H};

e = 1e-6 * L;
top[]    = Surface In BoundingBox{-e, -e, H - e, L + e, L + e, H + e};
bottom[] = Surface In BoundingBox{-e, -e, -e, L + e, L + e, e};
symx[]   = Surface In BoundingBox{-e, -e, -e, e, L + e, H + e};
symy[]   = Surface In BoundingBox{-e, -e, -e, L + e, e, H + e};
sidex[]  = Surface In BoundingBox{L - e, -e, -e, L + e, L + e, H + e};
sidey[]  = Surface In BoundingBox{-e, L - e, -e, L + e, L + e, H + e};
corner[] = Point In BoundingBox{-e, -e, H - e, e, e, H + e};

Physical Surface("top")    = top[];
Physical Surface("bottom") = bottom[];
Physical Surface("sym_x")  = symx[];
Physical Surface("sym_y")  = symy[];
Physical Surface("side_x") = sidex[];
Physical Surface("side_y") = sidey[];
Physical Volume("block")   = {1};

// size: h near the contact point, hc far away
Field[1] = Distance;
Field[1].PointsList = {corner[]};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h;
Field[2].SizeMax = hc;
Field[2].DistMin = rf;
Field[2].DistMax = rf + rg;
Background Field = 2;

Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm3D = 1; // Delaunay
Mesh.Optimize = 1;
