"""The environment the benchmark scripts run the brick in: one OpenMP/BLAS thread and, unless turned off,
transparent huge pages for glibc's large allocations (GLIBC_TUNABLES=glibc.malloc.hugetlb=1, glibc >= 2.35).

Why: most of the brick's setup time is first-touch page faults on large, short-lived blocks (MUMPS
fronts and the Schur complement that becomes (K+)_bb); with 2 MB pages there are 512 times fewer.
Results (Iter, n_A, residuals) are bitwise the same either way; only time changes. docs/brick-ablations.md ("Huge pages")
shows both.
"""
import os

TUNABLE = "glibc.malloc.hugetlb=1"


def environment(hugepages=True):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    tunables = env.get("GLIBC_TUNABLES", "")
    if hugepages and "glibc.malloc.hugetlb" not in tunables:
        env["GLIBC_TUNABLES"] = tunables + ":" + TUNABLE if tunables else TUNABLE
    return env


def describe(hugepages=True):
    return "transparent huge pages (GLIBC_TUNABLES=%s)" % TUNABLE if hugepages else "4 KB pages (--hugepages 0)"
