#!/usr/bin/python3
"""QP benchmark: Hessian products and time of conefeti's mprgp/mpgp against TAO's own
solvers, every solver run to the same projected-gradient tolerance measured by the benchmark
programs themselves (tutorials/qp/obstacle.cxx, tutorials/qp/disks.cxx; see their headers).

How the common tolerance is reached: each program is told the target |gP| <= rtol |b|
(-bench_rtol). conefeti's types stop on exactly that quantity (-tao_gttol is |b|-relative there).
TAO's solvers get -tao_gatol = factor * rtol * |b| on their own residual (the projected gradient
for blmvm, bncg, gpcg, tron; an interior-point residual for bqpip, pdipm; the Lagrangian gradient
and constraint norm for almm). The script starts with factor 1 and, when the program reports that
the independently measured |gP| missed the target although the solver claimed convergence, reruns
with factor / 10 (down to 1e-4). bqpip starts from factor 10 (its own residual can level off
above a tight tolerance). The factor used is printed in the tables.

With --defaults it compares instead the defaults of mprgp/mpgp, which follow the Hessian (an assembled one
gets ICC in face, the projected CG expansion and Gamma 2 unless the set has cone blocks:
src/qp/impls/mpgp/mpgpdefaults.cxx), with the old
defaults (no preconditioner, Dostal's expansion, Gamma 1, now given as options) and with TAO's bound solvers,
on the obstacle and the journal bearing at 100^2 and 316^2 unknowns and on the disks, and then old against
new defaults on the random ill-conditioned QPs of tests/qp (qp_known_solution), whose Hessian is a MATSHELL
(the defaults do not change there) or the same matrix stored as AIJ (-matrix aij).

Usage:  scripts/bench-qp.sh [--quick] [--defaults] [--out DIR] [--sizes small,large] [--problems obstacle,bearing,disks]
                           [--rtol 1e-6] [--timeout 180] [--tao-timeout 60] [--seeds 12345,1,2,3,4,5,6] [--jobs 2]
(--problems '' with --defaults: the random QPs only.)
Prints markdown tables; the raw JSON lines go to DIR/results.jsonl (default build/bench-qp).
"""
import re
import argparse
import json
import os
import platform
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def old_defaults(t, *chosen):
    """The defaults of mprgp/mpgp before they followed the Hessian (no PC, Dostal's expansion, Gamma 1), as
    options, except those a row sets itself: the tables of docs/qp-benchmark.md measured before that change
    stay reproducible (an assembled Hessian now gets ICC, the projected CG expansion and Gamma 2)."""
    opts = {"pc_type": "none", "expansion_projcg": "0", "gamma": "1"}
    return sum((["-tao_%s_%s" % (t, k), v] for k, v in opts.items() if k not in chosen), [])


# (label, program options); labels name the solver and any non-default options. In these tables "mprgp" and
# "mpgp" are the old defaults (old_defaults()); scripts/bench-qp.sh --defaults compares them with the new ones.
BOUND_SOLVERS = [
    ("mprgp", ["-tao_type", "mprgp"] + old_defaults("mprgp")),
    ("mpgp", ["-tao_type", "mpgp"] + old_defaults("mpgp")),
    ("blmvm", ["-tao_type", "blmvm"]),
    ("bncg", ["-tao_type", "bncg"]),
    ("gpcg", ["-tao_type", "gpcg"]),
    ("tron", ["-tao_type", "tron"]),
    # bqpip replaces infinite bounds by 1e20 and then stalls on the journal bearing (no progress in
    # 300 s at n = 9801); an inactive finite upper bound (the solution is below 1) fixes that
    # Its own residual can level off above a tight tolerance (4.8e-7 on the bearing at n = 9801), so
    # its search starts from a looser factor 10.
    ("bqpip, -upper 100", ["-tao_type", "bqpip", "-upper", "100"], {"factors": [10.0, 1.0, 1e-1, 1e-2]}),
    # TAO's gpcg, tron and bqpip precondition their inner KSP with ILU(0) by default; mprgp/mpgp do
    # not precondition at all. The same solvers without the preconditioner:
    ("gpcg, -pc_type none", ["-tao_type", "gpcg", "-pc_type", "none"]),
    ("tron, -pc_type none", ["-tao_type", "tron", "-pc_type", "none"]),
    ("bqpip, -upper 100 -pc_type none", ["-tao_type", "bqpip", "-upper", "100", "-pc_type", "none"], {"sizes": ["small"], "factors": [10.0, 1.0, 1e-1, 1e-2]}),  # 20x the products of bqpip with ILU
    # sensitivity of ours to the fixed step length (not the defaults)
    ("mprgp, -tao_mprgp_alpha 1", ["-tao_type", "mprgp", "-tao_mprgp_alpha", "1"] + old_defaults("mprgp")),
    # the projected CG expansion, preconditioning in face with ICC(0) (the counterpart of gpcg's ILU(0)),
    # and both with Gamma = 2 (fewer proportioning steps: the preconditioned CG steps make more progress)
    ("mprgp, -tao_mprgp_expansion_projcg", ["-tao_type", "mprgp", "-tao_mprgp_expansion_projcg"] + old_defaults("mprgp", "expansion_projcg")),
    ("mprgp, -tao_mprgp_pc_type icc", ["-tao_type", "mprgp", "-tao_mprgp_pc_type", "icc"] + old_defaults("mprgp", "pc_type")),
    ("mprgp, -tao_mprgp_pc_type icc -tao_mprgp_expansion_projcg -tao_mprgp_gamma 2",
     ["-tao_type", "mprgp", "-tao_mprgp_pc_type", "icc", "-tao_mprgp_expansion_projcg", "-tao_mprgp_gamma", "2"]),
    ("mpgp, -tao_mpgp_pc_type icc -tao_mpgp_expansion_projcg -tao_mpgp_gamma 2",
     ["-tao_type", "mpgp", "-tao_mpgp_pc_type", "icc", "-tao_mpgp_expansion_projcg", "-tao_mpgp_gamma", "2"]),
]
DISK_SOLVERS = [
    ("mpgp", ["-tao_type", "mpgp"] + old_defaults("mpgp")),
    # Kucera's MPGP as published: no arc steps (on by default since they cut the products on the disks and the brick)
    ("mpgp, -tao_mpgp_arc 0", ["-tao_type", "mpgp", "-tao_mpgp_arc", "0"] + old_defaults("mpgp")),
    # the default takes fixed steps 1.95/||A|| in its gradient projections; BB lengths and the shorter
    # 1/||A|| are options (BB is off by default: it did not pay on the contact problems)
    ("mpgp, -tao_mpgp_bb 1", ["-tao_type", "mpgp", "-tao_mpgp_bb", "1"] + old_defaults("mpgp")),
    ("mpgp, -tao_mpgp_alpha 1", ["-tao_type", "mpgp", "-tao_mpgp_alpha", "1"] + old_defaults("mpgp")),
    ("mpgp, -tao_mpgp_bb 1 -tao_mpgp_alpha 1", ["-tao_type", "mpgp", "-tao_mpgp_bb", "1", "-tao_mpgp_alpha", "1"] + old_defaults("mpgp")),
    ("mpgp, -tao_mpgp_bb 1 -tao_mpgp_alpha 1 -tao_mpgp_expansion_projcg", ["-tao_type", "mpgp", "-tao_mpgp_bb", "1", "-tao_mpgp_alpha", "1", "-tao_mpgp_expansion_projcg"] + old_defaults("mpgp", "expansion_projcg")),
    ("almm", ["-tao_type", "almm"], {"factors": [1.0, 1e-2, 1e-4]}),
    ("almm, -tao_almm_type classic", ["-tao_type", "almm", "-tao_almm_type", "classic"], {"timeout": 30, "sizes": ["small"]}),  # stalls
    ("pdipm", ["-tao_type", "pdipm", "-mat_mumps_icntl_14", "200"]),
]
# --defaults: the defaults chosen from the Hessian against the old ones and TAO's bound solvers
OLD_MPRGP = ["-tao_mprgp_pc_type", "none", "-tao_mprgp_expansion_projcg", "0", "-tao_mprgp_gamma", "1"]
OLD_MPGP = ["-tao_mpgp_pc_type", "none", "-tao_mpgp_expansion_projcg", "0", "-tao_mpgp_gamma", "1"]
DEFAULT_BOUND_SOLVERS = [
    ("mprgp (defaults: ICC, projected CG expansion, Gamma 2)", ["-tao_type", "mprgp"]),
    ("mpgp (defaults: ICC, projected CG expansion, Gamma 2)", ["-tao_type", "mpgp"]),
    ("mprgp, old defaults: " + " ".join(OLD_MPRGP), ["-tao_type", "mprgp"] + OLD_MPRGP),
    ("mpgp, old defaults: " + " ".join(OLD_MPGP), ["-tao_type", "mpgp"] + OLD_MPGP),
    ("mprgp, -tao_mprgp_pc_type none (the other defaults kept)", ["-tao_type", "mprgp", "-tao_mprgp_pc_type", "none"]),
    ("gpcg", ["-tao_type", "gpcg"]),
    ("blmvm", ["-tao_type", "blmvm"]),
    ("tron", ["-tao_type", "tron"]),
    ("bqpip, -upper 100", ["-tao_type", "bqpip", "-upper", "100"], {"factors": [10.0, 1.0, 1e-1, 1e-2]}),
    ("bncg", ["-tao_type", "bncg"]),
]
DEFAULT_DISK_SOLVERS = [
    ("mpgp (defaults: ICC, projected CG expansion, Gamma 2)", ["-tao_type", "mpgp"]),
    ("mpgp, old defaults: " + " ".join(OLD_MPGP), ["-tao_type", "mpgp"] + OLD_MPGP),
]
TAO_BOUND_SOLVERS = ("gpcg", "blmvm", "tron", "bqpip", "bncg")
# random ill-conditioned QPs of tests/qp: (kind, solver, cond); 50 units of 6 entries (300 unknowns), |gP| <= 1e-9 |b|
RANDOM_CASES = [("bounds", "tao_mprgp", "1e4"), ("bounds", "tao_mprgp", "1e8"), ("bounds", "tao_mpgp", "1e4"), ("disks", "tao_mpgp", "1e4"),
                ("mixed", "tao_mpgp", "1e2"), ("mixed", "tao_mpgp", "1e4"), ("cones", "tao_mpgp", "1e2"), ("cones", "tao_mpgp", "1e4")]

PROBLEMS = {
    # name: (program, extra options, solvers, {size: (n option, repeat)})
    "obstacle": ("obstacle", ["-problem", "obstacle"], BOUND_SOLVERS, {"small": ("99", 3), "large": ("319", 1)}),
    "bearing": ("obstacle", ["-problem", "bearing"], BOUND_SOLVERS, {"small": ("99", 3), "large": ("319", 1)}),
    "disks": ("disks", [], DISK_SOLVERS, {"small": ("70", 3), "large": ("224", 1)}),
}
PROBLEMS_DEFAULTS = {
    "obstacle": ("obstacle", ["-problem", "obstacle"], DEFAULT_BOUND_SOLVERS, {"small": ("100", 3), "large": ("316", 1)}),
    "bearing": ("obstacle", ["-problem", "bearing"], DEFAULT_BOUND_SOLVERS, {"small": ("100", 3), "large": ("316", 1)}),
    "disks": ("disks", [], DEFAULT_DISK_SOLVERS, {"small": ("70", 3), "large": ("224", 1)}),
}
FACTORS = [1.0, 1e-1, 1e-2, 1e-3, 1e-4]
CONVERGED = ("CONVERGED_GATOL", "CONVERGED_GRTOL", "CONVERGED_GTTOL", "CONVERGED_STEPTOL", "CONVERGED_MINF", "CONVERGED_USER")


def run(prog, opts, timeout):
    """Runs one benchmark program; returns (record or None, error text or None, wall seconds)."""
    cmd = [os.path.join(ROOT, "build", "tutorials", "qp", prog)] + opts
    env = dict(os.environ, PETSC_OPTIONS="", OMP_NUM_THREADS="1")
    t0 = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return None, "timeout after %d s" % timeout, time.time() - t0
    wall = time.time() - t0
    for line in p.stdout.splitlines():
        if line.startswith('{"bench"'):
            return json.loads(line), None, wall
    err = [l for l in (p.stdout + p.stderr).splitlines() if "Configure options" not in l]
    msg = next((l.split("PETSC ERROR:")[1].strip() for l in err if "PETSC ERROR:" in l and "----" not in l and l.split("PETSC ERROR:")[1].strip()), None)
    if msg is None:
        msg = (err[-1] if err else "no output") + " (exit %d)" % p.returncode
    return None, msg, wall


def bench_one(prog, base, label, opts, rtol, timeout, log, factors=FACTORS):
    """Runs a solver with factor 1, 0.1, ... until the measured |gP| meets the target."""
    best, note, cmd = None, None, None
    for f in factors:
        full = base + opts + ["-bench_rtol", "%g" % rtol, "-bench_own_factor", "%g" % f]
        rec, err, wall = run(prog, full, timeout)
        log.write(json.dumps({"label": label, "options": full, "record": rec, "error": err, "wall": wall}) + "\n")
        log.flush()
        if rec is None:  # keep the last run that finished, and say what the tighter one did
            note = err if best is None else "with factor %g: %s" % (f, err)
            break
        best, cmd = rec, " ".join(full)
        if rec["met"] or rec["reason"] not in CONVERGED or rec["solver"] in ("mprgp", "mpgp"):
            break
    if best is None:
        cmd = " ".join(full)
    return best, note, cmd


def fmt_row(label, rec, err, qref):
    if rec is None:
        return "| %s | - | - | - | - | - | **no** | - | - | %s |" % (label, ("no result: " if err.startswith("timeout") else "error: ") + err.replace("|", "/"))
    est = " (%d)" % rec["estimate_products"] if rec["estimate_products"] else ""
    gap = (rec["objective"] - qref) / abs(qref) if qref else float("nan")
    its = str(rec["iterations"]) + (" / %d" % rec["ksp_iterations"] if rec["ksp_iterations"] else "")
    src = {"counters": "", "log_matmult": "", "objective_gradient_calls": " f+g"}[rec["products_source"]]
    return "| %s | %s | %d%s%s | %.2f | %.2f | %.1e | %s | %g | %.0e | %s |" % (
        label, its, rec["hessian_products"], est, src, rec["cpu_time"], rec["time"], rec["gp_rel"], "yes" if rec["met"] else "**no**", rec["own_factor"], gap,
        rec["reason"] + ("; " + err.replace("|", "/") if err else ""))


def random_known(kind, solver, cond, matrix, old, timeout, seed=12345):
    """One run of tests/qp's qp_known_solution; returns (its, products or None, note, command)."""
    t = solver[4:]
    cmd = [os.path.join(ROOT, "build", "tests", "qp", "qp_known_solution"), "-kind", kind, "-solver", solver, "-cond", cond, "-units", "50", "-rtol", "1e-9", "-tol", "1",
           "-tao_max_it", "100000", "-matrix", matrix]
    if seed != 12345:
        cmd += ["-seed", str(seed)]
    if old:
        cmd += ["-tao_%s_pc_type" % t, "none", "-tao_%s_expansion_projcg" % t, "0", "-tao_%s_gamma" % t, "1"]
    env = dict(os.environ, PETSC_OPTIONS="", OMP_NUM_THREADS="1")
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return None, None, "timeout after %d s" % timeout, cmd
    m = re.search(r"its=(\d+) hessian_mults=(\d+)", p.stdout)
    if not m:
        err = re.search(r"PETSC ERROR: (TAO did not converge: \S+)", p.stdout + p.stderr)
        return None, None, err.group(1) if err else "exit %d" % p.returncode, cmd
    return int(m.group(1)), int(m.group(2)), "", cmd


def random_table(timeout, seeds, jobs):
    """Old against new defaults on the random QPs: the benchmark's seed (12345, tests/qp's) with the shell and the
    AIJ Hessian, and the AIJ Hessian over further seeds (the same layout and spectrum, another random matrix,
    solution and multipliers), whose spread says what a change on one seed is worth. A shell Hessian's defaults
    do not depend on the seed (they are the old ones), so only the AIJ rows are repeated."""
    from concurrent.futures import ThreadPoolExecutor
    extra = [s for s in seeds if s != 12345]
    runs = []
    for kind, solver, cond in RANDOM_CASES:
        for matrix in ("shell", "aij"):
            for seed in [12345] + (extra if matrix == "aij" else []):
                for old in (True, False):
                    runs.append((kind, solver, cond, matrix, old, seed))
    with ThreadPoolExecutor(max(1, jobs)) as ex:
        res = dict(zip(runs, ex.map(lambda r: random_known(r[0], r[1], r[2], r[3], r[4], timeout, r[5]), runs)))
    print("\n### random ill-conditioned QPs (tests/qp, qp_known_solution, 300 unknowns, |gP| <= 1e-9 |b|): old defaults against the defaults\n")
    print("Seed 12345 (tests/qp's) with both Hessians; the AIJ Hessian also over the seeds %s: the change per seed, and the spread of the\nold defaults' products over all %d seeds.\n" % (",".join(map(str, extra)) or "-", len(extra) + 1))
    print("| kind | solver | cond | Hessian | products, old defaults | products, defaults | change | change over the seeds: median (min .. max) | old defaults over the seeds (min .. max) |")
    print("|---|---|---|---|---|---|---|---|---|")
    cmds = []
    for kind, solver, cond in RANDOM_CASES:
        for matrix in ("shell", "aij"):
            r_old, r_new = res[(kind, solver, cond, matrix, True, 12345)], res[(kind, solver, cond, matrix, False, 12345)]
            cmds.append(" ".join(os.path.relpath(c, ROOT) if c.startswith(ROOT) else c for c in r_new[3]))
            a = "%d" % r_old[1] if r_old[1] is not None else r_old[2]
            b = "%d" % r_new[1] if r_new[1] is not None else r_new[2]
            ch = "%+.0f %%" % (100.0 * (r_new[1] - r_old[1]) / r_old[1]) if r_old[1] and r_new[1] is not None else "-"
            over, spread = "-", "-"
            if matrix == "aij" and extra:
                pairs = [(res[(kind, solver, cond, matrix, True, s)][1], res[(kind, solver, cond, matrix, False, s)][1]) for s in [12345] + extra]
                chs = sorted(100.0 * (n - o) / o for o, n in pairs if o and n is not None)
                olds = [o for o, _ in pairs if o]
                if chs:
                    over = "%+.0f %% (%+.0f .. %+.0f %%)%s" % (chs[len(chs) // 2], chs[0], chs[-1], "" if len(chs) == len(pairs) else ", %d failed" % (len(pairs) - len(chs)))
                if olds:
                    spread = "%d .. %d" % (min(olds), max(olds))
            print("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (kind, solver[4:], cond, matrix, a, b, ch, over, spread))
    print("\nCommands (the old defaults add -tao_<type>_pc_type none -tao_<type>_expansion_projcg 0 -tao_<type>_gamma 1; other seeds add -seed S):\n")
    for c in cmds:
        print("    " + c)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rtol", type=float, default=1e-6, help="target |gP| <= rtol |b| (default 1e-6)")
    ap.add_argument("--sizes", default="small,large")
    ap.add_argument("--problems", default="obstacle,bearing,disks")
    ap.add_argument("--timeout", type=int, default=180, help="seconds per run of mprgp/mpgp (a run that takes longer is reported as a timeout)")
    ap.add_argument("--tao-timeout", type=int, default=60, help="seconds per run of a TAO solver (keeps the whole benchmark under 15 minutes)")
    ap.add_argument("--quick", action="store_true", help="small sizes only")
    ap.add_argument("--defaults", action="store_true", help="the defaults chosen from the Hessian against the old defaults and TAO's bound solvers, and the random QPs of tests/qp")
    ap.add_argument("--seeds", default="12345,1,2,3,4,5,6", help="--defaults: seeds of the random QPs (12345 is tests/qp's; the others show the spread)")
    ap.add_argument("--jobs", type=int, default=2, help="--defaults: random QPs run at once (their product counts do not depend on the load)")
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "bench-qp"))
    args = ap.parse_args()
    sizes = ["small"] if args.quick else args.sizes.split(",")
    os.makedirs(args.out, exist_ok=True)
    t_start = time.time()
    with open(os.path.join(args.out, "results.jsonl"), "w") as log:
        print("QP benchmark: target |gP| <= %g |b|, measured by the programs; %s, %d cores, %s" % (args.rtol, platform.node(), os.cpu_count(), time.strftime("%Y-%m-%d %H:%M")))
        print("Load average at start: %.2f %.2f %.2f" % os.getloadavg())
        table = PROBLEMS_DEFAULTS if args.defaults else PROBLEMS
        for pname in [p for p in args.problems.split(",") if p]:
            prog, base0, solvers, sz = table[pname]
            for size in sizes:
                nopt, repeat = sz[size]
                base = base0 + ["-n", nopt, "-bench_repeat", str(repeat)]
                rows = []
                for entry in solvers:
                    label, opts, extra = entry if len(entry) == 3 else entry + ({},)
                    if size not in extra.get("sizes", [size]):
                        continue
                    limit = args.timeout if label.startswith("mp") else args.tao_timeout
                    rec, err, cmd = bench_one(prog, base, label, opts, args.rtol, min(limit, extra.get("timeout", limit)), log, extra.get("factors", FACTORS))
                    rows.append((label, rec, err, cmd))
                    sys.stderr.write("  %s %s %s: %s\n" % (pname, size, label, "error " + err if rec is None else "%d products, %.2f s CPU, %.2f s wall, met %s" % (rec["hessian_products"], rec["cpu_time"], rec["time"], rec["met"])))
                met = [r for _, r, _, _ in rows if r and r["met"]]
                qref = min(r["objective"] for r in met) if met else None
                n = next((r["n"] for _, r, _, _ in rows if r), 0)
                print("\n### %s, n = %d unknowns (%s -n %s, times: best of %d solve%s)\n" % (pname, n, prog, nopt, repeat, "s" if repeat > 1 else ""))
                sys.stdout.flush()
                print("| solver | iterations (/ inner KSP) | Hessian products (norm estimate) | CPU time [s] | wall time [s] | final \\|gP\\|/\\|b\\| | target met | own tol factor | objective gap | reason |")
                print("|---|---|---|---|---|---|---|---|---|---|")
                for label, rec, err, _ in rows:
                    print(fmt_row(label, rec, err, qref))
                tao = [(r["hessian_products"], label) for label, r, _, _ in rows if r and r["met"] and label.split(",")[0] in TAO_BOUND_SOLVERS]
                ours = [(r["hessian_products"], label.split(" ")[0]) for label, r, _, _ in rows if r and r["met"] and "(defaults" in label]
                if args.defaults and ours:
                    best = "TAO's fewest: %d (%s)" % min(tao) if tao else "no TAO solver in this table"
                    print("\nDefaults: %s; %s." % (", ".join("%s %d" % (n, p) for p, n in ours), best))
                print("\nCommands (build/tutorials/qp/...):\n")
                for label, rec, err, cmd in rows:
                    print("    %s %s" % (prog, cmd))
        if args.defaults:
            random_table(args.timeout, [int(x) for x in args.seeds.split(",")], args.jobs)
        print("\nTotal wall time of the benchmark: %.0f s" % (time.time() - t_start))


if __name__ == "__main__":
    main()
