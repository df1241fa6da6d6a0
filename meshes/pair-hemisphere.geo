// The upper body of a contact pair: an elastic hemisphere, flat face up, its curved face touching the body
// below (meshes/pair-block.geo) at the origin. Two elastic bodies with non-matching meshes (docs/validation.md,
// "Two elastic bodies"): two .geo files, two .msh files, two bodies of a scene, a contact zone between them.
//
// The hemisphere of radius R has its centre at (0,0,R): its curved surface touches the plane z = 0 at the
// origin. part = 4: the quarter x >= 0, y >= 0 (symmetry planes x = 0 and y = 0: Hertz); part = 2: the half
// y >= 0 (symmetry plane y = 0 only: a shift along x); part = 1: the whole hemisphere (Cattaneo-Mindlin, written
// when a node with friction on a symmetry plane was left out of contact; docs/contact.md). The mesh size is h within the
// distance rf of the origin, grows linearly to hc at the distance rf + rg, and is hc beyond.
// Physical surfaces (face selectors of the scene): grip (the flat face z = R), curved (the spherical surface,
// the contact face), for part = 2 and 4 sym_y (y = 0), for part = 4 sym_x (x = 0); physical volume: hemisphere.
//
// Mesh (from the repository root):
//   gmsh -3 meshes/pair-hemisphere.geo -setnumber part 2 -setnumber h 0.01 -o pair-hemisphere.msh
// scripts/bench-cattaneo.py sets the parameters this way.
SetFactory("OpenCASCADE");

DefineConstant[
  part = {4,    Name "Parameters/part: 4 quarter (x, y >= 0), 2 half (y >= 0), 1 whole"},
  R    = {1.0,  Name "Parameters/R: radius"},
  h    = {0.02, Name "Parameters/h: mesh size at the contact"},
  hc   = {0.15, Name "Parameters/hc: mesh size far from the contact"},
  rf   = {0.15, Name "Parameters/rf: radius of the finely meshed region"},
  rg   = {0.5,  Name "Parameters/rg: distance over which the size grows from h to hc"}
];
If (part != 4 && part != 2 && part != 1)
  Error("pair-hemisphere.geo: part must be 4 (quarter), 2 (half) or 1 (whole), got %g", part);
EndIf

// the lower half (latitudes -90..0 degrees), azimuth 0..360/part degrees
Sphere(1) = {0, 0, R, R, -Pi/2, 0, 2*Pi/part};

e = 1e-6 * R;
top[]  = Surface In BoundingBox{-R - e, -R - e, R - e, R + e, R + e, R + e};
symy[] = {};
If (part != 1)
  symy[] = Surface In BoundingBox{-R - e, -e, -e, R + e, e, R + e};
EndIf
symx[] = {};
If (part == 4)
  symx[] = Surface In BoundingBox{-e, -e, -e, e, R + e, R + e};
EndIf
all[]    = Abs(Boundary{ Volume{1}; });
curved[] = all[];
curved[] -= top[];
curved[] -= symy[];
curved[] -= symx[];

Physical Surface("grip")   = top[];
Physical Surface("curved") = curved[];
If (part != 1)
  Physical Surface("sym_y") = symy[];
EndIf
If (part == 4)
  Physical Surface("sym_x") = symx[];
EndIf
Physical Volume("hemisphere") = {1};

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
