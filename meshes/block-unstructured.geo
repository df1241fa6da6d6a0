// A block (0,1)x(0,1)x(0.5,1.5) meshed by gmsh without structure: its bottom face's triangles follow no grid, so on a
// slab generated as a box (-scene_body<b>_lower ...) the contact faces do not match (tests/mesh, node to surface).
//   gmsh -3 meshes/block-unstructured.geo -o block-unstructured.msh
// Physical groups: bottom (z = 0.5), top (z = 1.5), sides, and the volume block.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0.5, 1, 1, 1};
e = 1e-6;
bottom() = Surface In BoundingBox{-e, -e, 0.5 - e, 1 + e, 1 + e, 0.5 + e};
top() = Surface In BoundingBox{-e, -e, 1.5 - e, 1 + e, 1 + e, 1.5 + e};
all() = Boundary{Volume{1};};
sides() = all();
sides() -= bottom();
sides() -= top();
Physical Surface("bottom") = bottom();
Physical Surface("top") = top();
Physical Surface("sides") = sides();
Physical Volume("block") = {1};
Mesh.CharacteristicLengthMax = 0.3;
Mesh.Algorithm3D = 1; // Delaunay: deterministic for one thread
General.NumThreads = 1;
