#!/usr/bin/python3
"""Contact between two elastic bodies with non-matching meshes against Hertz and Cattaneo-Mindlin, computed by the
conefeti program over several meshes (docs/validation.md, "Two elastic bodies").

The pair: an elastic hemisphere of radius R = 1, flat face up (meshes/pair-hemisphere.geo, body 0), whose curved
face touches the top z = 0 of an elastic block [-5,5]x[-5,5]x[-5,0] (meshes/pair-block.geo, body 1, base clamped)
at the origin. Each body has its own Gmsh mesh, graded toward the contact, the hemisphere's size h there and the
block's --ratio x h, so the two contact surfaces do not match; a node-to-surface zone joins them (the hemisphere's
nodes are the slaves). By default the whole pair is modelled; --part 2 models the half y >= 0 of both bodies (the
Gmsh files' part 2) on rollers on the symmetry plane y = 0, where the friction nodes keep their friction along the
plane (docs/contact.md, "Friction on a symmetry plane"): half the unknowns for the same mesh size, and the shift
along x is symmetric about that plane. The hemisphere's flat face (the grip) is moved by (dx, 0, -dz), dz = 0.01:
P and Q are results, the normal and tangential components of the contact force (the JSON line's contact_force on
the hemisphere, times 2 for a half pair); the node counts of the tables are those of the model (the half's).

Cases:
  hertz    petsc-options/hertz-pair.opts: frictionless, dx = 0, hemisphere E1 = 1e9, nu1 = 0.3, block E2 = 2e9,
           nu2 = 0.2. Hertz for the computed P: E* = 1/((1 - nu1^2)/E1 + (1 - nu2^2)/E2),
           a = (3 P R/(4 E*))^(1/3), p0 = 3 P/(2 pi a^2), p(r) = p0 sqrt(1 - r^2/a^2).
  mindlin  petsc-options/cattaneo.opts: one material (E = 1e9, nu = 0.3: the normal and tangential problems
           decouple), Coulomb mu = 0.3. Hertz's a, p0 from P; Cattaneo-Mindlin's stick radius
           c = a (1 - Q/(mu P))^(1/3) and traction q(r) = mu p0 sqrt(1 - r^2/a^2) for c < r < a,
           mu p0 [sqrt(1 - r^2/a^2) - (c/a) sqrt(1 - r^2/c^2)] for r < c. dx is chosen for each target
           Q/(mu P) (--targets) from Mindlin's tangential compliance
           delta = 3 mu P (2 - nu)/(8 G a) [1 - (1 - Q/(mu P))^(2/3)] times a factor fitted to the runs already
           made (the grip and the base are at a finite distance: the bodies are not half-spaces); a run farther
           than --tolerance from its target is repeated once with the new factor.
  rigid-hertz     (no two-body features needed) the quarter hemisphere of meshes/pair-hemisphere.geo pressed by a
                  pressure on its grip onto a rigid plane, frictionless: Hertz with E* = E1/(1 - nu1^2)
  rigid-friction  (no two-body features needed) the whole hemisphere, its grip clamped, on a rigid plane raised
                  by dz into it, Coulomb mu = 0.3, pushed along x by a volume force fx chosen for each target
                  Q/(mu P). Not a validation (a rigid plane couples the normal and tangential problems; a volume
                  force is not a shift): it exercises the reading of pressures, tangential tractions and stick/slip
                  states and the plots; the theory curves are drawn for reference only. (A traction on the grip
                  instead rolls the hemisphere: its moment Q R exceeds what a contact of radius a resists, about P a.)

Measured per run (the HDF5 output, docs/output.md "/contact"; r = sqrt(x^2 + y^2) of the contact node):
  a   the midpoint between the farthest node in contact and the nearest separated node beyond it (in brackets)
  a (moment)  sqrt(5/2 sum(l r^2)/sum(l)) over the normal forces l of the nodes (Hertz: the mean of r^2 over p(r) is
      2 a^2/5): the spread of the force, free of the one node that lies at the edge
  p0  the pressure of the contact node nearest the axis; "p0 fit": p0 of the least-squares fit
      p^2 = p0^2 (1 - r^2/a^2) over the nodes with r < 0.8 a
  c   the midpoint between the farthest stick node and the nearest slip node beyond it (in brackets)
  q   the tangential traction's component along the shift (its sign chosen so that it is positive on the whole), and
      the RMS of q - q_Mindlin over the nodes in contact relative to mu p0

usage: scripts/bench-cattaneo.py --case hertz|mindlin|rigid-hertz|rigid-friction [--sizes 0.04,0.02,0.01]
           [--part 1|2] [--ratio 1.3] [--targets 0.25,0.5,0.75] [--tolerance 0.03] [--build build] [--ranks 1]
           [--block 5,5] [--write docs/validation.md] [--plot-dir docs/figures] [--check a=0.05,p0=0.1,c=1] [--keep DIR]
           [--extra "-option value ..."]
  --check: exit 1 unless every run converged and each quantity is within its bound: a, p0, p0_fit relative errors;
           c in units of the hemisphere's mesh size h (|c - c_theory| <= c_bound h)
"""
import argparse, importlib.util, json, math, os, subprocess, sys, tempfile, time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# the marked sections of docs/validation.md are written as bench-hertz.py writes its own
_spec = importlib.util.spec_from_file_location("hertz", os.path.join(ROOT, "scripts", "bench-hertz.py"))
hertz = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(hertz)
R = 1.0
MU = 0.3
# hertz: dissimilar materials; mindlin: one material
E1, NU1 = 1e9, 0.3                 # hemisphere
E2, NU2 = 2e9, 0.2                 # block (hertz only)
VOLUME = 2 * math.pi * R ** 3 / 3  # the hemisphere's
A_AIM = 0.1                        # the contact radius aimed at (a/R = 0.1): force driven cases get P = 4 E* a^3/(3 R)
DZ = 0.01                          # the grip's downward displacement (Hertz approach a^2/R for a = 0.1)
BLOCK = [5.0, 5.0]                 # the block: half width and height (50 a for a = 0.1); --block


def materials(case):
    """(E1, nu1, E2, nu2); E2 is None for a rigid plane"""
    if case == "hertz":
        return E1, NU1, E2, NU2
    if case == "mindlin":
        return E1, NU1, E1, NU1
    return E1, NU1, None, None


def estar(case):
    e1, n1, e2, n2 = materials(case)
    return 1.0 / ((1 - n1 ** 2) / e1 + ((1 - n2 ** 2) / e2 if e2 else 0.0))


def grip_pressure(case):
    """force driven cases: the pressure on the grip that gives Hertz's a = A_AIM (P = q pi R^2 = 4 E* a^3/(3 R))"""
    return 4 * estar(case) * A_AIM ** 3 / (3 * R) / (math.pi * R ** 2)


def hertz_of_P(case, P):
    """(a, p0) of Hertz's solution for the total normal force P"""
    a = (3 * P * R / (4 * estar(case))) ** (1 / 3)
    return a, 3 * P / (2 * math.pi * a ** 2)


def hertz_p(r, a, p0):
    """Hertz's pressure p0 sqrt(1 - r^2/a^2) at distances r (0 beyond a)"""
    return p0 * np.sqrt(np.clip(1 - (r / a) ** 2, 0, None))


def mindlin_q(r, a, p0, c):
    """Mindlin's tangential traction for the stick radius c, at distances r"""
    q = MU * hertz_p(r, a, p0)
    return q - np.where(r < c, MU * p0 * (c / a) * np.sqrt(np.clip(1 - (r / max(c, 1e-300)) ** 2, 0, None)), 0.0)


def mindlin_shift(P, k):
    """Mindlin's tangential compliance of two half-spaces of the hemisphere's material: the relative shift of
    distant points that gives Q = k mu P"""
    a, _ = hertz_of_P("mindlin", P)
    G = E1 / (2 * (1 + NU1))
    return 3 * MU * P * (2 * (2 - NU1) / G) / (16 * a) * (1 - (1 - k) ** (2 / 3))


def gmsh(geo, out, **params):
    cmd = ["gmsh", "-3", os.path.join(ROOT, "meshes", geo)]
    for k, v in params.items():
        cmd += ["-setnumber", k, repr(v)]
    subprocess.run(cmd + ["-o", out, "-v", "2"], check=True, stdout=subprocess.DEVNULL)


def mesh_nodes(msh):
    """the number of nodes of a Gmsh file (MSH 4: the $Nodes header's second number)"""
    with open(msh) as f:
        for line in f:
            if line.startswith("$Nodes"):
                return int(next(f).split()[1])
    return 0


def subdomains_for(msh):
    """METIS subdomains of a body: about 700 nodes each, at least 2"""
    return max(2, round(mesh_nodes(msh) / 700))


PART = {"hertz": 1, "mindlin": 1, "rigid-hertz": 4, "rigid-friction": 1}
SCENE = {"hertz": "hertz-pair.opts", "mindlin": "cattaneo.opts"}


def scene_options(case, h, ratio, tmp, dx=0.0):
    """the driver's options for one run: the two-body cases are petsc-options/hertz-pair.opts and cattaneo.opts
    with the meshes made here (the hemisphere's size h, the block's ratio h) and the grip's displacement
    (dx, 0, -DZ); the rigid cases are written out here"""
    part = PART[case]
    hemi = os.path.join(tmp, "hemisphere-%s-%g.msh" % (case, h))
    gmsh("pair-hemisphere.geo", hemi, part=part, h=h)
    if case in SCENE:
        block = os.path.join(tmp, "block-%s-%g.msh" % (case, h))
        gmsh("pair-block.geo", block, part=part, h=ratio * h, L=BLOCK[0], H=BLOCK[1])
        rollers = ["-scene_body0_fix_y", "sym_y", "-scene_body1_fix_y", "sym_y"] if part == 2 else []   # the symmetry plane y = 0
        return ["-options_file", os.path.join(ROOT, "petsc-options", SCENE[case]), "-scene_body0_mesh", hemi, "-scene_body0_subdomains", str(subdomains_for(hemi)),
                "-scene_body1_mesh", block, "-scene_body1_subdomains", str(subdomains_for(block)), "-scene_body0_displace0_value", "%r,0,%r" % (dx, -DZ)] + rollers
    opts = ["-scene_name", case, "-scene_body0_mesh", hemi, "-scene_body0_E", repr(E1), "-scene_body0_nu", repr(NU1), "-scene_body0_subdomains", str(subdomains_for(hemi))]
    if case == "rigid-hertz":   # the quarter, pressed by a traction on the grip
        return opts + ["-scene_body0_fix_x", "sym_x", "-scene_body0_fix_y", "sym_y", "-scene_body0_traction0_face", "grip", "-scene_body0_traction0_value",
                       "0,0,%r" % -grip_pressure(case)] + plane_zone_options("frictionless")
    # rigid-friction: the grip clamped, the plane raised by DZ into the hemisphere, a volume force along x (dx here)
    return opts + ["-scene_body0_fix", "grip", "-scene_body0_force", "%r,0,0" % dx] + plane_zone_options("coulomb", DZ)


def plane_zone_options(law, z=0.0):
    """the rigid plane z = z under the hemisphere (z > 0: an initial overlap, the approach)"""
    opts = ["-scene_zone0_type", "foundation", "-scene_zone0_shape", "plane", "-scene_zone0_body", "0", "-scene_zone0_face", "curved",
            "-scene_zone0_point", "0,0,%r" % z, "-scene_zone0_normal", "0,0,1", "-scene_zone0_law", law]
    return opts + (["-scene_zone0_friction", repr(MU)] if law == "coulomb" else [])


def command(build, ranks, opts, extra, base):
    return ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks), os.path.join(build, "conefeti")] + opts + extra + [
        "-output", base, "-summary_json", base + ".json", "-options_left", "0"]


def fit_p0(r, p, a):
    """p0 and a of the least-squares fit p^2 = p0^2 - (p0/a)^2 r^2 over the nodes with r < 0.8 a"""
    sel = (r < 0.8 * a) & (p > 0)
    if sel.sum() < 3:
        return float("nan"), float("nan")
    A = np.vstack([np.ones(sel.sum()), r[sel] ** 2]).T
    c0, c1 = np.linalg.lstsq(A, p[sel] ** 2, rcond=None)[0]
    return math.sqrt(max(c0, 0.0)), (math.sqrt(-c0 / c1) if c1 < 0 < c0 else float("nan"))


def ring_means(r, q, area, a, sel, width=0.125):
    """area-weighted means of q and r over the selected nodes in rings [k w a, (k + 1) w a) up to a"""
    rm, qm = [], []
    for k in range(int(round(1 / width))):
        m = sel & (r >= k * width * a) & (r < (k + 1) * width * a)
        if m.any() and area[m].sum() > 0:
            rm.append(np.sum(area[m] * r[m]) / area[m].sum())
            qm.append(np.sum(area[m] * q[m]) / area[m].sum())
    return np.array(rm), np.array(qm), None


def bracket(r, inner, outer):
    """(midpoint, farthest inner, nearest outer beyond it): a radius between two node sets"""
    r_in = r[inner].max() if inner.any() else 0.0
    beyond = outer & (r > r_in)
    r_out = r[beyond].min() if beyond.any() else r_in
    return 0.5 * (r_in + r_out), r_in, r_out


def analyse(case, base, js, part, h):
    with h5py.File(base + ".h5", "r") as f:
        X = f["/contact/coordinates"][()]
        p = f["/contact/pressure"][()]
        T = f["/contact/tangential_stress"][()]
        st = f["/contact/status"][()].reshape(-1)
        body = f["/contact/body"][()].reshape(-1)
        area = f["/contact/area"][()]
    r = np.hypot(X[:, 0], X[:, 1])
    touching = st != 0
    res = {"h": h, "n": js["n"], "subdomains": js["subdomains"], "iter": js["iter"], "nA": js["n_A"], "time": js["time_setup"] + js["time_solve"],
           "converged": js["converged"], "reason": js.get("reason", ""), "residual": js["residuals"]["max"], "X": X, "r": r, "p": p, "status": st, "area": area,
           "contact_nodes": js["contact_nodes"], "stick": js["stick"], "slip": js["slip"], "separated": js["separated"]}
    res["a"], res["a_in"], res["a_out"] = bracket(r, touching, ~touching)
    axis = np.argmin(r)
    res["p0"] = p[axis]
    res["P"] = part * abs(js["contact_force"][2])
    res["Q"] = part * abs(js["contact_force"][0])
    # the friction traction on the hemisphere is -tangential_stress when its nodes carry the rows (docs/output.md), the
    # traction on the block the opposite; both oppose... either way, q is taken along the shift's direction so that
    # it is positive where the bodies stick
    sign = -1.0 if (body == 0).all() else 1.0
    qx = sign * T[:, 0]
    if np.sum(qx[touching]) < 0:
        qx = -qx
    res["q"] = qx
    res["qabs"] = np.linalg.norm(T, axis=1)
    force_driven = case == "rigid-hertz"
    res["P_applied"] = grip_pressure(case) * math.pi * R ** 2 if force_driven else None
    Pth = res["P_applied"] if force_driven else res["P"]
    res["a_th"], res["p0_th"] = hertz_of_P(case, Pth)
    res["p0_fit"], res["a_fit"] = fit_p0(r, p, res["a_th"])
    res["p_rings"] = ring_means(r, p, area, res["a_th"], touching)[:2]
    # a half (quarter) model: the mean of p over Hertz's p(r) for the nodes on the symmetry planes and for the others,
    # over r < 0.7 a (where p(r) is not small), to see whether the planes' nodes carry their share
    ph = hertz_p(r, res["a_th"], res["p0_th"])
    inner = r < 0.7 * res["a_th"]
    plane = np.abs(X[:, 1]) <= 1e-9 * R          # y = 0 (half and quarter)
    if part == 4:
        plane |= np.abs(X[:, 0]) <= 1e-9 * R     # x = 0 (quarter)
    on_plane = inner & plane
    res["plane_ratio"] = (float(np.mean(p[on_plane] / ph[on_plane])), int(on_plane.sum()), float(np.mean(p[inner & ~on_plane] / ph[inner & ~on_plane])),
                          int((inner & ~on_plane).sum())) if part > 1 and on_plane.any() and (inner & ~on_plane).any() else None
    # the contact radius from the second moment of the normal forces: for Hertz's p(r), the mean of r^2 over the
    # pressure is 2 a^2/5 (free of the node that happens to lie at the edge)
    lam = p * area
    res["a_mom"] = math.sqrt(2.5 * np.sum(lam * r * r) / np.sum(lam)) if np.sum(lam) > 0 else float("nan")
    if case in ("mindlin", "rigid-friction"):
        k = res["Q"] / (MU * res["P"]) if res["P"] > 0 else float("nan")
        res["k"] = k
        res["c_th"] = res["a_th"] * max(1 - k, 0.0) ** (1 / 3)
        stick, slip = st == 1, st == 2
        res["c"], res["c_in"], res["c_out"] = bracket(r, stick, slip)
        qm = mindlin_q(r, res["a_th"], res["p0_th"], res["c_th"])
        res["q_rms"] = float(np.sqrt(np.mean((qx[touching] - qm[touching]) ** 2)) / (MU * res["p0_th"])) if touching.any() else float("nan")
        # ring means: the area-weighted mean of q over the nodes in rings of width a/8 (the nodal values of an
        # unstructured mesh scatter; a ring's resultant is what the mesh determines well), against Mindlin's at
        # the ring's area-weighted mean radius
        rm, qm_ring, qth_ring = ring_means(r, qx, area, res["a_th"], touching)
        res["rings"] = (rm, qm_ring)
        res["q_ring_rms"] = float(np.sqrt(np.mean((qm_ring - mindlin_q(rm, res["a_th"], res["p0_th"], res["c_th"])) ** 2)) / (MU * res["p0_th"])) if len(rm) else float("nan")
    return res


def run(a, case, h, tmp, dx=0.0):
    part = PART[case]
    opts = scene_options(case, h, a.ratio, tmp, dx)
    base = os.path.join(tmp, "%s-%g-%.3e" % (case, h, dx))
    cmd = command(a.build, a.ranks, opts, a.extra.split(), base)
    t0 = time.time()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.time() - t0
    shown = " ".join(cmd).replace(tmp, "<tmp>")
    print("# %s  (exit %d, %.0f s)" % (shown, proc.returncode, wall), file=sys.stderr)
    if proc.returncode not in (0, 2) or not os.path.exists(base + ".h5"):
        if proc.returncode == 2:
            print("bench-cattaneo.py: not converged and no output (add -output_unconverged to --extra to see it):\n%s" % proc.stdout[-2000:], file=sys.stderr)
            return None
        sys.exit("bench-cattaneo.py: %s failed (exit %d):\n%s" % (shown, proc.returncode, proc.stdout[-3000:]))
    with open(base + ".json") as f:
        js = json.loads(f.readline())
    res = analyse(case, base, js, part, h)
    res.update({"part": part, "wall": wall, "dx": dx, "cmd": shown})
    return res


def pct(x, ref):
    return 100.0 * (x - ref) / ref


def hertz_table(case, rows, ratio):
    applied = "applied %.4g" % rows[0]["P_applied"] if rows[0]["P_applied"] else "the contact force"
    out = ["| h hemisphere / block | n | subdomains | Iter | n_A | time [s] | P (%s) | a (Hertz) | a | err a | a (moment) | err | p0 (Hertz) | p0 (axis) | err p0 | p0 fit | err | max residual |" % applied,
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for x in rows:
        hb = "%.4g / %.4g" % (x["h"], ratio * x["h"]) if case == "hertz" else "%.4g / rigid" % x["h"]
        out.append("| %s (a/%.3g) | %d | %d | %d%s | %d | %.1f | %.4g | %.4f | %.4f (%.4f..%.4f) | %+.1f %% | %.4f | %+.1f %% | %.4g | %.4g | %+.1f %% | %.4g | %+.1f %% | %.1e |" % (
            hb, x["a_th"] / x["h"], x["n"], x["subdomains"], x["iter"], "" if x["converged"] else " (not converged)", x["nA"], x["time"], x["P"], x["a_th"], x["a"], x["a_in"],
            x["a_out"], pct(x["a"], x["a_th"]), x["a_mom"], pct(x["a_mom"], x["a_th"]), x["p0_th"], x["p0"], pct(x["p0"], x["p0_th"]), x["p0_fit"], pct(x["p0_fit"], x["p0_th"]), x["residual"]))
    out += ["", "Hertz from %s: E* = %.4g, a = (3 P R/(4 E*))^(1/3), p0 = 3 P/(2 pi a^2).%s" % ("the applied P" if rows[0]["P_applied"] else "each run's P", estar(case), model_note(case, rows))]
    ratios = ["h = %.4g: %.3f (%d nodes) and %.3f (%d)" % ((x["h"],) + x["plane_ratio"]) for x in rows if x.get("plane_ratio")]
    if ratios:
        out += ["", "Mean of p / p_Hertz(r) over the nodes with r < 0.7 a, on the symmetry plane%s and off it: " % (" y = 0" if rows[0]["part"] == 2 else "s") + "; ".join(ratios) + "."]
    return "\n".join(out)


def model_note(case, rows):
    """what part of the pair the runs modelled (the two-body cases)"""
    if case not in SCENE:
        return ""
    if rows[0]["part"] == 2:
        return " The half pair y >= 0 on rollers on y = 0: n and the node counts are the half's, P and Q twice its contact force."
    return " The whole pair."


def mindlin_table(case, rows, ratio):
    out = ["| h hemisphere / block | n | Iter | n_A | time [s] | %s | P |" % ("dx" if case == "mindlin" else "fx") + " Q | Q/(mu P) | a (Hertz) | a | err a | a (moment) | err | p0 (Hertz) | p0 (axis) | err p0 | p0 fit | err | "
           "c (Mindlin) | c | (c - c_M)/h | q RMS err / (mu p0): nodes, rings | stick / slip / separated |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for x in rows:
        hb = "%.4g / %.4g" % (x["h"], ratio * x["h"]) if case == "mindlin" else "%.4g / rigid" % x["h"]
        out.append("| %s | %d | %d%s | %d | %.1f | %.3e | %.4g | %.4g | %.3f | %.4f | %.4f (%.4f..%.4f) | %+.1f %% | %.4f | %+.1f %% | %.4g | %.4g | %+.1f %% | %.4g | %+.1f %% | %.4f | %.4f (%.4f..%.4f) | %+.2f | %.3f, %.3f | %d / %d / %d |" % (
            hb, x["n"], x["iter"], "" if x["converged"] else " (not converged)", x["nA"], x["time"], x["dx"], x["P"], x["Q"], x["k"], x["a_th"], x["a"], x["a_in"], x["a_out"],
            pct(x["a"], x["a_th"]), x["a_mom"], pct(x["a_mom"], x["a_th"]), x["p0_th"], x["p0"], pct(x["p0"], x["p0_th"]), x["p0_fit"], pct(x["p0_fit"], x["p0_th"]), x["c_th"], x["c"], x["c_in"], x["c_out"], (x["c"] - x["c_th"]) / x["h"], x["q_rms"], x["q_ring_rms"],
            x["stick"], x["slip"], x["separated"]))
    out += ["", "Theory from each run's P and Q: E* = %.4g, a = (3 P R/(4 E*))^(1/3), p0 = 3 P/(2 pi a^2), c = a (1 - Q/(mu P))^(1/3), mu = %g.%s" % (estar(case), MU, model_note(case, rows))]
    return "\n".join(out)


def plot_hertz(case, x, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    a, p0 = x["a_th"], x["p0_th"]
    rr = np.linspace(0, a, 200)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(rr / a, np.sqrt(1 - (rr / a) ** 2), "k-", label="Hertz p(r) = p0 sqrt(1 - r²/a²)")
    sel = x["r"] <= 2.0 * a
    ax.plot(x["r"][sel] / a, x["p"][sel] / p0, "o", ms=3, alpha=0.5, label="conefeti, nodal pressure (h = %.3g)" % x["h"])
    ax.plot(x["p_rings"][0] / a, x["p_rings"][1] / p0, "s--", ms=5, lw=0.8, label="ring means (width a/8)")
    ax.set_xlabel("r / a (Hertz)")
    ax.set_ylabel("p / p0 (Hertz)")
    ax.set_title({"hertz": "elastic hemisphere on an elastic block, non-matching meshes", "rigid-hertz": "elastic hemisphere on a rigid plane"}.get(case, case) +
                 (" (half pair)" if x["part"] == 2 and case in SCENE else ""), fontsize=10)
    ax.set_xlim(0, 2)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_mindlin(case, xs, path_profiles, path_map):
    """xs: the runs of one mesh, one per target"""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    colors = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple"]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for i, x in enumerate(xs):
        a, p0, c = x["a_th"], x["p0_th"], x["c_th"]
        rr = np.linspace(0, a, 300)
        sel = (x["r"] <= 1.6 * a)
        col = colors[i % len(colors)]
        lab = "Q/(mu P) = %.2f" % x["k"]
        ax1.plot(x["r"][sel] / a, x["p"][sel] / p0, "o", ms=2, color=col, alpha=0.35, label="conefeti nodes, %s" % lab)
        ax1.plot(x["p_rings"][0] / a, x["p_rings"][1] / p0, "s--", ms=5, lw=0.8, color=col, label="ring means")
        ax2.plot(x["r"][sel] / a, x["q"][sel] / (MU * p0), "o", ms=2, color=col, alpha=0.35, label="conefeti nodes, %s" % lab)
        ax2.plot(x["rings"][0] / a, x["rings"][1] / (MU * p0), "s--", ms=5, lw=0.8, color=col, label="ring means (width a/8)")
        ax2.plot(rr / a, mindlin_q(rr, a, p0, c) / (MU * p0), "-", color=col, lw=1.5, label="Mindlin, c/a = %.3f" % (c / a))
    rr = np.linspace(0, 1, 200)
    ax1.plot(rr, np.sqrt(1 - rr ** 2), "k-", lw=1.5, label="Hertz")
    ax2.plot(rr, np.sqrt(1 - rr ** 2), "k:", lw=1, label="mu p (full slip)")
    for ax, lab in ((ax1, "p / p0"), (ax2, "q / (mu p0), along the shift")):
        ax.set_xlabel("r / a (Hertz, from each run's P)")
        ax.set_ylabel(lab)
        ax.set_xlim(0, 1.6)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    ax1.set_ylim(bottom=0)
    fig.suptitle({"mindlin": "Cattaneo-Mindlin: hemisphere on a block, one material, non-matching meshes (h = %.3g" + (", half pair)" if xs[0]["part"] == 2 else ")"),
                  "rigid-friction": "hemisphere on a rigid plane, Coulomb, pushed by a volume force (a reading test, not a validation; h = %.3g)"}[case] % xs[0]["h"], fontsize=10)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(path_profiles)), exist_ok=True)
    fig.savefig(path_profiles, dpi=110)
    plt.close(fig)

    fig, axs = plt.subplots(1, len(xs), figsize=(4 * len(xs), 4.2), squeeze=False)
    t = np.linspace(0, 2 * np.pi, 300)
    for ax, x in zip(axs[0], xs):
        a, c = x["a_th"], x["c_th"]
        X, st = x["X"], x["status"]
        sel = x["r"] <= 1.5 * a
        for s, col, lab in ((0, "lightgray", "separated"), (1, "tab:blue", "stick"), (2, "tab:red", "slip")):
            m = sel & (st == s)
            # a half model y >= 0 mirrored to y < 0 (the symmetry plane y = 0)
            xs_, ys_ = (np.r_[X[m, 0], X[m, 0]], np.r_[X[m, 1], -X[m, 1]]) if x["part"] == 2 else (X[m, 0], X[m, 1])
            ax.scatter(xs_ / a, ys_ / a, s=6, c=col, label=lab)
        ax.plot(np.cos(t), np.sin(t), "k-", lw=1, label="a (Hertz)")
        ax.plot(c / a * np.cos(t), c / a * np.sin(t), "k--", lw=1, label="c (Mindlin)")
        ax.set_aspect("equal")
        ax.set_xlim(-1.5, 1.5)
        ax.set_ylim(-1.5, 1.5)
        ax.set_title("Q/(mu P) = %.2f" % x["k"], fontsize=10)
        ax.set_xlabel("x / a")
    axs[0][0].set_ylabel("y / a" + (" (y < 0 mirrored)" if xs[0]["part"] == 2 else ""))
    axs[0][-1].legend(fontsize=7, loc="upper right")
    fig.suptitle("stick/slip map of the contact nodes (h = %.3g)" % xs[0]["h"], fontsize=10)
    fig.tight_layout()
    fig.savefig(path_map, dpi=110)
    plt.close(fig)


def driven_runs(a, case, h, tmp, state):
    """the runs of one mesh for every target Q/(mu P); state carries the shift factor fitted so far"""
    rows = []
    for k in [float(t) for t in a.targets.split(",")]:
        x = None
        for attempt in range(2):
            P = state.get("P", 4 / 3 * estar(case) * math.sqrt(R) * DZ ** 1.5)   # the last run's (the normal problem does not depend on dx)
            if case == "mindlin":
                dx = state.get("s", 1.0) * mindlin_shift(P, k)
            else:   # rigid-friction: the volume force density, Q = s fx V (V the hemisphere's volume)
                dx = k * MU * P / (state.get("s", 0.3) * VOLUME)
            x = run(a, case, h, tmp, dx=dx)
            if x is None:
                break
            state["P"] = x["P"]
            if case == "rigid-friction":
                state["s"] = x["Q"] / (dx * VOLUME)
            elif 0 < x["k"] < 1 and dx > 0:   # (--targets 0: pressing alone, nothing to fit)
                state["s"] = dx / mindlin_shift(x["P"], x["k"])
            print("#   target %.2f: Q/(mu P) = %.3f, shift factor now %.3f" % (k, x["k"], state.get("s", 1.0)), file=sys.stderr)
            if abs(x["k"] - k) <= a.tolerance:
                break
        if x:
            x["target"] = k
            rows.append(x)
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case", default="hertz", choices=["hertz", "mindlin", "rigid-hertz", "rigid-friction"])
    ap.add_argument("--sizes", default="0.04,0.02,0.01", help="the hemisphere's mesh size h at the contact")
    ap.add_argument("--part", type=int, default=1, choices=[1, 2], help="hertz, mindlin: the whole pair (1) or the half y >= 0 on rollers on y = 0 (2)")
    ap.add_argument("--ratio", type=float, default=1.3, help="the block's mesh size at the contact / h")
    ap.add_argument("--targets", default="0.25,0.5,0.75", help="mindlin, rigid-friction: the Q/(mu P) aimed at")
    ap.add_argument("--tolerance", type=float, default=0.03, help="mindlin: repeat a run once when Q/(mu P) is farther than this from its target")
    ap.add_argument("--block", default="5,5", help="the block's half width and height (the finite-size check)")
    ap.add_argument("--build", default="build")
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--extra", default="")
    ap.add_argument("--keep", default=None, help="keep the meshes and outputs in this directory")
    ap.add_argument("--write", default=None, help="replace this case's table in the file (between its bench-cattaneo markers)")
    ap.add_argument("--section", default=None, help="the markers' name for --write (default: the case)")
    ap.add_argument("--plot-dir", default=None, help="PNGs of the finest mesh: hertz-pair-pressure.png (hertz); cattaneo-traction.png and cattaneo-stick-slip.png "
                    "(mindlin); <case>-... for the rigid cases")
    ap.add_argument("--check", default=None, help="e.g. a=0.05,p0=0.1,c=1: see above")
    a = ap.parse_args()
    if a.part != 1:
        if a.case not in SCENE:
            sys.exit("bench-cattaneo.py: --part %d is for --case hertz or mindlin (the rigid cases choose their own part)" % a.part)
        PART[a.case] = a.part
    sizes = [float(s) for s in a.sizes.split(",")]
    BLOCK[:] = [float(v) for v in a.block.split(",")]
    driven = a.case in ("mindlin", "rigid-friction")
    rows, state = [], {}
    with tempfile.TemporaryDirectory() as tmpdir:
        tmp = a.keep or tmpdir
        os.makedirs(tmp, exist_ok=True)
        for h in sizes:
            if driven:
                rows += driven_runs(a, a.case, h, tmp, state)
            else:
                x = run(a, a.case, h, tmp)
                if x:
                    rows.append(x)
    if not rows:
        sys.exit("bench-cattaneo.py: no run gave a result")
    table = (mindlin_table if driven else hertz_table)(a.case, rows, a.ratio)
    text = "command: `scripts/bench-cattaneo.py %s`\n\n%s" % (" ".join(sys.argv[1:]), table)
    print(text)
    if a.write:
        hertz.write_section(a.write, a.section or a.case, text, "bench-cattaneo")
    if a.plot_dir:
        hmin = min(x["h"] for x in rows)
        finest = [x for x in rows if x["h"] == hmin]
        name = {"hertz": "hertz-pair", "mindlin": "cattaneo"}.get(a.case, a.case)
        if driven:
            plot_mindlin(a.case, finest, os.path.join(a.plot_dir, "%s-traction.png" % name), os.path.join(a.plot_dir, "%s-stick-slip.png" % name))
        else:
            plot_hertz(a.case, finest[-1], os.path.join(a.plot_dir, "%s-pressure.png" % name))
    if a.check:
        bad = ["h = %g did not converge (%s)" % (x["h"], x["reason"]) for x in rows if not x["converged"]]
        if len(rows) < len(sizes) * (len(a.targets.split(",")) if driven else 1):
            bad.append("a run gave no result")
        for item in a.check.split(","):
            q, tol = item.split("=")
            tol = float(tol)
            for x in rows:
                if q == "c":
                    err = abs(x["c"] - x["c_th"]) / x["h"]
                    if not err <= tol:
                        bad.append("h = %g, Q/(mu P) = %.3f: c = %.4g, Mindlin's %.4g, %.2f h apart (allowed %g h)" % (x["h"], x["k"], x["c"], x["c_th"], err, tol))
                else:
                    ref = x["p0_th"] if q == "p0_fit" else x[q + "_th"]
                    if not abs(x[q] - ref) <= tol * ref:
                        bad.append("h = %g: %s = %.4g, %+.1f %% from the theory's %.4g (allowed %g %%)" % (x["h"], q, x[q], pct(x[q], ref), ref, 100 * tol))
        print("check: %s" % ("passed" if not bad else "failed: " + "; ".join(bad)))
        sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
