#!/usr/bin/python3
"""Check conefeti's HDF5 + XDMF output the way ParaView reads it.

usage: check-output.py BASENAME [--json FILE] [--von-mises-uniform S] [--rtol R]

BASENAME.xmf must be a well-formed XDMF 3 document whose DataItems all point (relative to the .xmf's
directory) to existing datasets of BASENAME.h5 with the declared dimensions, number type and precision;
topologies and attributes must have consistent sizes (nodes / cells), connectivities must index existing
nodes, every tetrahedron must be positively oriented, every float must be finite, the contact status must
be 0, 1 or 2, and no temporary file (.tmp) may be left. With --json (the run's -summary_json file) the
files must agree with the summary: subdomains, contact nodes and the separated/stick/slip counts. With
--von-mises-uniform S every tetrahedron's von Mises stress must equal S to a relative R (default 1e-6)."""
import json
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

fail = []


def check(cond, msg):
    if not cond:
        fail.append(msg)
    return cond


def main(argv):
    base, jsonfile, vm_uniform, rtol = argv[0], None, None, 1e-6
    i = 1
    while i < len(argv):
        if argv[i] == "--json": jsonfile = argv[i + 1]
        elif argv[i] == "--von-mises-uniform": vm_uniform = float(argv[i + 1])
        elif argv[i] == "--rtol": rtol = float(argv[i + 1])
        else: sys.exit("check-output.py: unknown option " + argv[i])
        i += 2
    xmf, h5 = base + ".xmf", base + ".h5"
    for f in (xmf, h5):
        if not check(os.path.isfile(f), "missing " + f):
            return report()
    for f in (xmf + ".tmp", h5 + ".tmp"):
        check(not os.path.exists(f), "temporary file left behind: " + f)
    root = ET.parse(xmf).getroot()
    check(root.tag == "Xdmf" and root.get("Version") in ("2.0", "3.0"), "root element is %s version %s, expected Xdmf 3.0" % (root.tag, root.get("Version")))
    domain = root.find("Domain")
    if not check(domain is not None, "no Domain element"):
        return report()
    grids = {g.get("Name"): g for g in domain.findall("Grid")}
    check("volume" in grids, "no volume grid")
    h = h5py.File(h5, "r")
    xdir = os.path.dirname(os.path.abspath(xmf))
    data = {}

    def item(elem, where):
        di = elem.find("DataItem")
        if not check(di is not None, where + ": no DataItem"):
            return None
        check(di.get("Format") == "HDF", where + ": Format %s, expected HDF" % di.get("Format"))
        fname, _, path = di.text.strip().partition(":")
        check(os.path.isfile(os.path.join(xdir, fname)), where + ": %s does not exist next to the .xmf" % fname)
        check(os.path.samefile(os.path.join(xdir, fname), h5), where + ": refers to %s, not %s" % (fname, h5))
        if not check(path in h, where + ": dataset %s missing" % path):
            return None
        ds = h[path]
        dims = tuple(int(x) for x in di.get("Dimensions").split())
        check(ds.shape == dims, where + ": %s has shape %s, the XDMF says %s" % (path, ds.shape, dims))
        kind = {"Int": "i", "Float": "f"}[di.get("NumberType", "Float")]
        check(ds.dtype.kind == kind, where + ": %s has dtype %s, the XDMF says %s" % (path, ds.dtype, di.get("NumberType")))
        check(ds.dtype.itemsize == int(di.get("Precision", "4")), where + ": %s has %d-byte items, the XDMF says %s" % (path, ds.dtype.itemsize, di.get("Precision")))
        a = ds[()]
        if kind == "f":
            check(np.all(np.isfinite(a)), where + ": %s has non-finite values" % path)
        data[path] = a
        return a

    sizes = {}
    for name, g in grids.items():
        topo, geom = g.find("Topology"), g.find("Geometry")
        if not check(topo is not None and geom is not None, name + ": needs Topology and Geometry"):
            continue
        check(geom.get("GeometryType") == "XYZ", name + ": GeometryType %s" % geom.get("GeometryType"))
        X = item(geom, name + "/Geometry")
        C = item(topo, name + "/Topology")
        if X is None or C is None:
            continue
        nn, ne = X.shape[0], int(topo.get("NumberOfElements"))
        check(C.shape[0] == ne, name + ": %d connectivity rows for %d elements" % (C.shape[0], ne))
        check(C.size == 0 or (C.min() >= 0 and C.max() < nn), name + ": connectivity outside 0..%d" % (nn - 1))
        ttype = topo.get("TopologyType")
        if ttype == "Tetrahedron":
            check(C.ndim == 2 and C.shape[1] == 4, name + ": tetrahedra need 4 nodes per row")
            P = X[C]
            vol = np.einsum("ij,ij->i", np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]), P[:, 3] - P[:, 0]) / 6
            check(np.all(vol > 0), name + ": %d tetrahedra are not positively oriented" % np.sum(vol <= 0))
        else:
            check(ttype == "Polyvertex" and topo.get("NodesPerElement") == "1", name + ": topology %s" % ttype)
        sizes[name] = (nn, ne)
        for att in g.findall("Attribute"):
            a = item(att, "%s/%s" % (name, att.get("Name")))
            if a is None:
                continue
            rows = nn if att.get("Center") == "Node" else ne
            check(att.get("Center") in ("Node", "Cell"), "%s/%s: Center %s" % (name, att.get("Name"), att.get("Center")))
            check(a.shape[0] == rows, "%s/%s: %d rows for %d %ss" % (name, att.get("Name"), a.shape[0], rows, att.get("Center").lower()))
            comps = 1 if a.ndim == 1 else a.shape[1]
            check(comps == {"Scalar": 1, "Vector": 3}[att.get("AttributeType")], "%s/%s: %d components for a %s" % (name, att.get("Name"), comps, att.get("AttributeType")))
    vm = data.get("/volume/von_mises")
    if vm is not None:
        check(np.all(vm >= 0), "von Mises stress is negative somewhere")
        if vm_uniform is not None:
            err = np.max(np.abs(vm - vm_uniform)) / abs(vm_uniform)
            print("von Mises: min %.9g max %.9g, expected %.9g everywhere (relative error %.2e)" % (vm.min(), vm.max(), vm_uniform, err))
            check(err <= rtol, "von Mises stress differs from %g by a relative %.2e > %g" % (vm_uniform, err, rtol))
    st = data.get("/contact/status")
    if st is not None:
        check(set(np.unique(st)) <= {0, 1, 2}, "contact status outside {0, 1, 2}")
        check(np.all(data["/contact/pressure"] >= -1e-6 * max(1.0, np.abs(data["/contact/pressure"]).max())), "negative contact pressure")
    if jsonfile:
        with open(jsonfile) as f:
            js = json.loads(f.readline())
        sub = data.get("/volume/subdomain")
        if sub is not None:
            check(len(np.unique(sub)) == js["subdomains"], "%d subdomain ids in the file, the summary has %d subdomains" % (len(np.unique(sub)), js["subdomains"]))
        check(h.attrs.get("contact_nodes") == js["contact_nodes"], "file attribute contact_nodes %s, summary %d" % (h.attrs.get("contact_nodes"), js["contact_nodes"]))
        check(bool(h.attrs.get("converged")) == bool(js["converged"]), "file attribute converged %s, summary %s" % (h.attrs.get("converged"), js["converged"]))
        if js["contact_nodes"]:
            check("contact" in grids, "no contact grid although the summary has contact nodes")
            if st is not None:
                counts = [int(np.sum(st == k)) for k in range(3)]
                check(counts == [js["separated"], js["stick"], js["slip"]], "status counts %s in the file, summary %s" % (counts, [js["separated"], js["stick"], js["slip"]]))
            # the nodal forces of the file (pressure times area) add up to the summary's sum of the normal forces,
            # and each node's normal is a unit vector
            pr, ar, nr = data.get("/contact/pressure"), data.get("/contact/area"), data.get("/contact/normal")
            if pr is not None and ar is not None and "normal_force" in js:
                total = float(np.sum(pr * ar))
                check(abs(total - js["normal_force"]) <= 1e-5 * max(abs(js["normal_force"]), 1e-300), "sum of pressure x area %.9g, summary normal_force %.9g" % (total, js["normal_force"]))
            if nr is not None:
                check(np.allclose(np.linalg.norm(nr, axis=1), 1.0, atol=1e-12), "contact normals are not unit vectors")
        else:
            check("contact" not in grids, "a contact grid although the summary has no contact node")
    print("grids: " + ", ".join("%s (%d nodes, %d elements)" % (k, v[0], v[1]) for k, v in sizes.items()))
    return report()


def report():
    for f in fail:
        print("check-output.py: " + f)
    if not fail:
        print("check-output.py: output checks passed")
    return 1 if fail else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
