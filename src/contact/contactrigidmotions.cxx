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
   diagnoses (no equilibrium, contactsolve.cxx). */
#include <conefeti/private/contactimpl.h>
#include <cmath>
#include <cstdio>
#include <string>

namespace {

/* a load works along a free motion when its work exceeds this fraction of the load's magnitude */
constexpr PetscReal kWorkTol = 1e-9;
/* entries below this (relative) are roundoff in a motion's description */
constexpr PetscReal kClean = 1e-9;

struct BodyFrame {
  PetscInt         nnodes = 0, offset = 0;
  const PetscReal *X    = nullptr;
  PetscReal        c[3] = {0, 0, 0}, L = 1;
  PetscBool        dirichlet = PETSC_FALSE;
};

PetscReal Norm3(const PetscReal v[3]) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

std::string Num(PetscReal v)
{
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g", (double)v);
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

/* "slide along x", "turn about an axis through (0.5, 0.5, 0) along z" */
std::string Describe(const Motion &m)
{
  if (!m.turn) return "slide along " + Direction(m.axis);
  std::string s = "turn about an axis through (" + Num(m.point[0]) + ", " + Num(m.point[1]) + ", " + Num(m.point[2]) + ") along " + Direction(m.axis);
  if (m.pitch != 0) s += " while sliding along it by " + Num(m.pitch) + " per radian";
  return s;
}

/* the same motion of space? (t at the origin and w agree) */
PetscBool SameMotion(const Motion &a, const BodyFrame &fa, const Motion &b, const BodyFrame &fb)
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
  return diff <= 1e-6 * scale ? PETSC_TRUE : PETSC_FALSE;
}

std::string BodyList(const std::vector<PetscInt> &bodies)
{
  std::string s = bodies.size() > 1 ? "bodies " : "body ";
  for (size_t i = 0; i < bodies.size(); i++) s += (i ? (i + 1 == bodies.size() ? " and " : ", ") : "") + std::to_string(bodies[i]);
  return s;
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

  /* who moves ("body 0", "bodies 0 and 1 together") and how ("slide along x"), and the first moved body's motion */
  void Phrase(const std::vector<PetscReal> &v, std::string &who, std::string &how, Motion *first) const
  {
    const std::vector<PetscInt> bodies = Bodies(v);
    std::vector<Motion>         ms;
    for (PetscInt b : bodies) ms.push_back(MakeMotion(frames[b], &v[6 * b]));
    *first         = ms[0];
    PetscBool same = PETSC_TRUE;
    for (size_t i = 1; i < ms.size(); i++) same = (same && SameMotion(ms[0], frames[bodies[0]], ms[i], frames[bodies[i]])) ? PETSC_TRUE : PETSC_FALSE;
    who = BodyList(bodies) + (bodies.size() > 1 ? " together" : "");
    if (same) how = Describe(ms[0]);
    else {
      how = "move (";
      for (size_t i = 0; i < ms.size(); i++) how += (i ? "; body " : "body ") + std::to_string(bodies[i]) + ": " + Describe(ms[i]);
      how += ")";
    }
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

} // namespace

/* Stop with an error naming the body and the motion when a rigid motion of the bodies is resisted by no
   Dirichlet condition and no contact row: no equilibrium when the load works along it, no unique
   displacement otherwise (an engineer wants to be told, not handed one of infinitely many answers). */
PetscErrorCode ContactCheckRigidMotions_Private(ContactModel cm, FEM fem, const std::vector<ContactZone> &zones, const std::vector<FEMHoldingRow> &rows)
{
  MPI_Comm        comm = PetscObjectComm((PetscObject)cm);
  PetscInt        nb, ndir, k;
  PetscReal      *free_motions;
  IS              is, all;
  const PetscInt *idx;
  Checker         ck{fem, zones, rows, {}, {}};

  PetscFunctionBegin;
  PetscCall(FEMComputeFreeRigidMotions(fem, (PetscInt)rows.size(), rows.data(), &k, &free_motions));
  if (!k) PetscFunctionReturn(PETSC_SUCCESS);
  /* a free motion: what follows only words the error, so its cost (gathering the Dirichlet dofs again) is paid
     on a run that stops */
  PetscCall(FEMGetNumBodies(fem, &nb));
  const PetscInt         n = 6 * nb;
  std::vector<PetscReal> M(free_motions, free_motions + (size_t)k * n); /* the free motions in motion coordinates, in echelon form */
  PetscCall(PetscFree(free_motions));
  PetscCallCXX(ck.frames.resize(nb));
  for (PetscInt b = 0; b < nb; b++) {
    BodyFrame &f = ck.frames[b];
    PetscCall(FEMGetBodyNodes(fem, b, &f.nnodes, &f.X));
    PetscCall(FEMGetBodyNodeOffset(fem, b, &f.offset));
    PetscCall(FEMComputeRigidMotionFrame(fem, b, f.c, &f.L));
  }
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

  /* the load as work per unit of each motion coordinate: force, and moment about the centroid / L */
  std::vector<PetscReal> g(n);
  PetscReal              magnitude = 0;
  for (PetscInt b = 0; b < nb; b++) {
    PetscReal F[3], Mo[3], mag;
    PetscCall(FEMComputeLoadResultant(fem, b, ck.frames[b].c, F, Mo, &mag));
    for (int q = 0; q < 3; q++) {
      g[6 * b + q]     = F[q];
      g[6 * b + 3 + q] = Mo[q] / ck.frames[b].L;
    }
    magnitude += mag;
  }
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
      work   = w / (first.turn ? Norm3(first.w) : Norm3(first.t));
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
