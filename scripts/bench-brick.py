#!/usr/bin/python3
"""The seed paper's Tables 1 and 2 side by side with ours: the brick with Coulomb friction.

Runs the conefeti program on petsc-options/brick.opts (-scene_refine k) for the paper's mesh sizes and both friction
coefficients and prints, per size: n, m, Iter, n_A (= QPP + QPQ + other) and the solve time, next to
the paper's Iter and n_A. Iter and n_A are machine independent; times are this machine's.

usage: scripts/bench-brick.py [--algorithms monolithic,merged,msa] [--sizes 4,6,8,10,12] [--rtol 1e-4]
                              [--extra "-option value ..."] [--build build] [--hugepages 1]
"""
import argparse, sys

import hugepages
from seedpaper import PAPER, run


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--algorithms", default="monolithic,merged,msa")
    ap.add_argument("--sizes", default="4,6,8,10,12")
    ap.add_argument("--frictions", default="0.1,0.3")
    ap.add_argument("--rtol", default="1e-4")
    ap.add_argument("--extra", default="")
    ap.add_argument("--build", default="build")
    ap.add_argument("--hugepages", type=int, default=1, help="1: run with transparent huge pages (scripts/hugepages.py), 0: without")
    a = ap.parse_args()
    extra = a.extra.split()
    env = hugepages.environment(a.hugepages)
    print("# brick with Coulomb friction: paper (Matlab 7, Pentium 4) vs conefeti (this machine, 1 core, %s)" % hugepages.describe(a.hugepages))
    print("# command: %s" % " ".join(sys.argv))
    print("# stopping: projected gradient and |G l - e| relative to |h| <= %s; Coulomb fixed point to the same tolerance" % a.rtol)
    for F in [float(x) for x in a.frictions.split(",")]:
        for alg in a.algorithms.split(","):
            print()
            print("F = %g, algorithm %s" % (F, alg))
            print("| n | m (paper) | m | Iter (paper) | Iter | n_A (paper) | n_A = QPP + QPQ + other | time (paper) | setup + solve | separated/stick/slip |")
            print("|---|---|---|---|---|---|---|---|---|---|")
            first = None
            for k in [int(x) for x in a.sizes.split(",")]:
                r = run(a.build, k, F, a.rtol, extra, env, alg)
                pm, pf = PAPER.get(r["n"], (None, {}))
                pi, pa, pt = pf.get(F, ("-", "-", "-"))
                first = first or r["nA"]
                print("| %d | %s | %d | %s | %s | %s | %d = %d + %d + %d | %s s | %.2f + %.2f s | %d/%d/%d |" % (
                    r["n"], pm if pm else "-", r["m"], pi, "%d" % r["iter"] if r["converged"] else "%d (not converged)" % r["iter"], pa, r["nA"], r["qpp"], r["qpq"], r["other"], pt, r["setup"], r["solve"], *r["nodes"]))
            print("growth of n_A from the smallest to the largest size: %.2fx" % (r["nA"] / first))

if __name__ == "__main__":
    main()
