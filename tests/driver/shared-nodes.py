#!/usr/bin/python3
"""usage: shared-nodes.py [--rtol r] -- conefeti-command... ---- conefeti-command...

Two runs of one scene whose contact surface is cut differently into zones (one zone, and two zones that share the
nodes of the line between them, or the same zone given twice): each writes its HDF5 output (-output is appended
here). The contact output must list every contact point once, the same points in both runs, with the same lumped
area and the same contact pressure within r (default 1e-4) of the largest pressure. Before contactsharednodes.cxx a
node on the line between two zones was a contact node twice, each copy with its zone's part of the area and an
arbitrary part of the force, and a zone given twice halved every pressure."""
import os
import shutil
import subprocess
import sys
import tempfile

import h5py

argv = sys.argv[1:]
rtol = 1e-4
if argv[:1] == ["--rtol"]:
    rtol, argv = float(argv[1]), argv[2:]
assert argv[0] == "--" and "----" in argv, __doc__
split = argv.index("----")
commands = [argv[1:split], argv[split + 1:]]
tmp = tempfile.mkdtemp(prefix="shared-nodes-")
points = []
try:
    for i, cmd in enumerate(commands):
        base = os.path.join(tmp, "run%d" % i)
        proc = subprocess.run(cmd + ["-output", base], capture_output=True, text=True)
        print(proc.stdout + proc.stderr)
        if proc.returncode != 0:
            sys.exit("run %d exited with %d" % (i, proc.returncode))
        with h5py.File(base + ".h5", "r") as f:
            x, p, a = f["/contact/coordinates"][:], f["/contact/pressure"][:], f["/contact/area"][:]
        keys = [tuple(round(float(c), 9) for c in xi) for xi in x]
        if len(set(keys)) != len(keys):
            sys.exit("run %d: %d contact points, %d of them listed twice" % (i, len(keys), len(keys) - len(set(keys))))
        points.append({k: (float(pi), float(ai)) for k, pi, ai in zip(keys, p, a)})
finally:
    shutil.rmtree(tmp, ignore_errors=True)
one, two = points
if set(one) != set(two):
    sys.exit("the runs have different contact points: %d and %d, %d in common" % (len(one), len(two), len(set(one) & set(two))))
pmax = max(abs(v[0]) for v in one.values())
worst = max(abs(one[k][0] - two[k][0]) for k in one)
area = max(abs(one[k][1] - two[k][1]) / one[k][1] for k in one)
print("contact points %d; largest pressure %.6g; largest difference of the pressures %.3g of it; of the areas %.3g" % (len(one), pmax, worst / pmax, area))
if not pmax > 0:
    sys.exit("no contact pressure: the scene tests nothing")
if worst > rtol * pmax or area > 1e-12:
    sys.exit("the pressures or areas differ (tolerance %g of the largest pressure, 1e-12 of the areas)" % rtol)
print("OK")
