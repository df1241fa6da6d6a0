#!/usr/bin/python3
"""Run a conefeti scene with a contact zone between bodies, -output to a temporary file, and check its contact nodes
(the HDF5 group /contact, docs/output.md) as a property of the pairing or of the solution:

  --conforming     every slave node has one master node, of weight exactly 1, at its own position, and gap 0: the
                   rows are node to node (conforming meshes)
  --flat           (non-matching meshes, one flat interface) every slave node's master point is the node itself
                   (gap 0, the normal the slave's outward +-z), with 1 to 3 master nodes whose weights are in
                   [1e-12, 1] and sum to 1
  --gap G          every contact node has the initial gap G (to 1e-12; negative: an overlap)
  --pressure P --rtol r   the patch test: every contact node carries the pressure P to a relative r (prints the
                   largest relative deviation |lambda_n/area - P|/P)

usage: check-pairing.py [checks] -- command ..."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np


def main(argv):
    checks, pressure, rtol, gapvalue = [], None, None, None
    while argv and argv[0] != "--":
        a = argv.pop(0)
        if a == "--pressure":
            pressure = float(argv.pop(0))
        elif a == "--rtol":
            rtol = float(argv.pop(0))
        elif a == "--gap":
            gapvalue = float(argv.pop(0))
        else:
            checks.append(a)
    cmd = argv[1:]
    failed = []
    with tempfile.TemporaryDirectory() as tmp:
        base = os.path.join(tmp, "run")
        run = subprocess.run(cmd + ["-output", base], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if run.returncode != 0:
            print(run.stdout)
            sys.exit("check-pairing.py: the run ended with status %d" % run.returncode)
        with h5py.File(base + ".h5", "r") as h:
            c = {k: h["/contact/" + k][()] for k in h["/contact"]}
    x, nodes, w, chi, gap, normal = c["coordinates"], c["master_nodes"], c["master_weights"], c["master_point"], c["gap"], c["normal"]
    n = x.shape[0]
    scale = max(1.0, np.abs(x).max())
    print("%d contact nodes" % n)
    if "--conforming" in checks:
        one = np.all(nodes[:, 0] >= 0) and np.all(nodes[:, 1:] == -1) and np.all(w[:, 0] == 1.0) and np.all(w[:, 1:] == 0.0)
        at = np.abs(chi - x).max()
        print("conforming: one master node of weight 1 per slave node: %s; largest |chi - x| %.1e; largest |gap| %.1e" % (one, at, np.abs(gap).max()))
        if not one or at > 1e-12 * scale or np.any(gap != 0):
            failed.append("conforming rows are not node to node")
    if "--flat" in checks:
        used = nodes >= 0
        wsum = np.where(used, w, 0).sum(axis=1)
        ok = np.all(used[:, 0]) and np.all((w[used] >= 1e-12) & (w[used] <= 1)) and np.all(w[~used] == 0) and np.allclose(wsum, 1, atol=1e-14, rtol=0)
        at = np.abs(chi - x).max()
        nz = np.abs(np.abs(normal[:, 2]) - 1).max()
        counts = [int(np.sum(used.sum(axis=1) == k)) for k in (1, 2, 3)]
        print("flat interface: master points at the slave nodes (largest |chi - x| %.1e, |gap| %.1e, |n_z| - 1 %.1e); slave nodes with 1, 2, 3 master nodes: %s; weights barycentric: %s"
              % (at, np.abs(gap).max(), nz, counts, ok))
        if not ok or at > 1e-12 * scale or np.abs(gap).max() > 1e-12 * scale or nz > 1e-12:
            failed.append("the pairing on the flat interface is wrong")
    if gapvalue is not None:
        err = np.abs(gap - gapvalue).max()
        print("gap: from %.9g to %.9g, expected %.9g everywhere" % (gap.min(), gap.max(), gapvalue))
        if not err <= 1e-12 * scale:
            failed.append("the initial gaps differ from %g by %.1e" % (gapvalue, err))
    if pressure is not None:
        pr = c["pressure"]
        dev = np.abs(pr - pressure).max() / abs(pressure)
        print("patch test: contact pressure from %.6g to %.6g, applied %.6g: max relative deviation %.3e (tolerance %g)" % (pr.min(), pr.max(), pressure, dev, rtol))
        if not dev <= rtol:
            failed.append("the contact pressure deviates by %.3e > %g" % (dev, rtol))
    for f in failed:
        print("FAILED: " + f)
    print("check-pairing: %s" % ("failed" if failed else "passed"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
