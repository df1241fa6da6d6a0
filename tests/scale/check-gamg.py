#!/usr/bin/python3
"""Run the gamg program (tutorials/contact/gamg.cxx) and check its one JSON line.

usage: check-gamg.py [--expect PYTHON_EXPRESSION]... -- command...

The test fails unless the command exits with 0, prints exactly one line starting with {"gamg": that parses as
JSON with every documented field, and every --expect expression is true with the JSON fields as variables."""
import json, subprocess, sys

FIELDS = {"gamg": str, "scene": str, "ranks": int, "n": int, "n_global": int, "iter": int, "converged": bool, "reason": str, "residual": float, "time_mesh": float,
          "time_assembly": float, "time_setup": float, "time_solve": float, "time": float, "peak_rss": float, "peak_rss_rank": float, "bytes_per_unknown": float}


def main(argv):
    expects = []
    while argv and argv[0] != "--":
        if argv[0] != "--expect":
            sys.exit("check-gamg.py: unknown option " + argv[0])
        expects.append(argv[1])
        argv = argv[2:]
    proc = subprocess.run(argv[1:], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(proc.stdout)
    fail = [] if proc.returncode == 0 else ["exit status %d, expected 0" % proc.returncode]
    js = [l for l in proc.stdout.splitlines() if l.startswith('{"gamg":')]
    if len(js) != 1:
        fail.append("%d JSON lines, expected 1" % len(js))
    else:
        data = json.loads(js[0])
        for k, t in FIELDS.items():
            if not (isinstance(data.get(k), t) or (t is float and isinstance(data.get(k), int))):
                fail.append("JSON field %s missing or not a %s" % (k, t.__name__))
        for e in expects:
            try:
                ok = eval(e, {}, dict(data))
            except Exception as ex:
                ok, e = False, "%s (%s)" % (e, ex)
            if not ok:
                fail.append("expectation failed: " + e)
    for f in fail:
        print("check-gamg.py: " + f)
    return 1 if fail else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
