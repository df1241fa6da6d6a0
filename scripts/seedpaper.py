"""The seed paper's brick for the brick scripts (bench-brick.py, goals-brick.py): its Tables 1 and 2, the
benchmark's goals, and one run of the brick tutorial with its printed counts."""
import os, re, subprocess, sys

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
    """Runs build/tutorials/contact/brick and returns its counts, times, node statuses and residuals; exits
    with the output when the run failed (exit status 2, ran but did not converge, is a result)."""
    exe = os.path.join(build, "tutorials", "contact", "brick")
    cmd = [exe, "-k", str(k), "-friction", str(F)] + (["-contact_coulomb_algorithm", algorithm] if algorithm else []) + ["-contact_rtol", str(rtol)] + extra
    out = subprocess.run(cmd, capture_output=True, text=True, env=env)
    text = out.stdout + out.stderr
    m = re.search(r"^n (\d+) m (\d+) Iter (\d+) n_A (\d+) \(QPP (\d+) \+ QPQ (\d+) \+ other (\d+)\) estimate (\d+) setup ([\d.]+) s solve ([\d.]+) s", text, re.M)
    nodes = re.search(r"nodes: (\d+) separated, (\d+) stick, (\d+) slip", text)
    res = re.search(r"residuals: (.*)", text)
    conv = out.returncode == 0 and re.search(r"^pipeline \w+; converged\b", text, re.M) is not None
    if not m or out.returncode not in (0, 2):
        sys.exit("brick failed (%s):\n%s" % (" ".join(cmd), text[-2000:]))
    v = [int(x) for x in m.groups()[:8]] + [float(m.group(9)), float(m.group(10))]
    return dict(n=v[0], m=v[1], iter=v[2], nA=v[3], qpp=v[4], qpq=v[5], other=v[6], est=v[7], setup=v[8], solve=v[9],
                nodes=tuple(int(x) for x in nodes.groups()) if nodes else (0, 0, 0), converged=conv, residuals=res.group(1) if res else "")
