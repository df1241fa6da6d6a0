/* ContactModel: contact zones on a FEM model -> constraint rows -> FETI -> ContactProblem -> primal
   recovery -> mechanical residuals and node states.

   Rows per contact node k (outward unit normal n of the first body, tangents t1, t2):
     N  u = n.(u_A - u_B) <= d_k   (foundation: u_B = 0, n = -plane normal, d_k = (x - point).plane normal)
     T1 u = t1.(u_A - u_B),  T2 u = t2.(u_A - u_B)   (only for Tresca and Coulomb nodes)
   With the Lagrangian term l'(B u - c), l_n >= 0 is the contact force magnitude and -T'l_t the
   friction force on the first body, so the slip rule reads: T u = 0 where |l_t| < g, and
   T u = s l_t with s >= 0 where |l_t| = g. Multipliers are nodal forces; stresses divide by the
   lumped nodal area of the contact face. */
#include <conefeti/private/contactimpl.h>
#include <conefeti/private/reproduciblesum.h>
#include <conefeti/sys.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

PetscClassId      CONTACTMODEL_CLASSID;
const char *const ContactZoneTypes[]    = {"foundation", "bodies", "ContactZoneType", "CONTACT_ZONE_", NULL};
const char *const ContactNodeStatuses[] = {"separated", "stick", "slip", "ContactNodeStatus", "CONTACT_NODE_", NULL};

namespace {

struct NodeInfo {
  PetscInt   zone, body, node, other_body = -1, other_node = -1;
  PetscReal  x[3], area, n[3], t1[3], t2[3], gap;
  ContactLaw law;
  PetscReal  coef; /* Tresca: bound as a nodal force; Coulomb: F */
  PetscInt   first_row;
};

struct ModelData {
  FEM                      fem = nullptr;
  std::vector<ContactZone> zones;
  std::vector<NodeInfo>    nodes;     /* all contact nodes, the same on every rank */
  std::vector<PetscInt>    unmatched; /* per zone: nodes of a node-to-node zone's first face without a partner */
  FETI                     feti   = nullptr;
  ContactProblem           cp     = nullptr;
  Vec                      lambda = nullptr, u = nullptr, alpha = nullptr;
  ContactPipeline          pipeline     = CONTACT_PIPELINE_LINEAR;
  ContactStatistics        linear_stats = {};

  /* contact nodes whose multipliers this rank owns */
  std::vector<PetscInt>  local; /* indices into nodes */
  std::vector<PetscInt>  mult;  /* 3 per local node: normal, t1, t2 multiplier indices (-1 when frictionless) */
  std::vector<PetscInt>  lbody, lnode;
  std::vector<PetscReal> lcoords, larea;
  PetscBool              setup = PETSC_FALSE, solved = PETSC_FALSE;
};

} // namespace

struct _ContactModelOps {
  PetscErrorCode (*unused)(void);
};
struct _p_ContactModel {
  PETSCHEADER(struct _ContactModelOps);
  ModelData *data;
};

namespace {

/* scaled by the largest entry first: no overflow for |v| near the largest real, no underflow near the smallest */
void Normalize(PetscReal v[3])
{
  const PetscReal m = std::max({std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
  if (!(m > 0)) return;
  for (int i = 0; i < 3; i++) v[i] /= m;
  const PetscReal s = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  for (int i = 0; i < 3; i++) v[i] /= s;
}

/* t1, t2 with (n, t1, t2) orthonormal, t1 built from the axis least aligned with n (deterministic) */
void Tangents(const PetscReal n[3], PetscReal t1[3], PetscReal t2[3])
{
  int axis = 0;
  for (int i = 1; i < 3; i++)
    if (std::fabs(n[i]) < std::fabs(n[axis])) axis = i;
  PetscReal e[3]    = {0, 0, 0};
  e[axis]           = 1;
  const PetscReal d = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
  for (int i = 0; i < 3; i++) t1[i] = e[i] - d * n[i];
  Normalize(t1);
  t2[0] = n[1] * t1[2] - n[2] * t1[1];
  t2[1] = n[2] * t1[0] - n[0] * t1[2];
  t2[2] = n[0] * t1[1] - n[1] * t1[0];
}

/* Dirichlet nodes are left out of contact: a row on a fixed dof would be a zero row of B. */
PetscErrorCode DirichletNodes(FEM fem, std::set<PetscInt> &fixed)
{
  IS              is, all;
  PetscInt        n;
  const PetscInt *idx;

  PetscFunctionBegin;
  PetscCall(FEMGetGlobalDirichletDofs(fem, &is));
  PetscCall(ISAllGather(is, &all));
  PetscCall(ISGetLocalSize(all, &n));
  PetscCall(ISGetIndices(all, &idx));
  for (PetscInt i = 0; i < n; i++) PetscCallCXX(fixed.insert(idx[i] / 3));
  PetscCall(ISRestoreIndices(all, &idx));
  PetscCall(ISDestroy(&all));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CollectZoneNodes(ContactModel cm, PetscInt z, const std::set<PetscInt> &fixed)
{
  ModelData                                                      &d    = *cm->data;
  const ContactZone                                              &zone = d.zones[z];
  PetscInt                                                        n, offset, nb, offB = 0;
  const PetscInt                                                 *nodes;
  const PetscReal                                                *areas, *normals, *X, *XB = nullptr;
  std::map<std::tuple<long long, long long, long long>, PetscInt> other;
  PetscReal                                                       scale = 0;

  PetscFunctionBegin;
  PetscCall(FEMGetTaggedNodes(d.fem, zone.body, zone.face, &n, &nodes, &areas, &normals));
  PetscCheck(n > 0, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONG, "contact zone %" PetscInt_FMT ": face '%s' of body %" PetscInt_FMT " has no node", z, zone.face, zone.body);
  PetscCall(FEMGetBodyNodes(d.fem, zone.body, &nb, &X));
  PetscCall(FEMGetBodyNodeOffset(d.fem, zone.body, &offset));
  for (PetscInt i = 0; i < 3 * nb; i++) scale = PetscMax(scale, PetscAbsReal(X[i]));
  const PetscReal tol = 1e-9 * PetscMax(scale, 1.0);
  auto            key = [tol](const PetscReal *x) { return std::make_tuple(std::llround(x[0] / tol), std::llround(x[1] / tol), std::llround(x[2] / tol)); };
  if (zone.type == CONTACT_ZONE_BODIES) {
    PetscInt         m, nbB;
    const PetscInt  *nodesB;
    const PetscReal *aB, *nB;
    PetscCall(FEMGetTaggedNodes(d.fem, zone.other_body, zone.other_face, &m, &nodesB, &aB, &nB));
    PetscCall(FEMGetBodyNodes(d.fem, zone.other_body, &nbB, &XB));
    PetscCall(FEMGetBodyNodeOffset(d.fem, zone.other_body, &offB));
    for (PetscInt i = 0; i < m; i++) other[key(&XB[3 * nodesB[i]])] = nodesB[i];
  }
  for (PetscInt i = 0; i < n; i++) {
    NodeInfo info;
    info.zone = z;
    info.body = zone.body;
    info.node = nodes[i];
    if (fixed.count(offset + nodes[i])) continue;
    for (int c = 0; c < 3; c++) info.x[c] = X[3 * nodes[i] + c];
    info.area = areas[i];
    info.law  = zone.law;
    info.coef = zone.law == CONTACT_TRESCA ? zone.coef * areas[i] : zone.coef;
    if (zone.type == CONTACT_ZONE_FOUNDATION) {
      PetscReal nu[3] = {zone.normal[0], zone.normal[1], zone.normal[2]};
      Normalize(nu);
      for (int c = 0; c < 3; c++) info.n[c] = -nu[c];
      info.gap = (info.x[0] - zone.point[0]) * nu[0] + (info.x[1] - zone.point[1]) * nu[1] + (info.x[2] - zone.point[2]) * nu[2];
    } else {
      auto it = other.find(key(info.x));
      if (it == other.end()) { /* a node of the first face without a partner on the second is not in contact */
        d.unmatched[z]++;
        continue;
      }
      info.other_body = zone.other_body;
      info.other_node = it->second;
      if (fixed.count(offB + info.other_node)) continue;
      for (int c = 0; c < 3; c++) info.n[c] = normals[3 * i + c];
      Normalize(info.n);
      info.gap = 0; /* conforming meshes: coinciding nodes */
    }
    Tangents(info.n, info.t1, info.t2);
    PetscCallCXX(d.nodes.push_back(info));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the rows of all contact nodes, appended to the model's B in node order (N, then T1, T2) */
PetscErrorCode AppendRows(ContactModel cm)
{
  ModelData               &d = *cm->data;
  std::vector<FETIRowKind> kinds;
  std::vector<PetscInt>    rowptr{0}, body, node, comp;
  std::vector<PetscScalar> coef, rhs;

  PetscFunctionBegin;
  for (auto &k : d.nodes) {
    const PetscReal *dirs[3] = {k.n, k.t1, k.t2};
    const int        nrows   = k.law == CONTACT_FRICTIONLESS ? 1 : 3;
    k.first_row              = (PetscInt)kinds.size();
    for (int r = 0; r < nrows; r++) {
      kinds.push_back(r == 0 ? FETI_ROW_CONTACT_NORMAL : FETI_ROW_CONTACT_TANGENTIAL);
      for (int c = 0; c < 3; c++) {
        body.push_back(k.body);
        node.push_back(k.node);
        comp.push_back(c);
        coef.push_back(dirs[r][c]);
        if (k.other_body >= 0) {
          body.push_back(k.other_body);
          node.push_back(k.other_node);
          comp.push_back(c);
          coef.push_back(-dirs[r][c]);
        }
      }
      rowptr.push_back((PetscInt)body.size());
      rhs.push_back(r == 0 ? k.gap : 0.0);
    }
  }
  if (!kinds.empty()) PetscCall(FEMAddConstraintRows(d.fem, (PetscInt)kinds.size(), kinds.data(), rowptr.data(), body.data(), node.data(), comp.data(), coef.data(), rhs.data()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the multipliers of the contact nodes this rank owns, and the ContactProblem */
PetscErrorCode BuildContactProblem(ContactModel cm)
{
  ModelData      &d = *cm->data;
  PetscInt        nrows, rstart, rend;
  const PetscInt *rows;
  Mat             F, Q;
  Vec             h, e, lt;
  const char     *prefix;

  PetscFunctionBegin;
  PetscCall(FEMGetAppendedRows(d.fem, &nrows, &rows));
  PetscCall(VecGetOwnershipRange(d.lambda, &rstart, &rend));
  for (size_t k = 0; k < d.nodes.size(); k++) {
    const NodeInfo &nd = d.nodes[k];
    const PetscInt  r  = rows[nd.first_row];
    if (r < rstart || r >= rend) continue;
    PetscCallCXX(d.local.push_back((PetscInt)k));
    PetscCallCXX(d.mult.insert(d.mult.end(), {r, nd.law == CONTACT_FRICTIONLESS ? -1 : rows[nd.first_row + 1], nd.law == CONTACT_FRICTIONLESS ? -1 : rows[nd.first_row + 2]}));
    PetscCallCXX(d.lbody.push_back(nd.body));
    PetscCallCXX(d.lnode.push_back(nd.node));
    PetscCallCXX(d.lcoords.insert(d.lcoords.end(), {nd.x[0], nd.x[1], nd.x[2]}));
    PetscCallCXX(d.larea.push_back(nd.area));
  }
  PetscCall(FETIGetOperators(d.feti, &F, NULL, NULL, &Q));
  PetscCall(FETIGetRHS(d.feti, &h, &e));
  PetscCall(FETIGetParticularSolution(d.feti, &lt));
  PetscCall(ContactProblemCreate(PetscObjectComm((PetscObject)cm), &d.cp));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)cm, &prefix));
  PetscCall(ContactProblemSetOptionsPrefix(d.cp, prefix));
  PetscCall(ContactProblemSetOperator(d.cp, F, h));
  PetscCall(ContactProblemSetProjector(d.cp, Q, lt));
  for (ContactLaw law : {CONTACT_FRICTIONLESS, CONTACT_TRESCA, CONTACT_COULOMB}) {
    std::vector<PetscInt>  n, t1, t2;
    std::vector<PetscReal> c;
    for (size_t j = 0; j < d.local.size(); j++) {
      const NodeInfo &nd = d.nodes[d.local[j]];
      if (nd.law != law) continue;
      n.push_back(d.mult[3 * j]);
      t1.push_back(d.mult[3 * j + 1]);
      t2.push_back(d.mult[3 * j + 2]);
      c.push_back(nd.coef);
    }
    PetscCall(ContactProblemAddNodes(d.cp, law, (PetscInt)n.size(), n.data(), t1.data(), t2.data(), c.data()));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/*@C
  ContactModelCreate - A contact model on a finite element model (the FEM must be set up).

  Collective

  Input Parameter:
. fem - the model (referenced)

  Output Parameter:
. cm - the contact model

  Level: beginner

.seealso: `ContactModelAddZone()`, `ContactModelSetUp()`, `ContactModelSolve()`
@*/
PetscErrorCode ContactModelCreate(FEM fem, ContactModel *cm)
{
  ContactModel c;
  const char  *prefix;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscHeaderCreate(c, CONTACTMODEL_CLASSID, "ContactModel", "Contact on a finite element model", "Contact", PetscObjectComm((PetscObject)fem), ContactModelDestroy, ContactModelView));
  PetscCallCXX(c->data = new ModelData);
  PetscCall(PetscObjectReference((PetscObject)fem));
  c->data->fem = fem;
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)fem, &prefix));
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)c, prefix));
  *cm = c;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelDestroy - Destroy a contact model.

  Collective

  Input Parameter:
. cm - the model

  Level: beginner

.seealso: `ContactModelCreate()`
@*/
PetscErrorCode ContactModelDestroy(ContactModel *cm)
{
  ModelData *d;

  PetscFunctionBegin;
  if (!*cm) PetscFunctionReturn(PETSC_SUCCESS);
  PetscValidHeaderSpecific(*cm, CONTACTMODEL_CLASSID, 1);
  if (--((PetscObject)(*cm))->refct > 0) {
    *cm = NULL;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  d = (*cm)->data;
  PetscCall(FEMDestroy(&d->fem));
  PetscCall(FETIDestroy(&d->feti));
  PetscCall(ContactProblemDestroy(&d->cp));
  PetscCall(VecDestroy(&d->lambda));
  PetscCall(VecDestroy(&d->u));
  PetscCall(VecDestroy(&d->alpha));
  delete d;
  PetscCall(PetscHeaderDestroy(cm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelAddZone - Add a contact zone (the same on every rank).

  Logically Collective

  Input Parameters:
+ cm   - the model
- zone - the zone (copied)

  Level: beginner

.seealso: `ContactZone`, `ContactModelSetUp()`
@*/
PetscErrorCode ContactModelAddZone(ContactModel cm, const ContactZone *zone)
{
  PetscInt nbodies;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  PetscCheck(!cm->data->setup, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONGSTATE, "ContactModelAddZone: add zones before ContactModelSetUp()");
  PetscCall(FEMGetNumBodies(cm->data->fem, &nbodies));
  PetscCheck(zone->body >= 0 && zone->body < nbodies, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_OUTOFRANGE, "contact zone: body %" PetscInt_FMT " does not exist (%" PetscInt_FMT " bodies)",
             zone->body, nbodies);
  if (zone->type == CONTACT_ZONE_BODIES)
    PetscCheck(zone->other_body >= 0 && zone->other_body < nbodies && zone->other_body != zone->body, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_OUTOFRANGE,
               "contact zone: the other body %" PetscInt_FMT " must exist and differ from body %" PetscInt_FMT, zone->other_body, zone->body);
  else
    PetscCheck(zone->normal[0] != 0 || zone->normal[1] != 0 || zone->normal[2] != 0, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONG,
               "contact zone: the foundation plane needs a nonzero normal");
  PetscCheck(zone->coef >= 0 && !PetscIsInfOrNanReal(zone->coef), PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_OUTOFRANGE, "contact zone: invalid %s %g (must be finite and >= 0)",
             zone->law == CONTACT_TRESCA ? "slip bound" : "friction coefficient", (double)zone->coef);
  PetscCallCXX(cm->data->zones.push_back(*zone));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelSetFromOptions - Options of the model's FETI and contact solvers (read at setup).

  Collective

  Input Parameter:
. cm - the model

  Notes:
  The FETI options (-feti_*) and the contact options (-contact_*, see `ContactProblemSetFromOptions()`)
  are read when `ContactModelSetUp()` creates those objects.

  Level: beginner

.seealso: `ContactModelSetUp()`
@*/
PetscErrorCode ContactModelSetFromOptions(ContactModel cm)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  if (cm->data->cp) PetscCall(ContactProblemSetFromOptions(cm->data->cp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelSetUp - Build the contact rows, the FETI operators and the dual contact problem.

  Collective

  Input Parameter:
. cm - the model

  Notes:
  Only what the zones call for is built: no zone means no contact rows (the solve is then a linear
  FETI solve), frictionless zones add normal rows only, Tresca and Coulomb zones add tangential rows.

  Before FETI is set up, the rigid motions of the bodies that no Dirichlet condition and no contact row
  resists are sought (a body without support on a frictionless floor, a body touching its support along
  one node line, bodies that float together): if there is one, the setup stops with an error
  (`PETSC_ERR_ARG_WRONG`) that names the bodies and the motion, says whether the load works along it
  (no equilibrium: the force along it or the moment about its axis) or not (no unique displacement),
  and how to hold it. See docs/contact.md, "No equilibrium, or no unique answer".

  Level: beginner

.seealso: `ContactModelSolve()`, `ContactModelGetPipeline()`, `FEMComputeLoadResultant()`
@*/
PetscErrorCode ContactModelSetUp(ContactModel cm)
{
  ModelData         *d;
  std::set<PetscInt> fixed;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  d = cm->data;
  if (d->setup) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DirichletNodes(d->fem, fixed));
  PetscCallCXX(d->unmatched.assign(d->zones.size(), 0));
  for (PetscInt z = 0; z < (PetscInt)d->zones.size(); z++) {
    PetscCall(CollectZoneNodes(cm, z, fixed));
    if (d->unmatched[z])
      PetscCall(PetscInfo(cm, "contact zone %" PetscInt_FMT ": %" PetscInt_FMT " nodes of the first face have no coinciding node on the second (not in contact)\n", z, d->unmatched[z]));
  }
  PetscCheck(d->zones.empty() || !d->nodes.empty(), PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONG,
             "the contact zones have no admissible node (all fixed, or no matching nodes between bodies)");
  PetscCall(AppendRows(cm));
  /* a rigid motion nothing resists would make the coarse matrix G G' singular (or nearly: garbage reported
     as converged); named here, before any factorization (contactrigidmotions.cxx) */
  {
    std::vector<ContactHoldingRow> holding;
    for (const NodeInfo &k : d->nodes) {
      const PetscReal *dirs[3] = {k.n, k.t1, k.t2};
      const int        nrows   = k.law == CONTACT_FRICTIONLESS || !(k.coef > 0) ? 1 : 3; /* tangential rows with a zero bound carry no force */
      for (int r = 0; r < nrows; r++) PetscCallCXX(holding.push_back({k.zone, k.body, k.node, k.other_body, k.other_node, {dirs[r][0], dirs[r][1], dirs[r][2]}}));
    }
    PetscCall(ContactCheckRigidMotions_Private(cm, d->fem, d->zones, holding));
  }
  PetscCall(FEMCreateFETI(d->fem, &d->feti));
  /* contact needs hundreds of F products: dense K+ blocks on the interface pay for their setup (-feti_kplus_explicit) */
  if (!d->zones.empty()) PetscCall(FETISetKplusExplicit(d->feti, PETSC_TRUE));
  PetscCall(FETISetFromOptions(d->feti));
  PetscCall(FETISetUp(d->feti));
  PetscCall(FETICreateVecs(d->feti, &d->u, &d->lambda, &d->alpha));
  if (!d->zones.empty()) {
    PetscCall(BuildContactProblem(cm));
    PetscCall(ContactProblemSetFromOptions(d->cp));
    PetscCall(ContactProblemSetUp(d->cp));
    PetscCall(ContactProblemGetPipeline(d->cp, &d->pipeline));
  } else d->pipeline = CONTACT_PIPELINE_LINEAR;
  d->setup = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelSolve - Solve: the linear FETI solve (no contact), or the contact pipeline, then the
  rigid-body amplitudes and the primal solution.

  Collective

  Input Parameter:
. cm - the model

  Notes:
  alpha comes from the augmented Lagrangian's multiplier of G l = e, alpha = -(GG')^{-1} G w with
  w = G'mu (`ContactProblemGetEqualityMultiplier()`), then u = K+(f - B'l) + R alpha.

  Level: beginner

.seealso: `ContactModelGetSolution()`, `ContactModelComputeResiduals()`
@*/
PetscErrorCode ContactModelSolve(ContactModel cm)
{
  ModelData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  PetscCall(ContactModelSetUp(cm));
  d = cm->data;
  if (d->pipeline == CONTACT_PIPELINE_LINEAR && !d->cp) {
    KSP                ksp;
    KSPConvergedReason reason;
    PetscInt           its;
    PetscCall(FETISolveLinear(d->feti, d->lambda, d->u));
    PetscCall(FETIGetKSP(d->feti, &ksp));
    PetscCall(KSPGetConvergedReason(ksp, &reason));
    PetscCall(KSPGetIterationNumber(ksp, &its));
    d->linear_stats                  = ContactStatistics{};
    d->linear_stats.pipeline         = CONTACT_PIPELINE_LINEAR;
    d->linear_stats.converged        = reason > 0 ? PETSC_TRUE : PETSC_FALSE;
    d->linear_stats.outer_iterations = its;
    d->linear_stats.products_qpp     = its + 1;
    PetscCall(PetscSNPrintf(d->linear_stats.reason, sizeof(d->linear_stats.reason), "linear FETI solve (projected CG): %s in %" PetscInt_FMT " iterations", KSPConvergedReasons[reason], its));
  } else {
    Mat      G;
    Vec      w, Gw;
    PetscInt ncoarse;
    Vec      lt;
    /* start from the particular solution: G l = e holds from the first iterate (the inner solver
       projects it onto the set) */
    PetscCall(FETIGetParticularSolution(d->feti, &lt));
    PetscCall(VecCopy(lt, d->lambda));
    PetscCall(ContactProblemSolve(d->cp, d->lambda));
    PetscCall(VecDuplicate(d->lambda, &w));
    PetscCall(ContactProblemGetEqualityMultiplier(d->cp, w));
    PetscCall(VecGetSize(d->alpha, &ncoarse));
    if (ncoarse) {
      PetscCall(FETIGetOperators(d->feti, NULL, &G, NULL, NULL));
      PetscCall(VecDuplicate(d->alpha, &Gw));
      PetscCall(MatMult(G, w, Gw));
      PetscCall(FETIApplyCoarseInverse(d->feti, Gw, d->alpha));
      PetscCall(VecScale(d->alpha, -1.0));
      PetscCall(VecDestroy(&Gw));
    }
    PetscCall(VecDestroy(&w));
    PetscCall(FETIRecoverPrimal(d->feti, d->lambda, d->alpha, d->u));
  }
  d->solved = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetFETI - The model's FETI problem (after setup).

  Not Collective

  Input Parameter:
. cm - the model

  Output Parameter:
. feti - the FETI problem (do not destroy)

  Level: intermediate

.seealso: `ContactModelSetUp()`
@*/
PetscErrorCode ContactModelGetFETI(ContactModel cm, FETI *feti)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  *feti = cm->data->feti;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetContactProblem - The dual contact problem (NULL without contact zones).

  Not Collective

  Input Parameter:
. cm - the model

  Output Parameter:
. cp - the problem (do not destroy)

  Level: intermediate

.seealso: `ContactProblem`
@*/
PetscErrorCode ContactModelGetContactProblem(ContactModel cm, ContactProblem *cp)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  *cp = cm->data->cp;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetPipeline - The pipeline the zones call for (after setup).

  Not Collective

  Input Parameter:
. cm - the model

  Output Parameter:
. pipeline - linear (no zone), frictionless, tresca or coulomb

  Level: beginner

.seealso: `ContactPipeline`
@*/
PetscErrorCode ContactModelGetPipeline(ContactModel cm, ContactPipeline *pipeline)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  *pipeline = cm->data->pipeline;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetSolution - The multipliers and the primal solution (after a solve).

  Not Collective

  Input Parameter:
. cm - the model

  Output Parameters:
+ lambda - dual vector (do not destroy), or NULL
- u      - primal vector, subdomain copies concatenated (do not destroy), or NULL

  Level: beginner

.seealso: `ContactModelSolve()`, `FEMPrimalToGlobal()`
@*/
PetscErrorCode ContactModelGetSolution(ContactModel cm, Vec *lambda, Vec *u)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  PetscCheck(cm->data->solved, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONGSTATE, "ContactModel: solve first");
  if (lambda) *lambda = cm->data->lambda;
  if (u) *u = cm->data->u;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetStatistics - Iterations and Hessian products of the last solve.

  Not Collective

  Input Parameter:
. cm - the model

  Output Parameter:
. stats - the statistics (for the linear pipeline: CG iterations as outer iterations, F products as QPP)

  Level: beginner

.seealso: `ContactStatistics`
@*/
PetscErrorCode ContactModelGetStatistics(ContactModel cm, ContactStatistics *stats)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  if (cm->data->cp) PetscCall(ContactProblemGetStatistics(cm->data->cp, stats));
  else *stats = cm->data->linear_stats;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetUnmatchedNodes - The number of nodes of node-to-node zones' first faces that have no
  node of the second face at the same position, and so are not in contact.

  Not Collective (the same on every rank)

  Input Parameter:
. cm - the model (set up)

  Output Parameter:
. n - the number, summed over the zones (0 on conforming meshes whose first face lies inside the second)

  Notes:
  Node-to-node contact needs conforming meshes: a first face larger than the second has such nodes by
  design, but a nonzero count on faces meant to match says the meshes do not (different cells, shifted
  bodies). The conefeti driver prints a note when it is nonzero; `ContactModelView()` gives it per zone.

  Level: intermediate

.seealso: `ContactModelAddZone()`, `ContactModelView()`
@*/
PetscErrorCode ContactModelGetUnmatchedNodes(ContactModel cm, PetscInt *n)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  PetscValidIntPointer(n, 2);
  PetscCheck(cm->data->setup, PetscObjectComm((PetscObject)cm), PETSC_ERR_ORDER, "Call ContactModelSetUp() first");
  *n = 0;
  for (PetscInt u : cm->data->unmatched) *n += u;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelGetNodes - The contact nodes whose multipliers this rank owns.

  Not Collective

  Input Parameter:
. cm - the model (set up)

  Output Parameters:
+ n      - number of local contact nodes
. body   - body of each
. node   - body node id of each
. coords - 3 coordinates per node
- area   - lumped nodal area of the contact face at each

  Level: intermediate

.seealso: `ContactModelGetNodeStates()`
@*/
PetscErrorCode ContactModelGetNodes(ContactModel cm, PetscInt *n, const PetscInt **body, const PetscInt **node, const PetscReal **coords, const PetscReal **area)
{
  ModelData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  d = cm->data;
  if (n) *n = (PetscInt)d->local.size();
  if (body) *body = d->lbody.data();
  if (node) *node = d->lnode.data();
  if (coords) *coords = d->lcoords.data();
  if (area) *area = d->larea.data();
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {

/* per local contact node: l_n, l_t (2), (N u - d), T u (2), slip bound g */
struct NodeValues {
  std::vector<PetscReal> ln, lt, gapres, tu, g;
};

PetscErrorCode EvaluateNodes(ContactModel cm, Vec Bu, NodeValues &v)
{
  ModelData             &d = *cm->data;
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
  v.g = bounds;
  for (size_t j = 0; j < n; j++) {
    const PetscInt rn = d.mult[3 * j] - rstart;
    v.ln[j]           = PetscRealPart(l[rn]);
    v.gapres[j]       = PetscRealPart(bu[rn] - (c ? c[rn] : 0.0));
    for (int q = 0; q < 2; q++) {
      if (d.mult[3 * j + 1 + q] < 0) continue;
      const PetscInt rt = d.mult[3 * j + 1 + q] - rstart;
      v.lt[2 * j + q]   = PetscRealPart(l[rt]);
      v.tu[2 * j + q]   = PetscRealPart(bu[rt]);
    }
  }
  PetscCall(VecRestoreArrayRead(d.lambda, &l));
  PetscCall(VecRestoreArrayRead(Bu, &bu));
  if (cvec) PetscCall(VecRestoreArrayRead(cvec, &c));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The regime from the multipliers: separated without pressure, slip on the boundary of the
   friction disk, stick inside it. Frictionless nodes in contact slide freely: slip. The margins
   (1e-4 of the largest pressure, 1e-3 of the slip bound) sit above the solver's tolerance. */
ContactNodeStatus Classify(PetscReal ln, PetscReal lnmax, const PetscReal lt[2], PetscReal g, PetscBool frictionless)
{
  if (ln <= 1e-4 * lnmax) return CONTACT_NODE_SEPARATED;
  if (frictionless || std::hypot(lt[0], lt[1]) >= (1 - 1e-3) * g) return CONTACT_NODE_SLIP;
  return CONTACT_NODE_STICK;
}

} // namespace

/*@C
  ContactModelComputeResiduals - The mechanical residuals of the solution (ALGORITHMS.md section 4),
  computed from u and lambda, not taken from the solver; and the counts of separated, stick and
  slip nodes.

  Collective

  Input Parameter:
. cm - the model (solved)

  Output Parameter:
. r - the residuals

  Notes:
  A node is separated when l_n <= 1e-4 max l_n; among the others, it slips when |l_t| >= (1 - 1e-3) g
  (on the boundary of its friction disk; frictionless nodes in contact always slip), and sticks
  otherwise. Whether stick nodes really do not move is what the slip_rule residual checks.

  Level: beginner

.seealso: `ContactResiduals`, `ContactModelGetNodeStates()`
@*/
PetscErrorCode ContactModelComputeResiduals(ContactModel cm, ContactResiduals *r)
{
  ModelData         *d;
  Mat                B;
  Vec                cvec, Ku, f, Btl, Bu;
  const FETIRowKind *kinds;
  PetscReal          nf, nbl, nres, umax, glue = 0;
  /* floor of the scales: a zero scale (no load, no pressure) gives 0/tiny = 0, not 0/0 (PETSC_MIN_REAL
     is the most negative real, not the smallest positive one) */
  constexpr PetscReal tiny = std::numeric_limits<PetscReal>::min();
  NodeValues          v;
  MPI_Comm            comm;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  d    = cm->data;
  comm = PetscObjectComm((PetscObject)cm);
  PetscCheck(d->solved, comm, PETSC_ERR_ARG_WRONGSTATE, "ContactModel: solve first");
  *r = ContactResiduals{};
  PetscCall(FETIGetConstraints(d->feti, &B, &cvec, &kinds));
  PetscCall(FETIGetLoad(d->feti, &f));
  /* equilibrium K u = f - B'l */
  PetscCall(VecDuplicate(d->u, &Ku));
  PetscCall(VecDuplicate(d->u, &Btl));
  PetscCall(FETIApplyK(d->feti, d->u, Ku));
  PetscCall(MatMultTranspose(B, d->lambda, Btl));
  PetscCall(VecNorm(f, NORM_2, &nf));
  PetscCall(VecNorm(Btl, NORM_2, &nbl));
  PetscCall(VecAXPY(Ku, -1.0, f));
  PetscCall(VecAXPY(Ku, 1.0, Btl));
  PetscCall(VecNorm(Ku, NORM_2, &nres));
  r->equilibrium = nres / PetscMax(PetscMax(nf, nbl), tiny);
  /* B u - c on gluing and Dirichlet rows */
  PetscCall(VecNorm(d->u, NORM_INFINITY, &umax));
  umax = PetscMax(umax, tiny);
  PetscCall(VecDuplicate(d->lambda, &Bu));
  PetscCall(MatMult(B, d->u, Bu));
  {
    const PetscScalar *bu, *c = NULL;
    PetscInt           m;
    PetscCall(VecGetLocalSize(Bu, &m));
    PetscCall(VecGetArrayRead(Bu, &bu));
    if (cvec) PetscCall(VecGetArrayRead(cvec, &c));
    for (PetscInt i = 0; i < m; i++)
      if (kinds[i] == FETI_ROW_GLUING || kinds[i] == FETI_ROW_DIRICHLET) glue = PetscMax(glue, PetscAbsReal(PetscRealPart(bu[i] - (c ? c[i] : 0.0))));
    PetscCall(VecRestoreArrayRead(Bu, &bu));
    if (cvec) PetscCall(VecRestoreArrayRead(cvec, &c));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &glue, 1, MPIU_REAL, MPIU_MAX, comm));
  r->gluing = glue / umax;
  if (d->cp) {
    PetscReal lmax[2] = {0, 0}, pen = 0, sign = 0, comp = 0, cone = 0, slip = 0;
    PetscCall(EvaluateNodes(cm, Bu, v));
    for (size_t j = 0; j < v.ln.size(); j++) {
      lmax[0] = PetscMax(lmax[0], v.ln[j]);
      lmax[1] = PetscMax(lmax[1], PetscMax(PetscAbsReal(v.ln[j]), std::hypot(v.lt[2 * j], v.lt[2 * j + 1])));
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, lmax, 2, MPIU_REAL, MPIU_MAX, comm));
    /* the scale of the contact stresses: the largest normal pressure, or (no pressure anywhere, e.g. a
       run without equilibrium) the largest contact multiplier, so that the ratios stay finite */
    const PetscReal lnmax = lmax[0], lscale = PetscMax(PetscMax(lnmax, lmax[1]), tiny), k = lscale / umax;
    for (size_t j = 0; j < v.ln.size(); j++) {
      const PetscReal ln = v.ln[j], *lt = &v.lt[2 * j], *tu = &v.tu[2 * j], g = v.g[j];
      pen  = PetscMax(pen, v.gapres[j]);
      sign = PetscMax(sign, -ln);
      comp = PetscMax(comp, PetscAbsReal(ln * v.gapres[j]));
      if (d->mult[3 * j + 1] >= 0) {
        cone = PetscMax(cone, std::hypot(lt[0], lt[1]) - g);
        /* natural residual of the slip rule: l_t = P_g(l_t + k T u) */
        PetscReal y[2] = {lt[0] + k * tu[0], lt[1] + k * tu[1]}, ny = std::hypot(y[0], y[1]);
        if (ny > g) y[0] *= g / ny, y[1] *= g / ny;
        slip = PetscMax(slip, std::hypot(lt[0] - y[0], lt[1] - y[1]));
      }
      r->counts[Classify(ln, lnmax, lt, g, d->mult[3 * j + 1] < 0 ? PETSC_TRUE : PETSC_FALSE)]++;
    }
    PetscReal m[6] = {pen, sign, comp, cone, slip, 0};
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, m, 6, MPIU_REAL, MPIU_MAX, comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, r->counts, 3, MPIU_INT, MPI_SUM, comm));
    r->penetration     = m[0] / umax;
    r->normal_sign     = m[1] / lscale;
    r->complementarity = m[2] / lscale / umax;
    r->friction_cone   = PetscMax(m[3], 0) / lscale;
    r->slip_rule       = m[4] / lscale;
  }
  r->max = PetscMax(PetscMax(PetscMax(r->equilibrium, r->gluing), PetscMax(r->penetration, r->normal_sign)), PetscMax(PetscMax(r->complementarity, r->friction_cone), r->slip_rule));
  PetscCall(VecDestroy(&Ku));
  PetscCall(VecDestroy(&Btl));
  PetscCall(VecDestroy(&Bu));
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
             first body is its opposite
. slip     - 3 per node: tangential displacement of the first body relative to the foundation or the other body
- status   - separated, stick or slip

  Level: intermediate

.seealso: `ContactModelComputeResiduals()`
@*/
PetscErrorCode ContactModelGetNodeStates(ContactModel cm, PetscReal pressure[], PetscReal traction[], PetscReal slip[], ContactNodeStatus status[])
{
  ModelData         *d;
  Mat                B;
  Vec                Bu, cvec;
  const FETIRowKind *kinds;
  NodeValues         v;
  PetscReal          lnmax = 0, umax;

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
  PetscCall(VecNorm(d->u, NORM_INFINITY, &umax));
  for (PetscReal ln : v.ln) lnmax = PetscMax(lnmax, ln);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &lnmax, 1, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)cm)));
  for (size_t j = 0; j < d->local.size(); j++) {
    const NodeInfo &nd = d->nodes[d->local[j]];
    if (pressure) pressure[j] = v.ln[j] / nd.area;
    for (int c = 0; c < 3; c++) {
      if (traction) traction[3 * j + c] = (v.lt[2 * j] * nd.t1[c] + v.lt[2 * j + 1] * nd.t2[c]) / nd.area;
      if (slip) slip[3 * j + c] = v.tu[2 * j] * nd.t1[c] + v.tu[2 * j + 1] * nd.t2[c];
    }
    if (status) status[j] = Classify(v.ln[j], lnmax, &v.lt[2 * j], v.g[j], d->mult[3 * j + 1] < 0 ? PETSC_TRUE : PETSC_FALSE);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactModelView - Describe the model: zones, contact nodes per law, the pipeline, FETI and the contact solver.

  Collective

  Input Parameters:
+ cm     - the model
- viewer - an ASCII viewer (or NULL)

  Level: beginner

.seealso: `ContactModelSolve()`
@*/
PetscErrorCode ContactModelView(ContactModel cm, PetscViewer viewer)
{
  ModelData *d;
  PetscBool  iascii;
  PetscInt   counts[3] = {0, 0, 0};

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cm, CONTACTMODEL_CLASSID, 1);
  d = cm->data;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(PetscObjectComm((PetscObject)cm), &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (!iascii) PetscFunctionReturn(PETSC_SUCCESS);
  for (auto &n : d->nodes) counts[n.law]++;
  PetscCall(PetscObjectPrintClassNamePrefixType((PetscObject)cm, viewer));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%zu contact zones; contact nodes: %" PetscInt_FMT " frictionless, %" PetscInt_FMT " Tresca, %" PetscInt_FMT " Coulomb; pipeline %s\n", d->zones.size(),
                                   counts[0], counts[1], counts[2], ContactPipelines[d->pipeline]));
  for (size_t z = 0; z < d->zones.size(); z++) {
    const ContactZone &zn = d->zones[z];
    if (zn.type == CONTACT_ZONE_FOUNDATION)
      PetscCall(PetscViewerASCIIPrintf(viewer, "zone %zu: body %" PetscInt_FMT " face %s on a rigid plane through (%g, %g, %g) with normal (%g, %g, %g), %s %g\n", z, zn.body, zn.face,
                                       (double)zn.point[0], (double)zn.point[1], (double)zn.point[2], (double)zn.normal[0], (double)zn.normal[1], (double)zn.normal[2], ContactLaws[zn.law],
                                       (double)zn.coef));
    else
      PetscCall(PetscViewerASCIIPrintf(
          viewer, "zone %zu: body %" PetscInt_FMT " face %s against body %" PetscInt_FMT " face %s (node to node), %s %g; %" PetscInt_FMT " nodes of the first face without a partner\n", z, zn.body,
          zn.face, zn.other_body, zn.other_face, ContactLaws[zn.law], (double)zn.coef, z < d->unmatched.size() ? d->unmatched[z] : 0));
  }
  if (d->cp) PetscCall(ContactProblemView(d->cp, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}
