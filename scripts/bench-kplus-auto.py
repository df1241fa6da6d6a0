#!/usr/bin/python3
"""-feti_kplus auto against the pure choices on the brick: what auto chose, CPU seconds, peak memory, Iter, n_A.

For each case (a brick size) the variants run back to back, one at a time, --repeat times in turn (A B C A B C),
one rank, each under /usr/bin/time: CPU seconds (user + sys of the whole run: setup and solve), the peak resident
set, and from the driver's JSON line Iter, n_A, the wall setup and solve times, the fingerprint and what auto
chose; "solve CPU" is the median CPU seconds times the solve's share of the median wall times (derived, not
measured). CPU seconds are what a loaded machine measures best; compare the variants of one case (they ran side by
side), not cases. Speed is never asserted: this is a benchmark, not a test.

usage: scripts/bench-kplus-auto.py [--build build] [--repeat 2] [--cases paper:12,hh6:1,...] [--variants "auto=,blocks=-feti_kplus explicit,factor=-feti_kplus implicit"]
  a variant's options may start with --build=DIR: that build's driver (e.g. "before=--build=../main/build")
  paper:k  petsc-options/brick.opts -scene_refine k (three cubes, the paper's sizes k = 4 ... 12)
  hh6:p    -scene_refine 6p -scene_body0_subdomains 3p,p,p (cubes of 6 cells, n = 9k(k+1)^2, k = 6p)
"""
import argparse, json, os, re, statistics, subprocess, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BRICK = os.path.join(ROOT, "petsc-options", "brick.opts")

ap = argparse.ArgumentParser()
ap.add_argument("--build", default="build")
ap.add_argument("--repeat", type=int, default=2)
ap.add_argument("--cases", default="paper:8,paper:10,paper:12,hh6:1,hh6:2,hh6:3")
ap.add_argument("--variants", default="auto=,blocks=-feti_kplus explicit,factor=-feti_kplus implicit")
a = ap.parse_args()
variants = [(v.split("=", 1)[0], v.split("=", 1)[1].split()) for v in a.variants.split(",")]


def program(extra):
    """a variant may run another build: its options start with --build=DIR (another worktree, for a before/after)"""
    if extra and extra[0].startswith("--build="):
        return os.path.join(extra[0][len("--build="):], "conefeti"), extra[1:]
    return os.path.join(a.build, "conefeti"), extra


def case_options(case):
    kind, v = case.split(":")
    v = int(v)
    if kind == "paper":
        return ["-scene_refine", str(v)]
    return ["-scene_refine", str(6 * v), "-scene_body0_subdomains", "%d,%d,%d" % (3 * v, v, v)]


print("| case | n | variant | K+ | Iter | n_A | CPU [s] (runs) | setup + solve wall [s] | solve CPU [s] (derived) | peak memory | fingerprint |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for case in a.cases.split(","):
    rows = {name: [] for name, _ in variants}
    for r in range(a.repeat):
        for name, extra in variants:
            with tempfile.NamedTemporaryFile("r") as tf:
                exe, opts = program(extra)
                cmd = ["/usr/bin/time", "-f", "%U %S %M", "-o", tf.name, exe, "-options_file", BRICK] + case_options(case) + opts
                p = subprocess.run(cmd, capture_output=True, text=True)
                u, s, m = tf.read().split()[-3:]
            js = [json.loads(l) for l in p.stdout.splitlines() if l.startswith('{"conefeti":')]
            if p.returncode != 0 or not js:
                rows[name].append(None)
                print("| %s | | %s | failed (exit %d) | | | | | | |" % (case, name, p.returncode))
                continue
            rows[name].append((float(u) + float(s), int(m) / 1024.0, js[0]))
    for name, _ in variants:
        ok = [x for x in rows[name] if x]
        if not ok:
            continue
        d = ok[0][2]
        cpus = [x[0] for x in ok]
        # the solve's share of the CPU seconds, by its share of the wall time of the same run (a loaded machine
        # stretches both phases alike; the driver reports no CPU time per phase)
        setup, solve = statistics.median(x[2]["time_setup"] for x in ok), statistics.median(x[2]["time_solve"] for x in ok)
        print("| %s | %d | %s | %s | %d | %d | %.2f (%s) | %.2f + %.2f | %.2f | %.0f MB | %s |" %
              (case, d["n"], name, d["kplus"], d["iter"], d["n_A"], statistics.median(cpus), ", ".join("%.2f" % c for c in cpus), setup, solve,
               statistics.median(cpus) * solve / (setup + solve), max(x[1] for x in ok), d["fingerprint"]))
