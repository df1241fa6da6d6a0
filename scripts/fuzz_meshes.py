"""Random scenes on meshed geometry for scripts/fuzz-scenes.py (--family meshes).

The box family of fuzz-scenes.py meshes its own boxes; this one takes the repository's Gmsh geometries
(meshes/*.geo) at random coarse mesh sizes, so that curved contact faces, unstructured tetrahedra, METIS
cuts of them, rigid spheres and cylinders, and two bodies with non-matching meshes are drawn too:

* hemisphere  a quarter hemisphere (meshes/hemisphere.geo, rollers on its symmetry planes) on a rigid plane,
              plane or tilted, touching, with a small or a large gap, or overlapping; pressed by a traction on its
              flat face (sometimes pulled away: no equilibrium), or its flat face moved down (clamped)
* indenter    the block of meshes/indentation.geo clamped at its base, pressed by a rigid sphere or a
              cylinder that overlaps its top (or stays clear of it: no load), sometimes a traction on a side
* pair        the hemisphere of meshes/pair-hemisphere.geo on the block of meshes/pair-block.geo (a quarter, a
              half or the whole pair; rollers on the symmetry planes), node to surface: the grip moved down
              (and sideways where no roller forbids it), or loaded by a traction (the hemisphere then floats)
* block-hole  the block with a hole (meshes/block-hole.geo) on a rigid floor: free (held by contact only),
              on rollers, or clamped at one end; pressure and shear on its top, a volume force
* volumes     the two volumes of meshes/two-volumes.geo, node to node on the surface between them: the lower
              one clamped, the upper one pressed and sheared on its top

Laws, materials, METIS counts (1 to 6 per body), 1 to 3 ranks, -fem_dirichlet, the Coulomb algorithm and
-contact_rtol are drawn as in the box family; sizes stay below about 3000 unknowns. The meshes are made
with gmsh on first use and kept in a cache directory (default: conefeti-fuzz-meshes in the system's
temporary directory), keyed by the .geo file and its parameters, so a scene's command line names a file
that exists after its run and reruns it exactly.

What the oracle knows: `solvable` (every body clamped or moved on an area, convex laws: a unique solution,
so a verdict of "no equilibrium" is false) and `no_equilibrium` (a floating body pulled away from its only
support, or sheared beyond 1.5 times what its friction can carry), as in the box family.
"""

import math
import os
import random
import subprocess
import tempfile

import fuzzdraw
from fuzzdraw import num

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
rng = random.Random()


def fmt(v):
    return f"{num(v) + 0.0:g}"  # + 0.0: no "-0"


def vec(v):
    return ",".join(fmt(x) for x in v)


def pick(weighted):
    return fuzzdraw.pick(rng, weighted)


def cache_dir():
    return os.environ.get("CONEFETI_FUZZ_MESHES") or os.path.join(tempfile.gettempdir(), "conefeti-fuzz-meshes")


def mesh_path(geo, params):
    """The cache file of meshes/<geo>.geo with these gmsh -setnumber parameters (made by ensure_meshes())."""
    tag = "-".join(f"{k}{fmt(v)}" for k, v in sorted(params.items()))
    return os.path.join(cache_dir(), f"{geo}-{tag or 'default'}.msh")


def ensure_meshes(scene):
    """Mesh every (geo, params) of the scene that is not in the cache yet; written to a temporary name and
    renamed, so a concurrent run never reads half a file. Returns an error message or None."""
    os.makedirs(cache_dir(), exist_ok=True)
    for geo, params in scene["meshes"]:
        path = mesh_path(geo, params)
        if os.path.exists(path):
            continue
        tmp = f"{path}.{os.getpid()}.tmp.msh"
        argv = ["gmsh", "-3", os.path.join(REPO, "meshes", geo + ".geo"), "-v", "1", "-o", tmp]
        for k, v in sorted(params.items()):
            argv += ["-clmax", fmt(v)] if k == "clmax" else ["-setnumber", k, fmt(v)]  # clmax: gmsh's own option
        try:
            p = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=120)
        except (OSError, subprocess.TimeoutExpired) as e:
            return f"gmsh failed on {geo}.geo {params}: {e}"
        if p.returncode != 0 or not os.path.exists(tmp):
            return f"gmsh failed on {geo}.geo {params}: {p.stdout.decode(errors='replace').strip()[-300:]}"
        os.replace(tmp, path)
    return None


def law(pressure):
    """A contact law with its coefficient: (law, coef); Tresca's slip bound is a stress, scaled by the pressure."""
    kind = pick([(3, "frictionless"), (2, "tresca"), (5, "coulomb")])
    if kind == "frictionless":
        return kind, None
    if kind == "tresca":
        return kind, num(pressure * pick([(1, 0.0), (3, 0.1), (3, 0.5), (2, 2.0)]))
    return kind, num(pick([(1, 0.0), (6, rng.uniform(0.05, 1.0)), (2, rng.uniform(1.0, 3.0))]))


def material():
    return num(10 ** rng.uniform(9, 12)), num(rng.uniform(0.0, 0.45))


def metis():
    return pick([(2, 1), (3, 2), (3, 4), (2, 6)])


class Scene:
    def __init__(self, kind):
        self.kind, self.args, self.meshes, self.notes = kind, [], [], []
        self.nsub, self.solvable, self.no_equilibrium, self.zero_load = 0, False, None, False
        self.laws = []

    def body(self, b, geo, params, E, nu, parts, extra=()):
        self.meshes.append((geo, params))
        p = f"-scene_body{b}_"
        self.args += [p + "mesh", mesh_path(geo, params), p + "E", fmt(E), p + "nu", fmt(nu), p + "subdomains", str(parts)]
        self.args += list(extra)
        self.nsub += parts

    def zone(self, z, opts, lawcoef):
        name, coef = lawcoef
        p = f"-scene_zone{z}_"
        for k, v in opts:
            self.args += [p + k, v]
        self.args += [p + "law", name]
        if name == "coulomb":
            self.args += [p + "friction", fmt(coef)]
        elif name == "tresca":
            self.args += [p + "slip_bound", fmt(coef)]
        self.laws.append((name, coef))

    def convex(self):
        return all(n != "coulomb" or c == 0 for n, c in self.laws)


def hemisphere():
    s = Scene("hemisphere")
    R = pick([(4, 1.0), (1, 1e-3), (1, 50.0)])
    E, nu = material()
    p = num(E * 10 ** rng.uniform(-5, -3))
    extra = ["-scene_body0_fix_x", "sym_x", "-scene_body0_fix_y", "sym_y"]
    if R != 1.0:
        extra += ["-scene_body0_scale", fmt(R)]
    mode = pick([(3, "traction"), (0.5, "pull"), (1.5, "displace")])
    if mode == "displace":
        extra += ["-scene_body0_displace0_face", "top", "-scene_body0_displace0_value", vec([0, 0, -R * 10 ** rng.uniform(-4, -2)])]
        s.solvable = True
    else:
        t = p * pick([(2, 0.0), (1, 0.1), (1, 1.0)])
        extra += ["-scene_body0_traction0_face", "top", "-scene_body0_traction0_value", vec([t * rng.uniform(-1, 1), t * rng.uniform(-1, 1), p if mode == "pull" else -p])]
        if mode == "pull":
            s.no_equilibrium = "the traction on the flat face pulls the hemisphere away from the plane, its only support along z"
    if rng.random() < 0.15:
        extra += ["-scene_body0_force", vec([0, 0, -E * 1e-5 / R])]
        s.no_equilibrium = None  # the weight may outweigh a pull: no verdict
    s.body(0, "hemisphere", {"h": pick([(1, 0.05), (1, 0.08), (1, 0.1)]), "hc": pick([(1, 0.2), (1, 0.3)])}, E, nu, metis(), extra)
    gap = pick([(2, ("touch", 0.0)), (2, ("small", 1e-3)), (1, ("large", 10 ** rng.uniform(0, 3))), (1, ("overlap", -1e-3))])
    s.notes.append(f"gap={gap[0]}")
    normal = [0.0, 0.0, 1.0] if rng.random() < 0.7 else [num(rng.uniform(-0.1, 0.1)), num(rng.uniform(-0.1, 0.1)), 1.0]
    s.zone(0, [("type", "foundation"), ("body", "0"), ("face", "curved"), ("point", vec([0, 0, -gap[1] * R])), ("normal", vec(normal))], law(p))
    return s


def indenter():
    s = Scene("indenter")
    L = pick([(3, 1.0), (1, 0.01), (1, 100.0)])  # the block is 20 L wide and high
    E, nu = material()
    extra = ["-scene_body0_fix", "bottom", "-scene_body0_fix_x", "sym_x", "-scene_body0_fix_y", "sym_y"]
    if L != 1.0:
        extra += ["-scene_body0_scale", fmt(L)]
    if rng.random() < 0.2:
        extra += ["-scene_body0_traction0_face", "side_x", "-scene_body0_traction0_value", vec([-E * 10 ** rng.uniform(-5, -3), 0, 0])]
    params = pick([(1, {"h": 0.5, "hc": 5, "rf": 2, "rg": 8}), (1, {"h": 1, "hc": 5, "rf": 3, "rg": 8})])
    s.body(0, "indentation", params, E, nu, metis(), extra)
    R = L * pick([(1, 1.0), (1, 5.0), (1, 20.0)])
    top = 20 * L
    gap = pick([(6, "overlap"), (1, "touch"), (1, "clear")])
    d = {"overlap": R * 10 ** rng.uniform(-4, -2), "touch": 0.0, "clear": -R * 1e-2}[gap]  # the overlap
    s.zero_load = gap != "overlap" and "-scene_body0_traction0_face" not in extra
    s.notes.append(f"gap={gap}")
    shape = pick([(2, "sphere"), (1, "cylinder")])
    opts = [("type", "foundation"), ("shape", shape), ("body", "0"), ("face", "top"), ("center", f"0,0,{top + R - d:.15g}"), ("radius", fmt(R))]  # all digits: d may be 1e-4 of it
    if shape == "cylinder":
        opts.append(("axis", rng.choice(["1,0,0", "0,1,0"])))
    s.notes.append(shape)
    s.zone(0, opts, law(E * 1e-3))
    s.solvable = True
    return s


def pair():
    s = Scene("pair")
    part = pick([(2, 4), (2, 2), (1, 1)])
    E0, nu0 = material()
    E1, nu1 = material()
    p = num(min(E0, E1) * 10 ** rng.uniform(-5, -3))
    rollers0, rollers1 = [], []
    if part in (4, 2):
        rollers0 += ["-scene_body0_fix_y", "sym_y"]
        rollers1 += ["-scene_body1_fix_y", "sym_y"]
    if part == 4:
        rollers0 += ["-scene_body0_fix_x", "sym_x"]
        rollers1 += ["-scene_body1_fix_x", "sym_x"]
    mode = pick([(3, "displace"), (2, "traction")])
    extra0 = list(rollers0)
    if mode == "displace":
        d = 10 ** rng.uniform(-3, -1.7)
        shift = [d * rng.uniform(-0.5, 0.5) if part != 4 else 0.0, d * rng.uniform(-0.5, 0.5) if part == 1 else 0.0, -d]
        extra0 += ["-scene_body0_displace0_face", "grip", "-scene_body0_displace0_value", vec(shift)]
        s.solvable = True
    else:
        t = [num(p * rng.uniform(-0.3, 0.3)) if part != 4 else 0.0, num(p * rng.uniform(-0.3, 0.3)) if part == 1 else 0.0, -p]
        extra0 += ["-scene_body0_traction0_face", "grip", "-scene_body0_traction0_value", vec(t)]
        s.notes.append("floating")
    s.body(0, "pair-hemisphere", {"part": part, "h": pick([(1, 0.05), (1, 0.08)]), "hc": 0.3, "rf": 0.2}, E0, nu0, metis(), extra0)
    s.body(1, "pair-block", {"part": part, "h": pick([(1, 0.08), (1, 0.1)]), "hc": 2, "rf": 0.3, "rg": 3}, E1, nu1, metis(), ["-scene_body1_fix", "base"] + rollers1)
    opts = [("type", "bodies"), ("body", "0"), ("face", "curved"), ("other_body", "1"), ("other_face", "top")]
    slave = pick([(2, None), (1, "body"), (1, "other")])
    if slave:
        opts.append(("slave", slave))
    dist = pick([(2, None), (1, 0.03), (1, 0.1)])
    if dist:
        opts.append(("search_distance", fmt(dist)))
    lc = law(p)
    s.zone(0, opts, lc)
    # no verdict on equilibrium when a traction leaves the hemisphere floating (free along z; a half also along x and
    # about y, the whole along x, y and about z): away from the axis the contact normals (along chi(x) - x) lean, so
    # the linearized model can carry a shear without friction once the hemisphere has slid far enough
    if mode == "traction" and math.hypot(t[0], t[1]) > 0:
        s.notes.append("sheared")
    s.notes.append(f"part={part}")
    return s


def block_hole():
    s = Scene("block-hole")
    E, nu = material()
    p = num(E * 10 ** rng.uniform(-5, -3))
    support = pick([(3, "none"), (1, "rollers"), (1, "clamped")])
    extra = []
    if support == "rollers":
        extra += ["-scene_body0_fix_x", "x0"]  # the end x = 0 on rollers along x: sliding along y stays free
    elif support == "clamped":
        extra += ["-scene_body0_fix", "x0"]
    ratio = pick([(2, 0.0), (2, 0.1), (1, 0.5), (1, 2.0)])
    tx, ty = p * ratio * rng.uniform(-1, 1), p * ratio * rng.uniform(-1, 1) * (rng.random() < 0.5)
    pull = rng.random() < 0.08
    tz = p if pull else -p
    extra += ["-scene_body0_traction0_face", "top", "-scene_body0_traction0_value", vec([tx, ty, tz])]
    if support == "clamped" and rng.random() < 0.3:
        extra += ["-scene_body0_traction1_face", "hole", "-scene_body0_traction1_value", vec([0, 0, -p * rng.uniform(0.1, 1)])]
    s.body(0, "block-hole", {}, E, nu, metis(), extra)
    gap = pick([(2, ("touch", 0.0)), (1, ("small", 1e-3)), (1, ("large", 10 ** rng.uniform(0, 3))), (1, ("overlap", -1e-4))])
    s.notes.append(f"gap={gap[0]}")
    lc = law(p)
    s.zone(0, [("type", "foundation"), ("body", "0"), ("face", "bottom"), ("point", vec([0, 0, -gap[1]])), ("normal", "0,0,1")], lc)
    s.notes.append(f"support={support}")
    s.solvable = support == "clamped"
    if support != "clamped":  # top and bottom both have the area 2: compare the tractions (rollers carry tx)
        t, carry = math.hypot(num(tx) if support == "none" else 0.0, num(ty)), {"frictionless": 0.0, "coulomb": (lc[1] or 0) * p, "tresca": lc[1] or 0}[lc[0]]
        if pull:
            s.no_equilibrium = "the top traction pulls the block away from the floor, its only support along z"
        elif t > 1.5 * carry + 1e-3 * p:
            s.no_equilibrium = f"the shear {t:.3g} on the block exceeds 1.5 x what the floor's {lc[0]} carries, {carry:.3g}"
    return s


def volumes():
    s = Scene("volumes")
    E0, nu0 = material()
    E1, nu1 = material()
    p = num(min(E0, E1) * 10 ** rng.uniform(-5, -3))
    mesh = {"clmax": pick([(1, 0.25), (1, 0.35)])}
    ratio = pick([(2, 0.0), (2, 0.15), (1, 1.0)])
    t = [p * ratio * rng.uniform(-1, 1), 0.0, -p]
    s.body(0, "two-volumes", mesh, E0, nu0, metis(), ["-scene_body0_volume", "lower", "-scene_body0_fix", "bottom"])
    upper_support = pick([(3, "none"), (1, "clamped")])
    extra = ["-scene_body1_volume", "upper", "-scene_body1_traction0_face", "top", "-scene_body1_traction0_value", vec(t)]
    if upper_support == "clamped":
        extra += ["-scene_body1_fix", "x1"]  # the end x = 2 of the upper block
    s.body(1, "two-volumes", mesh, E1, nu1, metis(), extra)
    lc = law(p)
    s.zone(0, [("type", "bodies"), ("body", "1"), ("face", "interface"), ("other_body", "0"), ("other_face", "interface")], lc)
    s.notes.append(f"upper={upper_support}")
    s.solvable = upper_support == "clamped"
    if upper_support == "none":
        carry = {"frictionless": 0.0, "coulomb": (lc[1] or 0) * p, "tresca": lc[1] or 0}[lc[0]]
        if abs(num(t[0])) > 1.5 * carry + 1e-3 * p:
            s.no_equilibrium = f"the shear {abs(num(t[0])):.3g} on the free upper block exceeds 1.5 x what the {lc[0]} interface carries, {carry:.3g}"
    return s


def generate(seed, index, max_ranks):
    """Scene index of seed in the mesh family: a dict as fuzz-scenes.py's generate() returns, with its own
    'args', 'describe' and 'meshes' (made by ensure_meshes() before the run)."""
    rng.seed(f"conefeti-fuzz-meshes:{seed}:{index}")
    kind = pick([(2, hemisphere), (2, indenter), (2.5, pair), (2, block_hole), (1.5, volumes)])
    s = kind()
    dirichlet = rng.choice(["multipliers", "primal"])
    args = ["-fem_dirichlet", dirichlet] + s.args
    algorithm = rng.choice(["msa", "merged", "monolithic"]) if any(n == "coulomb" for n, _ in s.laws) else None
    if algorithm:
        args += ["-contact_coulomb_algorithm", algorithm]
    rtol = pick([(6, None), (1, 1e-4), (1, 1e-5), (1, 1e-7)])
    if rtol:
        args += ["-contact_rtol", fmt(rtol)]
    ranks = max(1, min(pick([(6, 1), (2.5, 2), (1.5, 3)]), max_ranks, s.nsub))
    laws = ",".join(n + (f"({fmt(c)})" if c is not None else "") for n, c in s.laws)
    desc = f"mesh:{s.kind} {laws} {' '.join(s.notes)}" + (" load=0" if s.zero_load else "") + (" noeq" if s.no_equilibrium else "")
    solvable = s.solvable and s.convex() and not s.no_equilibrium
    return dict(args=args, describe=desc, meshes=s.meshes, ranks=ranks, rtol=rtol, solvable=solvable, no_equilibrium=s.no_equilibrium, zero_load=s.zero_load)
