#!/usr/bin/python3
"""Random contact scenes for the conefeti program: every run converges within the acceptance or says why not.

Each scene is a valid conefeti command line (docs/scenes.md) drawn from a seeded generator:

* 1 to 3 elastic boxes: one body on a rigid foundation plane; a block on a slab (the block's sides on
  the slab's node lines), with conforming meshes (node to node) or, in 4 of 10 blocks, its own cell size
  across the contact face (node to surface: "nonmatching" in the run's line); a third body on the block
  or beside it on the slab.
* supports: none (a body held only by contact), clamped faces (`_fix`), rollers (`_fix_x/_y/_z`), a
  clamped part of the contact face (the brick's layout); never the whole contact face.
* loads: pressure and shear on the top face, with the shear below, near or well beyond what friction
  can carry; a pull at the end face; a traction on part of the top face; volume forces; no load at all;
  a pull away from the support.
* foundations: gaps from a slight penetration (-1e-4 of the size) to 1000 times the size, sometimes a
  tilted plane; laws frictionless, tresca (slip bound >= 0, sometimes 0), coulomb with F in [0, 3],
  sometimes exactly 0.
* decompositions: structured (px,py,pz <= cells) or METIS (n <= cells); -fem_dirichlet multipliers or
  primal; -contact_coulomb_algorithm msa, merged or monolithic; -contact_rtol 1e-4 .. 1e-7 or the
  default; materials E in [1e9, 1e12], nu in [0, 0.45]; 1 to 3 MPI ranks; sometimes -scene_refine 2.
* the canonical scene (stacked along +z) is rotated (a permutation of the axes) and sometimes mirrored,
  so the faces x0 .. z1 and the normals all occur. Meshes stay below ~3000 unknowns.

With --family meshes the scenes come from scripts/fuzz_meshes.py instead: the Gmsh geometries of meshes/
(hemisphere, indentation block under a rigid sphere or cylinder, the hemisphere-on-block pair, the block with
a hole, two volumes of one file) meshed by gmsh at random coarse sizes; its header lists them.

Scene i of seed S depends only on (S, i): `--seed S --first i --count 1` reruns it alone.

Each run is classified:

  OK-converged      exit 0, "converged":true and every entry of "residuals" finite and <= acceptance, the
                    JSON field "acceptance" when the driver prints one, else --accept-factor x -contact_rtol
  OK-not-converged  exit 2, a "NOT CONVERGED: ..." line and "converged":false; marked SUSPECT (not a
                    failure) when every body is clamped on an area and every law is convex (frictionless,
                    Tresca, Coulomb F = 0): such a scene has a unique solution, which the solver did not reach
                    within its limits (an iteration limit, a stalled loop); not when a drawn
                    -contact_refine_max k allowed fewer tighter solves than the default and all k + 1 missed
  FAIL-wrong        exit 0 with a residual above the acceptance, a null residual, "converged":false, or a
                    scene that certainly has no equilibrium (a floating body whose net load points away
                    from its support, or whose net tangential load exceeds 1.5 x what friction can carry);
                    exit 2 with "converged":true or without a reason; exit 2 on such a scene with a unique
                    solution whose reason says there is none ("no equilibrium", "not unique"): a false
                    statement about the mechanics, as wrong as a wrong answer
  OK-refused        with --solver-options only: exit 1 with an error line ("conefeti: error: ...") that names
                    one of the drawn solver options, a combination the program says it does not take
  FAIL-crash        any other exit status (PETSc error, segfault, MPI abort, a valid scene rejected as bad
                    input), or no JSON line on exit 0/2
  FAIL-nan          nan or inf printed
  FAIL-hang         no exit within --timeout seconds

One line per run (scene kind/support, laws, gap kind, "load=0" for a scene without load, "noeq" for one
that certainly has no equilibrium); for a failure the command that reproduces it (to paste at the
repository root) and the error or reason. At the end: the counts per class, the failures grouped by cause
(class and message without its numbers, or the names of the residuals above the acceptance) with their
scene indices, and alone on the last line "N passed, M failed"; the exit status is 1 when a run failed.
--max-ranks caps the rank count of a scene without changing the scene.

Usage (from the repository root):
  scripts/fuzz-scenes.py --seed 1 --time-budget 100          # the ctest fuzz_random_scenes (tests/fuzz)
  scripts/fuzz-scenes.py --seed 7 --count 200                # a longer run
  scripts/fuzz-scenes.py --seed 7 --first 42 --count 1       # scene 42 of seed 7 alone
  scripts/fuzz-scenes.py --seed 7 --count 20 --dry-run       # print the commands, run nothing
  scripts/fuzz-scenes.py --max-ranks 1 ...                   # serial runs only
  scripts/fuzz-scenes.py --family meshes --seed 1 --count 50 # random scenes on the Gmsh geometries
  scripts/fuzz-scenes.py --solver-options --seed 1 ...       # each scene with 1-4 non-default solver options
                                                             # (scripts/fuzz_solver.py), the same scenes
"""

import argparse
import json
import math
import os
import random
import re
import shlex
import signal
import subprocess
import sys
import time

import fuzz_meshes
import fuzz_solver
import fuzzdraw
from fuzzdraw import num

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MPIEXEC_FLAGS = ["--allow-run-as-root", "--oversubscribe", "-n"]
DEFAULT_RTOL = 1e-6
MAX_NODES = 1000  # ~3000 unknowns


def fmt(v):
    if isinstance(v, int):
        return str(v)
    if v == int(v) and abs(v) < 1e15:
        return str(int(v))
    return repr(v)


def vec(v):
    return ",".join(fmt(x) for x in v)


# ----------------------------------------------------------------------------------------------
# Face selectors and the rotation of the canonical scene
# ----------------------------------------------------------------------------------------------
class Sel:
    """FACE[/COND...]: axis 0..2 and side 0 (lower) or 1 (upper) of the box, conditions (axis, op, value)."""

    def __init__(self, axis, side, conds=()):
        self.axis, self.side, self.conds = axis, side, list(conds)


class Frame:
    """Canonical coordinates -> written ones: first z -> -z when mirrored, then axis i -> axis perm[i]."""

    def __init__(self, perm, mirror):
        self.perm, self.mirror = perm, mirror

    def point(self, p):
        q = list(p)
        if self.mirror:
            q[2] = -q[2]
        out = [0.0] * 3
        for i in range(3):
            out[self.perm[i]] = q[i]
        return out

    vector = point

    def box(self, lower, upper):
        a, b = self.point(lower), self.point(upper)
        return [min(x, y) for x, y in zip(a, b)], [max(x, y) for x, y in zip(a, b)]

    def ints(self, t):
        out = [0] * 3
        for i in range(3):
            out[self.perm[i]] = t[i]
        return out

    def sel(self, s):
        side = 1 - s.side if (self.mirror and s.axis == 2) else s.side
        text = "xyz"[self.perm[s.axis]] + str(side)
        for axis, op, value in s.conds:
            if self.mirror and axis == 2:
                op = {"<": ">", ">": "<", "<=": ">=", ">=": "<="}[op]
                value = -value
            text += "/" + "xyz"[self.perm[axis]] + op + fmt(num(value, 10))  # conditions apply to centroids, half a cell away
        return text


# ----------------------------------------------------------------------------------------------
# The scene generator (canonical frame: bodies stacked along +z, foundations below them)
# ----------------------------------------------------------------------------------------------
class Body:
    def __init__(self, lower, h, cells):
        self.lower = list(lower)
        self.h = list(h)
        self.cells = list(cells)
        self.upper = [lower[d] + h[d] * cells[d] for d in range(3)]
        self.E = num(10 ** random_state.uniform(9, 12))
        self.nu = num(random_state.uniform(0.0, 0.45), 3)
        self.fix = []  # Sel
        self.fixc = {0: [], 1: [], 2: []}  # component -> [Sel]
        self.tractions = {}  # (axis, side) -> vector
        self.partial = []  # (Sel, vector, area)
        self.force = None
        self.decomp = None

    def size(self):
        return max(self.upper[d] - self.lower[d] for d in range(3))

    def area(self, axis):
        a, b = [d for d in range(3) if d != axis]
        return (self.upper[a] - self.lower[a]) * (self.upper[b] - self.lower[b])

    def volume(self):
        return (self.upper[0] - self.lower[0]) * (self.upper[1] - self.lower[1]) * (self.upper[2] - self.lower[2])

    def nodes(self, refine):
        return (self.cells[0] * refine + 1) * (self.cells[1] * refine + 1) * (self.cells[2] * refine + 1)

    def floating(self):
        return not self.fix and not any(self.fixc.values())

    def net_force(self):
        f = [0.0, 0.0, 0.0]
        for (axis, side), t in self.tractions.items():
            for d in range(3):
                f[d] += t[d] * self.area(axis)
        for sel, t, area in self.partial:
            for d in range(3):
                f[d] += t[d] * area
        if self.force:
            for d in range(3):
                f[d] += self.force[d] * self.volume()
        return f


class Zone:
    def __init__(self, **kw):
        self.type = "foundation"
        self.other_body = None
        self.other_face = None
        self.point = None
        self.normal = None
        self.coef = None
        self.__dict__.update(kw)


random_state = random.Random()


def pick(weighted):
    """weighted: [(weight, value)]"""
    return fuzzdraw.pick(random_state, weighted)


def law():
    name = pick([(1, "frictionless"), (1, "tresca"), (2, "coulomb")])
    coef = None
    if name == "coulomb":
        coef = pick([(1, 0.0), (4, num(random_state.uniform(0.05, 1.0), 2)), (1, num(random_state.uniform(1.0, 3.0), 2)), (0.3, 3.0)])
    return name, coef


def tresca_bound(zone, pressure):
    """A slip bound (a stress) around the pressure scale; sometimes 0."""
    return pick([(1, 0.0), (5, num(pressure * random_state.uniform(0.02, 1.5)))])


def top_load(body, coef_for_ratio):
    """Pressure and shear on the top face: shear below, near or beyond what friction can carry."""
    strain = 10 ** random_state.uniform(-5, -3)
    p = num(body.E * strain)
    mu = coef_for_ratio
    ratio = pick([(2, 0.0), (3, random_state.uniform(0, 0.5) * mu), (1, random_state.uniform(0.8, 1.2) * mu), (3, random_state.uniform(2, 4) * mu + 0.1), (1, random_state.uniform(0, 1.0))])
    angle = random_state.uniform(0, 2 * math.pi)
    s = ratio * p
    sign = -1.0 if random_state.random() < 0.92 else 1.0  # sometimes a pull away from the support
    body.tractions[(2, 1)] = [num(s * math.cos(angle)), num(s * math.sin(angle)), num(sign * p)]
    return p


def other_loads(body, p):
    if random_state.random() < 0.25:  # a pull at an end face
        side = random_state.randint(0, 1)
        body.tractions[(0, side)] = [num((1 if side else -1) * p * random_state.uniform(0.01, 0.2)), 0.0, 0.0]
    if random_state.random() < 0.25 and body.cells[0] >= 2:  # a traction on part of the top face
        k = random_state.randint(1, body.cells[0] - 1)
        c = body.lower[0] + k * body.h[0]
        area = (body.upper[0] - c) * (body.upper[1] - body.lower[1])
        body.partial.append((Sel(2, 1, [(0, ">", c)]), [0.0, num(p * random_state.uniform(-0.2, 0.2)), num(-p * random_state.uniform(0.1, 1))], area))
    if random_state.random() < 0.35:  # volume force, mostly toward the support
        g = p / body.size() * random_state.uniform(0.05, 1.0)
        body.force = [num(g * random_state.uniform(-0.2, 0.2)), num(g * random_state.uniform(-0.2, 0.2)), num(-g)]


def subdivide(body, refine):
    """A structured (px,py,pz <= cells) or METIS (n <= cells) decomposition."""
    c = [n * refine for n in body.cells]
    if random_state.random() < 0.6:
        body.decomp = ("structured", [random_state.randint(1, min(n, 3)) for n in c])
    else:
        body.decomp = ("metis", [random_state.randint(1, min(8, c[0] * c[1] * c[2]))])


def subdomain_count(body):
    kind, parts = body.decomp
    return parts[0] * parts[1] * parts[2] if kind == "structured" else parts[0]


def generate(seed, index, max_ranks):
    """The scene index of seed: a dict with the options, the ranks and what the oracle knows."""
    random_state.seed(f"conefeti-fuzz:{seed}:{index}")
    for _attempt in range(100):
        scene = try_generate(max_ranks)
        if scene:
            return scene
    raise RuntimeError(f"seed {seed} scene {index}: no scene within the size limit")


def try_generate(max_ranks):
    refine = 2 if random_state.random() < 0.15 else 1
    s = 2.0 ** random_state.randint(-4, 3)  # dyadic sizes: node coordinates of conforming faces coincide exactly
    h = [s * random_state.choice([0.25, 0.5, 1.0]) for _ in range(3)]
    kind = pick([(4, "one"), (4, "stack2"), (1.5, "stack3"), (1.5, "side3")])
    bodies, zones = [], []
    origin = [h[0] * random_state.randint(-3, 3), h[1] * random_state.randint(-3, 3), h[2] * random_state.randint(-2, 2)]
    b0 = Body(origin, h, [random_state.randint(1, 6), random_state.randint(1, 6), random_state.randint(1, 4)])
    bodies.append(b0)

    def foundation_under(b, bi):
        """A foundation zone under face z0 of body bi (the whole face or the part x > c)."""
        sel = Sel(2, 0)
        if b.cells[0] >= 2 and random_state.random() < 0.3:
            k = random_state.randint(1, b.cells[0] - 1)
            c = b.lower[0] + k * b.h[0]
            sel = Sel(2, 0, [(0, ">", c)])
            if random_state.random() < 0.5:
                b.fix.append(Sel(2, 0, [(0, "<", c)]))  # the brick's layout: the rest of the bottom clamped
                b.brick_k = k
        size = b.size()
        gapkind = pick([(2, "touch"), (2, "penetration"), (3, "small"), (1, "large")])
        gap = {"touch": 0.0, "penetration": -size * random_state.uniform(1e-5, 1e-4), "small": size * 10 ** random_state.uniform(-4, -2),
               "large": size * 10 ** random_state.uniform(0, 3)}[gapkind]
        normal = [0.0, 0.0, 1.0]
        if random_state.random() < 0.2:
            normal = [num(random_state.uniform(-0.1, 0.1), 2), num(random_state.uniform(-0.1, 0.1), 2), 1.0]
        centre = [(b.lower[0] + b.upper[0]) / 2, (b.lower[1] + b.upper[1]) / 2, b.lower[2] - gap]
        name, coef = law()
        z = Zone(body=bi, face=sel, point=[num(x, 8) for x in centre], normal=normal, law=name, coef=coef, gapkind=gapkind, area=b.area(2))
        zones.append(z)
        return z

    def block_on(lower_body, li, n_cells_z, hz):
        """A block on top of lower_body, its sides on lower_body's node lines (sometimes overhanging)."""
        lb = lower_body
        over = random_state.random() < 0.15
        lo_i = [random_state.randint(-1 if over else 0, lb.cells[d] - 1) for d in range(2)]
        # at least one cell of overlap: a block that touches the slab along an edge only is not meant
        hi_i = [random_state.randint(max(lo_i[d] + 1, 1), max(min(lo_i[d] + 4, lb.cells[d] + (1 if over else 0)), 1)) for d in range(2)]
        lower = [lb.lower[0] + lo_i[0] * lb.h[0], lb.lower[1] + lo_i[1] * lb.h[1], lb.upper[2]]
        cells = [hi_i[0] - lo_i[0], hi_i[1] - lo_i[1]]
        h = [lb.h[0], lb.h[1]]
        if random_state.random() < 0.4:  # non-matching: the block's own cell size across the contact face
            for d in range(2):
                c = max(1, cells[d] + random_state.choice([-1, 1, 2]))
                h[d] = cells[d] * lb.h[d] / c
                cells[d] = c
        b = Body(lower, [h[0], h[1], hz], [cells[0], cells[1], n_cells_z])
        b.upper[:2] = [lb.lower[d] + hi_i[d] * lb.h[d] for d in range(2)]  # on the slab's node lines, exactly
        bodies.append(b)
        bi = len(bodies) - 1
        # the part of the lower body's top under the block (the rest has no partner anyway)
        conds = []
        for d in range(2):
            if b.lower[d] > lb.lower[d]:
                conds.append((d, ">", b.lower[d]))
            if b.upper[d] < lb.upper[d]:
                conds.append((d, "<", b.upper[d]))
        under = Sel(2, 1, conds if random_state.random() < 0.6 else [])
        name, coef = law()
        overlap = (min(b.upper[0], lb.upper[0]) - max(b.lower[0], lb.lower[0])) * (min(b.upper[1], lb.upper[1]) - max(b.lower[1], lb.lower[1]))
        if random_state.random() < 0.7:
            z = Zone(type="bodies", body=bi, face=Sel(2, 0), other_body=li, other_face=under, law=name, coef=coef, area=overlap)
        else:
            z = Zone(type="bodies", body=li, face=under, other_body=bi, other_face=Sel(2, 0), law=name, coef=coef, area=overlap)
        z.upper, z.lower = bi, li
        z.nonmatching = h != [lb.h[0], lb.h[1]]
        zones.append(z)
        return b, z

    support_of = {}  # body -> the zone it rests on (its bottom), for the oracle
    if kind == "one":
        support = pick([(3, "floating"), (2, "clamped_end"), (1, "both_ends"), (1, "rollers"), (1, "side")])
        z = foundation_under(b0, 0)
        if support == "clamped_end":
            b0.fix.append(Sel(0, 0))
        elif support == "both_ends":
            # the zone keeps a node that is not fixed: a node line strictly between the clamped ones
            if b0.cells[0] < 2 or getattr(b0, "brick_k", 0) > b0.cells[0] - 2:
                return None
            b0.fix += [Sel(0, 0), Sel(0, 1)]
        elif support == "rollers":
            b0.fixc[0].append(Sel(0, 0))
            b0.fixc[1].append(Sel(1, 0))
        elif support == "side":
            b0.fix.append(Sel(1, random_state.randint(0, 1)))
        support_of[0] = z
    else:
        support = pick([(4, "clamped"), (2, "foundation"), (1, "cantilever"), (1, "rollers")])
        if support == "clamped":
            b0.fix.append(Sel(2, 0))
        elif support == "foundation":
            support_of[0] = foundation_under(b0, 0)
        elif support == "cantilever":
            b0.fix.append(Sel(0, 0))
        else:
            b0.fixc[2].append(Sel(2, 0))
            b0.fixc[0].append(Sel(0, 0))
            b0.fixc[1].append(Sel(1, 0))
        hz = s * random_state.choice([0.25, 0.5, 1.0])
        b1, z1 = block_on(b0, 0, random_state.randint(1, 4), hz)
        support_of[1] = z1
        if kind == "stack3":
            b2, z2 = block_on(b1, 1, random_state.randint(1, 3), hz)
            support_of[2] = z2
        elif kind == "side3":
            # beside body 1 on body 0, at least one cell of body 0 away from it
            free = [i for i in range(b0.cells[0]) if b0.lower[0] + (i + 1) * h[0] <= b1.lower[0] - h[0] or b0.lower[0] + i * h[0] >= b1.upper[0] + h[0]]
            if not free:
                return None
            i = random_state.choice(free)
            lower = [b0.lower[0] + i * h[0], b0.lower[1], b0.upper[2]]
            b2 = Body(lower, [h[0], h[1], hz], [1, random_state.randint(1, b0.cells[1]), random_state.randint(1, 3)])
            bodies.append(b2)
            name, coef = law()
            z2 = Zone(type="bodies", body=2, face=Sel(2, 0), other_body=0, other_face=Sel(2, 1), law=name, coef=coef, area=b2.area(2))
            z2.upper, z2.lower = 2, 0
            zones.append(z2)
            support_of[2] = z2
        if random_state.random() < 0.15:  # the top block also held at one end
            bodies[-1].fixc[0].append(Sel(0, 0))

    # loads: the top faces of the bodies that nothing rests on, sometimes the others
    zero = random_state.random() < 0.08  # no load at all: the answer is u = 0 (or a rigid lift out of a penetration)
    covered = {z.lower for z in zones if z.type == "bodies"}
    for bi, b in enumerate(bodies):
        if zero:
            break
        z = support_of.get(bi)
        mu = z.coef if (z and z.law == "coulomb") else (0.3 if z is None or z.law == "tresca" else 0.0)
        if bi not in covered or random_state.random() < 0.2:
            p = top_load(b, mu) if bi not in covered else num(b.E * 10 ** random_state.uniform(-5, -3))
            other_loads(b, p)
        elif random_state.random() < 0.3:
            b.force = [0.0, 0.0, num(-b.E * 1e-4 / b.size())]
    for z in zones:
        if z.law == "tresca":
            p = max([abs(t[2]) for b in bodies for t in b.tractions.values()] + [bodies[z.body].E * 1e-4])
            z.coef = tresca_bound(z, p)

    if sum(b.nodes(refine) for b in bodies) > MAX_NODES:
        if refine == 2 and sum(b.nodes(1) for b in bodies) <= MAX_NODES:
            refine = 1
        else:
            return None
    for b in bodies:
        subdivide(b, refine)
    nsub = sum(subdomain_count(b) for b in bodies)
    ranks = pick([(6, 1), (2.5, 2), (1.5, 3)])
    ranks = max(1, min(ranks, max_ranks, nsub))

    scene = dict(bodies=bodies, zones=zones, refine=refine, ranks=ranks, kind=kind, support=support, zero_load=zero,
                 dirichlet=random_state.choice(["multipliers", "primal"]),
                 algorithm=random_state.choice(["msa", "merged", "monolithic"]) if any(z.law == "coulomb" for z in zones) else None,
                 rtol=pick([(6, None), (1, 1e-4), (1, 1e-5), (1, 1e-7)]),
                 frame=Frame(random_state.sample([0, 1, 2], 3), random_state.random() < 0.3))
    scene["no_equilibrium"] = no_equilibrium(scene, support_of)
    # every body clamped on an area (no rigid mode left) and convex laws (frictionless, Tresca, Coulomb
    # with F = 0): a coercive convex problem, so a solution exists and is unique; exit 2 is suspect there
    scene["solvable"] = all(b.fix for b in bodies) and all(z.law != "coulomb" or z.coef == 0 for z in zones)
    return scene


def no_equilibrium(scene, support_of):
    """A reason why the scene certainly has no equilibrium, or None.

    For a body without any support, take it with every body resting on it (the bodies above it in
    the stack): their net load must be carried by the zone the body rests on, whose normal is +z.
    Contact pushes, so a net load away from the zone (+z) cannot be carried; friction carries at
    most F N (Coulomb, N the net pressing load) or g A (Tresca, A the zone's area) tangentially, and
    nothing when frictionless. A margin of 1.5 keeps the check certain."""
    bodies, zones = scene["bodies"], scene["zones"]
    above = {}
    for z in zones:
        if z.type == "bodies":
            above.setdefault(z.lower, []).append(z.upper)

    def group(b):
        out = [b]
        for u in above.get(b, []):
            out += group(u)
        return out

    for bi, z in support_of.items():
        members = group(bi)
        if not all(bodies[m].floating() for m in members):
            continue
        f = [0.0, 0.0, 0.0]
        for m in members:
            for d, v in enumerate(bodies[m].net_force()):
                f[d] += v
        total = math.sqrt(sum(v * v for v in f))
        if total == 0:
            continue
        if z.normal and (z.normal[0] or z.normal[1]):
            continue  # a tilted plane: the simple split below does not apply
        pressing = -f[2]
        tangential = math.hypot(f[0], f[1])
        if pressing < -1e-3 * total:
            return f"the net load {vec([num(v) for v in f])} on bodies {members} pulls them away from zone {zones.index(z)}"
        bound = {"frictionless": 0.0, "coulomb": (z.coef or 0.0) * max(pressing, 0.0), "tresca": (z.coef or 0.0) * z.area}[z.law]
        if tangential > 1.5 * bound + 1e-3 * total:
            return f"bodies {members}: net tangential load {tangential:.3g} > 1.5 x what zone {zones.index(z)} ({z.law}) can carry, {bound:.3g}"
    return None


def command(scene, name):
    """The conefeti options of a scene, in the written (rotated) frame."""
    if "args" in scene:  # the mesh family writes its own
        return ["-scene_name", name] + scene["args"]
    fr = scene["frame"]
    args = ["-scene_name", name]
    if scene["refine"] != 1:
        args += ["-scene_refine", str(scene["refine"])]
    args += ["-fem_dirichlet", scene["dirichlet"]]
    for bi, b in enumerate(scene["bodies"]):
        p = f"-scene_body{bi}_"
        lo, up = fr.box(b.lower, b.upper)
        args += [p + "lower", vec(lo), p + "upper", vec(up), p + "cells", vec(fr.ints(b.cells)), p + "E", fmt(b.E), p + "nu", fmt(b.nu)]
        kind, parts = b.decomp
        args += [p + "decomposition", kind, p + "subdomains", vec(fr.ints(parts) if kind == "structured" else parts)]
        if b.fix:
            args += [p + "fix", ",".join(fr.sel(s) for s in b.fix)]
        for c in range(3):
            if b.fixc[c]:
                args += [p + "fix_" + "xyz"[fr.perm[c]], ",".join(fr.sel(s) for s in b.fixc[c])]
        for (axis, side), t in b.tractions.items():
            args += [p + "traction_" + fr.sel(Sel(axis, side)), vec(fr.vector(t))]
        for k, (sel, t, _area) in enumerate(b.partial):
            args += [p + f"traction{k}_face", fr.sel(sel), p + f"traction{k}_value", vec(fr.vector(t))]
        if b.force:
            args += [p + "force", vec(fr.vector(b.force))]
    for zi, z in enumerate(scene["zones"]):
        p = f"-scene_zone{zi}_"
        args += [p + "type", z.type, p + "body", str(z.body), p + "face", fr.sel(z.face)]
        if z.type == "foundation":
            args += [p + "point", vec(fr.point(z.point)), p + "normal", vec(fr.vector(z.normal))]
        else:
            args += [p + "other_body", str(z.other_body), p + "other_face", fr.sel(z.other_face)]
        args += [p + "law", z.law]
        if z.law == "coulomb":
            args += [p + "friction", fmt(z.coef)]
        elif z.law == "tresca":
            args += [p + "slip_bound", fmt(z.coef)]
    if scene["algorithm"]:
        args += ["-contact_coulomb_algorithm", scene["algorithm"]]
    if scene["rtol"]:
        args += ["-contact_rtol", fmt(scene["rtol"])]
    return args


def describe(scene):
    if "describe" in scene:
        return scene["describe"]
    laws = ",".join(z.law + (f"({fmt(z.coef)})" if z.coef is not None else "") for z in scene["zones"])
    gaps = ",".join(z.gapkind for z in scene["zones"] if z.type == "foundation")
    return f"{scene['kind']}/{scene['support']} {laws}" + (f" gap={gaps}" if gaps else "") + (" load=0" if scene["zero_load"] else "") + (" noeq" if scene["no_equilibrium"] else "") + (" nonmatching" if any(getattr(z, "nonmatching", False) for z in scene["zones"]) else "")


# ----------------------------------------------------------------------------------------------
# Running and classifying
# ----------------------------------------------------------------------------------------------
NAN = re.compile(r"(?<![A-Za-z_])[-+]?(nan|inf|infinity)(?![A-Za-z_])", re.IGNORECASE)


def classify(rc, out, data, scene, accept_factor, drawn=()):
    """(class, detail) of one finished run; drawn: the solver options of --solver-options (words)."""
    m = NAN.search(out)
    if m:
        line = out[out.rfind("\n", 0, m.start()) + 1 : out.find("\n", m.end())]
        return "FAIL-nan", line.strip()[:200]
    if rc == 1 and drawn:
        refusal = re.search(r"^conefeti: error: (.*)$", out, re.MULTILINE)
        names = [w for w in drawn[::2]]
        if refusal and any(re.search(re.escape(n) + r"(?![A-Za-z_])", refusal.group(1)) for n in names):
            return "OK-refused", refusal.group(1)[:200]
    if rc not in (0, 2):
        return "FAIL-crash", f"exit {rc}: {first_error(out)}"
    if data is None:
        return "FAIL-crash", f"exit {rc} without a JSON line: {first_error(out)}"
    rtol = scene["rtol"] or DEFAULT_RTOL
    res = data.get("residuals") if isinstance(data.get("residuals"), dict) else {}
    acc = data.get("acceptance", res.get("acceptance"))
    acceptance = acc if isinstance(acc, (int, float)) and not isinstance(acc, bool) else accept_factor * rtol
    # the residuals: numbers (or null for a non-finite one); other entries (names, flags) are not residuals, and
    # "approximation" (how far a friction polygon's solution is from the disk law it stands for) is reported beside
    # the verdict, not in it
    res = {k: v for k, v in res.items() if k not in ("acceptance", "approximation") and (v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)))}
    if rc == 0:
        if data.get("converged") is not True:
            return "FAIL-wrong", f"exit 0 but converged={data.get('converged')}"
        bad = [k for k, v in res.items() if v is None or not math.isfinite(v)]
        if bad or not res:
            return "FAIL-wrong", ("converged with null residuals: " + ",".join(bad)) if bad else "converged without residuals"
        over = {k: v for k, v in res.items() if v > acceptance}
        if over:
            named = {k: v for k, v in over.items() if k != "max"} or over
            listed = ", ".join(f"{k} {v:.2g}" for k, v in sorted(named.items(), key=lambda kv: -kv[1]))
            return "FAIL-wrong", f"converged with residuals above the acceptance {acceptance:.2g}: {listed}"
        if scene["no_equilibrium"]:
            return "FAIL-wrong", "converged on a scene without equilibrium: " + scene["no_equilibrium"]
        return "OK-converged", f"max {res.get('max', 0):.2g} <= {acceptance:.2g}; Iter {data.get('iter')}, n_A {data.get('n_A')}, other {data.get('n_A_other')}"
    if data.get("converged") is not False:
        return "FAIL-wrong", f"exit 2 but converged={data.get('converged')}"
    m = re.search(r"^NOT CONVERGED:.*$", out, re.MULTILINE)
    if not m:
        return "FAIL-wrong", "exit 2 without a NOT CONVERGED line"
    reason = m.group(0)[len("NOT CONVERGED: ") :]
    if scene["solvable"] and FALSE_VERDICT.match(reason):
        return "FAIL-wrong", "a unique solution exists (every body clamped, convex laws), but: " + reason[:160]
    # with fewer tighter solves than the default 3 (a drawn -contact_refine_max k), a residual above the acceptance after
    # all k + 1 solves is what the user asked for, not a limit of the solver
    limit = [int(drawn[k + 1]) for k in range(0, len(drawn) - 1, 2) if drawn[k] == "-contact_refine_max"]
    limited = bool(limit) and re.search(rf"after {limit[0] + 1} solves? down to", reason) is not None
    suspect = "SUSPECT (every body clamped, convex laws: a solution exists): " if scene["solvable"] and not limited else ""
    return "OK-not-converged", suspect + reason[:160]


# the reasons that deny a solution exists or is unique (src/contact: the equilibrium and rigid-motion checks, smalxe's
# stagnation); a scene with a unique solution must not end with one of them
FALSE_VERDICT = re.compile(r"(no equilibrium|the displacement is not unique)")


def signature(cls, detail):
    """What failures of one cause share: the class and the message without its numbers (the names of the
    residuals above the acceptance for a wrong result)."""
    m = re.match(r"converged with residuals above the acceptance [^:]*: (.*)", detail)
    if m:
        return f"{cls}: residuals above the acceptance: " + ",".join(sorted(re.findall(r"([a-z_]+) ", m.group(1) + " ")))
    head, _, rest = detail.partition(": ") if detail.startswith("exit ") else ("", "", detail)
    text = re.sub(r"[-+]?\d+(\.\d*)?(e[-+]?\d+)?", "#", rest).split(" | WARNING")[0]
    return f"{cls}: {head + ': ' if head else ''}{text[:150]}"


def first_error(out):
    """The PETSc error message (its generic and its specific line), else the first line that looks like an error."""
    lines = out.splitlines()
    petsc = []
    for k, line in enumerate(lines):
        if "PETSC ERROR:" in line and "Error Message" in line:
            for follow in lines[k + 1 : k + 3]:
                text = follow.split("PETSC ERROR:", 1)[-1].strip()
                if not text or text.startswith("See ") or "PETSC ERROR" not in follow:
                    break
                petsc.append(text)
            break
    if petsc:
        return " | ".join(petsc)[:300]
    for line in lines:
        if re.search(r"Segmentation|signal|[Aa]bort|terminate|[Kk]illed|[Ee]rror|ERROR", line):
            return line.strip()[:300]
    return (lines[-1].strip() if lines else "no output")[:300]


def parse_json(out):
    data = None
    for line in out.splitlines():
        if line.startswith('{"conefeti":'):
            try:
                data = json.loads(line, parse_constant=lambda c: float("nan"))
            except ValueError:
                data = None
    return data


def run(argv, timeout):
    t0 = time.time()
    p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, cwd=REPO, start_new_session=True)
    try:
        out, _ = p.communicate(timeout=timeout)
        return p.returncode, out.decode(errors="replace"), time.time() - t0
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, _ = p.communicate()
        return None, out.decode(errors="replace"), time.time() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog="See the module docstring (head of this file) for the scenes and the classes.")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--count", type=int, default=None, help="scenes to run (default 50, or unlimited with --time-budget)")
    ap.add_argument("--first", type=int, default=0, help="index of the first scene")
    ap.add_argument("--time-budget", type=float, default=None, help="start no new run after this many seconds")
    ap.add_argument("--driver", default=os.path.join(REPO, "build", "conefeti"))
    ap.add_argument("--timeout", type=float, default=60, help="seconds per run before it counts as a hang")
    ap.add_argument("--accept-factor", type=float, default=10.0, help="acceptance = factor x -contact_rtol when the JSON has no 'acceptance'")
    ap.add_argument("--family", choices=["boxes", "meshes"], default="boxes", help="boxes meshed by the program (the default), or Gmsh geometries of meshes/ (scripts/fuzz_meshes.py)")
    ap.add_argument("--max-ranks", type=int, default=3)
    ap.add_argument("--mpiexec", default="mpiexec", help="MPI launcher for runs on 2 or 3 ranks")
    ap.add_argument("--dry-run", action="store_true", help="print the commands only")
    ap.add_argument("--verbose", action="store_true", help="print the whole output of failed runs")
    ap.add_argument("--solver-options", action="store_true", help="add 1-4 random non-default solver options to each scene (scripts/fuzz_solver.py); the scenes stay the same")
    a = ap.parse_args()
    count = a.count if a.count is not None else (None if a.time_budget else 50)
    driver = os.path.abspath(a.driver)
    shown = os.path.relpath(driver, REPO)
    if shown.startswith(".."):
        shown = driver
    if not a.dry_run and not os.access(driver, os.X_OK):
        sys.exit(f"--driver {a.driver}: not an executable (build it with scripts/build.sh)")

    rerun_extra = (f" --family {a.family}" if a.family != "boxes" else "") + (" --solver-options" if a.solver_options else "") + (f" --max-ranks {a.max_ranks}" if a.max_ranks != 3 else "") + (f" --driver {shlex.quote(shown)}" if shown != os.path.join("build", "conefeti") else "")
    t0 = time.time()
    passed = failed = 0
    classes = {}
    suspects = motions = proofs = 0
    groups = {}  # failure signature -> scene indices
    i = a.first
    while count is None or i < a.first + count:
        if a.time_budget is not None and time.time() - t0 > a.time_budget:
            print(f"time budget {a.time_budget:g} s reached after {i - a.first} runs")
            break
        scene = (fuzz_meshes.generate if a.family == "meshes" else generate)(a.seed, i, a.max_ranks)
        args = command(scene, f"fuzz{a.seed}_{i}" if a.family == "boxes" else f"fuzzmesh{a.seed}_{i}")
        drawn = fuzz_solver.draw(a.seed, i, bool(re.search(r"\b(coulomb|tresca)", describe(scene)))) if a.solver_options else []
        args += drawn
        shown_scene = describe(scene) + (" solver: " + " ".join(drawn) if drawn else "")
        prefix = [a.mpiexec] + MPIEXEC_FLAGS + [str(scene["ranks"])] if scene["ranks"] > 1 else []
        repro = " ".join(shlex.quote(x) for x in prefix + [shown] + args)
        if a.dry_run:
            print(f"# scene {i}: {shown_scene}\n{repro}")
            i += 1
            continue
        trouble = fuzz_meshes.ensure_meshes(scene) if a.family == "meshes" else None
        if trouble:  # not the program's fault: stop with the reason
            sys.exit(f"scene {i}: {trouble}")
        rc, out, dt = run(prefix + [driver] + args, a.timeout)
        if rc is None:
            cls, detail = "FAIL-hang", f"no exit within {a.timeout:g} s"
        else:
            cls, detail = classify(rc, out, parse_json(out), scene, a.accept_factor, drawn)
        classes[cls] = classes.get(cls, 0) + 1
        suspects += detail.startswith("SUSPECT")
        # a stagnated solve's sentence names the motion the load drives, and says when that motion proves that no
        # equilibrium exists (src/contact/contactrigidmotions.cxx); counted, since the log cuts the sentence short
        verdict = re.search(r"^NOT CONVERGED:.*$", out or "", re.MULTILINE)
        if verdict and "the multiplier grows along a rigid motion" in verdict.group(0):
            motions += 1
            proofs += "which proves it" in verdict.group(0)
        print(f"[{i}] np{scene['ranks']} {shown_scene}: {cls} ({dt:.1f} s) {detail}", flush=True)
        if cls.startswith("FAIL"):
            failed += 1
            groups.setdefault(signature(cls, detail), []).append(i)
            print(f"  repro: {repro}")
            print(f"  rerun: scripts/fuzz-scenes.py --seed {a.seed} --first {i} --count 1{rerun_extra}", flush=True)
            if a.verbose:
                print("  | " + "\n  | ".join(out.splitlines()))
        else:
            passed += 1
        i += 1
    if a.dry_run:
        return 0
    print("classes: " + ", ".join(f"{k} {v}" for k, v in sorted(classes.items())) + (f" ({suspects} SUSPECT)" if suspects else "") + f"; seed {a.seed}, {time.time() - t0:.0f} s")
    if motions:
        print(f"no equilibrium: {motions} sentences name the motion the load drives, {proofs} of them prove it")
    for sig, idx in sorted(groups.items(), key=lambda kv: -len(kv[1])):
        print(f"  {len(idx):3d} x {sig}: scenes {' '.join(map(str, idx))}")
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
