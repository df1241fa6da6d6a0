#!/usr/bin/python3
"""Run a conefeti command and check its one JSON summary line.

usage: check-json.py [--exit-code N] [--first-line REGEX] [--expect PYTHON_EXPRESSION]... [--no-file PATH]... -- command...

The command's output is printed. The test fails unless the command exits with N (default 0), prints
exactly one line starting with {"conefeti": that parses as JSON (no NaN or infinity) and has every
documented field with its type, the first output line other than progress lines matches --first-line (if given), and every
--expect expression is true with the JSON fields as variables (the residuals as `residuals`), the
pipeline line printed before the solve equals the JSON description of what ran, and no --no-file path
exists afterwards."""
import json
import os
import re
import subprocess
import sys

FIELDS = {
    "conefeti": str, "scene": str, "ranks": int, "pipeline": str, "description": str, "converged": bool, "reason": str,
    "n": int, "n_primal": int, "m": int, "m_gluing": int, "m_dirichlet": int, "m_normal": int, "m_tangential": int,
    "subdomains": int, "rigid_modes": int, "iter": int, "al_iter": int, "n_A": int, "n_A_qpp": int, "n_A_qpq": int,
    "n_A_other": int, "n_A_estimate": int, "norm_F": float, "time_setup": float, "time_solve": float, "time_phases": dict,
    "contact_nodes": int, "separated": int, "stick": int, "slip": int, "fixed_point": float, "feasibility": float,
    "acceptance": float, "refinements": int, "residuals": dict, "kplus": str, "kplus_blocks": int,
    "kplus_precision": str, "kplus_single": int, "kplus_factor_mb": float, "kplus_factor_double_mb": float,
}
PROGRESS = re.compile(r"^(setup|solve): ")
RESIDUALS = ["equilibrium", "gluing", "penetration", "normal_sign", "complementarity", "friction_cone", "slip_rule", "max"]


def reject(constant):
    raise ValueError("JSON has " + constant)


def main(argv):
    exit_code, first, expects, nofiles = 0, None, [], []
    while argv and argv[0] != "--":
        opt, val = argv[0], argv[1]
        argv = argv[2:]
        if opt == "--exit-code": exit_code = int(val)
        elif opt == "--first-line": first = val
        elif opt == "--expect": expects.append(val)
        elif opt == "--no-file": nofiles.append(val)
        else: sys.exit("check-json.py: unknown option " + opt)
    cmd = argv[1:]
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(proc.stdout)
    fail = []
    if proc.returncode != exit_code:
        fail.append("exit status %d, expected %d" % (proc.returncode, exit_code))
    lines = proc.stdout.splitlines()
    if first is not None:
        # progress lines (setup: ..., solve: ..., docs/output.md) come before it in a log
        head = next((l for l in lines if l.strip() and not PROGRESS.match(l)), "")
        if not re.search(first, head):
            fail.append("first line %r does not match %r" % (head, first))
    js = [l for l in lines if l.startswith('{"conefeti":')]
    if len(js) != 1:
        fail.append("%d JSON summary lines, expected 1" % len(js))
    else:
        try:
            data = json.loads(js[0], parse_constant=reject)
        except ValueError as e:
            data = None
            fail.append("JSON line does not parse: %s" % e)
        if data is not None:
            for k, t in FIELDS.items():
                if k not in data:
                    fail.append("JSON field %s missing" % k)
                elif not (isinstance(data[k], t) or (t is float and isinstance(data[k], int))) or (t is int and isinstance(data[k], bool)):
                    fail.append("JSON field %s = %r is not a %s" % (k, data[k], t.__name__))
            for k in RESIDUALS:
                if not isinstance(data.get("residuals", {}).get(k), (int, float)):
                    fail.append("JSON residual %s missing or not a finite number" % k)
            if "algorithm" not in data:
                fail.append("JSON field algorithm missing")
            # converged exactly when no check failed; a run that did not converge names the check
            if "failed_check" not in data:
                fail.append("JSON field failed_check missing")
            elif data.get("converged") is True and data["failed_check"] is not None:
                fail.append("converged with failed_check = %r" % data["failed_check"])
            elif data.get("converged") is False and not isinstance(data["failed_check"], str):
                fail.append("not converged without a failed_check")
            # the pipeline line printed before the solve must describe what ran
            pre = [l for l in lines if re.match(r"^conefeti [0-9.]+: pipeline ", l)]
            if pre and isinstance(data.get("description"), str) and pre[0].split(": pipeline ", 1)[1] != data["description"]:
                fail.append("the pipeline printed before the solve (%r) is not what ran (%r)" % (pre[0].split(": pipeline ", 1)[1], data["description"]))
            for e in expects:
                try:
                    ok = eval(e, {}, dict(data))
                except Exception as ex:  # a missing name is a failure, not a crash
                    ok, e = False, "%s (%s)" % (e, ex)
                if not ok:
                    fail.append("expectation failed: " + e)
    for f in nofiles:
        if os.path.exists(f):
            fail.append("%s exists, expected no file" % f)
    for f in fail:
        print("check-json.py: " + f)
    if not fail:
        print("check-json.py: JSON summary checks passed (%d expectations)" % len(expects))
    return 1 if fail else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
