#!/usr/bin/python3
"""The seed paper's Table 3: the disk-constrained method beside the approximate method of its reference [HKD04]
(Haslinger, Kucera, Dostal, J. Comput. Appl. Math. 164-165, 2004), in which each friction disk is replaced by a
polygon expressed through simple bounds only (-contact_friction_polygon k: k tangential multipliers per node,
|m_j| <= sin(pi/(2k)) g, a regular 2k-gon inscribed in the disk; docs/contact.md, "Friction polygons").

For each size of the brick (petsc-options/brick.opts, F = 0.3, -scene_refine 4 ... 12: n = 900 ... 18252) the
conefeti program runs with the disks and with k = 2 and k = 4, and the script reports, per run: multipliers m,
outer iterations, F products n_A, solve time, the verdict, and the error the approximation itself makes against
the disk solution of the same mesh: the relative displacement error |u_k - u_disk| / |u_disk| over the HDF5
output (-output), and the residual of the disk law that the polygon solution leaves (residuals.approximation of
the JSON line). The paper's times (its Table 3) are printed beside ours. Iter, n_A and the errors are machine
independent; times are this machine's.

usage: scripts/bench-table3.py [--sizes 4,6,8,10,12] [--polygons 2,4] [--algorithms monolithic,msa] [--repeat 3]
                               [--rtol 1e-6] [--build build] [--hugepages 1] [--markdown docs/table3.md]
"""
import argparse, json, os, platform, subprocess, sys, tempfile, time

import h5py
import numpy as np

import hugepages
from seedpaper import brick_n

# the seed paper's Table 3 (F = 0.3): n -> (m, Time, Time2, Time4), seconds on the paper's machine
PAPER = {900: (180, 2, 15, 61), 2646: (378, 12, 101, 548), 5832: (648, 38, 486, 2114), 10890: (990, 94, 1542, 7724), 18252: (1404, 254, 5004, 20534)}


def run(build, k, polygon, algorithm, rtol, workdir, env, output):
    """One run of one configuration: its JSON line (and, with output, the displacements of its HDF5 file)."""
    base = os.path.join(workdir, "k%d-p%d-%s" % (k, polygon, algorithm))
    cmd = [os.path.join(build, "conefeti"), "-options_file", "petsc-options/brick.opts", "-scene_refine", str(k), "-contact_friction_polygon", str(polygon),
           "-contact_coulomb_algorithm", algorithm, "-contact_rtol", str(rtol), "-summary_table", "0", "-summary_json", base + ".json"] + (["-output", base] if output else [])
    out = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    if out.returncode not in (0, 2) or not os.path.exists(base + ".json"):
        sys.exit("bench-table3.py: conefeti failed (%s):\n%s" % (" ".join(cmd), (out.stdout + out.stderr)[-2000:]))
    with open(base + ".json") as f:
        s = json.load(f)
    s["u"] = None
    if output:
        with h5py.File(base + ".h5", "r") as h:
            s["u"] = np.array(h["volume/displacement"])
    return s


def run_size(build, k, polygons, algorithm, rtol, env, repeat):
    """The disks and every polygon at one size, interleaved `repeat` times (the machine's load then falls on all
    of them alike); the counts are the same every time, the times are the smallest."""
    best = {}
    with tempfile.TemporaryDirectory() as wd:
        for r in range(repeat):
            for p in [0] + polygons:
                s = run(build, k, p, algorithm, rtol, wd, env, r == 0)
                if p not in best:
                    best[p] = s
                else:
                    best[p]["time_solve"] = min(best[p]["time_solve"], s["time_solve"])
    disk = best[0]
    polys = [best[p] for p in polygons]
    for s in polys:
        s["err"] = float(np.linalg.norm(s["u"] - disk["u"]) / np.linalg.norm(disk["u"]))
    return disk, polys


def fmt_time(t):
    return "%.2f" % t if t < 10 else "%.1f" % t


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", default="4,6,8,10,12", help="-scene_refine values (4 ... 12: n = 900 ... 18252)")
    ap.add_argument("--polygons", default="2,4")
    ap.add_argument("--algorithms", default="monolithic,msa", help="Coulomb algorithms, each a table (the first is the default's)")
    ap.add_argument("--rtol", type=float, default=1e-6)
    ap.add_argument("--repeat", type=int, default=5, help="runs per configuration; the times are the smallest")
    ap.add_argument("--build", default="build")
    ap.add_argument("--hugepages", type=int, default=1, help="1: transparent huge pages (scripts/hugepages.py), 0: without")
    ap.add_argument("--markdown", default="", help="also write the tables into this file (between the markers of docs/table3.md)")
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    env = hugepages.environment(a.hugepages)
    sizes = [int(x) for x in a.sizes.split(",")]
    polygons = [int(x) for x in a.polygons.split(",")]
    lines = []
    say = lambda s="": (print(s), lines.append(s))
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    say("<!-- made by: scripts/bench-table3.py %s -->" % " ".join(sys.argv[1:]))
    say("Command: `scripts/bench-table3.py %s` at commit %s on %s (%s, %d cores, 1 rank, %s, -contact_rtol %g; times: the solve, smallest of %d interleaved runs; load average %.1f at the start)." %
        (" ".join(sys.argv[1:]), commit or "?", platform.node() or "?", platform.machine(), os.cpu_count() or 0, hugepages.describe(a.hugepages), a.rtol, a.repeat, os.getloadavg()[0]))
    t_all = time.time()
    for algorithm in a.algorithms.split(","):
        rows = []
        for k in sizes:
            disk, polys = run_size(build, k, polygons, algorithm, a.rtol, env, a.repeat)
            rows.append((k, disk, polys))
        say()
        say("### Coulomb algorithm `%s`" % algorithm)
        say()
        say("| n | paper: m | paper: Time | " + " | ".join("paper: Time%d" % p for p in polygons if p in (2, 4)) + " | m: disks | " +
            " | ".join("m: k = %d" % p for p in polygons) + " | solve [s]: disks | " + " | ".join("k = %d" % p for p in polygons) + " |")
        say("|" + "---|" * (3 + len([p for p in polygons if p in (2, 4)]) + 1 + len(polygons) + 1 + len(polygons)))
        for k, disk, polys in rows:
            n = disk["n"]
            pm = PAPER.get(n)
            paper = [str(pm[0]), str(pm[1])] + [str(pm[2] if p == 2 else pm[3]) for p in polygons if p in (2, 4)] if pm else ["", ""] + ["" for p in polygons if p in (2, 4)]
            say("| %d | %s | %d | %s | %s | %s |" % (n, " | ".join(paper), disk["m"], " | ".join(str(s["m"]) for s in polys), fmt_time(disk["time_solve"]),
                                                  " | ".join(fmt_time(s["time_solve"]) for s in polys)))
        say()
        say("| n | Iter: disks | " + " | ".join("k = %d" % p for p in polygons) + " | n_A: disks | " + " | ".join("k = %d" % p for p in polygons) + " | " +
            " | ".join("error k = %d: displacement | disk law" % p for p in polygons) + " | verdict |")
        say("|" + "---|" * (2 + len(polygons) + 1 + len(polygons) + 2 * len(polygons) + 1))
        for k, disk, polys in rows:
            verdict = ", ".join("converged" if s["converged"] else "NOT converged (%s)" % s.get("failed_check") for s in [disk] + polys)
            if all(s["converged"] for s in [disk] + polys):
                verdict = "all converged"
            say("| %d | %d | %s | %d | %s | %s | %s |" % (disk["n"], disk["iter"], " | ".join(str(s["iter"]) for s in polys), disk["n_A"], " | ".join(str(s["n_A"]) for s in polys),
                                                     " | ".join("%.2e | %.1e" % (s["err"], s["residuals"]["approximation"]) for s in polys), verdict))
        say()
        say("| n | paper: Time2 / Time | ours: time k = 2 / disks | n_A k = 2 / disks | paper: Time4 / Time | ours: time k = 4 / disks | n_A k = 4 / disks |")
        say("|---|---|---|---|---|---|---|")
        for k, disk, polys in rows:
            pm = PAPER.get(disk["n"])
            cells = []
            for p, s in zip(polygons, polys):
                if p not in (2, 4):
                    continue
                cells += ["%.1f" % ((pm[2] if p == 2 else pm[3]) / pm[1]) if pm else "", "%.2f" % (s["time_solve"] / disk["time_solve"]), "%.2f" % (s["n_A"] / disk["n_A"])]
            say("| %d | %s |" % (disk["n"], " | ".join(cells)))
    say()
    say("Whole run: %.0f s wall." % (time.time() - t_all))
    if a.markdown:
        begin, end = "<!-- table3: begin -->", "<!-- table3: end -->"
        text = open(a.markdown).read() if os.path.exists(a.markdown) else begin + "\n" + end + "\n"
        i, j = text.find(begin), text.find(end)
        if i < 0 or j < i:
            sys.exit("bench-table3.py: %s has no %s ... %s markers" % (a.markdown, begin, end))
        with open(a.markdown, "w") as f:
            f.write(text[:i + len(begin)] + "\n" + "\n".join(lines) + "\n" + text[j:])


if __name__ == "__main__":
    main()
