// An elastic hemisphere, flat face up, pressed onto a rigid plane (Hertz, force driven): a quarter of it.
//
// The hemisphere of radius R has its centre at (0,0,R): its curved surface touches the plane z = 0 at the
// origin, which lies on both symmetry planes x = 0 and y = 0. The mesh size is h within the distance rf of
// the origin (the contact radius a should be a few h and below rf), grows linearly to hc at the distance
// rf + rg, and is hc beyond. Physical surfaces (face selectors of the scene): top (the flat face z = R),
// curved (the spherical surface, the contact face), sym_x (x = 0), sym_y (y = 0); physical volume: ball.
//
// Mesh (from the repository root):  gmsh -3 meshes/hemisphere.geo -setnumber h 0.01 -o hemisphere.msh
// scripts/bench-hertz.py sets h this way; petsc-options/hemisphere.opts is the scene.
SetFactory("OpenCASCADE");

DefineConstant[
  R  = {1.0,  Name "Parameters/R: radius"},
  h  = {0.02, Name "Parameters/h: mesh size at the contact"},
  hc = {0.15, Name "Parameters/hc: mesh size far from the contact"},
  rf = {0.2,  Name "Parameters/rf: radius of the finely meshed region"},
  rg = {0.5,  Name "Parameters/rg: distance over which the size grows from h to hc"}
];

// the lower half (latitudes -90..0 degrees), the quarter x >= 0, y >= 0 (azimuth 0..90 degrees)
Sphere(1) = {0, 0, R, R, -Pi/2, 0, Pi/2};

e = 1e-6 * R;
top[]    = Surface In BoundingBox{-e, -e, R - e, R + e, R + e, R + e};
symx[]   = Surface In BoundingBox{-e, -e, -e, e, R + e, R + e};
symy[]   = Surface In BoundingBox{-e, -e, -e, R + e, e, R + e};
all[]    = Abs(Boundary{ Volume{1}; });
curved[] = all[];
curved[] -= top[];
curved[] -= symx[];
curved[] -= symy[];
bottom[] = Point In BoundingBox{-e, -e, -e, e, e, e};

Physical Surface("top")    = top[];
Physical Surface("curved") = curved[];
Physical Surface("sym_x")  = symx[];
Physical Surface("sym_y")  = symy[];
Physical Volume("ball")    = {1};

// size: h near the contact point, hc far away
Field[1] = Distance;
Field[1].PointsList = {bottom[]};
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
