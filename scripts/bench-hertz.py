#!/usr/bin/python3
"""Hertz validation: rigid sphere indentation of an elastic block (and an elastic hemisphere pressed onto a
rigid plane), computed by the conefeti program over several meshes and compared with Hertz's solution.

Cases (quarter models with symmetry planes x = 0 and y = 0; E = 1e9, nu = 0.3, R = 1; Hertz: E* = E/(1 - nu^2)):
  box         petsc-options/indentation.opts: a uniform box mesh (0,1)^3, n cells per axis (h = 1/n), clamped
              base, sphere pressed to d = 0.01 (a = sqrt(R d) = 0.1, P = 4/3 E* R^1/2 d^3/2, p0 = 2 E* a/(pi R))
  indentation the same block and sphere on a Gmsh mesh refined near the contact (meshes/indentation.geo, size h
              at the contact); needs a body read from a mesh (-scene_body<b>_mesh)
  hemisphere  petsc-options/hemisphere.opts: an elastic hemisphere (meshes/hemisphere.geo) pressed by P onto a
              rigid plane (a = (3 P R/(4 E*))^1/3 = 0.1, p0 = 3 P/(2 pi a^2)); needs -scene_body<b>_mesh

Per mesh: h at the contact, n (unknowns), subdomains, Iter, n_A, time (setup + solve), and from the HDF5 output:
a (contact radius: the midpoint between the farthest contact node and the nearest separated node from the
axis), P (the total force: 4 times the z component of the summary's contact force, the quarter model's
resultant), p0 (the pressure of the node on the axis), each with its error relative to Hertz. The finest
mesh's nodal pressures are plotted against Hertz's p(r) = p0 sqrt(1 - r^2/a^2).

usage: scripts/bench-hertz.py [--case box|indentation|hemisphere] [--sizes 10,20,30 | 0.04,0.02,0.01]
                              [--build build] [--ranks 1] [--write docs/validation.md] [--plot docs/figures/hertz-box.png]
                              [--check a=0.05,P=0.1,p0=0.1] [--extra "-option value ..."]
"""
import argparse, json, math, os, re, subprocess, sys, tempfile, time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
E, NU, R = 1e9, 0.3, 1.0
ESTAR = E / (1 - NU ** 2)
D = 0.01                                   # indentation depth of the box and indentation cases
Q = 4.664e5                                # pressure on the hemisphere's flat face (petsc-options/hemisphere.opts)


def hertz(case):
    """(a, P, p0) of Hertz's solution for the case"""
    if case == "hemisphere":
        P = Q * math.pi * R ** 2
        a = (3 * P * R / (4 * ESTAR)) ** (1 / 3)
        return a, P, 3 * P / (2 * math.pi * a ** 2)
    a = math.sqrt(R * D)
    return a, 4 / 3 * ESTAR * math.sqrt(R) * D ** 1.5, 2 * ESTAR * a / (math.pi * R)


def has_mesh_reader(build):
    out = subprocess.run([os.path.join(build, "conefeti"), "-help", "-scene_body0_lower", "0,0,0"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    return "scene_body0_mesh" in out


HBLOCK = 20.0                              # the graded block's width and height (meshes/indentation.geo): 200 a
HFAR = 1.0                                 # its mesh size far from the contact: the size grows from h by about 0.1 per unit of
                                           # distance (2.0, the .geo's default, leaves P about 1 % higher: docs/validation.md)


def gmsh(geo, h, out, **params):
    cmd = ["gmsh", "-3", os.path.join(ROOT, "meshes", geo), "-setnumber", "h", repr(h)]
    for k, v in params.items():
        cmd += ["-setnumber", k, repr(v)]
    subprocess.run(cmd + ["-o", out, "-v", "2"], check=True, stdout=subprocess.DEVNULL)


def options(case, size, tmp, subdomains=16):
    """the driver's options for one mesh, and h at the contact (subdomains: of the graded indentation block)"""
    if case == "box":
        n = int(size)
        sub = 2 if n <= 16 else 3
        return ["-options_file", os.path.join(ROOT, "petsc-options", "indentation.opts"), "-scene_body0_cells", "%d,%d,%d" % (n, n, n),
                "-scene_body0_subdomains", "%d,%d,%d" % (sub, sub, sub)], 1.0 / n
    h = float(size)
    msh = os.path.join(tmp, "%s-%g.msh" % (case, h))
    if case == "indentation":
        gmsh("indentation.geo", h, msh, L=HBLOCK, H=HBLOCK, hc=HFAR)
        return ["-scene_name", "indentation-graded", "-scene_body0_mesh", msh, "-scene_body0_E", repr(E), "-scene_body0_nu", repr(NU), "-scene_body0_subdomains", str(subdomains),
                "-scene_body0_fix", "bottom", "-scene_body0_fix_x", "sym_x", "-scene_body0_fix_y", "sym_y",
                "-scene_zone0_type", "foundation", "-scene_zone0_shape", "sphere", "-scene_zone0_body", "0", "-scene_zone0_face", "top",
                "-scene_zone0_center", "0,0,%r" % (HBLOCK + R - D), "-scene_zone0_radius", repr(R), "-scene_zone0_law", "frictionless"], h
    gmsh("hemisphere.geo", h, msh)
    return ["-options_file", os.path.join(ROOT, "petsc-options", "hemisphere.opts"), "-scene_body0_mesh", msh], h


def run(build, case, size, ranks, extra, tmp):
    opts, h = options(case, size, tmp)
    base = os.path.join(tmp, "%s-%s" % (case, size))
    cmd = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks), os.path.join(build, "conefeti")] + opts + extra + ["-output", base, "-summary_json", base + ".json", "-options_left", "0"]
    t0 = time.time()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.time() - t0
    if proc.returncode != 0:
        sys.exit("bench-hertz.py: %s failed (exit %d):\n%s" % (" ".join(cmd), proc.returncode, proc.stdout[-3000:]))
    with open(base + ".json") as f:
        js = json.loads(f.readline())
    with h5py.File(base + ".h5", "r") as f:
        X = f["/contact/coordinates"][()]
        p = f["/contact/pressure"][()]
        st = f["/contact/status"][()].reshape(-1)
    r = np.hypot(X[:, 0], X[:, 1])
    touching = st != 0
    a_in = r[touching].max() if touching.any() else 0.0
    a_out = r[~touching & (r > a_in)].min() if (~touching & (r > a_in)).any() else a_in
    axis = np.argmin(r)
    return {"h": h, "n": js["n"], "subdomains": js["subdomains"], "iter": js["iter"], "nA": js["n_A"], "time": js["time_setup"] + js["time_solve"], "wall": wall,
            "converged": js["converged"], "a": 0.5 * (a_in + a_out), "a_in": a_in, "a_out": a_out, "P": 4 * abs(js["contact_force"][2]), "p0": p[axis],
            "r": r, "p": p, "touching": touching, "cmd": " ".join(cmd)}


def table(case, rows):
    aH, PH, p0H = hertz(case)
    err = lambda x, ref: 100.0 * (x - ref) / ref
    out = ["| h at the contact | n | subdomains | Iter | n_A | time [s] | a | err a | P | err P | p0 | err p0 |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for x in rows:
        out.append("| %.4g (a/%.3g) | %d | %d | %d%s | %d | %.1f | %.4f (%.4f..%.4f) | %+.1f %% | %.4g | %+.1f %% | %.4g | %+.1f %% |" % (
            x["h"], aH / x["h"], x["n"], x["subdomains"], x["iter"], "" if x["converged"] else " (not converged)", x["nA"], x["time"], x["a"], x["a_in"], x["a_out"], err(x["a"], aH), x["P"],
            err(x["P"], PH), x["p0"], err(x["p0"], p0H)))
    out.append("")
    out.append("Hertz: a = %.4g, P = %.4g, p0 = %.4g." % (aH, PH, p0H))
    return "\n".join(out)


def plot(case, x, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    aH, PH, p0H = hertz(case)
    rr = np.linspace(0, aH, 200)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(rr / aH, np.sqrt(1 - (rr / aH) ** 2), "k-", label="Hertz p(r) = p0 sqrt(1 - r²/a²)")
    sel = x["r"] <= 2.0 * aH
    ax.plot(x["r"][sel] / aH, x["p"][sel] / p0H, "o", ms=3, label="conefeti, nodal pressure (h = %.3g)" % x["h"])
    ax.set_xlabel("r / a (Hertz)")
    ax.set_ylabel("p / p0 (Hertz)")
    ax.set_title({"box": "rigid sphere into a block, uniform box mesh", "indentation": "rigid sphere into a block, graded mesh",
                  "hemisphere": "elastic hemisphere on a rigid plane"}[case])
    ax.set_xlim(0, 2)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    fig.savefig(path, dpi=110)


def write_section(path, case, text, script="bench-hertz"):
    """replace the text between <!-- script:case --> and <!-- /script:case --> in path (also bench-cattaneo.py's)"""
    with open(path) as f:
        doc = f.read()
    start, end = "<!-- %s:%s -->" % (script, case), "<!-- /%s:%s -->" % (script, case)
    if start not in doc or end not in doc:
        sys.exit("%s.py: %s has no %s ... %s markers" % (script, path, start, end))
    doc = re.sub(re.escape(start) + ".*?" + re.escape(end), lambda m: start + "\n" + text + "\n" + end, doc, flags=re.S)
    with open(path, "w") as f:
        f.write(doc)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case", default="box", choices=["box", "indentation", "hemisphere"])
    ap.add_argument("--sizes", default=None, help="box: cells per axis (default 10,20,30); indentation, hemisphere: h at the contact (default 0.04,0.02,0.01)")
    ap.add_argument("--build", default="build")
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--extra", default="")
    ap.add_argument("--write", default=None, help="replace this case's table in the file (between its bench-hertz markers)")
    ap.add_argument("--plot", default=None, help="PNG of the finest mesh's nodal pressure against Hertz's p(r)")
    ap.add_argument("--check", default=None, help="e.g. a=0.05,P=0.1,p0=0.1: exit 1 unless every mesh converged and has these quantities within these relative errors of Hertz's")
    a = ap.parse_args()
    sizes = (a.sizes or ("10,20,30" if a.case == "box" else "0.04,0.02,0.01")).split(",")
    if a.case != "box" and not has_mesh_reader(a.build):
        sys.exit("bench-hertz.py: --case %s needs bodies read from Gmsh meshes (-scene_body<b>_mesh), which this conefeti does not have" % a.case)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for s in sizes:
            rows.append(run(a.build, a.case, s, a.ranks, a.extra.split(), tmp))
            print("# %s" % rows[-1]["cmd"].replace(tmp, "<tmp>"), file=sys.stderr)
    text = "command: `scripts/bench-hertz.py %s`\n\n%s" % (" ".join(sys.argv[1:]), table(a.case, rows))
    print(text)
    if a.write:
        write_section(a.write, a.case, text)
    if a.plot:
        plot(a.case, rows[-1], a.plot)
    if a.check:
        ref = dict(zip(("a", "P", "p0"), hertz(a.case)))
        bad = ["h = %g did not converge" % x["h"] for x in rows if not x["converged"]]
        for item in a.check.split(","):
            q, tol = item.split("=")
            bad += ["h = %g: %s = %.4g, %+.1f %% from Hertz's %.4g (allowed %g %%)" % (x["h"], q, x[q], 100 * (x[q] / ref[q] - 1), ref[q], 100 * float(tol))
                    for x in rows if abs(x[q] - ref[q]) > float(tol) * ref[q]]
        print("check: %s" % ("passed" if not bad else "failed: " + "; ".join(bad)))
        sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
