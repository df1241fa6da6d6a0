#!/usr/bin/python3
"""The preconditioner of the contact QP's FETI dual (-contact_pc_type none, lumped, dirichlet) on a family of scenes.

For each scene and each preconditioner the conefeti driver runs once under /usr/bin/time with -log_view; the table
gives Iter, n_A (F products of the inner solves), the preconditioner's applications and seconds (the FETIPCApply
event: count and max time over the ranks), the F products' seconds and count (FETI_MultF, with the norm estimate's
and the residual's), the coarse solves of the whole run (FETICoarseSolve: the projectors of the Hessian products,
of the preconditioner and of the outer loop), the solve's wall seconds, the program's CPU seconds (user + system of
every rank) and the largest mechanical residual. Counts and residuals do
not depend on the machine; times do (a shared machine: compare CPU seconds and ratios within one run).

usage: scripts/bench-dualpc.py [--scenes brick:1,2,3] [--pcs none,lumped,dirichlet] [--extra "-opt v ..."]
                               [--meshes DIR] [--ranks 1] [--build build]
  --scenes  a comma list of NAME:p (the brick family at H/h = 6: -scene_refine 6p -scene_body0_subdomains 3p,p,p,
            with -feti_kplus_explicit 0 from p = 4) where NAME is brick (Coulomb F = 0.3) or brick-frictionless, or
            NAME alone for an options file petsc-options/NAME.opts as it is (twobodies, hertz, ...)
  --pcs     the -contact_pc_type values to compare; NAME+projcg: with the projected CG expansion of the inner
            solvers (mpgp and mprgp: -contact_tao_smalxe_subsolver_tao_mpgp_expansion_projcg ...)
  --extra   options for every run
  --meshes  a directory with the Gmsh meshes the options files name (-scene_bodyK_mesh X becomes DIR/basename(X));
            make them with gmsh -3 meshes/NAME.geo -o DIR/NAME.msh (hemisphere, pair-hemisphere, pair-block, block-hole)
Prints a markdown table.
"""
import argparse, json, os, re, subprocess, sys

import hugepages
import logview

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def scene_options(spec, meshes=None):
    name, _, p = spec.partition(":")
    opts = ["-options_file", os.path.join(ROOT, "petsc-options", name + ".opts")]
    if meshes:
        with open(opts[1]) as f:
            for key, value in re.findall(r"^\s*(-scene_body\d+_mesh)\s+(\S+)", f.read(), re.M):
                opts += [key, os.path.join(meshes, os.path.basename(value))]
    if p:
        p = int(p)
        opts += ["-scene_refine", str(6 * p), "-scene_body0_subdomains", "%d,%d,%d" % (3 * p, p, p)]
        if p >= 4:
            opts += ["-feti_kplus_explicit", "0"]  # the explicit blocks take 1.6 GB at p = 4 (docs/scale.md)
    return opts


def run(build, ranks, opts, env):
    cmd = ["/usr/bin/time", "-f", "bench-dualpc-cpu %U %S", os.path.join(build, "conefeti")] + opts + ["-summary_table", "0", "-log_view"]
    if ranks > 1:
        cmd = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks)] + cmd
    out = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT)
    line = next((l for l in out.stdout.splitlines() if l.startswith('{"conefeti":')), None)
    if out.returncode not in (0, 2) or line is None:
        sys.exit("bench-dualpc: failed (%s):\n%s" % (" ".join(cmd), (out.stdout + out.stderr)[-3000:]))
    j = json.loads(line)
    j["cpu"] = sum(float(u) + float(s) for u, s in re.findall(r"bench-dualpc-cpu ([\d.]+) ([\d.]+)", out.stderr))
    j["events"] = logview.events(out.stdout)
    j["rc"] = out.returncode
    return j


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default="brick:1,brick:2,brick:3")
    ap.add_argument("--pcs", default="none,lumped,dirichlet")
    ap.add_argument("--extra", default="")
    ap.add_argument("--meshes", default=None)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--build", default="build")
    a = ap.parse_args()
    env = hugepages.environment(True)
    print("Command: `scripts/bench-dualpc.py %s` (%d rank%s; CPU: user + system seconds of the whole program)" % (" ".join(sys.argv[1:]), a.ranks, "s" if a.ranks > 1 else ""))
    print()
    print("| scene | n | -contact_pc_type | Iter | n_A | PC applications | PC [s] | F products [s] | coarse solves | solve [s] | CPU [s] | max residual | converged |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    projcg = ["-contact_tao_smalxe_subsolver_tao_mpgp_expansion_projcg", "-contact_tao_smalxe_subsolver_tao_mprgp_expansion_projcg"]
    for spec in a.scenes.split(","):
        for pc in a.pcs.split(","):
            name, plus, _ = pc.partition("+projcg")
            j = run(a.build, a.ranks, scene_options(spec, a.meshes) + ["-contact_pc_type", name] + (projcg if plus else []) + a.extra.split(), env)
            pcn, pct = j["events"].get("FETIPCApply", (0, 0.0))
            fn, ft = j["events"].get("FETI_MultF", (0, 0.0))
            cn, _ = j["events"].get("FETICoarseSolve", (0, 0.0))
            print("| %s | %d | %s | %d | %d | %d | %.2f | %.2f (%d) | %d | %.2f | %.1f | %.1e | %s |" %
                  (spec, j["n"], pc, j["iter"], j["n_A"], pcn, pct, ft, fn, cn, j["time_solve"], j["cpu"], j["residuals"]["max"],
                   "yes" if j["converged"] and j["rc"] == 0 else "NO"),
                  flush=True)


if __name__ == "__main__":
    main()
