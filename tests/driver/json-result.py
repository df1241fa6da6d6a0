#!/usr/bin/python3
"""Read a conefeti run's output on stdin and print its JSON summary's machine-independent counts as one
RESULT line (key=value), for tests/tools/same-results.sh: the same scene on 1, 2, 3 ranks must give the
same counts and the same multipliers (their fingerprint). Times, norms and residuals (MPI reductions,
rounding-dependent) are left out; the rank count too."""
import json
import sys

COUNTS = ["n", "n_primal", "m", "m_gluing", "m_dirichlet", "m_normal", "m_tangential", "subdomains", "rigid_modes",
          "iter", "al_iter", "n_A", "n_A_qpp", "n_A_qpq", "n_A_other", "n_A_estimate", "contact_nodes", "separated", "stick", "slip"]
text = sys.stdin.read()
lines = [l for l in text.splitlines() if l.startswith('{"conefeti":')]
if len(lines) != 1:
    print(text)
    sys.exit("json-result.py: %d JSON summary lines, expected 1" % len(lines))
d = json.loads(lines[0])
print("RESULT scene=%s pipeline=%s converged=%s %s fingerprint=%s" % (d["scene"], d["pipeline"], d["converged"], " ".join("%s=%d" % (k, d[k]) for k in COUNTS), d["fingerprint"]))
