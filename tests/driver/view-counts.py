#!/usr/bin/python3
"""usage: view-counts.py -- conefeti-command... -contact_tao_view

The counts of the solver's view and of the summary agree: every smalxe view says how many outer
iterations its solve ran ("last solve: N outer iterations"), PETSc's line of the same view
("total number of iterations=M", the index of the last, counted from 0) says N - 1, the JSON line's
al_iter is the sum of the N over the solves, and iter is N when there is one solve (not msa)."""
import json
import re
import subprocess
import sys

cmd = sys.argv[sys.argv.index("--") + 1:]
proc = subprocess.run(cmd, capture_output=True, text=True)
out = proc.stdout + proc.stderr
lines = out.splitlines()
fail = []
if proc.returncode != 0:
    fail.append("exit status %d" % proc.returncode)
runs = []
for i, line in enumerate(lines):
    m = re.search(r"^(\s*)last solve: (\d+) outer iterations", line)
    if not m:
        continue
    n = int(m.group(2))
    # the view's own PETSc line: the first "total number of iterations" indented as the view's header (2 less)
    indent = " " * (len(m.group(1)) - 2)
    total = next((int(t.group(1)) for t in (re.match(r"^" + indent + r"total number of iterations=(\d+)", l) for l in lines[i + 1:]) if t), None)
    runs.append(n)
    print("view: last solve %d outer iterations, PETSc's total number of iterations=%s" % (n, total))
    if total != n - 1:
        fail.append("the view says %d outer iterations and PETSc's line %s (expected %d)" % (n, total, n - 1))
record = next((json.loads(l) for l in lines if l.startswith('{"conefeti":')), None)
if not runs:
    fail.append("no 'last solve: N outer iterations' line in the view")
if record is None:
    fail.append("no JSON line")
else:
    print("JSON: iter %s, al_iter %s, algorithm %s" % (record["iter"], record["al_iter"], record["algorithm"]))
    if record["al_iter"] != sum(runs):
        fail.append("al_iter %s, the views' outer iterations sum to %d" % (record["al_iter"], sum(runs)))
    if record["algorithm"] != "msa" and (len(runs) != 1 or record["iter"] != runs[0]):
        fail.append("iter %s, the view says %s" % (record["iter"], runs))
for f in fail:
    print("view-counts.py: " + f)
if not fail:
    print("view-counts.py: the view and the summary give the same counts")
sys.exit(1 if fail else 0)
