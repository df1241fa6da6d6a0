/* Judging a solution of a contact model by its mechanics, independently of the solver's own test:
   the residuals of equilibrium, gluing and supports, non-penetration, the sign of the contact force,
   complementarity, the friction cone and the slip rule, computed from u and lambda; and the state of
   each contact node (separated, stick, slip).

   Each residual is relative to a scale of its own body (equilibrium, gluing) or zone (the contact
   checks), so that a lightly loaded body next to a heavily loaded one is judged on its own forces and
   displacements, and the verdict does not depend on the order of the zones. A scale is never smaller
   than kScaleFloor times the largest scale of its kind in the scene: below that, double precision cannot
   resolve a body's forces in one solve of the whole scene, so its residual is measured on the floor. A
   scene without any load has all scales 0; its exact solution is u = 0, lambda = 0, whose residuals are
   0 (0 over the smallest positive real), not 0/0. */
#include <conefeti/private/contactmodelimpl.h>
#include <conefeti/private/allgather.h>
#include <algorithm>
#include <cmath>
#include <limits>

const char *const ContactChecks[] = {"equilibrium", "gluing", "penetration", "normal_sign", "complementarity", "friction_cone", "slip_rule", "ContactCheck", "CONTACT_CHECK_", NULL};

namespace {

constexpr PetscReal kScaleFloor = 1e-6;
constexpr PetscReal kTiny       = std::numeric_limits<PetscReal>::min();

/* per local contact node: l_n, l_t (2), (N u - d), T u (2), slip bound g; with a friction polygon of k directions l_t
   and T u in the (t1, t2) frame are made from the k multipliers m_j and row values D_j u, kept too (k per node) */
struct NodeValues {
  std::vector<PetscReal> ln, lt, gapres, tu, g, m, du;
};

PetscErrorCode EvaluateNodes(ContactModel cm, Vec Bu, NodeValues &v)
{
  ContactModelData      &d = *cm->data;
  const PetscScalar     *l, *bu, *c = NULL;
  PetscInt               rstart;
  Mat                    B;
  Vec                    cvec;
  const FETIRowKind     *kinds;
  std::vector<PetscReal> bounds(d.local.size());

  PetscFunctionBegin;
  PetscCall(FETIGetConstraints(d.feti, &B, &cvec, &kinds));
  PetscCall(VecGetOwnershipRange(d.lambda, &rstart, NULL));
  PetscCall(VecGetArrayRead(d.lambda, &l));
  PetscCall(VecGetArrayRead(Bu, &bu));
  if (cvec) PetscCall(VecGetArrayRead(cvec, &c));
  PetscCall(ContactProblemGetSlipBounds(d.cp, d.lambda, bounds.data()));
  const size_t n = d.local.size();
  v.ln.assign(n, 0);
  v.lt.assign(2 * n, 0);
  v.gapres.assign(n, 0);
  v.tu.assign(2 * n, 0);
  v.m.assign(d.polygon * n, 0);
  v.du.assign(d.polygon * n, 0);
  v.g = bounds;
  for (size_t j = 0; j < n; j++) {
    const PetscInt rn = d.mult[d.stride * j] - rstart;
    v.ln[j]           = PetscRealPart(l[rn]);
    v.gapres[j]       = PetscRealPart(bu[rn] - (c ? c[rn] : 0.0));
    if (d.mult[d.stride * j + 1] < 0) continue; /* frictionless */
    if (d.polygon) {
      for (PetscInt q = 0; q < d.polygon; q++) {
        const PetscInt rt       = d.mult[d.stride * j + 1 + q] - rstart;
        v.m[d.polygon * j + q]  = PetscRealPart(l[rt]);
        v.du[d.polygon * j + q] = PetscRealPart(bu[rt]);
      }
      ContactPolygonTraction(d.polygon, &v.m[d.polygon * j], &v.lt[2 * j]);
      ContactPolygonTangentialMotion(d.polygon, &v.du[d.polygon * j], &v.tu[2 * j]);
      continue;
    }
    for (int q = 0; q < 2; q++) {
      const PetscInt rt = d.mult[d.stride * j + 1 + q] - rstart;
      v.lt[2 * j + q]   = PetscRealPart(l[rt]);
      v.tu[2 * j + q]   = PetscRealPart(bu[rt]);
    }
  }
  PetscCall(VecRestoreArrayRead(d.lambda, &l));
  PetscCall(VecRestoreArrayRead(Bu, &bu));
  if (cvec) PetscCall(VecRestoreArrayRead(cvec, &c));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the largest normal multiplier of each zone (over all ranks) */
PetscErrorCode ZonePressureMax(ContactModel cm, const NodeValues &v, std::vector<PetscReal> &lnmax)
{
  ContactModelData &d = *cm->data;

  PetscFunctionBegin;
  lnmax.assign(d.zones.size(), 0);
  for (size_t j = 0; j < d.local.size(); j++) {
    PetscReal &m = lnmax[d.nodes[d.local[j]].zone];
    m            = PetscMax(m, v.ln[j]);
  }
  if (!lnmax.empty()) PetscCall(MPIU_Allreduce(MPI_IN_PLACE, lnmax.data(), (PetscMPIInt)lnmax.size(), MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)cm)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether the node's free components all lie along its normal, so that it cannot move tangentially: the axis of a
   quarter model, where two symmetry planes fix the other components (FrictionOnRollers() made it frictionless) */
bool Pinned(const ContactNodeInfo &nd)
{
  for (int c = 0; c < 3; c++)
    if (!(nd.fixed & (1u << c)) && 1 - nd.n[c] * nd.n[c] > 1e-12) return false;
  return true;
}

/* The regime from the multipliers: separated without pressure (relative to the largest pressure of the
   node's zone), slip on the boundary of the friction disk (or of the friction polygon of k directions, k > 0),
   stick inside it. Frictionless nodes in contact slide freely: slip, unless pinned (they cannot move
   tangentially: stick). The margins (1e-4 of the largest pressure, 1e-3 of the slip bound) sit above the
   solver's tolerance. */
ContactNodeStatus Classify(PetscReal ln, PetscReal lnmax, const PetscReal lt[2], PetscReal g, PetscBool frictionless, PetscInt k, bool pinned)
{
  if (ln <= 1e-4 * lnmax) return CONTACT_NODE_SEPARATED;
  if (pinned) return CONTACT_NODE_STICK;
  if (frictionless || (k ? ContactPolygonGauge(k, lt, g) >= 1 - 1e-3 : std::hypot(lt[0], lt[1]) >= (1 - 1e-3) * g)) return CONTACT_NODE_SLIP;
  return CONTACT_NODE_STICK;
}

/* the natural residual of the slip rule of the disk law: |l_t - P_g(l_t + k T u)|, with P_g the projection onto the
   disk of radius g; zero exactly when |l_t| <= g, T u = 0 inside the disk and T u along l_t on its circle */
PetscReal DiskSlipResidual(const PetscReal lt[2], const PetscReal tu[2], PetscReal g, PetscReal k)
{
  PetscReal y[2] = {lt[0] + k * tu[0], lt[1] + k * tu[1]}, ny = std::hypot(y[0], y[1]);
  if (ny > g) y[0] *= g / ny, y[1] *= g / ny;
  return std::hypot(lt[0] - y[0], lt[1] - y[1]);
}

/* The body of every global subdomain (gathered: a row of B may reach a subdomain of another rank), with the
   first primal dof of each, sorted by that dof. */
PetscErrorCode SubdomainBodies(ContactModel cm, std::vector<PetscInt> &start, std::vector<PetscInt> &body)
{
  ContactModelData     &d    = *cm->data;
  MPI_Comm              comm = PetscObjectComm((PetscObject)cm);
  PetscInt              nlocal;
  std::vector<PetscInt> mine;

  PetscFunctionBegin;
  PetscCall(FEMGetNumSubdomains(d.fem, NULL, &nlocal, NULL));
  for (PetscInt s = 0; s < nlocal; s++) {
    PetscInt b, primal;
    PetscCall(FEMGetSubdomainMesh(d.fem, s, &b, NULL, NULL, NULL, NULL));
    PetscCall(FETIGetSubdomainOffset(d.feti, s, &primal, NULL));
    PetscCallCXX(mine.insert(mine.end(), {primal, b}));
  }
  std::vector<PetscInt> all;
  PetscCall(ConeFETIAllgather(comm, mine, all));
  std::vector<std::pair<PetscInt, PetscInt>> pairs;
  for (size_t i = 0; i + 1 < all.size(); i += 2) PetscCallCXX(pairs.emplace_back(all[i], all[i + 1]));
  std::sort(pairs.begin(), pairs.end());
  start.clear();
  body.clear();
  for (auto &p : pairs) {
    PetscCallCXX(start.push_back(p.first));
    PetscCallCXX(body.push_back(p.second));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* r / max(scale, floor * largest scale of the kind, the smallest positive real) */
PetscReal Relative(PetscReal r, PetscReal scale, PetscReal largest) { return r / PetscMax(PetscMax(scale, kScaleFloor * largest), kTiny); }

/* K u_D, u_D = B_D' c_D the displacements the data impose (zero elsewhere): the values of the Dirichlet rows of B and
   the initial overlaps (negative gaps) of the contact normal rows. These are the forces they would exert with every
   other dof held, part of a body's force scale. With -fem_dirichlet primal the Dirichlet part is in f (its lifting
   term); with multipliers f does not see it, and a prescribed rigid motion (a grip moving a body toward an obstacle it
   does not reach) has f = 0, B'l = 0 and K u = 0 in exact arithmetic; so has a floating body lifted rigidly out of
   an initial overlap. Without this term their equilibrium residual would be rounding over rounding. NULL when the
   data impose no displacement. */
PetscErrorCode DataDisplacementForce(ContactModel cm, Mat B, Vec cvec, const FETIRowKind *kinds, Vec *KuD)
{
  Vec          cD, uD;
  PetscScalar *a;
  PetscInt     m;
  PetscReal    cmax = 0;

  PetscFunctionBegin;
  *KuD = NULL;
  if (!cvec) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecDuplicate(cvec, &cD));
  PetscCall(VecCopy(cvec, cD));
  PetscCall(VecGetLocalSize(cD, &m));
  PetscCall(VecGetArray(cD, &a));
  for (PetscInt i = 0; i < m; i++) {
    a[i] = ContactImposedValue_Private(kinds[i], PetscRealPart(a[i]));
    cmax = PetscMax(cmax, PetscAbsScalar(a[i]));
  }
  PetscCall(VecRestoreArray(cD, &a));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &cmax, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)cm)));
  if (cmax > 0) {
    PetscCall(VecDuplicate(cm->data->u, &uD));
    PetscCall(VecDuplicate(cm->data->u, KuD));
    PetscCall(MatMultTranspose(B, cD, uD));
    PetscCall(FETIApplyK(cm->data->feti, uD, *KuD));
    PetscCall(VecDestroy(&uD));
  }
  PetscCall(VecDestroy(&cD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/*@C
  ContactModelComputeResiduals - The mechanical residuals of the solution, computed from u and lambda,
  not taken from the solver; where each is largest; and the counts of separated, stick and slip nodes.

  Collective

  Input Parameter:
. cm - the model (solved)

  Output Parameter:
. r - the residuals

  Notes:
  Each residual is relative to a scale of the body or zone where it is measured (see `ContactResiduals`):
  a body's forces max(|f_b|, |(B'l)_b|, |(K u)_b|, |(K u_D)_b|) (u_D the displacements the data impose: the values
  of the Dirichlet rows and the initial overlaps of the contact rows, zero elsewhere; with -fem_dirichlet primal the
  Dirichlet part is in f), a body's largest displacement, a zone's largest
  contact multiplier. A scale below 1e-6 times the largest of its kind in the scene is raised to that, and
  a scene without load (all scales 0) has residuals 0 for the exact solution u = 0, l = 0.

  A node is separated when l_n <= 1e-4 times the largest l_n of its zone; among the others, it slips when
  |l_t| >= (1 - 1e-3) g (on the boundary of its friction disk; frictionless nodes in contact always slip, unless
  every free component of theirs lies along the normal), and
  sticks otherwise. Whether stick nodes really do not move is what the slip_rule residual checks.

  With friction polygons (-contact_friction_polygon k, `ContactProblemAddPolygonNodes()`) friction_cone and slip_rule
  judge the law the solver solved, each tangential multiplier m_j in [-c g, c g] (c = sin(pi/(2k))) with
  m_j = P(m_j + k_z D_j u), so that a converged polygon solve is one that solved its own problem; the disk law it
  approximates is judged apart, in approximation (not in max, not in the verdict), and a node slips when its
  tangential force is on the polygon's boundary.

  `ContactModelSolve()` computes them for its verdict; a second call with u and lambda unchanged (their
  `PetscObjectState`) returns the same values without computing them again.

  Level: beginner

.seealso: `ContactResiduals`, `ContactModelGetNodeStates()`, `ContactModelSolve()`
@*/
PetscErrorCode ContactModelComputeResiduals(ContactModel cm, ContactResiduals *r)
{
  ContactModelData     *d;
  Mat                   B;
  Vec                   cvec, Ku, f, Btl, Bu, KuD = NULL;
  const FETIRowKind    *kinds;
  PetscInt              nbodies, nlocal, ustart, rstart;
  MPI_Comm              comm;
  std::vector<PetscInt> substart, subbody;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  PetscAssertPointer(r, 2);
  d    = cm->data;
  comm = PetscObjectComm((PetscObject)cm);
  PetscCheck(d->solved, comm, PETSC_ERR_ARG_WRONGSTATE, "ContactModel: solve first");
  {
    PetscObjectState su, sl;
    PetscCall(PetscObjectStateGet((PetscObject)d->u, &su));
    PetscCall(PetscObjectStateGet((PetscObject)d->lambda, &sl));
    if (su == d->residuals_state[0] && sl == d->residuals_state[1]) { /* the same u and lambda as last time */
      *r = d->residuals;
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  *r = ContactResiduals{};
  for (PetscInt &w : r->where) w = -1;
  PetscCall(FEMGetNumBodies(d->fem, &nbodies));
  PetscCall(FETIGetConstraints(d->feti, &B, &cvec, &kinds));
  PetscCall(FETIGetLoad(d->feti, &f));
  PetscCall(SubdomainBodies(cm, substart, subbody));

  /* per body: |K u - f + B'l|^2, |f|^2, |B'l|^2, |K u|^2, |K u_D|^2 (sums) and max |u| */
  std::vector<PetscReal> sums(5 * nbodies, 0), umax(nbodies, 0);
  PetscCall(VecDuplicate(d->u, &Ku));
  PetscCall(VecDuplicate(d->u, &Btl));
  PetscCall(FETIApplyK(d->feti, d->u, Ku));
  PetscCall(MatMultTranspose(B, d->lambda, Btl));
  PetscCall(DataDisplacementForce(cm, B, cvec, kinds, &KuD));
  PetscCall(VecGetOwnershipRange(d->u, &ustart, NULL));
  PetscCall(FEMGetNumSubdomains(d->fem, NULL, &nlocal, NULL));
  {
    const PetscScalar *ku, *fa, *bl, *ua, *kd = NULL;
    if (KuD) PetscCall(VecGetArrayRead(KuD, &kd));
    PetscCall(VecGetArrayRead(Ku, &ku));
    PetscCall(VecGetArrayRead(f, &fa));
    PetscCall(VecGetArrayRead(Btl, &bl));
    PetscCall(VecGetArrayRead(d->u, &ua));
    for (PetscInt s = 0; s < nlocal; s++) {
      PetscInt b, nn, primal;
      PetscCall(FEMGetSubdomainMesh(d->fem, s, &b, &nn, NULL, NULL, NULL));
      PetscCall(FETIGetSubdomainOffset(d->feti, s, &primal, NULL));
      for (PetscInt i = primal - ustart; i < primal - ustart + 3 * nn; i++) {
        const PetscReal res = PetscRealPart(ku[i] - fa[i] + bl[i]);
        sums[5 * b + 0] += res * res;
        sums[5 * b + 1] += PetscRealPart(fa[i] * fa[i]);
        sums[5 * b + 2] += PetscRealPart(bl[i] * bl[i]);
        sums[5 * b + 3] += PetscRealPart(ku[i] * ku[i]);
        if (kd) sums[5 * b + 4] += PetscRealPart(kd[i] * kd[i]);
        umax[b] = PetscMax(umax[b], PetscAbsScalar(ua[i]));
      }
    }
    PetscCall(VecRestoreArrayRead(Ku, &ku));
    PetscCall(VecRestoreArrayRead(f, &fa));
    PetscCall(VecRestoreArrayRead(Btl, &bl));
    PetscCall(VecRestoreArrayRead(d->u, &ua));
    if (KuD) PetscCall(VecRestoreArrayRead(KuD, &kd));
  }
  PetscCall(VecDestroy(&KuD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sums.data(), (PetscMPIInt)sums.size(), MPIU_REAL, MPIU_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, umax.data(), (PetscMPIInt)umax.size(), MPIU_REAL, MPIU_MAX, comm));
  /* a body's force scale: the largest of its loads, its multipliers' forces, its elastic forces and the forces its
     prescribed displacements exert */
  const auto force    = [&](PetscInt b) { return PetscSqrtReal(std::max({sums[5 * b + 1], sums[5 * b + 2], sums[5 * b + 3], sums[5 * b + 4]})); };
  PetscReal  forcemax = 0, dispmax = 0;
  for (PetscInt b = 0; b < nbodies; b++) {
    forcemax = PetscMax(forcemax, force(b));
    dispmax  = PetscMax(dispmax, umax[b]);
  }
  for (PetscInt b = 0; b < nbodies; b++) {
    const PetscReal e = Relative(PetscSqrtReal(sums[5 * b]), force(b), forcemax);
    if (e > r->equilibrium || r->where[CONTACT_CHECK_EQUILIBRIUM] < 0) {
      r->equilibrium                      = e;
      r->where[CONTACT_CHECK_EQUILIBRIUM] = b;
    }
  }

  /* B u - c on gluing and Dirichlet rows, relative to the largest displacement of the row's body */
  PetscCall(VecDuplicate(d->lambda, &Bu));
  PetscCall(MatMult(B, d->u, Bu));
  PetscCall(VecGetOwnershipRange(Bu, &rstart, NULL));
  {
    const PetscScalar     *bu, *c = NULL;
    PetscInt               m;
    std::vector<PetscReal> glue(nbodies, 0);
    PetscCall(VecGetLocalSize(Bu, &m));
    PetscCall(VecGetArrayRead(Bu, &bu));
    if (cvec) PetscCall(VecGetArrayRead(cvec, &c));
    for (PetscInt i = 0; i < m; i++) {
      if (kinds[i] != FETI_ROW_GLUING && kinds[i] != FETI_ROW_DIRICHLET) continue;
      PetscInt        ncols;
      const PetscInt *cols;
      PetscCall(MatGetRow(B, rstart + i, &ncols, &cols, NULL));
      PetscInt b = 0;
      if (ncols > 0) {
        const size_t s = (size_t)(std::upper_bound(substart.begin(), substart.end(), cols[0]) - substart.begin());
        b              = s > 0 ? subbody[s - 1] : 0;
      }
      PetscCall(MatRestoreRow(B, rstart + i, &ncols, &cols, NULL));
      glue[b] = PetscMax(glue[b], PetscAbsReal(PetscRealPart(bu[i] - (c ? c[i] : 0.0))));
    }
    PetscCall(VecRestoreArrayRead(Bu, &bu));
    if (cvec) PetscCall(VecRestoreArrayRead(cvec, &c));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, glue.data(), (PetscMPIInt)glue.size(), MPIU_REAL, MPIU_MAX, comm));
    for (PetscInt b = 0; b < nbodies; b++) {
      const PetscReal e = Relative(glue[b], umax[b], dispmax);
      if (e > r->gluing || r->where[CONTACT_CHECK_GLUING] < 0) {
        r->gluing                      = e;
        r->where[CONTACT_CHECK_GLUING] = b;
      }
    }
  }

  if (d->cp) {
    const size_t           nz = d->zones.size();
    NodeValues             v;
    std::vector<PetscReal> lnmax, lzone(nz, 0), m(6 * nz, 0), uzone(nz, 0);
    PetscCall(EvaluateNodes(cm, Bu, v));
    PetscCall(ZonePressureMax(cm, v, lnmax));
    /* the force scale of a zone: its largest pressure, or (no pressure anywhere in it, e.g. a run without
       equilibrium) its largest contact multiplier, so that the ratios stay finite */
    for (size_t j = 0; j < v.ln.size(); j++) {
      PetscReal &l = lzone[d->nodes[d->local[j]].zone];
      l            = PetscMax(l, PetscMax(PetscAbsReal(v.ln[j]), std::hypot(v.lt[2 * j], v.lt[2 * j + 1])));
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, lzone.data(), (PetscMPIInt)nz, MPIU_REAL, MPIU_MAX, comm));
    PetscReal lall = 0;
    for (size_t z = 0; z < nz; z++) lall = PetscMax(lall, PetscMax(lzone[z], lnmax[z]));
    for (size_t z = 0; z < nz; z++) {
      const ContactZone &zn = d->zones[z];
      uzone[z]              = PetscMax(umax[zn.body], zn.type == CONTACT_ZONE_BODIES ? umax[zn.other_body] : 0.0);
      /* floors: the largest displacement of the scene, the largest force (contact or body load) */
      uzone[z] = PetscMax(PetscMax(uzone[z], kScaleFloor * dispmax), kTiny);
      lzone[z] = PetscMax(PetscMax(PetscMax(lzone[z], lnmax[z]), kScaleFloor * PetscMax(lall, forcemax)), kTiny);
    }
    for (size_t j = 0; j < v.ln.size(); j++) {
      const PetscInt  z  = d->nodes[d->local[j]].zone;
      const PetscReal ln = v.ln[j], *lt = &v.lt[2 * j], *tu = &v.tu[2 * j], g = v.g[j], k = lzone[z] / uzone[z];
      PetscReal      *mz = &m[6 * z];
      mz[0]              = PetscMax(mz[0], v.gapres[j] / uzone[z]);                                 /* penetration */
      mz[1]              = PetscMax(mz[1], -ln / lzone[z]);                                         /* normal sign */
      mz[2]              = PetscMax(mz[2], PetscAbsReal(ln * v.gapres[j]) / (lzone[z] * uzone[z])); /* complementarity */
      if (d->mult[d->stride * j + 1] >= 0 && !d->polygon) {
        mz[3] = PetscMax(mz[3], (std::hypot(lt[0], lt[1]) - g) / lzone[z]); /* friction cone */
        mz[4] = PetscMax(mz[4], DiskSlipResidual(lt, tu, g, k) / lzone[z]); /* natural residual of the slip rule: l_t = P_g(l_t + k T u) */
      } else if (d->mult[d->stride * j + 1] >= 0) {
        /* the polygon law the solver solved: each multiplier m_j in [-c g, c g], and m_j = P(m_j + k D_j u) (stick rows
           do not move, a multiplier on its bound moves its row the way of its sign) */
        const PetscReal cg = ContactPolygonBoundFactor(d->polygon) * g, *mj = &v.m[d->polygon * j], *dj = &v.du[d->polygon * j];
        PetscReal       s2 = 0;
        for (PetscInt q = 0; q < d->polygon; q++) {
          const PetscReal e = mj[q] - PetscMin(PetscMax(mj[q] + k * dj[q], -cg), cg);
          mz[3]             = PetscMax(mz[3], (PetscAbsReal(mj[q]) - cg) / lzone[z]);
          s2 += e * e;
        }
        mz[4] = PetscMax(mz[4], PetscSqrtReal(s2) / lzone[z]);
        /* the disk law the polygon approximates: cone and slip rule of the tangential force sum_j m_j d_j */
        mz[5] = PetscMax(mz[5], PetscMax(std::hypot(lt[0], lt[1]) - g, DiskSlipResidual(lt, tu, g, k)) / lzone[z]);
      }
      r->counts[Classify(ln, lnmax[z], lt, g, d->mult[d->stride * j + 1] < 0 ? PETSC_TRUE : PETSC_FALSE, d->polygon, Pinned(d->nodes[d->local[j]]))]++;
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, m.data(), (PetscMPIInt)m.size(), MPIU_REAL, MPIU_MAX, comm));
    for (size_t z = 0; z < nz; z++) r->approximation = PetscMax(r->approximation, m[6 * z + 5]);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, r->counts, 3, MPIU_INT, MPI_SUM, comm));
    PetscReal *zonal[5] = {&r->penetration, &r->normal_sign, &r->complementarity, &r->friction_cone, &r->slip_rule};
    for (int q = 0; q < 5; q++) {
      for (size_t z = 0; z < nz; z++) {
        const PetscReal e = PetscMax(m[6 * z + q], 0.0);
        if (e > *zonal[q] || r->where[CONTACT_CHECK_PENETRATION + q] < 0) {
          *zonal[q]                               = e;
          r->where[CONTACT_CHECK_PENETRATION + q] = (PetscInt)z;
        }
      }
    }
  }
  const PetscReal all[CONTACT_NUM_CHECKS] = {r->equilibrium, r->gluing, r->penetration, r->normal_sign, r->complementarity, r->friction_cone, r->slip_rule};
  r->worst                                = CONTACT_CHECK_EQUILIBRIUM;
  for (int q = 0; q < CONTACT_NUM_CHECKS; q++) {
    /* a residual that is not a number is the worst of all */
    if (!(all[q] <= r->max)) {
      r->max   = all[q];
      r->worst = (ContactCheck)q;
      if (PetscIsInfOrNanReal(all[q])) break;
    }
  }
  PetscCall(VecDestroy(&Ku));
  PetscCall(VecDestroy(&Btl));
  PetscCall(VecDestroy(&Bu));
  d->residuals = *r;
  PetscCall(PetscObjectStateGet((PetscObject)d->u, &d->residuals_state[0]));
  PetscCall(PetscObjectStateGet((PetscObject)d->lambda, &d->residuals_state[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetNodeStates - Contact-surface fields at this rank's contact nodes (order of
  `ContactModelGetNodes()`).

  Collective

  Input Parameter:
. cm - the model (solved)

  Output Parameters (any may be NULL):
+ pressure - normal contact stress l_n / area
. traction - 3 per node: tangential stress vector (l_t1 t1 + l_t2 t2) / area; the friction traction on the
             node's body (a zone's slave body between bodies) is its opposite
. slip     - 3 per node: tangential displacement of the node's body relative to the foundation or, between bodies, to
             the master point (interpolated with its barycentric weights)
- status   - separated, stick or slip (the rule of `ContactModelComputeResiduals()`)

  Level: intermediate

.seealso: `ContactModelComputeResiduals()`
@*/
PetscErrorCode ContactModelGetNodeStates(ContactModel cm, PetscReal pressure[], PetscReal traction[], PetscReal slip[], ContactNodeStatus status[])
{
  ContactModelData      *d;
  Mat                    B;
  Vec                    Bu, cvec;
  const FETIRowKind     *kinds;
  NodeValues             v;
  std::vector<PetscReal> lnmax;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  d = cm->data;
  PetscCheck(d->solved, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONGSTATE, "ContactModel: solve first");
  if (!d->cp) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(FETIGetConstraints(d->feti, &B, &cvec, &kinds));
  PetscCall(VecDuplicate(d->lambda, &Bu));
  PetscCall(MatMult(B, d->u, Bu));
  PetscCall(EvaluateNodes(cm, Bu, v));
  PetscCall(VecDestroy(&Bu));
  PetscCall(ZonePressureMax(cm, v, lnmax));
  for (size_t j = 0; j < d->local.size(); j++) {
    const ContactNodeInfo &nd = d->nodes[d->local[j]];
    if (pressure) pressure[j] = v.ln[j] / nd.area;
    for (int c = 0; c < 3; c++) {
      if (traction) traction[3 * j + c] = (v.lt[2 * j] * nd.t1[c] + v.lt[2 * j + 1] * nd.t2[c]) / nd.area;
      if (slip) slip[3 * j + c] = v.tu[2 * j] * nd.t1[c] + v.tu[2 * j + 1] * nd.t2[c];
    }
    if (status) status[j] = Classify(v.ln[j], lnmax[nd.zone], &v.lt[2 * j], v.g[j], d->mult[d->stride * j + 1] < 0 ? PETSC_TRUE : PETSC_FALSE, d->polygon, Pinned(nd));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetContactForce - The resultant of the contact forces on the first bodies of a zone (the `ContactZone`'s
  body; or of all zones), from the multipliers: the sum over its contact nodes of -(l_n n + l_t1 t1 + l_t2 t2) (the force
  the obstacle or the other body exerts, as it enters the equilibrium K u = f - B'l), and the sum of l_n.

  Collective

  Input Parameters:
+ cm   - the model (solved)
- zone - the zone, or -1 for all zones together

  Output Parameters:
+ force  - the resultant force vector (3 entries), or NULL
- normal - the sum of the normal multipliers l_n (the magnitude of the normal forces), or NULL

  Notes:
  For a rigid punch or indenter pressed along one direction, the total force P is the component of force
  along that direction (the normals of a curved obstacle tilt, so the sum of l_n is slightly larger).
  Components of a node fixed by a Dirichlet condition do not enter its rows (`ContactZone`) and not the sum.
  In a zone between bodies whose slave is the other body (`ContactZoneSlave`), the nodes are the other body's and
  the force on them is turned around: the sum is still the force on the zone's body (action and reaction).

  Level: intermediate

.seealso: `ContactModelGetNodeStates()`, `ContactModelGetNodeGeometry()`
@*/
PetscErrorCode ContactModelGetContactForce(ContactModel cm, PetscInt zone, PetscReal force[], PetscReal *normal)
{
  ContactModelData  *d;
  Mat                B;
  Vec                Bu, cvec;
  const FETIRowKind *kinds;
  NodeValues         v;
  PetscReal          sum[4] = {0, 0, 0, 0};

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  d = cm->data;
  PetscCheck(d->solved, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONGSTATE, "ContactModel: solve first");
  PetscCheck(zone >= -1 && zone < (PetscInt)d->zones.size(), PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_OUTOFRANGE,
             "ContactModelGetContactForce: zone %" PetscInt_FMT " does not exist (%zu zones)", zone, d->zones.size());
  if (d->cp) {
    /* l_n and the tangential force in the (t1, t2) frame, also from a friction polygon's multipliers */
    PetscCall(FETIGetConstraints(d->feti, &B, &cvec, &kinds));
    PetscCall(VecDuplicate(d->lambda, &Bu));
    PetscCall(MatMult(B, d->u, Bu));
    PetscCall(EvaluateNodes(cm, Bu, v));
    PetscCall(VecDestroy(&Bu));
    for (size_t j = 0; j < d->local.size(); j++) {
      const ContactNodeInfo &nd = d->nodes[d->local[j]];
      if (zone >= 0 && nd.zone != zone) continue;
      const PetscReal sign = nd.body == d->zones[nd.zone].body ? 1.0 : -1.0; /* on the zone's body: the reaction of the force on a slave other body */
      sum[3] += v.ln[j];
      for (int c = 0; c < 3; c++)
        if (!(nd.fixed & (1u << c))) sum[c] -= sign * (v.ln[j] * nd.n[c] + v.lt[2 * j] * nd.t1[c] + v.lt[2 * j + 1] * nd.t2[c]);
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sum, 4, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)cm)));
  if (force)
    for (int c = 0; c < 3; c++) force[c] = sum[c];
  if (normal) *normal = sum[3];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* what a failed check means, for the sentence that says why a solve did not converge */
PetscErrorCode ContactResidualsDescribe_Private(const ContactResiduals *r, ContactCheck c, char buf[], size_t len)
{
  static const char *const meaning[CONTACT_NUM_CHECKS] = {"the forces on the body do not balance: K u != f - B'l",
                                                          "the body's subdomains do not fit together or its supports move: B u != c",
                                                          "nodes pass through the obstacle",
                                                          "contact forces pull instead of push",
                                                          "contact forces act across open gaps",
                                                          "friction forces exceed their bound",
                                                          "stick nodes move, or slipping nodes do not move against their friction force"};
  const PetscReal          value[CONTACT_NUM_CHECKS]   = {r->equilibrium, r->gluing, r->penetration, r->normal_sign, r->complementarity, r->friction_cone, r->slip_rule};
  const bool               perbody                     = c == CONTACT_CHECK_EQUILIBRIUM || c == CONTACT_CHECK_GLUING;

  PetscFunctionBegin;
  if (r->where[c] >= 0) PetscCall(PetscSNPrintf(buf, len, "%s of %s %" PetscInt_FMT " is %.1e (%s)", ContactChecks[c], perbody ? "body" : "contact zone", r->where[c], (double)value[c], meaning[c]));
  else PetscCall(PetscSNPrintf(buf, len, "%s is %.1e (%s)", ContactChecks[c], (double)value[c], meaning[c]));
  PetscFunctionReturn(PETSC_SUCCESS);
}
