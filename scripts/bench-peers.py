#!/usr/bin/python3
"""The solvers a PETSc user would try first for frictionless contact, on conefeti's problem, in one run.

The frictionless brick (petsc-options/brick-frictionless.opts) at each -scene_refine k is solved by
  - conefeti: the driver (build/conefeti, its JSON line) and the same library call inside the peers program
    (build/tutorials/contact/peers -peers_solver conefeti), which also measures its displacement;
  - the peers: the assembled primal problem with the bound u_z >= -gap (tutorials/contact/peers.cxx) by SNES VI
    and TAO with CG + ML / GAMG or a sparse Cholesky (the list PEERS below).
Every solution is judged by the same measure, computed by the peers program from the displacement alone: the
relative error against a reference (conefeti at -contact_rtol 1e-10) and the mechanical residuals (penetration,
sign of the reaction, complementarity, equilibrium). A solve the solver calls converged whose largest residual
exceeds -peers_acceptance (1e-5, conefeti's acceptance at its default tolerance) is a WRONG answer.

Times vary by +-30% on a shared machine: every peer run is preceded by a conefeti run (interleaved), and its
ratio is taken against that neighbour. Iterations, products and residuals do not depend on the load.

Writes the tables between the markers of docs/peers.md and the plot docs/peers.png (unless --no-docs), and
prints them.

usage: scripts/bench-peers.py [--sizes 10,22] [--large] [--only REGEX] [--timeout 1800] [--build build]
                              [--hugepages 1] [--no-docs] [--save FILE] [--from-saved FILE]
  --sizes  -scene_refine values (n = 9 k (k+1)^2: 10 -> 10890, 22 -> 104742, 48 -> 1.04e6)
  --large  add k = 48 (n = 1.04e6; not run by default: see docs/peers.md for why)
  --save   every result goes to this JSON file as it comes (default <build>/bench-peers.json);
           --from-saved FILE writes the tables and the plot from it without running anything
"""
import argparse, json, os, platform, re, shutil, subprocess, sys, tempfile, time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import hugepages

SCENE = ["-options_file", "petsc-options/brick-frictionless.opts"]
# The peers run with PETSc's default tolerances (what a user tries first); they reach a smaller residual than
# conefeti at its default -contact_rtol 1e-6, so conefeti also runs once at -contact_rtol 1e-9 (TIGHT).
# TRON, GPCG and BQPIP take -ksp_* and -pc_* unprefixed; BNLS's solver is -tao_bnk_ksp_*, -tao_bnk_pc_*.
ML = ["-ksp_type", "cg", "-pc_type", "ml"]
GAMG = ["-ksp_type", "cg", "-pc_type", "gamg"]
CHOL = ["-ksp_type", "preonly", "-pc_type", "cholesky", "-pc_factor_mat_solver_type", "mumps"]
TAO = lambda t: ["-peers_solver", "tao", "-tao_type", t]
VI = lambda t: ["-peers_solver", "snes", "-snes_type", t]
PEERS = [
    ("TRON, CG + ML", TAO("tron") + ML),
    ("TRON, CG + GAMG", TAO("tron") + GAMG),
    ("TRON, Cholesky (MUMPS)", TAO("tron") + CHOL),
    ("VI rsls, CG + ML", VI("vinewtonrsls") + ML),
    ("VI rsls, CG + GAMG", VI("vinewtonrsls") + GAMG),
    ("VI rsls, Cholesky (MUMPS)", VI("vinewtonrsls") + CHOL),
    ("VI ssls, CG + ML", VI("vinewtonssls") + ML),
    ("GPCG, CG + ML", TAO("gpcg") + ML),
    ("BQPIP, CG + ML", TAO("bqpip") + ML),
    ("BQPIP, CG + ML, bounds +-1 m", TAO("bqpip") + ML + ["-peers_free_bound", "1"]),
    ("BNLS, CG + ML", TAO("bnls") + ["-tao_bnk_ksp_type", "cg", "-tao_bnk_pc_type", "ml"]),
    ("BLMVM (no linear solver)", TAO("blmvm")),
]
TIGHT = "1e-9"
CONEFETI = "conefeti"


def run(cmd, env, timeout):
    t0 = time.time()
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, "timeout after %d s" % timeout, time.time() - t0
    return out, out.stdout + out.stderr, time.time() - t0


def json_line(text, key):
    for line in text.splitlines():
        if line.startswith('{"%s":' % key):
            d = json.loads(line)
            return d if key == "conefeti" else d[key]  # the driver's line is flat ({"conefeti": version, ...})
    return None


def error_message(text):
    """the first line of a PETSc error report (or the last line of the output)"""
    m = re.search(r"\[0\]PETSC ERROR: (?!-+)(?!See )(.*\S)", text)
    if m:
        rest = re.findall(r"\[0\]PETSC ERROR: (.*\S)", text)
        detail = [r for r in rest if not r.startswith(("---", "See ", "Petsc Release", "Configure", "#", "WARNING", "Option left", "PETSc Option Table", "-")) and "Caught signal" not in r and " named " not in r]
        sig = "Caught signal" in text and "crash (signal): " or ""
        return sig + "; ".join(detail[:2])[:200]
    lines = [l for l in text.splitlines() if l.strip()]
    return lines[-1][:200] if lines else "no output"


def peers(build, k, args, env, timeout):
    exe = os.path.join(build, "tutorials", "contact", "peers")
    cmd = [exe] + SCENE + ["-scene_refine", str(k)] + args
    out, text, wall = run(cmd, env, timeout)
    r = json_line(text, "peers") if out else None
    if r is None:
        return dict(status="crash" if out else "timeout", message=error_message(text) if out else text, wall=wall, cmd=cmd)
    r["wall"] = wall
    r["cmd"] = cmd
    if r["solver_converged"] and r["right"]:
        r["status"] = "ok"
    elif r["solver_converged"]:
        r["status"] = "WRONG, called converged"
    elif r["right"]:
        r["status"] = "not converged (answer right)"
    else:
        r["status"] = "not converged"
    return r


def driver(build, k, env, timeout):
    cmd = [os.path.join(build, "conefeti")] + SCENE + ["-scene_refine", str(k), "-summary_table", "0"]
    out, text, wall = run(cmd, env, timeout)
    r = json_line(text, "conefeti") if out else None
    if r is None:
        sys.exit("bench-peers.py: the conefeti driver failed (%s):\n%s" % (" ".join(cmd), text[-2000:]))
    return r


def total(r):
    """CPU seconds of setup + solve: on a shared machine less dependent on the other jobs than wall-clock time"""
    return r["cpu_setup"] + r["cpu_solve"]


def wall(r):
    return r["time_setup"] + r["time_solve"]


def fmt(x, spec="%.1e"):
    return spec % x if isinstance(x, (int, float)) and x >= 0 else "-"


def git_commit():
    try:
        return subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    except OSError:
        return "?"


def tables(results, args):
    lines = []
    lines.append("Command: `%s` (commit %s; %s, %d cores, %s; %s)." % (" ".join(["scripts/bench-peers.py"] + args), git_commit(), platform.processor() or platform.machine(), os.cpu_count(),
                                                                 time.strftime("%Y-%m-%d"), hugepages.describe(True)))
    lines.append("")
    for k, res in results:
        ref, drv, cf = res["reference"], res["driver"], res["conefeti"]
        lines.append("### n = %d (-scene_refine %d, %d contact nodes, %d pressed)" % (cf["n"], k, cf["contact_nodes"], cf["pressed"]))
        lines.append("")
        lines.append("conefeti driver (build/conefeti, its JSON line): wall-clock setup %.2f s + solve %.2f s, Iter %d, n_A %d, converged %s. Reference: conefeti at -contact_rtol 1e-10 "
                     "(largest residual %.1e)." % (drv["time_setup"], drv["time_solve"], drv["iter"], drv["n_A"], str(drv["converged"]).lower(), ref["residual_max"]))
        lines.append("")
        lines.append("| solver | verdict | iterations | linear it. | products | CPU setup [s] | CPU solve [s] | wall [s] | time / conefeti's | error u | largest residual | worst check |")
        lines.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
        cft = [total(c) for c in res["conefeti_runs"]]
        lines.append("| conefeti (smalxe + mprgp, FETI) | %s | %d | - | %d F | %.2f | %.2f | %.2f | 1 (median of %d runs: %.2f s) | %s | %.1e | %s |" %
                     (cf["status"], cf["iterations"], cf["products"], cf["cpu_setup"], cf["cpu_solve"], wall(cf), len(cft), sorted(cft)[len(cft) // 2], fmt(cf["error_u"]), cf["residual_max"], worst(cf)))
        t = res["tight"]
        lines.append("| conefeti at -contact_rtol %s | %s | %d | - | %d F | %.2f | %.2f | %.2f | %.2f | %s | %.1e | %s |" %
                     (TIGHT, t["status"], t["iterations"], t["products"], t["cpu_setup"], t["cpu_solve"], wall(t), total(t) / sorted(cft)[len(cft) // 2], fmt(t["error_u"]), t["residual_max"], worst(t)))
        for name, r, neighbour in res["peers"]:
            if "residual_max" not in r:
                lines.append("| %s | **%s**: %s | - | - | - | - | - | - | - | - | - | - |" % (name, r["status"], r["message"].replace("|", "/")))
                continue
            ratio = total(r) / total(neighbour)
            verdict = r["status"] if r["status"] == "ok" else "**%s** (%s)" % (r["status"], r["reason"])
            lines.append("| %s | %s | %d | %d | %d | %.2f | %.2f | %.2f | %.2f | %s | %.1e | %s |" % (name, verdict, r["iterations"], r["linear_iterations"], r["products"], r["cpu_setup"], r["cpu_solve"],
                                                                                             wall(r), ratio, fmt(r["error_u"]), r["residual_max"], worst(r)))
        lines.append("")
    lines.append("Columns: *products* are MatMult calls of the solve (with K and, for multigrid, the coarser levels) for the peers, "
                 "F products (n_A, two subdomain solves each) for conefeti; *CPU* is the process's user + system time (one rank), "
                 "*wall* the wall-clock setup + solve; *time / conefeti's* is the CPU setup + solve over that of the "
                 "conefeti run just before it (for the tight conefeti row: over the median); *error u* = |u - u_ref| / |u_ref|; residuals relative, from u alone (tutorials/contact/peers.cxx).")
    return "\n".join(lines)


def worst(r):
    checks = ["penetration", "normal_sign", "complementarity", "equilibrium"]
    return max(checks, key=lambda c: r[c])


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    series = {}
    for k, res in results:
        cf = res["conefeti"]
        cft = sorted(total(c) for c in res["conefeti_runs"])
        series.setdefault(CONEFETI, []).append((cf["n"], cft[len(cft) // 2], True))
        for name, r, _ in res["peers"]:
            if "residual_max" in r:
                series.setdefault(name, []).append((cf["n"], total(r), r["status"] == "ok"))
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for name, pts in series.items():
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        style = dict(color="black", linewidth=2.5, marker="o") if name == CONEFETI else dict(marker="o", linewidth=1)
        line, = ax.plot(xs, ys, label=name, **style)
        bad = [p for p in pts if not p[2]]
        if bad:
            ax.plot([p[0] for p in bad], [p[1] for p in bad], linestyle="none", marker="x", markersize=11, color=line.get_color())
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("n (unknowns)")
    ax.set_ylabel("setup + solve, CPU seconds")
    ax.set_title("Frictionless brick: conefeti and the PETSc peers (x: wrong or not converged)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def write_docs(text, md, png, results):
    begin, end = "<!-- bench-peers: begin (scripts/bench-peers.py writes this part) -->", "<!-- bench-peers: end -->"
    page = open(md).read() if os.path.exists(md) else "# conefeti and its PETSc peers\n\n%s\n%s\n" % (begin, end)
    if begin not in page or end not in page:
        sys.exit("bench-peers.py: %s has no markers %s ... %s" % (md, begin, end))
    head, rest = page.split(begin, 1)
    _, tail = rest.split(end, 1)
    open(md, "w").write(head + begin + "\n" + text + "\n\n![time against n](peers.png)\n" + end + tail)
    plot(results, png)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sizes", default="10,22")
    ap.add_argument("--large", action="store_true")
    ap.add_argument("--only", default="", help="run only the peers whose name matches this regular expression")
    ap.add_argument("--timeout", type=int, default=1800, help="wall-clock seconds per run (a loaded machine stretches them); a peer that takes longer is reported as such")
    ap.add_argument("--build", default="build")
    ap.add_argument("--hugepages", type=int, default=1)
    ap.add_argument("--no-docs", action="store_true")
    ap.add_argument("--docs", default="docs")
    ap.add_argument("--save", default=None, help="every result is written here as it comes (a run cut short keeps what it measured)")
    ap.add_argument("--from-saved", metavar="FILE", help="run nothing: write the tables and the plot from a file of --save")
    a = ap.parse_args()
    if a.from_saved:
        saved = json.load(open(a.from_saved))
        results = [(k, res) for k, res in saved["results"] if "conefeti" in res]
        text = tables(results, saved["args"])
        print(text)
        if not a.no_docs:
            write_docs(text, os.path.join(a.docs, "peers.md"), os.path.join(a.docs, "peers.png"), results)
        return
    a.save = a.save or os.path.join(a.build, "bench-peers.json")
    env = hugepages.environment(a.hugepages)
    sizes = [int(x) for x in a.sizes.split(",")] + ([48] if a.large else [])
    chosen = [(n, args) for n, args in PEERS if re.search(a.only, n)]
    results = []
    failed = {}  # peer name -> n at which it failed: not run at larger sizes (a failure does not heal with size)
    tmp = tempfile.mkdtemp(prefix="bench-peers-")
    for k in sizes:
        refpath = os.path.join(tmp, "ref%d.bin" % k)
        ref = peers(a.build, k, ["-peers_solver", "conefeti", "-contact_rtol", "1e-10", "-peers_save", refpath], env, 10 * a.timeout)
        if ref.get("status") != "ok":
            sys.exit("bench-peers.py: the reference solve failed at k = %d: %s" % (k, ref))
        R = ["-peers_reference", refpath]
        drv = driver(a.build, k, env, a.timeout)
        tight = peers(a.build, k, ["-peers_solver", "conefeti", "-contact_rtol", TIGHT] + R, env, a.timeout)
        res = dict(reference=ref, driver=drv, tight=tight, conefeti_runs=[], peers=[])
        for name, args in chosen:
            if name in failed:
                res["peers"].append((name, dict(status="not run", message="failed at n = %d" % failed[name]), None))
                continue
            cf = peers(a.build, k, ["-peers_solver", "conefeti"] + R, env, a.timeout)  # the neighbour of this peer run
            if cf.get("status") != "ok":
                sys.exit("bench-peers.py: conefeti failed at k = %d: %s" % (k, cf))
            res["conefeti_runs"].append(cf)
            r = peers(a.build, k, args + R, env, a.timeout)
            res["peers"].append((name, r, cf))
            res["conefeti"] = res["conefeti_runs"][0]
            json.dump(dict(args=sys.argv[1:], results=results + [(k, res)]), open(a.save, "w"))
            if r["status"] != "ok":
                failed[name] = ref["n"]
            print("k = %d  %-28s %-28s %s" % (k, name, r["status"], "time ratio %.2f, residual %.1e, error %.1e" % (total(r) / total(cf), r["residual_max"], r["error_u"]) if "residual_max" in r else r.get("message", "")), flush=True)
        if not res["conefeti_runs"]:
            res["conefeti_runs"].append(peers(a.build, k, ["-peers_solver", "conefeti"] + R, env, a.timeout))
        res["conefeti"] = res["conefeti_runs"][0]
        results.append((k, res))
        json.dump(dict(args=sys.argv[1:], results=results), open(a.save, "w"))
        os.remove(refpath)
    text = tables(results, sys.argv[1:])
    print(text)
    if not a.no_docs:
        write_docs(text, os.path.join(a.docs, "peers.md"), os.path.join(a.docs, "peers.png"), results)
    shutil.rmtree(tmp)


if __name__ == "__main__":
    main()
