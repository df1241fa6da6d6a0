#!/usr/bin/python3
"""The cost of the dual preconditioner (-contact_pc_type, src/contact/contactpc.cxx) in applications and coarse solves.

usage: dualpc-counts.py restart -- conefeti-command...
       dualpc-counts.py projections -- command-A... -- command-B...

Every command gets -contact_tao_view -log_view appended and must converge within the acceptance.

restart: the inner solver applies the preconditioner only where a CG or expansion step uses the direction: the
  applications (the view's "preconditioner applications", the same count as -log_view's FETIPCApply) are fewer
  than CG + expansion + proportioning steps + solves, which is what computing the direction at every restart
  (after each expansion and proportioning step and at each start) costs at least.
projections: A applies M without FETI's own projector, B with it (-contact_pc_inner_projector 0 and 1), where smalxe's
  P on both sides makes them the same operator (-contact_pc_contact_rows_scaled 0: P P M P P = P M P). Both take the
  same outer iterations and F products (n_A up to 2 apart: rounding), with the same largest residual within the
  acceptance, and B's coarse solves (-log_view's FETICoarseSolve) exceed A's by 2 per application (the rest, the
  Hessian products' and the outer loop's, are the same up to the rounding's product or two)."""
import json
import re
import subprocess
import sys

import os

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import logview  # noqa: E402  (scripts/logview.py: the -log_view reader of the benchmark scripts)


def run(cmd):
    cmd = cmd + ["-contact_tao_view", "-log_view"]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    out = proc.stdout + proc.stderr
    print(" ".join(cmd))
    line = next((l for l in proc.stdout.splitlines() if l.startswith('{"conefeti":')), None)
    if proc.returncode != 0 or line is None:
        print(out[-4000:])
        sys.exit("dualpc-counts.py: the command failed (exit %d)" % proc.returncode)
    j = json.loads(line)
    ev = logview.events(proc.stdout)
    # the inner solvers' views (mprgp, mpgp: "(nested 0)"), each with its preconditioner applications, summed
    steps, apps = [0, 0, 0, 0], 0
    for m in re.finditer(r"solves (\d+), iterations \d+ \(nested 0\): CG (\d+), expansion (\d+), proportioning (\d+)\n(\s*preconditioner applications: (\d+))?", out):
        steps = [a + int(b) for a, b in zip(steps, m.groups()[:4])]
        apps += int(m.group(6) or 0)
    r = {
        "iter": j["iter"], "n_A": j["n_A"], "max": j["residuals"]["max"], "acceptance": j["acceptance"], "converged": j["converged"],
        "pc_events": ev.get("FETIPCApply", (0, 0.0))[0], "coarse": ev.get("FETICoarseSolve", (0, 0.0))[0], "F": ev.get("FETI_MultF", (0, 0.0))[0],
        "steps": tuple(steps) if any(steps) else None, "apps": apps if apps else None,
    }
    print("  " + ", ".join("%s %s" % kv for kv in r.items()))
    return r


def main(argv):
    mode = argv[1]
    rest = argv[argv.index("--") + 1:]
    fail = []
    if mode == "restart":
        r = run(rest)
        if not r["converged"] or r["max"] > r["acceptance"]:
            fail.append("not converged within the acceptance")
        if r["steps"] is None or r["apps"] is None:
            fail.append("no step counts or preconditioner applications in the view")
        else:
            solves, cg, exp, prop = r["steps"]
            if r["apps"] != r["pc_events"]:
                fail.append("view: %d applications, -log_view FETIPCApply %d" % (r["apps"], r["pc_events"]))
            if not r["apps"] < cg + exp + prop + solves:
                fail.append("%d applications, not fewer than CG %d + expansion %d + proportioning %d + solves %d" % (r["apps"], cg, exp, prop, solves))
            if not prop > 0:
                fail.append("no proportioning step: the property says nothing")
    elif mode == "projections":
        k = rest.index("--")
        a, b = run(rest[:k]), run(rest[k + 1:])
        for name, r in (("A", a), ("B", b)):
            if not r["converged"] or r["max"] > r["acceptance"]:
                fail.append("%s not converged within the acceptance" % name)
            if not r["apps"] or r["apps"] != r["pc_events"]:
                fail.append("%s: preconditioner applications %s, FETIPCApply %d" % (name, r["apps"], r["pc_events"]))
        if a["iter"] != b["iter"] or abs(a["n_A"] - b["n_A"]) > 2:
            fail.append("Iter %d and %d, n_A %d and %d: not the same operator?" % (a["iter"], b["iter"], a["n_A"], b["n_A"]))
        if not fail:
            extra = (b["coarse"] - a["coarse"]) / b["apps"]
            print("coarse solves: A %d, B %d; B's more per application %.2f" % (a["coarse"], b["coarse"], extra))
            if not 1.8 <= extra <= 2.2:
                fail.append("B's coarse solves exceed A's by %.2f per application, expected 2" % extra)
    else:
        sys.exit("dualpc-counts.py: unknown mode " + mode)
    for f in fail:
        print("dualpc-counts.py: " + f)
    print("dualpc-counts.py: " + ("FAILED" if fail else "passed"))
    return 1 if fail else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
