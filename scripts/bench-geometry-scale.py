#!/usr/bin/python3
"""Scale on real geometry: the graded Hertz indentation (meshes/indentation.geo, a Gmsh mesh decomposed by
METIS) at 10^5 unknowns on 1 and 2 ranks, beside the paper's brick of about the same size with the same
number of subdomains: n, subdomains, Iter, n_A, setup and solve time, peak memory (the sum over the ranks
of each process's largest resident set, from GNU time) and memory per unknown.

    scripts/bench-geometry-scale.py [--h 0.007] [--subdomains 48] [--ranks 1,2] [--write docs/validation.md]

Times are this machine's and vary with its load (2 shared cores): compare them within one run only; the
counts and the memory do not depend on the load."""
import argparse
import importlib.util
import json
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
spec = importlib.util.spec_from_file_location("hertz", os.path.join(ROOT, "scripts", "bench-hertz.py"))
hertz = importlib.util.module_from_spec(spec)
spec.loader.exec_module(hertz)


def run(build, opts, ranks, tmp, tag):
    """one run of the conefeti program: its JSON summary and the peak memory summed over the ranks [bytes]"""
    js = os.path.join(tmp, tag + ".json")
    mem = os.path.join(tmp, tag + ".mem")
    cmd = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks), "/usr/bin/time", "-f", "maxrss %M", "-a", "-o", mem,
           os.path.join(build, "conefeti")] + opts + ["-summary_json", js, "-summary_table", "0", "-options_left", "0"]
    if os.path.exists(mem):
        os.remove(mem)
    t0 = time.time()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if proc.returncode != 0:
        sys.exit("bench-geometry-scale.py: %s failed (exit %d):\n%s" % (" ".join(cmd), proc.returncode, proc.stdout[-3000:]))
    with open(js) as f:
        j = json.loads(f.readline())
    with open(mem) as f:
        kb = sum(int(m) for m in re.findall(r"maxrss (\d+)", f.read()))
    j["memory"] = kb * 1024.0
    j["wall"] = time.time() - t0
    return j


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--h", type=float, default=0.007, help="mesh size at the contact of the graded block")
    ap.add_argument("--subdomains", type=int, default=48, help="METIS subdomains of both scenes")
    ap.add_argument("--brick-refine", type=int, default=22, help="-scene_refine of the brick (22: n = 104742)")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--build", default="build")
    ap.add_argument("--write", default=None, help="replace the table in this file (between its bench-geometry-scale markers)")
    args = ap.parse_args()
    build = os.path.join(ROOT, args.build) if not os.path.isabs(args.build) else args.build
    ranks = [int(r) for r in args.ranks.split(",")]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        indentation, _ = hertz.options("indentation", args.h, tmp, args.subdomains)
        brick = ["-options_file", os.path.join(ROOT, "petsc-options", "brick.opts"), "-scene_refine", str(args.brick_refine),
                 "-scene_body0_decomposition", "metis", "-scene_body0_subdomains", str(args.subdomains)]
        scenes = [("graded indentation, frictionless (Gmsh, h = %g)" % args.h, indentation), ("brick, Coulomb F = 0.3 (box)", brick)]
        for r in ranks:  # interleaved: the two scenes side by side on each rank count
            for k, (name, opts) in enumerate(scenes):
                j = run(build, opts, r, tmp, "s%d-r%d" % (k, r))
                rows.append((name, r, j))
                print("# %s, %d rank(s): n %d, Iter %d, n_A %d, setup %.1f s, solve %.1f s, %.0f MB" %
                      (name, r, j["n"], j["iter"], j["n_A"], j["time_setup"], j["time_solve"], j["memory"] / 2**20), flush=True)
    lines = ["command: `scripts/bench-geometry-scale.py --h %g --subdomains %d --brick-refine %d --ranks %s`" % (args.h, args.subdomains, args.brick_refine, args.ranks), "",
             "| scene | ranks | n | subdomains | Iter | n_A | setup [s] | solve [s] | peak memory | per unknown | converged |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, r, j in rows:
        lines.append("| %s | %d | %d | %d | %d | %d | %.1f | %.1f | %.0f MB | %.1f KB | %s |" % (name, r, j["n"], j["subdomains"], j["iter"], j["n_A"], j["time_setup"], j["time_solve"],
                                                                                        j["memory"] / 2**20, j["memory"] / 1024.0 / j["n"], "yes" if j["converged"] else "NO"))
    text = "\n".join(lines)
    print(text)
    if args.write:
        with open(args.write) as f:
            page = f.read()
        begin, end = "<!-- bench-geometry-scale -->", "<!-- /bench-geometry-scale -->"
        if begin not in page:
            sys.exit("bench-geometry-scale.py: %s has no %s marker" % (args.write, begin))
        head, rest = page.split(begin, 1)
        tail = rest.split(end, 1)[1]
        with open(args.write, "w") as f:
            f.write(head + begin + "\n" + text + "\n" + end + tail)


if __name__ == "__main__":
    main()
