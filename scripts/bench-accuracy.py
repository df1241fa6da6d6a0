#!/usr/bin/python3
"""What accuracy costs: the seed paper's brick with Coulomb friction solved to a range of tolerances.

For each friction coefficient and mesh size, runs the conefeti program on petsc-options/brick.opts with
-contact_rtol from loose to tight and prints, per tolerance: outer iterations, F products (n_A), setup and
solve time, the mechanical residuals (docs/contact.md, "Judging a solution") of its JSON line, computed from u and
lambda (not from the solver), and the separated/stick/slip node counts. Iter, n_A and the residuals are
machine independent; times are this machine's.

With --check it also asserts what the tables are meant to show, and exits 1 otherwise: every run
converges, the largest mechanical residual is at most 10 * rtol, and it falls as the tolerance tightens.

usage: scripts/bench-accuracy.py [--sizes 8,12] [--frictions 0.1,0.3] [--rtols 1e-2,...,1e-8]
                                 [--algorithm monolithic] [--extra "-option value ..."] [--build build] [--hugepages 1] [--check]
"""
import argparse, sys

import hugepages
from seedpaper import RESIDUALS, run


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", default="8,12", help="-scene_refine values (8: n = 5832, 12: n = 18252)")
    ap.add_argument("--frictions", default="0.1,0.3")
    ap.add_argument("--rtols", default="1e-2,1e-3,1e-4,1e-5,1e-6,1e-7,1e-8")
    ap.add_argument("--algorithm", default="monolithic")
    ap.add_argument("--extra", default="")
    ap.add_argument("--build", default="build")
    ap.add_argument("--hugepages", type=int, default=1, help="1: run with transparent huge pages (scripts/hugepages.py), 0: without")
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    rtols = [float(x) for x in a.rtols.split(",")]
    env = hugepages.environment(a.hugepages)
    failures = []
    print("# what accuracy costs: brick with Coulomb friction, algorithm %s, this machine (1 core, %s)" % (a.algorithm, hugepages.describe(a.hugepages)))
    print("# command: %s" % " ".join(sys.argv))
    print("# residuals: relative, computed by conefeti from u and lambda (docs/contact.md, Judging a solution); max = the largest of them")
    for F in [float(x) for x in a.frictions.split(",")]:
        for k in [int(x) for x in a.sizes.split(",")]:
            rows = [(rtol, run(a.build, k, F, rtol, a.extra.split(), env, a.algorithm)) for rtol in rtols]
            print()
            print("F = %g, n = %d" % (F, rows[0][1]["n"]))
            print("| -contact_rtol | Iter | n_A | n_A / loosest | setup + solve [s] | max residual | " + " | ".join(RESIDUALS) + " | separated/stick/slip |")
            print("|" + "---|" * (7 + len(RESIDUALS)))
            prev = None
            for rtol, r in rows:
                mx = max(r["res"])
                print("| %.0e | %d | %d | %.1f | %.2f + %.2f | %.1e | %s | %d/%d/%d |" % (
                    rtol, r["iter"], r["nA"], r["nA"] / rows[0][1]["nA"], r["setup"], r["solve"], mx,
                    " | ".join("%.1e" % v for v in r["res"]), *r["nodes"]))
                where = "F = %g, n = %d, rtol %.0e" % (F, r["n"], rtol)
                if not r["converged"]:
                    failures.append("%s: not converged" % where)
                if mx > 10 * rtol:
                    failures.append("%s: max residual %.1e > 10 rtol" % (where, mx))
                if prev is not None and mx >= prev:
                    failures.append("%s: max residual %.1e did not fall (previous tolerance: %.1e)" % (where, mx, prev))
                prev = mx
    if a.check:
        for f in failures:
            print("CHECK FAILED: " + f)
        print("check: %s" % ("passed" if not failures else "%d failure(s)" % len(failures)))
        sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
