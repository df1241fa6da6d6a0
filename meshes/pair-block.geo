// The lower body of a contact pair: an elastic block whose top face z = 0 the hemisphere of
// meshes/pair-hemisphere.geo touches at the origin. Its own mesh, with its own size at the contact, so that the
// two meshes do not match (docs/validation.md, "Two elastic bodies").
//
// part = 4: the quarter [0,L]x[0,L]x[-H,0] (symmetry planes x = 0 and y = 0: Hertz); part = 2: the half
// [-L,L]x[0,L]x[-H,0] (symmetry plane y = 0: a shift along x); part = 1: the whole [-L,L]x[-L,L]x[-H,0]
// (Cattaneo-Mindlin). The mesh size is h within
// the distance rf of the origin, grows linearly to hc at the distance rf + rg, and is hc beyond.
// Physical surfaces (face selectors of the scene): top (z = 0, the contact face), base (z = -H), sides (the
// vertical faces not on a symmetry plane), for part = 2 and 4 sym_y (y = 0), for part = 4 sym_x (x = 0);
// physical volume: block.
//
// Mesh (from the repository root):
//   gmsh -3 meshes/pair-block.geo -setnumber part 2 -setnumber h 0.013 -o pair-block.msh
// scripts/bench-cattaneo.py sets the parameters this way.
SetFactory("OpenCASCADE");

DefineConstant[
  part = {4,    Name "Parameters/part: 4 quarter (x, y >= 0), 2 half (y >= 0), 1 whole"},
  L    = {5.0,  Name "Parameters/L: half width of the block"},
  H    = {5.0,  Name "Parameters/H: height of the block"},
  h    = {0.026, Name "Parameters/h: mesh size at the contact"},
  hc   = {1.0,  Name "Parameters/hc: mesh size far from the contact"},
  rf   = {0.15, Name "Parameters/rf: radius of the finely meshed region"},
  rg   = {4.0,  Name "Parameters/rg: distance over which the size grows from h to hc"}
];
If (part != 4 && part != 2 && part != 1)
  Error("pair-block.geo: part must be 4 (quarter), 2 (half) or 1 (whole), got %g", part);
EndIf

x0 = (part == 4) ? 0 : -L;
y0 = (part == 1) ? -L : 0;
Box(1) = {x0, y0, -H, L - x0, L - y0, H};

e = 1e-6 * L;
top[]   = Surface In BoundingBox{x0 - e, y0 - e, -e, L + e, L + e, e};
base[]  = Surface In BoundingBox{x0 - e, y0 - e, -H - e, L + e, L + e, -H + e};
symy[]  = {};
If (part != 1)
  symy[] = Surface In BoundingBox{x0 - e, -e, -H - e, L + e, e, e};
EndIf
symx[]  = {};
If (part == 4)
  symx[] = Surface In BoundingBox{-e, -e, -H - e, e, L + e, e};
EndIf
sides[] = Abs(Boundary{ Volume{1}; });
sides[] -= top[];
sides[] -= base[];
sides[] -= symy[];
sides[] -= symx[];

Physical Surface("top")   = top[];
Physical Surface("base")  = base[];
If (part != 1)
  Physical Surface("sym_y") = symy[];
EndIf
Physical Surface("sides") = sides[];
If (part == 4)
  Physical Surface("sym_x") = symx[];
EndIf
Physical Volume("block") = {1};

// size: h near the contact point (the origin), hc far away
Field[1] = MathEval;
Field[1].F = "Sqrt(x*x + y*y + z*z)";
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
