#!/usr/bin/python3
"""Compare one count of two conefeti runs from their JSON summary lines.

usage: fewer-json.py EXPRESSION -- COMMAND_A -- COMMAND_B

Runs both commands; EXPRESSION is evaluated with the JSON fields of each run as variables (e.g.
"n_A + n_A_other", every F product of the solve). Fails unless both runs converged and A's value is
strictly smaller than B's. Prints both values."""
import json
import subprocess
import sys


def run(cmd, expr):
    r = subprocess.run(cmd, capture_output=True, text=True)
    lines = [l for l in r.stdout.splitlines() if l.startswith('{"conefeti":')]
    if r.returncode != 0 or len(lines) != 1:
        print(r.stdout[-3000:], r.stderr[-3000:])
        sys.exit("fewer-json.py: %s exited %d with %d JSON lines" % (" ".join(cmd), r.returncode, len(lines)))
    d = json.loads(lines[0])
    if not d["converged"]:
        sys.exit("fewer-json.py: %s did not converge: %s" % (" ".join(cmd), d["reason"]))
    return eval(expr, {}, d)


def main(argv):
    if len(argv) < 4 or argv[1] != "--" or argv.count("--") < 2:
        sys.exit(__doc__)
    expr = argv[0]
    rest = argv[2:]
    k = rest.index("--")
    a, b = run(rest[:k], expr), run(rest[k + 1:], expr)
    print("%s: A %s, B %s" % (expr, a, b))
    if not a < b:
        sys.exit("fewer-json.py: %s of A is not smaller" % expr)


if __name__ == "__main__":
    main(sys.argv[1:])
