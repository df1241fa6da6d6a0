#!/usr/bin/python3
"""Write the tetrahedral mesh of a box that FEMAddBox() generates (nx x ny x nz hexahedra, each cut into the
6 Kuhn tetrahedra along its main diagonal, src/fem/femmesh.cxx) as a Gmsh file, through Gmsh's Python API,
so that reading the file back must give the generator's model exactly.

usage: write-box-msh.py OUT.msh --lower x,y,z --upper x,y,z --cells nx,ny,nz [--version 2.2|4.1] [--binary]
                        [--invert] [--hexahedra] [--mirror x|y|z|xy|...]

Physical groups: the faces x0 x1 y0 y1 z0 z1 are the surfaces "left" "right" "front" "back" "bottom" "top",
except x1, which is the unnamed surface 7 (an unnamed group is selected by its number); the volume is
"solid". --invert lists the nodes of the first tetrahedron in the wrong order (an inverted element);
--hexahedra writes the hexahedra instead of tetrahedra (a mesh with no tetrahedron). --mirror y (an even number of
cells along y) cuts the cells of the lower half along y as the mirror images of the upper half's (their diagonal and
their boundary quads reflected), so that the mesh is symmetric about the middle plane and its upper half is the
generator's box of that half: a whole model to compare a half model on rollers with. --mirror xy does so along x and
y (a whole model for a quarter model)."""
import argparse

import gmsh

KUHN = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
ODD = [False, True, True, False, False, True]
NAMES = {"x0": (1, "left"), "x1": (7, None), "y0": (2, "front"), "y1": (3, "back"), "z0": (4, "bottom"), "z1": (5, "top")}

p = argparse.ArgumentParser()
p.add_argument("out")
p.add_argument("--lower", default="0,0,0")
p.add_argument("--upper", default="1,1,1")
p.add_argument("--cells", default="2,2,2")
p.add_argument("--version", default="4.1")
p.add_argument("--binary", action="store_true")
p.add_argument("--invert", action="store_true")
p.add_argument("--hexahedra", action="store_true")
p.add_argument("--mirror", default="", help="axes along which the lower half mirrors the upper half: x, y, z, xy, ...")
a = p.parse_args()
lo = [float(v) for v in a.lower.split(",")]
hi = [float(v) for v in a.upper.split(",")]
n = [int(v) for v in a.cells.split(",")]
if set(a.mirror) - set("xyz"):
    p.error("--mirror takes axes among x, y, z, got '%s'" % a.mirror)
axes = ["xyz".index(c) for c in a.mirror]
for e in axes:
    if n[e] % 2:
        p.error("--mirror %s needs an even number of cells along %s, got %d" % (a.mirror, "xyz"[e], n[e]))


def mirrored(index, axis):  # is the cell (or quad) with this index along axis in a reflected lower half?
    return axis in axes and index < n[axis] // 2


def node(i, j, k):  # 1-based Gmsh tag of the generator's node id i + (nx+1)(j + (ny+1)k)
    return 1 + i + (n[0] + 1) * (j + (n[1] + 1) * k)


coords = []
for k in range(n[2] + 1):
    for j in range(n[1] + 1):
        for i in range(n[0] + 1):
            c = (i, j, k)
            coords += [lo[d] + (hi[d] - lo[d]) * c[d] / n[d] for d in range(3)]
cells = []
for k in range(n[2]):
    for j in range(n[1]):
        for i in range(n[0]):
            if a.hexahedra:
                cells += [node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
                          node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)]
                continue
            flip = [mirrored(c, e) for e, c in enumerate((i, j, k))]

            def corner(off):  # the cell's corner at these offsets, reflected along the mirror axis in the lower half
                o = [1 - off[e] if flip[e] else off[e] for e in range(3)]
                return node(i + o[0], j + o[1], k + o[2])
            for t in range(6):
                off = [0, 0, 0]
                v = [corner(off)]
                for s in range(3):
                    off[KUHN[t][s]] = 1
                    v.append(corner(off))
                if ODD[t] != (sum(flip) % 2 == 1):  # a reflection reverses the orientation
                    v[1], v[2] = v[2], v[1]
                cells += v
if a.invert:
    cells[1], cells[2] = cells[2], cells[1]

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.model.add("box")
vol = gmsh.model.addDiscreteEntity(3)
gmsh.model.mesh.addNodes(3, vol, list(range(1, len(coords) // 3 + 1)), coords)
gmsh.model.mesh.addElementsByType(vol, 5 if a.hexahedra else 4, [], cells)
gmsh.model.addPhysicalGroup(3, [vol], 100)
gmsh.model.setPhysicalName(3, 100, "solid")
# boundary faces: each face's quads cut along the diagonal from the lowest to the highest corner
for face, (tag, name) in NAMES.items():
    d, side = "xyz".index(face[0]), int(face[1])
    u, w = [e for e in range(3) if e != d]
    tris = []
    for b in range(n[w]):
        for c in range(n[u]):
            fu, fw = mirrored(c, u), mirrored(b, w)

            def at(du, dw):
                ijk = [0, 0, 0]
                ijk[d], ijk[u], ijk[w] = side * n[d], c + (1 - du if fu else du), b + (1 - dw if fw else dw)
                return node(*ijk)
            if a.hexahedra:
                tris += [at(0, 0), at(1, 0), at(1, 1), at(0, 1)]
            elif fu != fw:  # reflected once: the same cut as the tetrahedra, the orientation kept
                tris += [at(0, 0), at(1, 1), at(1, 0), at(0, 0), at(0, 1), at(1, 1)]
            else:
                tris += [at(0, 0), at(1, 0), at(1, 1), at(0, 0), at(1, 1), at(0, 1)]
    s = gmsh.model.addDiscreteEntity(2)
    gmsh.model.mesh.addElementsByType(s, 3 if a.hexahedra else 2, [], tris)
    gmsh.model.addPhysicalGroup(2, [s], tag)
    if name:
        gmsh.model.setPhysicalName(2, tag, name)
gmsh.option.setNumber("Mesh.MshFileVersion", float(a.version))
gmsh.option.setNumber("Mesh.Binary", 1 if a.binary else 0)
gmsh.write(a.out)
gmsh.finalize()
