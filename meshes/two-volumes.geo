// Two volumes sharing a face: the slab "lower" (0,2)x(0,1)x(0,0.5) and the block "upper" (0,2)x(0,1)x(0.5,1),
// meshed conformingly. With -scene_body<b>_volume a scene makes a body of either one; the surface "interface"
// between them is a boundary of each (tests/mesh: -scene_body<b>_volume).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 0.5};
Box(2) = {0, 0, 0.5, 2, 1, 0.5};
BooleanFragments{Volume{1, 2}; Delete;}{}
e = 1e-6;
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 2 + e, 1 + e, e};
Physical Surface("interface") = Surface In BoundingBox{-e, -e, 0.5 - e, 2 + e, 1 + e, 0.5 + e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 1 - e, 2 + e, 1 + e, 1 + e};
Physical Volume("lower") = Volume In BoundingBox{-e, -e, -e, 2 + e, 1 + e, 0.5 + e};
Physical Volume("upper") = Volume In BoundingBox{-e, -e, 0.5 - e, 2 + e, 1 + e, 1 + e};
Mesh.CharacteristicLengthMax = 0.25;
General.NumThreads = 1;
