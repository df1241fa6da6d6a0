// A steel block 2 x 1 x 1 (m) with a cylindrical hole of radius 0.25 along y: the example scene
// petsc-options/block-hole.opts presses it onto a rigid floor. Mesh it with
//   gmsh -3 meshes/block-hole.geo -o meshes/block-hole.msh
// The physical groups are the names the scene uses: bottom (z = 0), top (z = 1), hole, sides, and the
// volume steel. Only elements of physical groups are written, so the volume needs one too.
SetFactory("OpenCASCADE");
DefineConstant[ h = {0.18, Name "mesh size"} ]; // gmsh -setnumber h <size> overrides it
Box(1) = {0, 0, 0, 2, 1, 1};
Cylinder(2) = {1, 0, 0.5, 0, 1, 0, 0.25};
BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};
e = 1e-6;
bottom() = Surface In BoundingBox{-e, -e, -e, 2 + e, 1 + e, e};
top() = Surface In BoundingBox{-e, -e, 1 - e, 2 + e, 1 + e, 1 + e};
hole() = Surface In BoundingBox{0.75 - e, -e, 0.25 - e, 1.25 + e, 1 + e, 0.75 + e};
all() = Boundary{Volume{3};};
sides() = all();
sides() -= bottom();
sides() -= top();
sides() -= hole();
Physical Surface("bottom") = bottom();
Physical Surface("top") = top();
Physical Surface("hole") = hole();
Physical Surface("sides") = sides();
Physical Volume("steel") = {3};
Mesh.CharacteristicLengthMax = h;
Mesh.CharacteristicLengthMin = h / 2;
Mesh.Algorithm3D = 1; // Delaunay: deterministic for one thread
General.NumThreads = 1;
