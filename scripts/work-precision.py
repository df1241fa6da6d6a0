#!/usr/bin/python3
"""Work-precision pictures: what each digit of accuracy costs, per Coulomb algorithm.

For each case (a scene, a mesh size, a friction law) the conefeti driver solves once at a tight reference
tolerance (-contact_rtol 1e-12, monolithic for Coulomb) and then at every tolerance of --rtols with every
algorithm of the case (Coulomb: monolithic, msa, merged; Tresca and frictionless: their one pipeline). Each
run writes its HDF5 output (docs/output.md); the error of a run is

  * the displacement error  |u - u_ref| / |u_ref|  over every node of /volume/displacement (the same mesh
    and node order in every run of a case: one rank, the same scene), and
  * the largest mechanical residual of its JSON line (residuals.max: equilibrium, gluing, penetration,
    complementarity, cone, slip rule; computed from u and lambda, not by the solver).

The cost is n_A (products with F, machine independent: the main axis) and the solve time (time_solve of the
JSON line; the setup does not depend on the tolerance). Runs are interleaved (tolerance by tolerance, every
algorithm and case in turn) so that the machine's drift spreads over all curves alike. A run that does not
converge at its tolerance (exit status 2) still counts: it wrote its output (-output_unconverged).

Output: docs/figures/work-precision-<case>.png (four panels: displacement error and largest residual
against n_A and against solve time), a Markdown table per case on stdout (--table FILE writes it there too)
and the raw results as JSON (--json FILE). Filled markers: the separated/stick/slip counts equal the
reference's; open markers: not yet.

usage: scripts/work-precision.py [--cases brick8-F0.3,...] [--rtols 1e-1,...,1e-10] [--ref-rtol 1e-12]
                                 [--build build] [--figures docs/figures] [--json FILE] [--table FILE]
                                 [--replot FILE.json] [--hugepages 1] [--repeat 1]
cases (name: scene options):
"""
import argparse, json, os, subprocess, sys, tempfile, time

import hugepages

SCENES = {
    # name: (title, options, algorithms)
    "brick4-F0.3": ("brick, n = 900, Coulomb F = 0.3", ["-options_file", "petsc-options/brick.opts", "-scene_refine", "4"], "coulomb"),  # the test's
    "brick8-F0.3": ("brick, n = 5832, Coulomb F = 0.3", ["-options_file", "petsc-options/brick.opts", "-scene_refine", "8"], "coulomb"),
    "brick8-F0.1": ("brick, n = 5832, Coulomb F = 0.1", ["-options_file", "petsc-options/brick-f01.opts", "-scene_refine", "8"], "coulomb"),
    "brick12-F0.3": ("brick, n = 18252, Coulomb F = 0.3", ["-options_file", "petsc-options/brick.opts", "-scene_refine", "12"], "coulomb"),
    "brick12-F0.1": ("brick, n = 18252, Coulomb F = 0.1", ["-options_file", "petsc-options/brick-f01.opts", "-scene_refine", "12"], "coulomb"),
    "brick8-tresca": ("brick, n = 5832, Tresca", ["-options_file", "petsc-options/brick-tresca.opts", "-scene_refine", "8"], "single"),
    "brick8-frictionless": ("brick, n = 5832, frictionless", ["-options_file", "petsc-options/brick-frictionless.opts", "-scene_refine", "8"], "single"),
    "brick12-tresca": ("brick, n = 18252, Tresca", ["-options_file", "petsc-options/brick-tresca.opts", "-scene_refine", "12"], "single"),
    "brick12-frictionless": ("brick, n = 18252, frictionless", ["-options_file", "petsc-options/brick-frictionless.opts", "-scene_refine", "12"], "single"),
    "twobodies": ("two bodies, Coulomb F = 0.3", ["-options_file", "petsc-options/twobodies.opts"], "coulomb"),
    "indentation": ("Hertz indentation (rigid sphere, block of 20^3 cells), frictionless", ["-options_file", "petsc-options/indentation.opts", "-scene_body0_cells", "20,20,20",
                                                                                         "-scene_body0_subdomains", "3,3,3"], "single"),
}
# figures: which cases share a picture (Tresca and frictionless beside the Coulomb curves of the same mesh)
FIGURES = {
    "brick4-F0.3": ["brick4-F0.3"],
    "brick8-F0.3": ["brick8-F0.3", "brick8-tresca", "brick8-frictionless"],
    "brick8-F0.1": ["brick8-F0.1"],
    "brick12-F0.3": ["brick12-F0.3", "brick12-tresca", "brick12-frictionless"],
    "brick12-F0.1": ["brick12-F0.1"],
    "twobodies": ["twobodies"],
    "indentation": ["indentation"],
}
__doc__ += "".join("  %-22s %s: %s\n" % (k, v[0], " ".join(v[1])) for k, v in SCENES.items())

ALGORITHMS = ["monolithic", "msa", "merged"]
STYLE = {"monolithic": ("C0", "o"), "msa": ("C1", "s"), "merged": ("C2", "^"), "tresca": ("C3", "D"), "frictionless": ("C4", "v")}


def run(build, case, algorithm, rtol, outdir, env, ref=False):
    """One driver run; returns the JSON line's fields plus the displacement."""
    import h5py
    title, opts, kind = SCENES[case]
    base = os.path.join(outdir, "%s-%s-%g" % (case, algorithm, rtol))
    cmd = [os.path.join(build, "conefeti")] + opts + ["-contact_rtol", "%g" % rtol, "-output", base, "-output_unconverged",
                                                      "-summary_table", "0", "-summary_json", base + ".json"]
    if kind == "coulomb":
        cmd += ["-contact_coulomb_algorithm", algorithm]
    if ref:  # the reference: rounding decides the last residuals; do not let the acceptance refuse it
        cmd += ["-contact_acceptance_factor", "1e3"]
    t = time.time()
    out = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.time() - t
    if out.returncode not in (0, 2) or not os.path.exists(base + ".json"):
        print("work-precision.py: the driver failed (%s), exit %d:\n%s" % (" ".join(cmd), out.returncode, (out.stdout + out.stderr)[-2000:]), file=sys.stderr)
        return None, None
    with open(base + ".json") as f:
        j = json.load(f)
    with h5py.File(base + ".h5", "r") as h:
        u = h["volume/displacement"][()]
    for ext in (".h5", ".xmf", ".json"):
        os.remove(base + ext)
    return dict(case=case, algorithm=algorithm, rtol=rtol, converged=out.returncode == 0, iter=j["iter"], nA=j["n_A"],
                nA_other=j["n_A_other"], setup=j["time_setup"], solve=j["time_solve"], wall=wall, n=j["n"],
                states=[j["separated"], j["stick"], j["slip"]], residual=j["residuals"]["max"], refinements=j.get("refinements", 0),
                command=" ".join(c for c in cmd if not c.startswith(outdir))), u


def algorithms_of(case):
    kind = SCENES[case][2]
    if kind == "coulomb":
        return ALGORITHMS
    return ["tresca"] if "tresca" in case else ["frictionless"]


def measure(a):
    import numpy as np
    env = hugepages.environment(a.hugepages)
    env["OMPI_MCA_ess_singleton_isolated"] = "1"  # one rank: no Open MPI daemon to start (about 1 s less per run)
    results, refs, failed = [], {}, []
    with tempfile.TemporaryDirectory(prefix="work-precision-") as outdir:
        for case in a.cases:
            alg = algorithms_of(case)[0]
            r, u = run(a.build, case, alg, a.ref_rtol, outdir, env, ref=True)
            if r is None:
                sys.exit("work-precision.py: the reference of %s failed" % case)
            refs[case] = (r, u)
            print("# reference %s: %s at rtol %g, n = %d, Iter %d, n_A %d, max residual %.1e, states %s" % (
                case, alg, a.ref_rtol, r["n"], r["iter"], r["nA"], r["residual"], "/".join(map(str, r["states"]))), file=sys.stderr)
        for rep in range(a.repeat):
            for rtol in a.rtols:  # interleaved: every case and algorithm at one tolerance, then the next
                for case in a.cases:
                    ref, uref = refs[case]
                    for alg in algorithms_of(case):
                        r, u = run(a.build, case, alg, rtol, outdir, env)
                        if r is None:
                            failed.append("%s %s %g" % (case, alg, rtol))
                            continue
                        r["error"] = float(np.linalg.norm(u - uref) / np.linalg.norm(uref))
                        r["final_states"] = r["states"] == ref["states"]
                        r["repeat"] = rep
                        results.append(r)
                        if a.json:  # a partial result survives an interrupted run
                            with open(a.json + ".partial", "w") as f:
                                json.dump(dict(results=results, references={c: refs[c][0] for c in refs}), f)
                        print("%s %s rtol %g: n_A %d, solve %.2f s, error %.1e, residual %.1e, states %s%s" % (
                            case, alg, rtol, r["nA"], r["solve"], r["error"], r["residual"], "/".join(map(str, r["states"])),
                            "" if r["converged"] else " (not converged)"), file=sys.stderr)
    return dict(results=results, failed=failed, references={c: refs[c][0] for c in refs}, rtols=a.rtols, ref_rtol=a.ref_rtol,
                machine=hugepages.describe(a.hugepages), command=" ".join(sys.argv))


def merged_rows(data, case, alg):
    """The rows of one curve, ordered by tolerance; repeated runs give the median time (counts do not change)."""
    import statistics
    rows = {}
    for r in data["results"]:
        if r["case"] == case and r["algorithm"] == alg:
            rows.setdefault(r["rtol"], []).append(r)
    out = []
    for rtol in sorted(rows, reverse=True):
        rs = rows[rtol]
        r = dict(rs[0])
        r["solve"] = statistics.median(x["solve"] for x in rs)
        r["solves"] = [x["solve"] for x in rs]
        out.append(r)
    return out


def final_from(rows):
    """The loosest tolerance from which the node states equal the reference's at every tighter tolerance."""
    first = None
    for r in reversed(rows):  # tightest first
        if not r["final_states"]:
            break
        first = r["rtol"]
    return first


def plot(data, figures):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    os.makedirs(figures, exist_ok=True)
    made = []
    cases = {r["case"] for r in data["results"]}
    for fig_name, members in FIGURES.items():
        members = [c for c in members if c in cases]
        if not members:
            continue
        fig, axes = plt.subplots(2, 2, figsize=(11, 8.5), sharey="row")
        for case in members:
            for alg in algorithms_of(case):
                rows = merged_rows(data, case, alg)
                if not rows:
                    continue
                color, marker = STYLE[alg]
                label = alg if SCENES[case][2] == "coulomb" else SCENES[case][0].split(", ")[-1]
                for i, (ykey, ylabel) in enumerate([("error", "displacement error |u - u_ref| / |u_ref|"), ("residual", "largest mechanical residual")]):
                    for j, (xkey, xlabel) in enumerate([("nA", "n_A (products with F)"), ("solve", "solve time [s]")]):
                        ax = axes[i][j]
                        xs = [max(r[xkey], 1e-3) for r in rows]
                        ys = [max(r[ykey], 1e-17) for r in rows]
                        ax.loglog(xs, ys, "-" if SCENES[case][2] == "coulomb" else "--", color=color, lw=1.2, label=label if (i, j) == (0, 0) else None)
                        for r, x, y in zip(rows, xs, ys):
                            ax.plot([x], [y], marker, color=color, ms=6, mfc=color if r["final_states"] else "white", mew=1.2)
                            if not r["converged"]:
                                ax.plot([x], [y], "x", color="k", ms=8)
                        if ykey == "residual":  # label each point of the monolithic curve by its tolerance
                            if alg == "monolithic" and xkey == "nA":
                                for r, x, y in zip(rows, xs, ys):
                                    ax.annotate("%.0e" % r["rtol"], (x, y), textcoords="offset points", xytext=(4, 3), fontsize=6, color=color)
                        ax.set_xlabel(xlabel)
                        if j == 0:
                            ax.set_ylabel(ylabel)
                        ax.grid(True, which="major", alpha=0.4)
                        ax.grid(True, which="minor", alpha=0.12)
        ref = data["references"][members[0]]
        axes[0][0].plot([], [], "o", color="gray", mfc="gray", label="states final")
        axes[0][0].plot([], [], "o", color="gray", mfc="white", label="states not final")
        if any(not r["converged"] for r in data["results"] if r["case"] in members):
            axes[0][0].plot([], [], "x", color="k", label="not converged")
        axes[0][0].legend(fontsize=8, loc="lower left")
        fig.suptitle("%s: -contact_rtol %g to %g against a reference at %g\n(n_A is machine independent; times: %s, median of %d)" % (
            SCENES[members[0]][0], max(data["rtols"]), min(data["rtols"]), data["ref_rtol"], "this machine, 1 core",
            max(len(r["solves"]) for r in merged_rows(data, members[0], algorithms_of(members[0])[0]))), fontsize=10)
        fig.tight_layout()
        path = os.path.join(figures, "work-precision-%s.png" % fig_name)
        fig.savefig(path, dpi=90)
        plt.close(fig)
        made.append(path)
    return made


def plot_summary(data, figures, case="brick12-F0.3"):
    """One small picture for the README: displacement error against n_A, the three algorithms."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    members = [c for c in FIGURES.get(case, []) if any(r["case"] == c for r in data["results"])]
    if not members:
        return None
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for c in members:
        for alg in algorithms_of(c):
            rows = merged_rows(data, c, alg)
            color, marker = STYLE[alg]
            ax.loglog([r["nA"] for r in rows], [max(r["error"], 1e-17) for r in rows], "-" if SCENES[c][2] == "coulomb" else "--", color=color,
                      label=alg if SCENES[c][2] == "coulomb" else SCENES[c][0].split(", ")[-1])
            for r in rows:
                ax.plot([r["nA"]], [max(r["error"], 1e-17)], marker, color=color, mfc=color if r["final_states"] else "white")
    for r in merged_rows(data, members[0], "monolithic"):
        ax.annotate("%.0e" % r["rtol"], (r["nA"], max(r["error"], 1e-17)), textcoords="offset points", xytext=(4, 3), fontsize=6, color="C0")
    ax.plot([], [], "o", color="gray", mfc="white", label="stick/slip/separated not final")
    ax.set_xlabel("n_A (products with F; machine independent)")
    ax.set_ylabel("|u - u_ref| / |u_ref|")
    ax.set_title("%s: error against work, -contact_rtol %g to %g" % (SCENES[members[0]][0], max(data["rtols"]), min(data["rtols"])), fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(figures, "work-precision.png")
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return path


def table(data):
    lines = ["# work-precision: %s" % data["command"], "# times: %s; references at -contact_rtol %g" % (data["machine"], data["ref_rtol"])]
    cases = []
    for r in data["results"]:
        if r["case"] not in cases:
            cases.append(r["case"])
    for case in cases:
        ref = data["references"][case]
        lines += ["", "%s (reference: %s, Iter %d, n_A %d, max residual %.1e, separated/stick/slip %s)" % (
            SCENES[case][0], ref["algorithm"], ref["iter"], ref["nA"], ref["residual"], "/".join(map(str, ref["states"])))]
        lines += ["| algorithm | -contact_rtol | Iter | n_A | solve [s] | displacement error | max residual | separated/stick/slip |", "|---|---|---|---|---|---|---|---|"]
        for alg in algorithms_of(case):
            rows = merged_rows(data, case, alg)
            for r in rows:
                lines.append("| %s | %.0e | %d | %d | %s | %.1e | %.1e | %s%s |" % (
                    alg, r["rtol"], r["iter"], r["nA"], "/".join("%.2f" % s for s in r["solves"]), r["error"], r["residual"],
                    "/".join(map(str, r["states"])), "" if r["final_states"] else " *") + ("" if r["converged"] else " (not converged)"))
            f = final_from(rows)
            lines.append("| %s | states final from %s | | | | | | |" % (alg, "%.0e" % f if f else "never"))
    lines.append("")
    lines.append("* : separated/stick/slip differ from the reference's")
    for f in data.get("failed", []):
        lines.append("failed (the driver ended with an error): %s" % f)
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="brick8-F0.3,brick8-F0.1,brick12-F0.3,brick12-F0.1,brick8-tresca,brick8-frictionless,twobodies,indentation")
    ap.add_argument("--rtols", default="1e-1,1e-2,1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10")
    ap.add_argument("--ref-rtol", type=float, default=1e-12)
    ap.add_argument("--build", default="build")
    ap.add_argument("--figures", default="docs/figures")
    ap.add_argument("--json", help="write the raw results here")
    ap.add_argument("--table", help="write the Markdown tables here too")
    ap.add_argument("--replot", help="do not run: plot the results of an earlier --json file")
    ap.add_argument("--hugepages", type=int, default=1)
    ap.add_argument("--repeat", type=int, default=1, help="runs per point (times: the median; counts do not change)")
    ap.add_argument("--no-plots", action="store_true", help="tables only (no matplotlib needed)")
    ap.add_argument("--check", action="store_true", help="exit 1 unless every run converged, the displacement error falls as the "
                    "tolerance tightens, and the node states equal the reference's at the tightest tolerance")
    a = ap.parse_args()
    a.cases = a.cases.split(",")
    for c in a.cases:
        if c not in SCENES:
            sys.exit("work-precision.py: unknown case %s (known: %s)" % (c, ", ".join(SCENES)))
    a.rtols = [float(x) for x in a.rtols.split(",")]
    if a.replot:
        with open(a.replot) as f:
            data = json.load(f)
    else:
        data = measure(a)
        if a.json:
            with open(a.json, "w") as f:
                json.dump(data, f, indent=1)
    text = table(data)
    print(text)
    if a.table:
        with open(a.table, "w") as f:
            f.write(text + "\n")
    if not a.no_plots:
        for p in plot(data, a.figures) + [plot_summary(data, a.figures)]:
            if p:
                print("# wrote %s" % p, file=sys.stderr)
    if a.check:
        failures = check(data)
        for f in failures:
            print("CHECK FAILED: " + f)
        print("check: %s" % ("passed" if not failures else "%d failure(s)" % len(failures)))
        sys.exit(1 if failures else 0)


def check(data):
    """What the pictures are meant to show, as properties of the runs."""
    failures = ["%s: the driver failed" % f for f in data.get("failed", [])]
    cases = []
    for r in data["results"]:
        if r["case"] not in cases:
            cases.append(r["case"])
    for case in cases:
        for alg in algorithms_of(case):
            rows = merged_rows(data, case, alg)
            for r in rows:
                if not r["converged"]:
                    failures.append("%s %s rtol %g: not converged" % (case, alg, r["rtol"]))
            for prev, r in zip(rows, rows[1:]):
                if not r["error"] < prev["error"]:
                    failures.append("%s %s: the displacement error did not fall from rtol %g (%.1e) to %g (%.1e)" % (
                        case, alg, prev["rtol"], prev["error"], r["rtol"], r["error"]))
            if rows and not rows[-1]["final_states"]:
                failures.append("%s %s rtol %g: node states %s differ from the reference's" % (case, alg, rows[-1]["rtol"], rows[-1]["states"]))
    return failures


if __name__ == "__main__":
    main()
