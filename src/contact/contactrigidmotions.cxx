/* The rigid motions of the bodies that nothing resists, checked at ContactModelSetUp() before FETI is set
   up, and the work of the load along them.

   A free rigid motion r (K r = 0 and B r = 0) leaves the problem without a unique solution, and without
   any when the load works along it (f'r != 0). FETI meets it in the coarse matrix G G' = R'B'B R: exactly
   singular with one subdomain per body (an error that names no body), or nearly singular with several,
   where roundoff lets the factorization through and the solve reports garbage as converged. So the
   motion is found here, named, and the run stops with the cause and the cure.

   The motions themselves come from FEMComputeFreeRigidMotions() (src/fem/femrigidmotions.cxx: the Gram
   matrix of the Dirichlet dofs and the rows that can hold the bodies, evaluated on each body's 6 rigid
   motions), given the contact rows that can resist one: normal rows, and tangential rows that carry a
   force (friction coefficient or slip bound > 0). This file only tells the user which bodies move, how,
   why nothing holds them and whether the load works along the motion. Contact normal rows resist in one
   direction only: a body pulled off its support has a resisted but unbalanced motion, which the solver
   diagnoses (no equilibrium, contactsolve.cxx); for that verdict this file names the motion from the growth
   of the equality's multiplier, and says whether it proves that no equilibrium exists. */
#include <conefeti/private/contactmodelimpl.h>
#include <petscblaslapack.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace {

/* a load works along a free motion when its work exceeds this fraction of the load's magnitude */
constexpr PetscReal kWorkTol = 1e-9;
/* entries below this (relative) are roundoff in a motion's description */
constexpr PetscReal kClean = 1e-9;
/* and below this in a motion found from a multiplier's growth over a few dozen outer iterations */
constexpr PetscReal kNoise = 5e-2;
/* a turn about an axis farther than 1/kFarAxis body radii from the body is told as a slide */
constexpr PetscReal kFarAxis = 0.2;

struct BodyFrame {
  PetscInt         nnodes = 0, offset = 0;
  const PetscReal *X    = nullptr;
  PetscReal        c[3] = {0, 0, 0}, L = 1;
  PetscBool        dirichlet = PETSC_FALSE;
};

PetscReal Norm3(const PetscReal v[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

std::string Num(PetscReal v, int digits = 6)
{
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.*g", digits, (double)v);
  return buf;
}

/* "x", "-y", or "(0.6, 0.8, 0)" for a unit vector */
std::string Direction(const PetscReal a[3])
{
  static const char *axes[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; i++)
    if (std::fabs(a[(i + 1) % 3]) < kClean && std::fabs(a[(i + 2) % 3]) < kClean) return std::string(a[i] < 0 ? "-" : "") + axes[i];
  char buf[96];
  std::snprintf(buf, sizeof(buf), "(%.3g, %.3g, %.3g)", (double)(std::fabs(a[0]) < kClean ? 0 : a[0]), (double)(std::fabs(a[1]) < kClean ? 0 : a[1]), (double)(std::fabs(a[2]) < kClean ? 0 : a[2]));
  return buf;
}

/* A rigid motion u(x) = t + w x (x - c) of one body, from its 6 motion coordinates */
struct Motion {
  PetscReal t[3], w[3];
  PetscBool turn;
  PetscReal axis[3], point[3], pitch; /* turn: the axis (unit), its point nearest c, the slide along it per radian */
};

Motion MakeMotion(const BodyFrame &f, const PetscReal v[6])
{
  Motion m;
  for (int i = 0; i < 3; i++) {
    m.t[i] = v[i];
    m.w[i] = v[3 + i] / f.L;
  }
  const PetscReal nt = Norm3(m.t), nw = Norm3(m.w);
  m.turn  = nw * f.L > kClean * nt ? PETSC_TRUE : PETSC_FALSE;
  m.pitch = 0;
  if (m.turn) {
    for (int i = 0; i < 3; i++) m.axis[i] = m.w[i] / nw;
    /* the points where u is parallel to w: c + (w x t)/|w|^2 + s w */
    const PetscReal wxt[3] = {m.w[1] * m.t[2] - m.w[2] * m.t[1], m.w[2] * m.t[0] - m.w[0] * m.t[2], m.w[0] * m.t[1] - m.w[1] * m.t[0]};
    const PetscReal scale  = f.L + Norm3(f.c);
    for (int i = 0; i < 3; i++) {
      m.point[i] = f.c[i] + wxt[i] / (nw * nw);
      if (std::fabs(m.point[i]) < kClean * scale) m.point[i] = 0;
    }
    m.pitch = (m.t[0] * m.axis[0] + m.t[1] * m.axis[1] + m.t[2] * m.axis[2]) / nw;
    if (std::fabs(m.pitch) < kClean * f.L) m.pitch = 0;
  } else
    for (int i = 0; i < 3; i++) m.axis[i] = nt > 0 ? m.t[i] / nt : 0;
  return m;
}

/* The displacement of motion m at x: a slide's t, or a turn about the axis through m.point (as told: on its grid)
   with the slide along it */
void Displace(const Motion &m, const PetscReal x[3], PetscReal u[3])
{
  if (!m.turn) {
    for (int i = 0; i < 3; i++) u[i] = m.t[i];
    return;
  }
  const PetscReal y[3] = {x[0] - m.point[0], x[1] - m.point[1], x[2] - m.point[2]};
  for (int i = 0; i < 3; i++) u[i] = m.pitch * m.w[i] + m.w[(i + 1) % 3] * y[(i + 2) % 3] - m.w[(i + 2) % 3] * y[(i + 1) % 3];
}

/* a motion's size per unit: the work along it is a force along a slide, a moment about a turn's axis */
PetscReal UnitOf(const Motion &m) { return m.turn ? Norm3(m.w) : Norm3(m.t); }

/* "slide along x", "turn about an axis through (0.5, 0.5, 0) along z" (a motion found numerically: 3 digits) */
std::string Describe(const Motion &m, int digits = 6)
{
  if (!m.turn) return "slide along " + Direction(m.axis);
  std::string s = "turn about an axis through (" + Num(m.point[0], digits) + ", " + Num(m.point[1], digits) + ", " + Num(m.point[2], digits) + ") along " + Direction(m.axis);
  if (m.pitch != 0) s += " while sliding along it by " + Num(m.pitch, digits) + " per radian";
  return s;
}

/* the same motion of space? (t at the origin and w agree) */
PetscBool SameMotion(const Motion &a, const BodyFrame &fa, const Motion &b, const BodyFrame &fb, PetscReal tol = 1e-6)
{
  PetscReal scale = 0, diff = 0;
  for (int i = 0; i < 3; i++) {
    /* translation at the origin: t - w x c */
    const int       j = (i + 1) % 3, k = (i + 2) % 3;
    const PetscReal ta = a.t[i] - (a.w[j] * fa.c[k] - a.w[k] * fa.c[j]), tb = b.t[i] - (b.w[j] * fb.c[k] - b.w[k] * fb.c[j]);
    const PetscReal L = PetscMax(fa.L, fb.L) + PetscMax(Norm3(fa.c), Norm3(fb.c));
    diff              = PetscMax(diff, PetscMax(std::fabs(ta - tb), L * std::fabs(a.w[i] - b.w[i])));
    scale             = PetscMax(scale, PetscMax(PetscMax(std::fabs(ta), std::fabs(tb)), L * PetscMax(std::fabs(a.w[i]), std::fabs(b.w[i]))));
  }
  return diff <= tol * scale ? PETSC_TRUE : PETSC_FALSE;
}

std::string BodyList(const std::vector<PetscInt> &bodies)
{
  std::string s = bodies.size() > 1 ? "bodies " : "body ";
  for (size_t i = 0; i < bodies.size(); i++) s += (i ? (i + 1 == bodies.size() ? " and " : ", ") : "") + std::to_string(bodies[i]);
  return s;
}

/* how the bodies move: one motion ("slide along x"), or each its own ("move (body 1: ...; body 2: ...)") */
std::string How(const std::vector<PetscInt> &bodies, const std::vector<Motion> &ms, PetscBool same, int digits)
{
  if (same) return Describe(ms[0], digits);
  std::string how = "move (";
  for (size_t i = 0; i < ms.size(); i++) how += (i ? "; body " : "body ") + std::to_string(bodies[i]) + ": " + Describe(ms[i], digits);
  return how + ")";
}

struct Checker {
  FEM                               fem;
  const std::vector<ContactZone>   &zones;
  const std::vector<FEMHoldingRow> &rows;
  std::vector<BodyFrame>            frames;
  std::vector<PetscInt>             dirichlet; /* all Dirichlet dofs, global numbering */

  PetscInt BodyOfNode(PetscInt g) const
  {
    for (size_t b = 0; b < frames.size(); b++)
      if (g >= frames[b].offset && g < frames[b].offset + frames[b].nnodes) return (PetscInt)b;
    return -1;
  }

  /* the bodies a motion (6 coordinates per body) moves, and its part on each */
  std::vector<PetscInt> Bodies(const std::vector<PetscReal> &v) const
  {
    PetscReal vmax = 0;
    for (PetscReal x : v) vmax = PetscMax(vmax, std::fabs(x));
    std::vector<PetscInt> bodies;
    for (size_t b = 0; b < frames.size(); b++) {
      PetscReal m = 0;
      for (int q = 0; q < 6; q++) m = PetscMax(m, std::fabs(v[6 * b + q]));
      if (m > kClean * vmax) bodies.push_back((PetscInt)b);
    }
    return bodies;
  }

  /* who moves ("body 0", "bodies 0 and 1 together") and how ("slide along x"), and the first moved body's motion;
     told, if asked: the bodies that move and each one's motion as the phrase tells it (numeric: its axis' point on
     the grid) */
  void Phrase(const std::vector<PetscReal> &v, std::string &who, std::string &how, Motion *first, PetscBool numeric = PETSC_FALSE, std::vector<std::pair<PetscInt, Motion>> *told = nullptr) const
  {
    const std::vector<PetscInt> bodies = Bodies(v);
    std::vector<Motion>         ms;
    for (PetscInt b : bodies) ms.push_back(MakeMotion(frames[b], &v[6 * b]));
    if (numeric) /* points on a grid of a power of ten, at least a hundredth of the body's size */
      for (size_t i = 0; i < ms.size(); i++)
        if (ms[i].turn) {
          const PetscReal grid = std::pow(10.0, std::ceil(std::log10(1e-2 * frames[bodies[i]].L)));
          for (PetscReal &p : ms[i].point) p = grid * std::round(p / grid) + 0.0;
        }
    const int digits = numeric ? 3 : 6;
    *first           = ms[0];
    PetscBool same   = PETSC_TRUE;
    for (size_t i = 1; i < ms.size(); i++) same = (same && SameMotion(ms[0], frames[bodies[0]], ms[i], frames[bodies[i]], numeric ? 5e-2 : 1e-6)) ? PETSC_TRUE : PETSC_FALSE;
    /* bodies told to move together move by the first one's motion (a motion of space: Displace() needs no frame) */
    if (told)
      for (size_t i = 0; i < ms.size(); i++) told->emplace_back(bodies[i], same ? ms[0] : ms[i]);
    /* "together": one motion, or (at setup) one free motion that needs them all; bodies that a multiplier's growth
       moves each its own way are not together */
    who = BodyList(bodies) + (bodies.size() > 1 && (same || !numeric) ? " together" : "");
    how = How(bodies, ms, same, digits);
  }

  /* why nothing resists the motion on these bodies, and how to hold them */
  void Explain(const std::vector<PetscReal> &v, PetscBool checkaxis, std::string &why, std::string &cure) const
  {
    const std::vector<PetscInt> bodies = Bodies(v);
    std::vector<std::string>    reasons;
    std::string                 supports, friction;
    for (PetscInt b : bodies) {
      const std::string who   = bodies.size() > 1 ? "body " + std::to_string(b) + ": " : "";
      const Motion      m     = MakeMotion(frames[b], &v[6 * b]);
      PetscBool         zoned = PETSC_FALSE, onaxis = PETSC_TRUE, held = PETSC_FALSE;
      std::string       reason = who + (frames[b].dirichlet ? "its supports (Dirichlet conditions) do not stop it" : "no support (Dirichlet condition) holds it");
      for (size_t z = 0; z < zones.size(); z++) {
        const ContactZone &zn = zones[z];
        if (zn.body != b && !(zn.type == CONTACT_ZONE_BODIES && zn.other_body == b)) continue;
        zoned = PETSC_TRUE;
        if (zn.law == CONTACT_FRICTIONLESS) reason += ", and its frictionless contact zone " + std::to_string(z) + " carries no tangential force";
        else if (zn.coef == 0) reason += ", and its contact zone " + std::to_string(z) + (zn.law == CONTACT_COULOMB ? " has friction coefficient 0" : " has slip bound 0");
        if (zn.law == CONTACT_FRICTIONLESS || zn.coef == 0) friction += (friction.empty() ? "" : ", ") + std::string("-scene_zone") + std::to_string(z) + "_law coulomb";
      }
      if (!zoned) reason += (frames[b].dirichlet ? ", and no contact zone touches it" : " and no contact zone touches it");
      /* a turn that every holding node of the body sits on */
      if (checkaxis && m.turn) {
        auto offaxis = [&](const PetscReal *x) {
          const PetscReal y[3] = {x[0] - m.point[0], x[1] - m.point[1], x[2] - m.point[2]};
          const PetscReal c[3] = {y[1] * m.axis[2] - y[2] * m.axis[1], y[2] * m.axis[0] - y[0] * m.axis[2], y[0] * m.axis[1] - y[1] * m.axis[0]};
          held                 = PETSC_TRUE;
          if (Norm3(c) > 1e-9 * frames[b].L) onaxis = PETSC_FALSE;
        };
        for (PetscInt g : dirichlet)
          if (g / 3 >= frames[b].offset && g / 3 < frames[b].offset + frames[b].nnodes) offaxis(&frames[b].X[3 * (g / 3 - frames[b].offset)]);
        for (const FEMHoldingRow &r : rows) {
          if (r.body == b) offaxis(&frames[b].X[3 * r.node]);
          if (r.other_body == b)
            for (PetscInt v = 0; v < r.nother; v++) offaxis(&frames[b].X[3 * r.other_node[v]]);
        }
        if (held && onaxis) reason += "; every node that holds it lies on that axis";
      }
      reasons.push_back(reason);
      supports += (supports.empty() ? "" : " or ") + std::string("-scene_body") + std::to_string(b) + "_fix";
    }
    why = "";
    for (size_t i = 0; i < reasons.size(); i++) why += (i ? "; " : "") + reasons[i];
    cure = std::string(bodies.size() > 1 ? "hold them" : "hold it") + " with a support (FEMSetDirichlet(); in a scene " + supports + ", or _fix_x, _fix_y, _fix_z for one component)";
    if (!friction.empty()) cure += " or with friction (" + friction + " with _friction F > 0)";
  }
};

/* The frame (centroid, size) and the nodes of every body */
PetscErrorCode GetFrames(FEM fem, std::vector<BodyFrame> &frames)
{
  PetscInt nb;

  PetscFunctionBegin;
  PetscCall(FEMGetNumBodies(fem, &nb));
  PetscCallCXX(frames.assign(nb, BodyFrame{}));
  for (PetscInt b = 0; b < nb; b++) {
    BodyFrame &f = frames[b];
    PetscCall(FEMGetBodyNodes(fem, b, &f.nnodes, &f.X));
    PetscCall(FEMGetBodyNodeOffset(fem, b, &f.offset));
    PetscCall(FEMComputeRigidMotionFrame(fem, b, f.c, &f.L));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The load as work per unit of each motion coordinate (force, and moment about the centroid / L), and the sum of
   the bodies' load magnitudes */
PetscErrorCode GetLoadWork(FEM fem, const std::vector<BodyFrame> &frames, std::vector<PetscReal> &g, PetscReal *magnitude)
{
  PetscFunctionBegin;
  PetscCallCXX(g.assign(6 * frames.size(), 0.0));
  *magnitude = 0;
  for (size_t b = 0; b < frames.size(); b++) {
    PetscReal F[3], Mo[3], mag;
    PetscCall(FEMComputeLoadResultant(fem, (PetscInt)b, frames[b].c, F, Mo, &mag));
    for (int q = 0; q < 3; q++) {
      g[6 * b + q]     = F[q];
      g[6 * b + 3 + q] = Mo[q] / frames[b].L;
    }
    *magnitude += mag;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Every Dirichlet dof (global numbering) in ck.dirichlet, and which bodies have one */
PetscErrorCode GatherDirichletDofs(FEM fem, Checker &ck)
{
  IS              is, all;
  PetscInt        ndir;
  const PetscInt *idx;

  PetscFunctionBegin;
  PetscCall(FEMGetGlobalDirichletDofs(fem, &is));
  PetscCall(ISAllGather(is, &all));
  PetscCall(ISDestroy(&is));
  PetscCall(ISGetLocalSize(all, &ndir));
  PetscCall(ISGetIndices(all, &idx));
  PetscCallCXX(ck.dirichlet.assign(idx, idx + ndir));
  PetscCall(ISRestoreIndices(all, &idx));
  PetscCall(ISDestroy(&all));
  for (PetscInt g : ck.dirichlet) {
    const PetscInt b = ck.BodyOfNode(g / 3);
    if (b >= 0) ck.frames[b].dirichlet = PETSC_TRUE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Which motion each body makes (nullptr: at rest), and the largest displacement of the motions told at their
   bodies (a turn's |w| L on top of its centroid's) */
PetscReal MotionsOf(const Checker &ck, const std::vector<std::pair<PetscInt, Motion>> &told, std::vector<const Motion *> &of)
{
  PetscReal scale = 0;
  of.assign(ck.frames.size(), nullptr);
  for (const auto &bm : told) {
    const BodyFrame &f = ck.frames[bm.first];
    PetscReal        uc[3];
    of[bm.first] = &bm.second;
    Displace(bm.second, f.c, uc);
    scale = PetscMax(scale, Norm3(uc) + (bm.second.turn ? Norm3(bm.second.w) * f.L : 0));
  }
  return scale;
}

/* The jump of contact node k's rows under the motions (its side minus the weighted master points; v_n > 0 closes
   the gap): the normal part and the size of the tangential part. The whole jump, also in components a row leaves
   out for the node's Dirichlet conditions: a motion that proves anything moves no support, so it vanishes there */
void NodeJump(const Checker &ck, const std::vector<const Motion *> &of, const ContactNodeInfo &k, PetscReal *vn, PetscReal *vt)
{
  PetscReal j[3] = {0, 0, 0}, u[3];
  if (of[k.body]) Displace(*of[k.body], &ck.frames[k.body].X[3 * k.node], j);
  for (PetscInt v = 0; v < k.nmaster; v++)
    if (k.other_body >= 0 && of[k.other_body]) {
      Displace(*of[k.other_body], &ck.frames[k.other_body].X[3 * k.master[v]], u);
      for (int q = 0; q < 3; q++) j[q] -= k.weight[v] * u[q];
    }
  const PetscReal v1 = j[0] * k.t1[0] + j[1] * k.t1[1] + j[2] * k.t1[2], v2 = j[0] * k.t2[0] + j[1] * k.t2[1] + j[2] * k.t2[2];
  *vn = j[0] * k.n[0] + j[1] * k.n[1] + j[2] * k.n[2];
  *vt = PetscSqrtReal(v1 * v1 + v2 * v2);
}

/* Whether the motion told (each moving body's rigid motion) proves that no equilibrium exists. An equilibrium
   has contact forces l in the admissible set (l_n >= 0; Coulomb: |l_t| <= F l_n; Tresca: |l_t| <= s) with
   G l = e, that is l'B R a = f'R a for every rigid motion R a of the subdomains: the contact forces would do
   the load's work along the motion. So a motion that moves no support, and along which the admissible contact
   forces can do at most D < the load's work (Farkas' lemma), rules out any equilibrium. Along a jump v of a
   node's rows (v_n > 0 closes the gap), the most work of its admissible forces is 0 when v_n <= 0 and, for
   Coulomb, v_n + F |v_t| <= 0 (otherwise unbounded: no proof), plus s |v_t| for Tresca. A friction polygon
   (-contact_friction_polygon) is inscribed in its disk (contactpolygon.cxx), so the disk's bounds hold for it too.
   The checks hold to 1e-8 of the motion's largest displacement, the told axis' point being rounded to its grid (a
   node on the tipping edge moves by rounding only), and the load must outwork D by 1e-6 of the most it could do
   (its magnitude times that displacement): a load through the edge has an equilibrium, and a moment of roundoff
   about the rounded axis proves nothing. work: the load's along the motion told; resisted: D; violation: the
   largest violation of a check, relative to the largest displacement (PETSC_MAX_REAL when nothing moves). */
PetscBool ProvesNoEquilibrium(const Checker &ck, const ContactModelData &d, const std::vector<std::pair<PetscInt, Motion>> &told, const std::vector<PetscReal> &g, PetscReal magnitude, PetscReal *work,
                              PetscReal *resisted, PetscReal *violation)
{
  std::vector<const Motion *> of;
  const PetscReal             scale = MotionsOf(ck, told, of);
  PetscReal                   worst = 0; /* the largest violation of a check, in displacement */
  *work = *resisted = 0;
  *violation        = PETSC_MAX_REAL;
  for (const auto &bm : told) {
    const BodyFrame &f = ck.frames[bm.first];
    PetscReal        uc[3];
    Displace(bm.second, f.c, uc);
    for (int q = 0; q < 3; q++) *work += g[6 * bm.first + q] * uc[q] + g[6 * bm.first + 3 + q] * f.L * (bm.second.turn ? bm.second.w[q] : 0);
  }
  if (!(scale > 0)) return PETSC_FALSE;
  for (PetscInt gd : ck.dirichlet) { /* a support must not move */
    const PetscInt b = ck.BodyOfNode(gd / 3);
    PetscReal      u[3];
    if (b < 0 || !of[b]) continue;
    Displace(*of[b], &ck.frames[b].X[3 * (gd / 3 - ck.frames[b].offset)], u);
    worst = PetscMax(worst, std::fabs(u[gd % 3]));
  }
  for (const ContactNodeInfo &k : d.nodes) {
    PetscReal vn, vt;
    NodeJump(ck, of, k, &vn, &vt);
    worst = PetscMax(worst, vn);
    if (k.law == CONTACT_FRICTIONLESS || !(k.coef > 0)) continue;
    if (k.law == CONTACT_COULOMB) worst = PetscMax(worst, vn + k.coef * vt);
    else *resisted += k.coef * vt;
  }
  *violation = worst / scale;
  return *violation <= 1e-8 && *work - *resisted > 1e-6 * magnitude * scale ? PETSC_TRUE : PETSC_FALSE;
}

/* The motion told, polished until it proves that no equilibrium exists, when a motion near it does. A motion found
   from a multiplier's growth and rounded to be told misses the edge its bodies tip over by the growth's noise and
   by the rounding of its axis' point (an edge at y = 0.0625 told at 0.06), so the nodes on that edge close by a
   little and the check fails although the turn about the edge itself passes. So, a few passes: every contact node
   whose check the motion breaks (its jump closes, or leaves the polar of its Coulomb cone) keeps its jump at zero
   from then on (the normal component; the whole jump at a Coulomb node), the moving bodies' supports stay put, and
   the motion becomes the nearest one that does so (the least change of its coordinates: per group of bodies that
   move as one, the translation at the first body's centroid and the turn times its size; rows scaled to unit
   length, rows of roundoff left out). The first pass projects whatever broke, a support too. Polishing only
   proposes: ProvesNoEquilibrium() decides. On success told holds the polished motions
   (the same bodies, none of them at rest) and *passes the passes taken; on failure told is left as it was. */
PetscErrorCode PolishProof(ContactModel cm, const Checker &ck, const ContactModelData &d, PetscBool together, const std::vector<PetscReal> &g, PetscReal magnitude,
                           std::vector<std::pair<PetscInt, Motion>> &told, PetscInt *passes, PetscReal *work, PetscReal *resisted, PetscReal *violation)
{
  constexpr int            kPasses = 5;
  const size_t             ng      = together ? 1 : told.size();
  const PetscInt           n       = 6 * (PetscInt)ng;
  std::vector<PetscInt>    group(ck.frames.size(), -1), nz;
  std::vector<char>        active(d.nodes.size(), 0);
  std::vector<PetscReal>   x(n), r(n), lambda(n);
  std::vector<PetscScalar> M((size_t)n * n), Ms((size_t)n * n, 0.0); /* Ms: the supports' rows */
  PetscReal                size = 0;                                 /* the sum of the terms' sizes in the row being built: below 1e-12 of it, a row is roundoff */

  PetscFunctionBegin;
  *passes = 0;
  if (told.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  for (size_t i = 0; i < told.size(); i++) group[told[i].first] = together ? 0 : (PetscInt)i;
  auto frame = [&](size_t q) -> const BodyFrame & { return ck.frames[told[q].first]; };
  for (size_t q = 0; q < ng; q++) {
    const Motion &m = told[q].second;
    Displace(m, frame(q).c, &x[6 * q]);
    for (int k = 0; k < 3; k++) x[6 * q + 3 + k] = m.turn ? m.w[k] * frame(q).L : 0;
  }
  /* r += factor * (dir . u_b(X)) as a function of the coordinates: dir . (t + (s / L) x y) = dir . t + s . (y x dir) / L */
  auto addU = [&](PetscInt b, const PetscReal *X, const PetscReal dir[3], PetscReal factor) {
    const PetscInt q = b >= 0 ? group[b] : -1;
    if (q < 0) return;
    const BodyFrame &f    = frame(q);
    const PetscReal  y[3] = {X[0] - f.c[0], X[1] - f.c[1], X[2] - f.c[2]};
    for (int k = 0; k < 3; k++) {
      r[6 * q + k] += factor * dir[k];
      r[6 * q + 3 + k] += factor * (y[(k + 1) % 3] * dir[(k + 2) % 3] - y[(k + 2) % 3] * dir[(k + 1) % 3]) / f.L;
    }
    size += std::fabs(factor) * (1 + Norm3(y) / f.L);
  };
  /* the row built, scaled to unit length, into A; a row of roundoff (a node's two sides in one group cancel) is left out */
  auto addRow = [&](std::vector<PetscScalar> &A) {
    PetscReal nr = 0;
    nz.clear();
    for (PetscInt i = 0; i < n; i++)
      if (r[i] != 0) {
        nz.push_back(i);
        nr += r[i] * r[i];
      }
    if (nr > PetscSqr(1e-12 * size))
      for (PetscInt i : nz)
        for (PetscInt j : nz) A[i + n * j] += r[i] * r[j] / nr;
    for (PetscInt i : nz) r[i] = 0;
    size = 0;
  };
  for (PetscInt gd : ck.dirichlet) {
    const PetscInt b = ck.BodyOfNode(gd / 3);
    if (b < 0 || group[b] < 0) continue;
    const PetscReal *X      = &ck.frames[b].X[3 * (gd / 3 - ck.frames[b].offset)];
    const PetscReal  dir[3] = {gd % 3 == 0 ? 1.0 : 0.0, gd % 3 == 1 ? 1.0 : 0.0, gd % 3 == 2 ? 1.0 : 0.0};
    addU(b, X, dir, 1);
    addRow(Ms);
  }
  std::vector<std::pair<PetscInt, Motion>> polished = told;
  std::vector<const Motion *>              of;
  for (int pass = 1; pass <= kPasses; pass++) {
    const PetscReal scale  = MotionsOf(ck, polished, of);
    PetscInt        broken = 0, held = 0, left = 0;
    if (!(scale > 0)) break;
    /* the contact nodes whose check the motion breaks, each held from the pass that finds it broken on */
    for (size_t i = 0; i < d.nodes.size(); i++) {
      const ContactNodeInfo &k = d.nodes[i];
      PetscReal              vn, vt;
      NodeJump(ck, of, k, &vn, &vt);
      if (!active[i] && (vn > 1e-9 * scale || (k.law == CONTACT_COULOMB && k.coef > 0 && vn + k.coef * vt > 1e-9 * scale))) {
        active[i] = 1;
        broken++;
      }
      held += active[i];
    }
    /* the first pass projects anyway: the motion told may fail by a support it moves, whose rows the projection holds */
    if (!broken && pass > 1) { /* nothing more to hold at zero: a motion near this one does not prove it either */
      PetscCall(PetscInfo(cm, "polishing, pass %d: the motion breaks no check it did not break before\n", pass));
      break;
    }
    /* the normal equations of the rows held at zero, and their null space */
    M = Ms;
    for (size_t i = 0; i < d.nodes.size(); i++) {
      const ContactNodeInfo &k = d.nodes[i];
      if (!active[i]) continue;
      const PetscBool  cone    = k.law == CONTACT_COULOMB && k.coef > 0 ? PETSC_TRUE : PETSC_FALSE;
      const PetscReal *dirs[3] = {k.n, k.t1, k.t2};
      for (int c = 0; c < (cone ? 3 : 1); c++) {
        addU(k.body, &ck.frames[k.body].X[3 * k.node], dirs[c], 1);
        for (PetscInt v = 0; v < k.nmaster; v++) addU(k.other_body, &ck.frames[k.other_body].X[3 * k.master[v]], dirs[c], -k.weight[v]);
        addRow(M);
      }
    }
    {
      PetscBLASInt             bn, lwork = -1, info;
      PetscScalar              wq;
      std::vector<PetscScalar> wk;
      PetscCall(PetscBLASIntCast(n, &bn));
      PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "L", &bn, M.data(), &bn, lambda.data(), &wq, &lwork, &info));
      if (!info) {
        PetscCall(PetscBLASIntCast((PetscInt)PetscRealPart(wq), &lwork));
        PetscCallCXX(wk.resize(lwork));
        PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "L", &bn, M.data(), &bn, lambda.data(), wk.data(), &lwork, &info));
      }
      if (info) {
        PetscCall(PetscInfo(cm, "polishing, pass %d: LAPACK syev failed (info %d)\n", pass, (int)info));
        break;
      }
    }
    /* x: its projection on the eigenvectors of (numerically) zero eigenvalue, ascending */
    std::vector<PetscReal> y(n, 0.0);
    const PetscReal        tol = 1e-10 * PetscMax(lambda[n - 1], 1.0);
    for (PetscInt e = 0; e < n && lambda[e] <= tol; e++, left++) {
      PetscReal c = 0;
      for (PetscInt i = 0; i < n; i++) c += PetscRealPart(M[i + n * e]) * x[i];
      for (PetscInt i = 0; i < n; i++) y[i] += c * PetscRealPart(M[i + n * e]);
    }
    /* every group must still move: the phrase names its bodies */
    PetscReal xmax = 0;
    for (PetscReal a : x) xmax = PetscMax(xmax, std::fabs(a));
    PetscBool still = PETSC_TRUE;
    for (size_t q = 0; q < ng; q++) {
      PetscReal ymax = 0;
      for (int k = 0; k < 6; k++) ymax = PetscMax(ymax, std::fabs(y[6 * q + k]));
      if (!(ymax > 1e-3 * xmax)) still = PETSC_FALSE;
    }
    if (!still) {
      PetscCall(PetscInfo(cm, "polishing, pass %d: %" PetscInt_FMT " contact nodes held still leave %" PetscInt_FMT " of %" PetscInt_FMT " motion coordinates, which stop a body the motion moves\n",
                          pass, held, left, n));
      break;
    }
    x = y;
    for (size_t i = 0; i < told.size(); i++) polished[i].second = MakeMotion(frame(together ? 0 : i), &x[6 * (together ? 0 : i)]);
    PetscReal       pw, pr, pv;
    const PetscBool proves = ProvesNoEquilibrium(ck, d, polished, g, magnitude, &pw, &pr, &pv);
    PetscCall(PetscInfo(cm,
                        "polishing, pass %d: %" PetscInt_FMT " contact nodes held still leave %" PetscInt_FMT " of %" PetscInt_FMT
                        " motion coordinates; largest violation of a check %g, the load's work %g, the slip bounds' most %g\n",
                        pass, held, left, n, (double)pv, (double)pw, (double)pr));
    if (proves) {
      told       = polished;
      *passes    = pass;
      *work      = pw;
      *resisted  = pr;
      *violation = pv;
      break;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/* Stop with an error naming the body and the motion when a rigid motion of the bodies is resisted by no
   Dirichlet condition and no contact row: no equilibrium when the load works along it, no unique
   displacement otherwise (an engineer wants to be told, not handed one of infinitely many answers). */
PetscErrorCode ContactCheckRigidMotions_Private(ContactModel cm, FEM fem, const std::vector<ContactZone> &zones, const std::vector<FEMHoldingRow> &rows)
{
  MPI_Comm   comm = PetscObjectComm((PetscObject)cm);
  PetscInt   nb, k;
  PetscReal *free_motions;
  Checker    ck{fem, zones, rows, {}, {}};

  PetscFunctionBegin;
  PetscCall(FEMComputeFreeRigidMotions(fem, (PetscInt)rows.size(), rows.data(), &k, &free_motions));
  if (!k) PetscFunctionReturn(PETSC_SUCCESS);
  /* a free motion: what follows only words the error, so its cost (gathering the Dirichlet dofs again) is paid
     on a run that stops */
  PetscCall(FEMGetNumBodies(fem, &nb));
  const PetscInt         n = 6 * nb;
  std::vector<PetscReal> M(free_motions, free_motions + (size_t)k * n); /* the free motions in motion coordinates, in echelon form */
  PetscCall(PetscFree(free_motions));
  PetscCall(GetFrames(fem, ck.frames));
  PetscCall(GatherDirichletDofs(fem, ck));

  std::vector<PetscReal> g;
  PetscReal              magnitude;
  PetscCall(GetLoadWork(fem, ck.frames, g, &magnitude));
  /* every free motion, grouped by who moves ("body 0: slide along x, slide along y"), each shown along the
     positive axis (its sign is arbitrary; +z rather than -z); the first one the load works along (echelon
     order: slides before turns) is the one the message names */
  std::string list, lastwho;
  PetscInt    worked = -1;
  PetscReal   work   = 0;
  for (PetscInt j = 0; j < k; j++) {
    std::vector<PetscReal> v(M.begin() + j * n, M.begin() + (j + 1) * n);
    std::string            who, how;
    Motion                 first;
    PetscReal              vmax = 0, w = 0;
    ck.Phrase(v, who, how, &first);
    const PetscReal *a   = first.axis;
    const int        big = std::fabs(a[0]) >= std::fabs(a[1]) && std::fabs(a[0]) >= std::fabs(a[2]) ? 0 : (std::fabs(a[1]) >= std::fabs(a[2]) ? 1 : 2);
    if (a[big] < 0) {
      for (PetscInt l = 0; l < n; l++) M[j * n + l] = v[l] = -v[l];
      ck.Phrase(v, who, how, &first);
    }
    if (j < 8) list += who == lastwho ? ", " + how : (j ? "; " : "") + who + ": " + how;
    lastwho = who;
    for (PetscInt l = 0; l < n; l++) {
      vmax = PetscMax(vmax, std::fabs(v[l]));
      w += g[l] * v[l];
    }
    /* per unit of the motion: a force along a slide, a moment about a turn's axis */
    if (worked < 0 && std::fabs(w) > kWorkTol * magnitude * vmax) {
      worked = j;
      work   = w / UnitOf(first);
    }
  }
  if (k > 8) list += "; and " + std::to_string(k - 8) + " more";

  std::string why, cure, msg;
  if (worked >= 0) {
    std::vector<PetscReal> v(M.begin() + worked * n, M.begin() + (worked + 1) * n);
    std::string            who, how;
    Motion                 m;
    char                   amount[128];
    /* the sign of the motion the load pushes along */
    if (work < 0) {
      for (PetscReal &x : v) x = -x;
      work = -work;
    }
    ck.Phrase(v, who, how, &m);
    ck.Explain(v, PETSC_TRUE, why, cure);
    if (m.turn) std::snprintf(amount, sizeof(amount), "the moment of the load about that axis is %.4g N m", (double)work);
    else std::snprintf(amount, sizeof(amount), "the load along that motion is %.4g N", (double)work);
    msg = "no equilibrium: " + who + " can " + how + " and nothing resists it (" + why + "): " + amount + ". Free rigid motions: " + list + ". Fix: " + cure;
  } else {
    std::vector<PetscReal> any(n, 0.0);
    for (PetscInt j = 0; j < k; j++)
      for (PetscInt l = 0; l < n; l++) any[l] += std::fabs(M[j * n + l]);
    if (k == 1) any.assign(M.begin(), M.end());
    ck.Explain(any, k == 1 ? PETSC_TRUE : PETSC_FALSE, why, cure);
    msg = std::string("the displacement is not unique: nothing resists ") + (k > 1 ? "these rigid motions" : "this rigid motion") + ": " + list + " (" + why + "); the load does no work along " +
          (k > 1 ? "them" : "it") + ", so the solution holds any amount of " + (k > 1 ? "them" : "it") + ". Fix: " + cure;
  }
  if (msg.size() > 1900) msg = msg.substr(0, 1890) + " ...";
  SETERRQ(comm, PETSC_ERR_NOT_CONVERGED, "%s", msg.c_str());
}

/* The rigid motion of the bodies along which the multiplier of G l = e grew where the contact solve stagnated
   (TaoSMALXEGetMultiplierGrowth()): the motion the load drives and the contact zones do not stop, told as the
   setup's check tells a free motion. Its rigid-body amplitudes, alpha = -(G G')^-1 G w, give the displacement
   R alpha; fitted per body by a rigid motion, it must be one (a body's subdomains move together: the gluing rows
   are equalities, so their multipliers' growth cannot pull the subdomains apart) and the load must work along it,
   else the phrase stays empty and the solver's sentence goes without it. The growth comes from a finite number of
   outer iterations, so the motion is rounded: bodies below 1e-2 of the largest motion are dropped, and so are the
   parts of the axis (or of a slide's direction) and the slide along the axis below kNoise; a turn about an axis
   farther than 5 body radii is a slide; points lie on a grid (a power of ten, at least a hundredth of the body's
   size) and have 3 digits. A phrase longer than maxlen (several bodies that move apart) only names the bodies, as
   brief always does; -info gives it whole. proof: why the motion told proves that no equilibrium exists
   (ProvesNoEquilibrium(); when the rounded motion does not, the motion polished by PolishProof(), which the phrase
   then tells), or empty. */
PetscErrorCode ContactDescribeStagnatedMotion_Private(ContactModel cm, FEM fem, FETI feti, Tao tao, Vec alpha, Vec u, size_t maxlen, std::string &phrase, std::string &brief, std::string &proof)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)cm);
  Vec                w, x, up, ug, X;
  Mat                R;
  PetscInt           its, nb, lo, hi;
  const PetscScalar *ua, *xa;
  /* the setup check's phrasing, without zones or holding rows (nothing here says why a motion is free) */
  const std::vector<ContactZone>   none;
  const std::vector<FEMHoldingRow> norows;
  Checker                          ck{fem, none, norows, {}, {}};

  PetscFunctionBegin;
  phrase.clear();
  brief.clear();
  proof.clear();
  PetscCall(TaoGetSolution(tao, &x));
  PetscCall(VecDuplicate(x, &w));
  PetscCall(TaoSMALXEGetMultiplierGrowth(tao, w, &its));
  if (!its) {
    PetscCall(VecDestroy(&w));
    PetscCall(PetscInfo(cm, "no growth of the equality's multiplier kept (a loop shorter than -tao_smalxe_stagnation_its)\n"));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(VecDuplicate(alpha, &x));
  PetscCall(VecSet(x, 0.0));
  PetscCall(FETIComputeAlphaFromEquality(feti, w, x));
  PetscCall(VecDestroy(&w));
  PetscCall(FETIGetKernel(feti, &R));
  PetscCall(VecDuplicate(u, &up));
  PetscCall(MatMult(R, x, up));
  PetscCall(VecDestroy(&x));
  PetscCall(FEMCreateGlobalCoordinates(fem, &X));
  PetscCall(VecDuplicate(X, &ug));
  PetscCall(FEMPrimalToGlobal(fem, up, ug));
  PetscCall(VecDestroy(&up));

  /* per body the normal equations of the fit u(x) ~ sum_q v_q r_q(x), r_q the body's 6 motions (translations e_q,
     turns e_q x (x - c) / L), and |u|^2 for the fit's residual: summed over the owned nodes, then over the ranks */
  PetscCall(GetFrames(fem, ck.frames));
  const std::vector<BodyFrame> &frames = ck.frames;
  nb                                   = (PetscInt)frames.size();
  std::vector<PetscReal> sums((size_t)nb * 43, 0.0); /* per body: N (36), rhs (6), |u|^2 */
  PetscCall(VecGetOwnershipRange(ug, &lo, &hi));
  PetscCall(VecGetArrayRead(ug, &ua));
  PetscCall(VecGetArrayRead(X, &xa));
  for (PetscInt i = 0; i < (hi - lo) / 3; i++) {
    const PetscInt b = ck.BodyOfNode(lo / 3 + i);
    if (b < 0) continue;
    const BodyFrame &f = frames[b];
    PetscReal        r[6][3], y[3];
    for (int k = 0; k < 3; k++) y[k] = (PetscRealPart(xa[3 * i + k]) - f.c[k]) / f.L;
    for (int q = 0; q < 3; q++) {
      /* e_q, and e_q x y */
      for (int k = 0; k < 3; k++) r[q][k] = q == k ? 1 : 0;
      r[3 + q][q]           = 0;
      r[3 + q][(q + 1) % 3] = -y[(q + 2) % 3];
      r[3 + q][(q + 2) % 3] = y[(q + 1) % 3];
    }
    PetscReal *S = &sums[(size_t)b * 43];
    for (int p = 0; p < 6; p++) {
      for (int q = 0; q < 6; q++) S[6 * p + q] += r[p][0] * r[q][0] + r[p][1] * r[q][1] + r[p][2] * r[q][2];
      for (int k = 0; k < 3; k++) S[36 + p] += r[p][k] * PetscRealPart(ua[3 * i + k]);
    }
    for (int k = 0; k < 3; k++) S[42] += PetscSqr(PetscRealPart(ua[3 * i + k]));
  }
  PetscCall(VecRestoreArrayRead(X, &xa));
  PetscCall(VecRestoreArrayRead(ug, &ua));
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&ug));
  PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, sums.data(), (PetscMPIInt)sums.size(), MPIU_REAL, MPIU_SUM, comm));

  /* solve each 6 x 6 system (SPD for a body with three nodes off a line; a pivot below 1e-12 of the first counts as
     singular) by LAPACK's Cholesky; a body that the growth does not move rigidly (a residual above a tenth of the
     largest body's |u|) makes the motion no rigid one: no phrase */
  std::vector<PetscReal> v((size_t)6 * nb, 0.0), misfit(nb, 0.0); /* misfit: |u - R v|^2 / |u|^2 of each body */
  PetscReal              umax = 0;
  for (PetscInt b = 0; b < nb; b++) umax = PetscMax(umax, sums[(size_t)b * 43 + 42]);
  for (PetscInt b = 0; b < nb; b++) {
    PetscReal   *S = &sums[(size_t)b * 43], *vb = &v[(size_t)6 * b];
    PetscScalar  N[36], rhs[6];
    PetscBLASInt six = 6, one = 1, info;
    if (!(S[42] > 0)) continue;
    for (int q = 0; q < 36; q++) N[q] = S[q];
    for (int q = 0; q < 6; q++) rhs[q] = S[36 + q];
    PetscCallBLAS("LAPACKpotrf", LAPACKpotrf_("L", &six, N, &six, &info));
    bool spd = info == 0;
    for (int q = 0; q < 6 && spd; q++) spd = PetscSqr(PetscRealPart(N[7 * q])) > 1e-12 * S[0];
    if (!spd) {
      PetscCall(PetscInfo(cm, "body %" PetscInt_FMT ": its nodes do not determine a rigid motion\n", b));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    PetscCallBLAS("LAPACKpotrs", LAPACKpotrs_("L", &six, &one, N, &six, rhs, &six, &info));
    for (int q = 0; q < 6; q++) vb[q] = PetscRealPart(rhs[q]);
    PetscReal fitted = 0; /* |R v|^2 = v'rhs at the least-squares v; the residual is |u|^2 - that */
    for (int i = 0; i < 6; i++) fitted += vb[i] * S[36 + i];
    misfit[b] = PetscMax(S[42] - fitted, 0) / S[42];
    PetscCall(PetscInfo(cm, "body %" PetscInt_FMT ": a rigid fit of the multiplier's growth over %" PetscInt_FMT " outer iterations leaves %g of the largest body's displacement (%g of its own)\n", b,
                        its, (double)PetscSqrtReal(misfit[b] * S[42] / umax), (double)PetscSqrtReal(misfit[b])));
    if (S[42] - fitted > 1e-2 * umax) PetscFunctionReturn(PETSC_SUCCESS);
  }
  /* drop the growth's noise: bodies that hardly move, a turn too slow to matter beside the slide, the parts of the
     axis (or of the slide's direction) and the slide along the axis below kNoise */
  PetscReal vmax = 0;
  for (PetscReal a : v) vmax = PetscMax(vmax, std::fabs(a));
  if (!(vmax > 0)) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt b = 0; b < nb; b++) {
    PetscReal *t = &v[6 * b], *w = &v[6 * b + 3], bmax = 0;
    for (int q = 0; q < 6; q++) bmax = PetscMax(bmax, std::fabs(v[6 * b + q]));
    if (bmax < 1e-2 * vmax) {
      for (int q = 0; q < 6; q++) v[6 * b + q] = 0;
      continue;
    }
    if (misfit[b] > 1e-2) { /* a body the phrase would name must move rigidly itself, within a tenth */
      PetscCall(PetscInfo(cm, "body %" PetscInt_FMT " moves, but not rigidly\n", b));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    const PetscReal nt = Norm3(t), nw = Norm3(w); /* w is turn times L: comparable with t; nt / nw is the axis' distance in radii */
    if (nw < kFarAxis * nt) w[0] = w[1] = w[2] = 0;
    PetscReal *dir = Norm3(w) > 0 ? w : t, nd = Norm3(dir);
    for (int k = 0; k < 3; k++)
      if (std::fabs(dir[k]) < kNoise * nd) dir[k] = 0;
    if (Norm3(w) > 0) {
      const PetscReal n2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2], along = (t[0] * w[0] + t[1] * w[1] + t[2] * w[2]) / n2;
      if (std::fabs(along) * PetscSqrtReal(n2) < kNoise * PetscMax(nt, PetscSqrtReal(n2)))
        for (int k = 0; k < 3; k++) t[k] -= along * w[k];
    }
  }

  /* the load must work along it: the direction it drives */
  std::vector<PetscReal> g;
  PetscReal              magnitude, work = 0;
  PetscCall(GetLoadWork(fem, frames, g, &magnitude));
  for (size_t l = 0; l < v.size(); l++) work += g[l] * v[l];
  vmax = 0;
  for (PetscReal a : v) vmax = PetscMax(vmax, std::fabs(a));
  if (!(work > kWorkTol * magnitude * vmax)) {
    PetscCall(PetscInfo(cm, "the load does no positive work along the multiplier's growth (%g)\n", (double)work));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  std::string                              who, how;
  Motion                                   m;
  char                                     amount[96];
  std::vector<std::pair<PetscInt, Motion>> told;
  PetscReal                                toldwork, bound, violation;
  ck.Phrase(v, who, how, &m, PETSC_TRUE, &told);
  const PetscBool apart = how.rfind("move (", 0) == 0 ? PETSC_TRUE : PETSC_FALSE; /* bodies that move apart: no one axis, no one number */
  /* the motion as told, checked against every contact node and support; when that fails, polished */
  PetscCall(GatherDirichletDofs(fem, ck));
  PetscBool proves = ProvesNoEquilibrium(ck, *cm->data, told, g, magnitude, &toldwork, &bound, &violation);
  PetscCall(PetscInfo(cm, "the motion told %s that no equilibrium exists: its largest violation of a check %g (of its largest displacement), the load's work along it %g, the slip bounds' most %g\n",
                      proves ? "proves" : "does not prove", (double)violation, (double)(toldwork / UnitOf(m)), (double)(bound / UnitOf(m))));
  PetscInt passes = 0;
  if (!proves) PetscCall(PolishProof(cm, ck, *cm->data, apart ? PETSC_FALSE : PETSC_TRUE, g, magnitude, told, &passes, &toldwork, &bound, &violation));
  /* one verdict and one motion on every rank, rank 0's: the checks' thresholds are sharp, and LAPACK need not give the
     same bits on different processors */
  {
    PetscReal nums[3] = {toldwork, bound, violation};
    PetscCallMPI(MPI_Bcast(&proves, 1, MPIU_BOOL, 0, comm));
    PetscCallMPI(MPI_Bcast(&passes, 1, MPIU_INT, 0, comm));
    PetscCallMPI(MPI_Bcast(nums, 3, MPIU_REAL, 0, comm));
    PetscCallMPI(MPI_Bcast(told.data(), (PetscMPIInt)(told.size() * sizeof(told[0])), MPI_BYTE, 0, comm));
    toldwork  = nums[0];
    bound     = nums[1];
    violation = nums[2];
  }
  if (passes) {
    std::vector<PetscInt> bodies;
    std::vector<Motion>   ms;
    for (const auto &bm : told) {
      bodies.push_back(bm.first);
      ms.push_back(bm.second);
    }
    proves = PETSC_TRUE;
    m      = ms[0];
    how    = How(bodies, ms, apart ? PETSC_FALSE : PETSC_TRUE, 3);
    PetscCall(PetscInfo(cm, "the motion polished proves it (in %" PetscInt_FMT " pass%s): %s\n", passes, passes > 1 ? "es" : "", how.c_str()));
  } else if (!proves) PetscCall(PetscInfo(cm, "the motion polished does not prove it either: the motion told stays\n"));
  const PetscReal unit  = UnitOf(m);
  const char     *units = m.turn ? "N m" : "N";
  /* the load's work along the motion told (the one the proof compares), unless rounding made it no work */
  work = (toldwork > 0 ? toldwork : work) / unit;
  if (apart) std::snprintf(amount, sizeof(amount), "the load works along it");
  else if (m.turn) std::snprintf(amount, sizeof(amount), "the load's moment about that axis: %.3g N m", (double)work);
  else std::snprintf(amount, sizeof(amount), "the load along it: %.3g N", (double)work);
  if (proves) {
    char resist[128];
    if (!(bound > 1e-8 * toldwork)) std::snprintf(resist, sizeof(resist), "no admissible contact force resists that motion");
    else if (apart) std::snprintf(resist, sizeof(resist), "along that motion the slip bounds resist by less than the load works");
    else std::snprintf(resist, sizeof(resist), "along that motion the slip bounds resist with at most %.3g %s", (double)(bound / unit), units);
    proof = resist;
  }
  phrase = who + " would " + how + " (" + amount + ")";
  brief  = who + " would move (the load works along that motion; -info :contact gives each body's)";
  PetscCall(PetscInfo(cm, "the multiplier's growth is a rigid motion: %s\n", phrase.c_str()));
  if (phrase.size() > maxlen) phrase = brief;
  PetscFunctionReturn(PETSC_SUCCESS);
}
