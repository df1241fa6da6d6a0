#!/usr/bin/env bash
# usage: make-meshes.sh SOURCE_DIR OUT_DIR
# The mesh files of the tests/mesh tests, made at test time (none is committed): the generator's box in the
# four Gmsh encodings (write-box-msh.py) and mirrored boxes, broken files for the error tests, and meshes/block-hole.geo, two-volumes.geo and block-unstructured.geo meshed by gmsh
# (block-hole.geo also in second order, for an error test).
set -euo pipefail
src=$1; out=$2
mkdir -p "$out"
w="/usr/bin/python3 $src/tests/mesh/write-box-msh.py"
box="--lower 0,0,0 --upper 1,0.5,2 --cells 3,2,4"
$w "$out/box-2.2.msh" $box --version 2.2
$w "$out/box-2.2-binary.msh" $box --version 2.2 --binary
$w "$out/box-4.1.msh" $box --version 4.1
$w "$out/box-4.1-binary.msh" $box --version 4.1 --binary
$w "$out/inverted.msh" $box --invert
$w "$out/hexahedra.msh" $box --hexahedra
# whole models whose halves (quarters) are generated boxes on rollers (symmetry-plane.py)
$w "$out/brick-mirrored.msh" --lower 0,0,0 --upper 3,1,1 --cells 12,4,4 --mirror y
$w "$out/slab-mirrored.msh" --lower 0,0,-0.501 --upper 3,1,-0.001 --cells 12,4,2 --mirror y
$w "$out/block-mirrored.msh" --lower=-1,-1,0 --upper 1,1,1 --cells 8,8,4 --mirror xy
head -c 1500 "$out/box-4.1.msh" >"$out/truncated.msh"
head -c 3000 "$out/box-4.1-binary.msh" >"$out/truncated-binary.msh"
gmsh -3 "$src/meshes/block-hole.geo" -o "$out/block-hole.msh" >"$out/block-hole.log" 2>&1 || { cat "$out/block-hole.log"; exit 1; }
gmsh -3 "$src/meshes/two-volumes.geo" -o "$out/two-volumes.msh" >"$out/two-volumes.log" 2>&1 || { cat "$out/two-volumes.log"; exit 1; }
gmsh -3 "$src/meshes/block-unstructured.geo" -o "$out/block-unstructured.msh" >"$out/block-unstructured.log" 2>&1 || { cat "$out/block-unstructured.log"; exit 1; }
# the Hertz pair of petsc-options/hertz-pair.opts, coarse (a curved slave face split between two zones)
gmsh -3 "$src/meshes/pair-hemisphere.geo" -setnumber part 1 -setnumber h 0.05 -o "$out/pair-hemisphere.msh" >"$out/pair-hemisphere.log" 2>&1 || { cat "$out/pair-hemisphere.log"; exit 1; }
gmsh -3 "$src/meshes/pair-block.geo" -setnumber part 1 -setnumber h 0.06 -o "$out/pair-block.msh" >"$out/pair-block.log" 2>&1 || { cat "$out/pair-block.log"; exit 1; }
# a curved (second-order) mesh, and one file of two separate blocks without physical volumes: one body each, both errors
gmsh -3 -order 2 "$src/meshes/block-hole.geo" -o "$out/block-hole-order2.msh" >"$out/block-hole-order2.log" 2>&1 || { cat "$out/block-hole-order2.log"; exit 1; }
cat >"$out/two-pieces.geo" <<'GEO'
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {2, 0, 0, 1, 1, 1};
Mesh.MeshSizeMax = 0.5;
GEO
gmsh -3 "$out/two-pieces.geo" -o "$out/two-pieces.msh" >"$out/two-pieces.log" 2>&1 || { cat "$out/two-pieces.log"; exit 1; }
# a box with a Physical Surface and no Physical Volume: Gmsh writes the surface's triangles only (the most common mistake)
cat >"$out/no-physical-volume.geo" <<'GEO'
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Physical Surface("bottom") = {5};
Mesh.MeshSizeMax = 0.5;
GEO
gmsh -3 "$out/no-physical-volume.geo" -o "$out/no-physical-volume.msh" >"$out/no-physical-volume.log" 2>&1 || { cat "$out/no-physical-volume.log"; exit 1; }
echo "make-meshes.sh: meshes in $out"
