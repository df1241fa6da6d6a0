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

Usage:  scripts/bench-qp.sh [--quick] [--out DIR] [--sizes small,large] [--problems obstacle,bearing,disks]
                           [--rtol 1e-6] [--timeout 180] [--tao-timeout 60]
Prints markdown tables; the raw JSON lines go to DIR/results.jsonl (default build/bench-qp).
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# (label, program options); labels name the solver and any non-default options
BOUND_SOLVERS = [
    ("mprgp", ["-tao_type", "mprgp"]),
    ("mpgp", ["-tao_type", "mpgp"]),
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
    ("mprgp, -tao_mprgp_alpha 1", ["-tao_type", "mprgp", "-tao_mprgp_alpha", "1"]),
    # the projected CG expansion, preconditioning in face with ICC(0) (the counterpart of gpcg's ILU(0)),
    # and both with Gamma = 2 (fewer proportioning steps: the preconditioned CG steps make more progress)
    ("mprgp, -tao_mprgp_expansion_projcg", ["-tao_type", "mprgp", "-tao_mprgp_expansion_projcg"]),
    ("mprgp, -tao_mprgp_pc_type icc", ["-tao_type", "mprgp", "-tao_mprgp_pc_type", "icc"]),
    ("mprgp, -tao_mprgp_pc_type icc -tao_mprgp_expansion_projcg -tao_mprgp_gamma 2",
     ["-tao_type", "mprgp", "-tao_mprgp_pc_type", "icc", "-tao_mprgp_expansion_projcg", "-tao_mprgp_gamma", "2"]),
    ("mpgp, -tao_mpgp_pc_type icc -tao_mpgp_expansion_projcg -tao_mpgp_gamma 2",
     ["-tao_type", "mpgp", "-tao_mpgp_pc_type", "icc", "-tao_mpgp_expansion_projcg", "-tao_mpgp_gamma", "2"]),
]
DISK_SOLVERS = [
    ("mpgp", ["-tao_type", "mpgp"]),
    # Kucera's MPGP as published: no arc steps (on by default since they cut the products on the disks and the brick)
    ("mpgp, -tao_mpgp_arc 0", ["-tao_type", "mpgp", "-tao_mpgp_arc", "0"]),
    # the default takes fixed steps 1.95/||A|| in its gradient projections; BB lengths and the shorter
    # 1/||A|| are options (BB is off by default: it did not pay on the contact problems)
    ("mpgp, -tao_mpgp_bb 1", ["-tao_type", "mpgp", "-tao_mpgp_bb", "1"]),
    ("mpgp, -tao_mpgp_alpha 1", ["-tao_type", "mpgp", "-tao_mpgp_alpha", "1"]),
    ("mpgp, -tao_mpgp_bb 1 -tao_mpgp_alpha 1", ["-tao_type", "mpgp", "-tao_mpgp_bb", "1", "-tao_mpgp_alpha", "1"]),
    ("mpgp, -tao_mpgp_bb 1 -tao_mpgp_alpha 1 -tao_mpgp_expansion_projcg", ["-tao_type", "mpgp", "-tao_mpgp_bb", "1", "-tao_mpgp_alpha", "1", "-tao_mpgp_expansion_projcg"]),
    ("almm", ["-tao_type", "almm"], {"factors": [1.0, 1e-2, 1e-4]}),
    ("almm, -tao_almm_type classic", ["-tao_type", "almm", "-tao_almm_type", "classic"], {"timeout": 30, "sizes": ["small"]}),  # stalls
    ("pdipm", ["-tao_type", "pdipm", "-mat_mumps_icntl_14", "200"]),
]
PROBLEMS = {
    # name: (program, extra options, solvers, {size: (n option, repeat)})
    "obstacle": ("obstacle", ["-problem", "obstacle"], BOUND_SOLVERS, {"small": ("99", 3), "large": ("319", 1)}),
    "bearing": ("obstacle", ["-problem", "bearing"], BOUND_SOLVERS, {"small": ("99", 3), "large": ("319", 1)}),
    "disks": ("disks", [], DISK_SOLVERS, {"small": ("70", 3), "large": ("224", 1)}),
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


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rtol", type=float, default=1e-6, help="target |gP| <= rtol |b| (default 1e-6)")
    ap.add_argument("--sizes", default="small,large")
    ap.add_argument("--problems", default="obstacle,bearing,disks")
    ap.add_argument("--timeout", type=int, default=180, help="seconds per run of mprgp/mpgp (a run that takes longer is reported as a timeout)")
    ap.add_argument("--tao-timeout", type=int, default=60, help="seconds per run of a TAO solver (keeps the whole benchmark under 15 minutes)")
    ap.add_argument("--quick", action="store_true", help="small sizes only")
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "bench-qp"))
    args = ap.parse_args()
    sizes = ["small"] if args.quick else args.sizes.split(",")
    os.makedirs(args.out, exist_ok=True)
    t_start = time.time()
    with open(os.path.join(args.out, "results.jsonl"), "w") as log:
        print("QP benchmark: target |gP| <= %g |b|, measured by the programs; %s, %d cores, %s" % (args.rtol, platform.node(), os.cpu_count(), time.strftime("%Y-%m-%d %H:%M")))
        print("Load average at start: %.2f %.2f %.2f" % os.getloadavg())
        for pname in args.problems.split(","):
            prog, base0, solvers, sz = PROBLEMS[pname]
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
                print("\nCommands (build/tutorials/qp/...):\n")
                for label, rec, err, cmd in rows:
                    print("    %s %s" % (prog, cmd))
        print("\nTotal wall time of the benchmark: %.0f s" % (time.time() - t_start))


if __name__ == "__main__":
    main()
