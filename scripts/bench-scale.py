#!/usr/bin/python3
"""The brick at a fixed subdomain size H/h, from 10^4 to 10^6 unknowns: conefeti beside one CG + GAMG solve of the same mesh.

For each size p the brick (petsc-options/brick.opts, Coulomb friction F) gets -scene_refine k = H/h * p and
-scene_body0_subdomains 3p,p,p (cubes of H/h cells per edge, n = 9 k (k+1)^2). On every rank count it runs
  - the conefeti driver (its JSON line: n, subdomains, Iter, n_A, time_setup, time_solve, kplus; -log_view for
    where the time goes), and
  - the gamg program (tutorials/contact/gamg.cxx: the same scene options, contact zones ignored, CG + GAMG with the
    rigid-body near-null space, rtol 1e-8; its JSON line),
each under /usr/bin/time -f %M, one process per rank: the peak memory is the sum of the ranks' peak resident sets.
Runs are one at a time (never two big ones at once). The result is a markdown table, the top -log_view events of
each conefeti run and a PNG (time and memory against n, with the GAMG line), written between the markers
"<!-- bench-scale begin -->" and "<!-- bench-scale end -->" of --doc (default docs/scale.md; created if missing)
and to --png; also printed.

usage: scripts/bench-scale.py [--sizes 2,4] [--full] [--ranks 1,2] [--repeat 1] [--hh 6] [--friction 0.3] [--extra "-opt v ..."]
                              [--build build] [--doc docs/scale.md] [--png docs/figures/scale.png] [--hugepages 1]
  --sizes p,...  subdomains 3p x p x p (default 2,4: n = 18252, 135000); --full adds p = 8 (n = 1037232, about 3 min
                 and 13 GB with the defaults of the time of writing: run it alone on the machine)
  --repeat r     r runs per size and rank count (the rank counts alternate: 1, 2, 1, 2, ...); the run with the
                 median solve time stands for its rank count, and the speed-up line gives the median and range of
                 the r ratios of back-to-back pairs (the shared host's speed drifts by 10-30%)
  --extra        options for the conefeti driver only (the levers: -feti_kplus_explicit 0, ...)
  --no-doc       print only
  --save f.json  also write the rows (with every -log_view event) to f.json; --load a.json,b.json adds saved rows to
                 the table (a --full run made alone, a lever's run), --sizes "" runs nothing new
The wrapper events (the solve and setup stages, TaoSolve, QPSolve, the MatMult of every shell) are left out of
"where the time goes": they contain the others.
"""
import argparse, atexit, glob, json, os, re, shutil, subprocess, sys, tempfile

import hugepages
import logview

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BRICK = os.path.join(ROOT, "petsc-options", "brick.opts")
BEGIN, END = "<!-- bench-scale begin -->", "<!-- bench-scale end -->"


PROGRAMS = {"conefeti": "conefeti", "gamg": os.path.join("tutorials", "contact", "gamg")}


TIMES = tempfile.mkdtemp(prefix="bench-scale-")
atexit.register(shutil.rmtree, TIMES, True)


def command(build, program, ranks):
    """One /usr/bin/time per rank, so that every rank reports its own peak resident set and CPU seconds, each into a
    file of its own (under mpiexec the ranks' stderr lines reach the pipe interleaved, and a line may be lost or cut)"""
    timed = ["sh", "-c", '/usr/bin/time -f "bench-scale-maxrss-kb %M cpu %U %S" -o "$0/time.${OMPI_COMM_WORLD_RANK:-0}" "$@"', TIMES, os.path.join(build, PROGRAMS[program])]
    if ranks == 1:
        return timed
    return ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks)] + timed


def run(cmd, env, key, ranks):
    for f in glob.glob(os.path.join(TIMES, "time.*")):
        os.remove(f)
    out = subprocess.run(cmd, capture_output=True, text=True, env=env)
    line = next((l for l in out.stdout.splitlines() if l.startswith('{"%s":' % key)), None)
    if out.returncode not in (0, 2) or line is None:
        sys.exit("bench-scale: failed (%s):\n%s" % (" ".join(cmd), (out.stdout + out.stderr)[-3000:]))
    times = "".join(open(f).read() for f in sorted(glob.glob(os.path.join(TIMES, "time.*"))))
    rss = [int(m) * 1024 for m in re.findall(r"bench-scale-maxrss-kb (\d+)", times)]
    if len(rss) != ranks:
        sys.exit("bench-scale: /usr/bin/time reported %d of %d ranks (%s)" % (len(rss), ranks, " ".join(cmd)))
    cpu = sum(float(u) + float(s) for u, s in re.findall(r"bench-scale-maxrss-kb \d+ cpu ([\d.]+) ([\d.]+)", times))
    j = json.loads(line)
    j["cpu"] = cpu  # user + system seconds of every rank, the whole program
    return j, sum(rss), out.stdout, out.returncode


WRAPPERS = {"ContactSceneSolve", "ContactSceneSetUp", "ContactSolve", "TaoSolve", "QPSolve", "MatMult", "QPHessianMult", "KSPSolve", "PCApply", "FETISetUp", "SNESSolve"}


def log_events(text, top=8):
    """The events of a -log_view table with their max time over the ranks and count, largest first"""
    ev = logview.events(text)
    return sorted(((n, c, t) for n, (c, t) in ev.items() if n not in WRAPPERS), key=lambda e: -e[2])[:top], ev


def fmt_bytes(b):
    return "%.2f GB" % (b / 1e9) if b >= 1e9 else "%.0f MB" % (b / 1e6)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", default="2,4")
    ap.add_argument("--full", action="store_true", help="add p = 8 (n = 1037232)")
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--hh", type=int, default=6, help="cells per subdomain edge, H/h")
    ap.add_argument("--friction", default="0.3")
    ap.add_argument("--extra", default="", help="options for the conefeti driver only")
    ap.add_argument("--build", default="build")
    ap.add_argument("--doc", default=os.path.join(ROOT, "docs", "scale.md"))
    ap.add_argument("--png", default=os.path.join(ROOT, "docs", "figures", "scale.png"))
    ap.add_argument("--no-doc", action="store_true")
    ap.add_argument("--save", default="")
    ap.add_argument("--load", default="")
    ap.add_argument("--repeat", type=int, default=1, help="runs per size and rank count, alternating the rank counts; the median solve stands for them")
    ap.add_argument("--hugepages", type=int, default=1, help="1: transparent huge pages (scripts/hugepages.py), 0: without")
    a = ap.parse_args()
    sizes = [int(p) for p in a.sizes.split(",") if p]
    if a.full and 8 not in sizes:
        sizes.append(8)
    ranks = [int(r) for r in a.ranks.split(",")]
    env = hugepages.environment(a.hugepages)
    rows = []
    for f in [f for f in a.load.split(",") if f]:
        rows += json.load(open(f))
    for p in sizes:
        k = a.hh * p
        scene = ["-options_file", BRICK, "-scene_refine", str(k), "-scene_body0_subdomains", "%d,%d,%d" % (3 * p, p, p), "-scene_zone0_friction", a.friction]
        # the rank counts alternate (1, 2, 1, 2, ...) so that a slow spell of the shared host hits both alike
        runs = {r: [] for r in ranks}
        for i in range(a.repeat):
            for r in ranks:
                c, cmem, cout, crc = run(command(a.build, "conefeti", r) + scene + ["-summary_table", "0", "-log_view"] + a.extra.split(), env, "conefeti", r)
                g, gmem, _, _ = run(command(a.build, "gamg", r) + scene, env, "gamg", r)
                runs[r].append((c, cmem, cout, crc, g, gmem))
        for r in ranks:
            # the run with the median solve time stands for the rank count; every solve time is kept
            ordered = sorted(runs[r], key=lambda t: t[0]["time_solve"])
            c, cmem, cout, crc, _, _ = ordered[(len(ordered) - 1) // 2]
            gordered = sorted(runs[r], key=lambda t: t[4]["time"])
            g, gmem = gordered[(len(gordered) - 1) // 2][4:6]
            top, events = log_events(cout)
            F = events.get("FETI_MultF", (0, 0.0))
            row = dict(p=p, k=k, hh=a.hh, options=a.extra, ranks=r, n=c["n"], subdomains=c["subdomains"], iter=c["iter"], nA=c["n_A"], converged=all(t[0]["converged"] and t[3] == 0 for t in runs[r]), setup=c["time_setup"],
                       solve=c["time_solve"], solves=[t[0]["time_solve"] for t in runs[r]], cpu=c["cpu"], mem=cmem, kplus=c.get("kplus", "?"), res=c["residuals"]["max"], F=F, top=top, events=events, gamg=g, gmem=gmem)
            rows.append(row)
            print("p=%d ranks=%d n=%d: conefeti Iter %d n_A %d setup %.2f solve %.2f (of %s) mem %s (%s); gamg %d its %.2f s mem %s" % (
                p, r, row["n"], row["iter"], row["nA"], row["setup"], row["solve"], ", ".join("%.2f" % x for x in row["solves"]), fmt_bytes(cmem), row["kplus"], g["iter"], g["time"], fmt_bytes(gmem)), flush=True)

    if a.save:
        with open(a.save, "w") as f:
            json.dump(rows, f)
    rows.sort(key=lambda w: (w["n"], w["ranks"]))
    out = []
    out.append("Command: `scripts/bench-scale.py %s` (brick, Coulomb F = %s, H/h = %d, subdomains 3p x p x p; %s; the machine is shared, times vary by 10-30%%)." % (
        " ".join(sys.argv[1:]), a.friction, a.hh, hugepages.describe(a.hugepages)))
    out.append("")
    if a.load:
        out.append("Rows from earlier runs of the script: %s (each row's options say how it differs from the defaults)." % a.load)
        out.append("")
    out.append("| n | subdomains | ranks | options | Iter | n_A | K+ | setup + solve [s] | CPU [s] | F product [ms] | peak memory | per unknown | GAMG: its, mesh + assembly + setup + solve [s] | GAMG CPU [s] | GAMG memory | GAMG per unknown | conefeti / GAMG: wall, CPU | max residual |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for w in rows:
        g = w["gamg"]
        fms = 1e3 * w["F"][1] / w["F"][0] if w["F"][0] else float("nan")
        out.append("| %d | %d | %d | %s | %s | %d | %s | %.1f + %.1f | %.1f | %.1f | %s | %.1f KB | %d, %.2f + %.2f + %.2f + %.2f = %.1f | %.1f | %s | %.1f KB | %.1f, %.1f | %.1e |" % (
            w["n"], w["subdomains"], w["ranks"], w.get("options") or "defaults", "%d" % w["iter"] if w["converged"] else "%d (not converged)" % w["iter"], w["nA"], w["kplus"], w["setup"], w["solve"], w["cpu"], fms,
            fmt_bytes(w["mem"]), w["mem"] / w["n"] / 1e3, g["iter"], g["time_mesh"], g["time_assembly"], g["time_setup"], g["time_solve"], g["time"], g["cpu"], fmt_bytes(w["gmem"]),
            w["gmem"] / g["n"] / 1e3, (w["setup"] + w["solve"]) / g["time"], w["cpu"] / g["cpu"], w["res"]))
    out.append("")
    speedups = []
    for w in rows:
        one = next((v for v in rows if v["n"] == w["n"] and v["ranks"] == 1 and v.get("options") == w.get("options")), None)
        if w["ranks"] > 1 and one:
            pairs = [x / y for x, y in zip(one.get("solves", [one["solve"]]), w.get("solves", [w["solve"]]))]
            pairs.sort()
            speedups.append("n = %d%s: %d ranks %.2fx (median of %d back-to-back pair%s%s)" % (
                w["n"], ", " + w["options"] if w.get("options") else "", w["ranks"], pairs[(len(pairs) - 1) // 2] if len(pairs) % 2 else 0.5 * (pairs[len(pairs) // 2 - 1] + pairs[len(pairs) // 2]),
                len(pairs), "s" if len(pairs) > 1 else "", ", range %.2f-%.2f" % (pairs[0], pairs[-1]) if len(pairs) > 1 else ""))
    if speedups:
        out.append("Solve phase on several ranks against one (the ratio of the solve times of runs made one after the other): " + "; ".join(speedups) + ".")
        out.append("")
    out.append("Where the time goes (conefeti, -log_view: the 8 events with the largest max time over the ranks, wrappers left out; events nest, so times overlap; (count)):")
    out.append("")
    for w in rows:
        w["top"] = sorted(((e, c, t) for e, (c, t) in w["events"].items() if e not in WRAPPERS), key=lambda e: -e[2])[:8]
        out.append("- n = %d, %d rank%s%s: %s" % (w["n"], w["ranks"], "s" if w["ranks"] > 1 else "", ", " + w["options"] if w.get("options") else "", ", ".join("%s %.1f s (%d)" % (e, t, c) for e, c, t in w["top"])))
    text = "\n".join(out)
    print(text)

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
        for r, opt in sorted({(w["ranks"], w.get("options") or "") for w in rows}):
            sel = [w for w in rows if w["ranks"] == r and (w.get("options") or "") == opt]
            n = [w["n"] for w in sel]
            label = "conefeti%s, %d rank%s" % (" " + opt if opt else "", r, "s" if r > 1 else "")
            ax1.loglog(n, [w["setup"] + w["solve"] for w in sel], "o-", label=label)
            ax2.loglog(n, [w["mem"] / 1e9 for w in sel], "o-", label=label)
        for r in sorted({w["ranks"] for w in rows}):
            sel = sorted({w["n"]: w for w in rows if w["ranks"] == r}.values(), key=lambda w: w["n"])
            n = [w["n"] for w in sel]
            ax1.loglog(n, [w["gamg"]["time"] for w in sel], "s--", label="CG + GAMG (linear, no contact), %d rank%s" % (r, "s" if r > 1 else ""))
            ax2.loglog(n, [w["gmem"] / 1e9 for w in sel], "s--", label="CG + GAMG, %d rank%s" % (r, "s" if r > 1 else ""))
        n = sorted({w["n"] for w in rows})
        ax2.loglog(n, [3e3 * x / 1e9 for x in n], ":", color="gray", label="goal: 3 KB per unknown")
        ax1.set_xlabel("n (primal unknowns)")
        ax1.set_ylabel("wall time [s]")
        ax2.set_xlabel("n (primal unknowns)")
        ax2.set_ylabel("peak memory, all ranks [GB]")
        ax1.set_title("brick, Coulomb F = %s, H/h = %d" % (a.friction, a.hh))
        ax2.set_title("peak resident memory")
        for ax in (ax1, ax2):
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
        fig.tight_layout()
        if not a.no_doc:
            os.makedirs(os.path.dirname(a.png), exist_ok=True)
            fig.savefig(a.png, dpi=110)
            print("wrote %s" % a.png)
    except ImportError:
        print("bench-scale: matplotlib missing (apt-get install python3-matplotlib): no plot")

    if a.no_doc:
        return
    block = BEGIN + "\n" + text + "\n\n![time and memory against n](figures/%s)\n" % os.path.basename(a.png) + END
    old = open(a.doc).read() if os.path.exists(a.doc) else "# Scale\n\n" + BEGIN + "\n" + END + "\n"
    if BEGIN in old and END in old:
        new = old[:old.index(BEGIN)] + block + old[old.index(END) + len(END):]
    else:
        new = old.rstrip("\n") + "\n\n" + block + "\n"
    with open(a.doc, "w") as f:
        f.write(new)
    print("wrote %s" % a.doc)


if __name__ == "__main__":
    main()
