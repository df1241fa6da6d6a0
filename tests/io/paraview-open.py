"""Open conefeti's XDMF output with ParaView's own readers (run by pvpython).

usage: pvpython paraview-open.py BASENAME

Both ParaView XDMF readers (XDMFReader: XDMF 2 library; Xdmf3ReaderS: XDMF 3) must read BASENAME.xmf
into a volume grid of tetrahedra with the point array displacement and the cell arrays von_mises,
subdomain, body, and (when the file has one) a contact grid of points with pressure, tangential_stress,
tangential_displacement and status; sizes and the displacement values must equal the HDF5 datasets."""
import sys

import h5py
import numpy as np
from paraview import servermanager
from paraview.simple import Xdmf3ReaderS, XDMFReader
from vtkmodules.util.numpy_support import vtk_to_numpy

base = sys.argv[1]
h5 = h5py.File(base + ".h5", "r")
want = {"volume": (["displacement"], ["von_mises", "subdomain", "body"]),
        "contact": (["pressure", "tangential_stress", "tangential_displacement", "status"], [])}
fail = []


def blocks(d):
    if d.IsA("vtkCompositeDataSet"):
        it = d.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            yield it.GetCurrentDataObject()
            it.GoToNextItem()
    else:
        yield d


for name, make in (("XDMFReader", lambda: XDMFReader(FileNames=[base + ".xmf"])), ("Xdmf3ReaderS", lambda: Xdmf3ReaderS(FileName=[base + ".xmf"]))):
    reader = make()
    reader.UpdatePipeline()
    data = servermanager.Fetch(reader)
    found = {}
    for b in blocks(data):
        pts = [b.GetPointData().GetArrayName(i) for i in range(b.GetPointData().GetNumberOfArrays())]
        grid = "volume" if "displacement" in pts else "contact"
        found[grid] = b
        print("%s: %s grid, %d points, %d cells, point arrays %s, cell arrays %s" % (name, grid, b.GetNumberOfPoints(), b.GetNumberOfCells(), pts,
              [b.GetCellData().GetArrayName(i) for i in range(b.GetCellData().GetNumberOfArrays())]))
    expected = ["volume"] + (["contact"] if "contact" in h5 else [])
    if sorted(found) != sorted(expected):
        fail.append("%s read grids %s, expected %s" % (name, sorted(found), expected))
        continue
    for grid in expected:
        b = found[grid]
        nn, ne = h5[grid + "/coordinates"].shape[0], h5[grid + "/connectivity"].shape[0]
        if (b.GetNumberOfPoints(), b.GetNumberOfCells()) != (nn, ne):
            fail.append("%s %s: %d points, %d cells; the HDF5 file has %d, %d" % (name, grid, b.GetNumberOfPoints(), b.GetNumberOfCells(), nn, ne))
        for arr in want[grid][0]:
            if b.GetPointData().GetArray(arr) is None:
                fail.append("%s %s: no point array %s" % (name, grid, arr))
        for arr in want[grid][1]:
            if b.GetCellData().GetArray(arr) is None:
                fail.append("%s %s: no cell array %s" % (name, grid, arr))
        if grid == "volume":
            if b.GetCellType(0) != 10:  # VTK_TETRA
                fail.append("%s: volume cells are VTK type %d, not tetrahedra" % (name, b.GetCellType(0)))
            u = vtk_to_numpy(b.GetPointData().GetArray("displacement"))
            if not np.array_equal(u, h5["volume/displacement"][()]):
                fail.append("%s: the displacement ParaView reads differs from the HDF5 dataset" % name)
for f in fail:
    print("paraview-open.py: " + f)
print("paraview-open.py: " + ("ParaView reads the output" if not fail else "FAILED"))
sys.exit(1 if fail else 0)
