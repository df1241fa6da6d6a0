#!/usr/bin/python3
"""FETI benchmark: prints the Markdown tables of docs/feti-benchmark.md.

usage: scripts/bench-feti.py [--build build] [--ranks 2] [--quick] [--parts factor,scaling,compare,memory] [--hugepages 1]

  factor   sparse Cholesky of one subdomain (petsc / cholmod / mumps) on 1e3 - 1e5 dofs: factorization
           time, time of one K+ application (two triangular solves), peak memory; 1 rank
  scaling  weak scaling of FETI at fixed H/h on the clamped cube (tutorials/feti/ex2_elasticity.cxx):
           setup time, time per F product, CG iterations, peak RSS per primal unknown, up to > 1M unknowns
  compare  FETI against CG + GAMG (rigid-body near-null space) and a direct MUMPS Cholesky on the same
           mesh, and the time ratios
  memory   where the peak RSS goes at about 1M primal unknowns for H/h = 4, 6, 8 (PETSc's -log_view_memory:
           resident memory added inside each setup event, summed over ranks)

Every number is the RESULT line of one run of feti_ex2_elasticity (best of --repeat runs for times)."""
import argparse
import os
import re
import subprocess
import sys

import hugepages

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1",
           OMPI_MCA_btl_vader_single_copy_mechanism="none", OMPI_MCA_btl="self,vader", OMPI_MCA_pml="ob1", PETSC_OPTIONS="")


def run(exe, ranks, args, repeat=1, timeout=3600):
    """Run the driver; return the RESULT dictionary with the best times of `repeat` runs, or None on failure."""
    best = None
    for _ in range(repeat):
        cmd = ["mpiexec", "-n", str(ranks), exe] + args
        try:
            out = subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=timeout).stdout
        except subprocess.TimeoutExpired:
            return None
        m = re.search(r"^RESULT (.*)$", out, re.M)
        if not m:
            sys.stderr.write("failed: %s\n%s\n" % (" ".join(cmd), out[-2000:]))
            return None
        r = {k: (float(v) if re.match(r"^-?[0-9.e+-]+$", v) else v) for k, v in (kv.split("=") for kv in m.group(1).split())}
        if r.get("converged") == "false":  # its counts and times would read as a result
            sys.stderr.write("not converged: %s\n%s\n" % (" ".join(cmd), out[-2000:]))
            return None
        if best is None:
            best = r
        else:
            for k in ("setup", "solve", "Fproduct", "factor", "Kplus"):
                best[k] = min(best[k], r[k])
    return best


def factor_table(exe, repeat):
    print("### Sparse Cholesky of one subdomain (1 rank)\n")
    print("One clamped cube of m^3 cells as a single floating subdomain (Total FETI); factorization of the regularized")
    print("K_s (symbolic + numeric), one K+ application, peak RSS of the whole run.\n")
    print("| dofs | solver | factorization [s] | K+ application [ms] | peak RSS [MB] |")
    print("|---:|---|---:|---:|---:|")
    for m in (6, 14, 22, 31):
        for solver in ("cholmod", "mumps", "petsc"):
            if solver == "petsc" and m > 22:
                print("| %d | petsc | not run: natural ordering only (bandwidth fill), estimated > 10 min | | |" % (3 * (m + 1) ** 3))
                continue
            r = run(exe, 1, ["-cells", str(m), "-fem_subdomains", "1,1,1", "-feti_pc_type", "none", "-feti_ksp_max_it", "5",
                             "-feti_sub_pc_factor_mat_solver_type", solver], repeat)
            if r is None:
                print("| %d | %s | failed | | |" % (3 * (m + 1) ** 3, solver))
                continue
            print("| %d | %s | %.3f | %.2f | %.0f |" % (r["primal"], solver, r["factor"], 1e3 * r["Kplus"], r["rss"] / 2**20))
    print()


def scaling_table(exe, ranks, repeat, quick):
    print("### Weak scaling at fixed H/h (%d ranks)\n" % ranks)
    print("Clamped cube of n^3 cells cut into p^3 cubic subdomains of H/h = n/p cells per side; Total FETI, CHOLMOD,")
    print("CG to relative residual 1e-8 (unpreconditioned, i.e. the projected gradient). Setup = mesh, assembly, kernels,")
    print("factorizations, coarse problem (the Dirichlet preconditioner's factorizations are in the solve).\n")
    print("| H/h | preconditioner | subdomains | primal unknowns | dual | coarse | CG iterations | setup [s] | solve [s] | F product [ms] | K+ [ms] | peak RSS [MB] | RSS / primal unknown [B] |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    configs = [(8, 2, "dirichlet"), (8, 3, "dirichlet"), (8, 4, "dirichlet"), (8, 6, "dirichlet"), (8, 8, "dirichlet"), (8, 4, "lumped"), (8, 8, "lumped"),
               (12, 2, "dirichlet"), (12, 3, "dirichlet"), (12, 4, "dirichlet"), (12, 6, "dirichlet"), (12, 6, "lumped")]
    if quick:
        configs = [(8, 2, "dirichlet"), (8, 3, "dirichlet"), (8, 3, "lumped"), (12, 2, "dirichlet")]
    for m, p, pc in configs:
        r = run(exe, ranks, ["-cells", str(m * p), "-fem_subdomains", "%d,%d,%d" % (p, p, p), "-feti_pc_type", pc], repeat)
        if r is None:
            print("| %d | %s | %d | failed | | | | | | | | | |" % (m, pc, p ** 3))
            continue
        print("| %d | %s | %d | %d | %d | %d | %d | %.2f | %.2f | %.2f | %.2f | %.0f | %.0f |" % (m, pc, r["subdomains"], r["primal"], r["dual"], r["coarse"], r["iterations"], r["setup"], r["solve"],
                                                                                      1e3 * r["Fproduct"], 1e3 * r["Kplus"], r["rss"] / 2**20, r["rss"] / r["primal"]))
    print()


def compare_table(exe, ranks, repeat, quick):
    print("### FETI against single-domain PETSc solvers on the same mesh (%d ranks)\n" % ranks)
    print("Same cube and loads; GAMG: CG + GAMG with the rigid-body near-null space to 1e-8; Cholesky: MUMPS. Total = setup + solve;")
    print("ratio = other solver's total / FETI's total (> 1: FETI faster).\n")
    print("| cells | unknowns | solver | iterations | setup [s] | solve [s] | total [s] | ratio | peak RSS [MB] |")
    print("|---:|---:|---|---:|---:|---:|---:|---:|---:|")
    sizes = [(24, 3), (48, 6), (72, 6)] if not quick else [(24, 3)]
    for n, p in sizes:
        feti = run(exe, ranks, ["-cells", str(n), "-fem_subdomains", "%d,%d,%d" % (p, p, p)], repeat)
        rows = [("feti (%d subdomains)" % (p ** 3), feti)]
        # the global matrix is assembled by the ranks' subdomains, so the same decomposition distributes it
        decomposition = ["-fem_subdomains", "%d,%d,%d" % (p, p, p)]
        rows.append(("gamg", run(exe, ranks, ["-cells", str(n), "-solver", "gamg"] + decomposition, repeat)))
        if n <= 48:
            rows.append(("cholesky", run(exe, ranks, ["-cells", str(n), "-solver", "cholesky"] + decomposition, 1)))
        ftotal = feti["setup"] + feti["solve"] if feti else None
        for name, r in rows:
            if r is None:
                print("| %d | | %s | failed | | | | | |" % (n, name))
                continue
            total = r["setup"] + r["solve"]
            print("| %d | %d | %s | %d | %.2f | %.2f | %.2f | %s | %.0f |" % (n, r["unknowns"], name, r["iterations"], r["setup"], r["solve"], total,
                                                                          "%.2f" % (total / ftotal) if ftotal else "", r["rss"] / 2**20))
        if n > 48:
            print("| %d | %d | cholesky | not run: MUMPS fill on 1M 3D unknowns exceeds the time budget of this script | | | | | |" % (n, 3 * (n + 1) ** 3))
    print()


def memory_events(exe, ranks, args):
    """Run once with -log_view_memory; return the RESULT dictionary and the resident memory [bytes] each
    event added (last column, summed over ranks and calls), or None on failure."""
    cmd = ["mpiexec", "-n", str(ranks), exe] + args + ["-log_view", "-log_view_memory"]
    out = subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=3600).stdout
    m = re.search(r"^RESULT (.*)$", out, re.M)
    if not m:
        sys.stderr.write("failed: %s\n%s\n" % (" ".join(cmd), out[-2000:]))
        return None
    r = {k: (float(v) if re.match(r"^-?[0-9.e+-]+$", v) else v) for k, v in (kv.split("=") for kv in m.group(1).split())}
    rmi = {}
    for line in out.splitlines():
        f = line.split()
        if len(f) > 20 and f[0] in ("FEMSetUp", "FEMDecompose", "FEMAssembly", "FETISetUp", "FETIAssembly", "FETIFactor"):
            rmi[f[0]] = float(f[-1]) * 1e6  # PETSc prints decimal megabytes
    return r, rmi


def memory_table(exe, ranks, quick):
    print("### Where the memory goes (%d ranks, lumped preconditioner)\n" % ranks)
    print("Resident memory each setup stage added (PETSc's `-log_view_memory`, summed over the ranks), in bytes per primal")
    print("unknown. Mesh = the boxes and the decomposition; K_s, f_s = subdomain assembly (SBAIJ); FETI operators = global")
    print("load, R, the arrays of the B and B' products, and the transient G' and G G' (assembled before the factorizations,")
    print("whose allocations then reuse that memory); factors = the subdomain Cholesky factorizations (CHOLMOD) and the")
    print("coarse one (on rank 0); other FETI setup = kernels, fixing dofs, work vectors; rest = MPI and PETSc start-up, the")
    print("preconditioner's index sets, the solve's vectors and allocator slack (peak RSS minus the stages). CG to 1e-8; the")
    print("times are of the same run (with -log_view_memory on, on a machine with two cores).\n")
    print("| H/h | subdomains | primal unknowns | mesh | K_s, f_s | FETI operators | factors | other FETI setup | rest | peak RSS / primal unknown [B] | CG iterations | setup [s] | solve [s] |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    configs = [(4, 14), (6, 10), (8, 8)] if not quick else [(4, 4), (8, 2)]
    for m, p in configs:
        res = memory_events(exe, ranks, ["-cells", str(m * p), "-fem_subdomains", "%d,%d,%d" % (p, p, p), "-feti_pc_type", "lumped"])
        if res is None:
            print("| %d | %d | failed | | | | | | | | | | |" % (m, p ** 3))
            continue
        r, e = res
        n = r["primal"]
        mesh = e.get("FEMSetUp", 0) + e.get("FEMDecompose", 0)
        assembly = e.get("FEMAssembly", 0)
        operators = e.get("FETIAssembly", 0)
        factors = e.get("FETIFactor", 0)
        other = e.get("FETISetUp", 0) - operators - factors
        rest = r["rss"] - mesh - assembly - e.get("FETISetUp", 0)
        print("| %d | %d | %d | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %d | %.2f | %.2f |" % (m, r["subdomains"], n, mesh / n, assembly / n, operators / n, factors / n, other / n, rest / n,
                                                                                   r["rss"] / n, r["iterations"], r["setup"], r["solve"]))
    print()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build"))
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="small sizes only (a smoke test of the script)")
    ap.add_argument("--parts", default="factor,scaling,compare,memory")
    ap.add_argument("--hugepages", type=int, default=1, help="1: run with transparent huge pages (scripts/hugepages.py), 0: without")
    a = ap.parse_args()
    ENV.update({k: v for k, v in hugepages.environment(a.hugepages).items() if k in ("OMP_NUM_THREADS", "GLIBC_TUNABLES")})
    exe = os.path.join(a.build, "tutorials", "feti", "feti_ex2_elasticity")
    if not os.path.exists(exe):
        sys.exit("no %s: build first (scripts/build.sh)" % exe)
    cpu = subprocess.run(["sh", "-c", "grep -m1 'model name' /proc/cpuinfo | cut -d: -f2"], capture_output=True, text=True).stdout.strip()
    print("Machine: %s, %d cores, %s; command: scripts/bench-feti.py %s\n" % (cpu, os.cpu_count(), hugepages.describe(a.hugepages), " ".join(sys.argv[1:])))
    parts = a.parts.split(",")
    if "factor" in parts:
        factor_table(exe, a.repeat)
    if "scaling" in parts:
        scaling_table(exe, a.ranks, a.repeat, a.quick)
    if "compare" in parts:
        compare_table(exe, a.ranks, a.repeat, a.quick)
    if "memory" in parts:
        memory_table(exe, a.ranks, a.quick)


if __name__ == "__main__":
    main()
