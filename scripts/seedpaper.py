"""The seed paper's brick for the brick scripts (bench-brick.py, goals-brick.py, bench-accuracy.py): its
Tables 1 and 2, the benchmark's goals, and one run of the conefeti program on petsc-options/brick.opts,
read from its JSON line."""
import json, os, subprocess, sys

BRICK = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "petsc-options", "brick.opts")
# the mechanical residuals of the JSON line, in the order of the tables
RESIDUALS = ["equilibrium", "gluing", "penetration", "normal_sign", "complementarity", "friction_cone", "slip_rule"]

PAPER = {  # n: (m, {F: (Iter, n_A, time in s)})
    900: (180, {0.1: (5, 102, 1), 0.3: (7, 140, 2)}),
    2646: (378, {0.1: (5, 180, 11), 0.3: (7, 186, 12)}),
    5832: (648, {0.1: (5, 156, 34), 0.3: (7, 169, 38)}),
    10890: (990, {0.1: (5, 112, 67), 0.3: (7, 153, 94)}),
    18252: (1404, {0.1: (5, 155, 221), 0.3: (7, 176, 254)}),
}

ITER_GOAL = {0.1: 5, 0.3: 7}  # the benchmark's goals: Iter <= 5 (F = 0.1) and <= 7 (F = 0.3)
GROWTH_GOAL = 1.3  # n_A(largest) / n_A(900)
TIME_GOAL = 1.0  # seconds for n = 18252 on one core


def brick_n(k):
    """The brick's n for k cells per cube edge: the undecomposed mesh's unknowns without the clamped face."""
    return 9 * k * (k + 1) ** 2


def run(build, k, F, rtol, extra, env, algorithm=None):
    """Runs the conefeti program on petsc-options/brick.opts (the one definition of the brick) with
    -scene_refine k and friction F, and returns the counts, times, node states and mechanical residuals of
    its JSON line (docs/output.md); exits with the output when the run failed (exit status 2, ran but
    did not converge, is a result)."""
    cmd = [os.path.join(build, "conefeti"), "-options_file", BRICK, "-scene_refine", str(k), "-scene_zone0_friction", str(F),
           "-summary_table", "0", "-options_left", "0"] + (["-contact_coulomb_algorithm", algorithm] if algorithm else []) + ["-contact_rtol", str(rtol)] + extra
    out = subprocess.run(cmd, capture_output=True, text=True, env=env)
    line = next((l for l in out.stdout.splitlines() if l.startswith('{"conefeti":')), None)
    if out.returncode not in (0, 2) or line is None:
        sys.exit("brick failed (%s):\n%s" % (" ".join(cmd), (out.stdout + out.stderr)[-2000:]))
    j = json.loads(line)
    if "n" not in j:
        sys.exit("brick did not run a solve (%s):\n%s" % (" ".join(cmd), line))
    res = j.get("residuals") or {}
    # n_A as the brick tables print it: every F product of the solve, QPP + QPQ + other (the JSON's n_A
    # leaves out the few products outside the inner solvers)
    return dict(n=j["n"], m=j["m"], iter=j["iter"], nA=j["n_A"] + j["n_A_other"], qpp=j["n_A_qpp"], qpq=j["n_A_qpq"], other=j["n_A_other"], est=j["n_A_estimate"],
                setup=j["time_setup"], solve=j["time_solve"], nodes=(j["separated"], j["stick"], j["slip"]), converged=out.returncode == 0 and j["converged"],
                res=[float("nan") if res.get(r) is None else res[r] for r in RESIDUALS])
