/* The contact solve: pipeline choice, the Coulomb loops (MSA, merged, monolithic), statistics.

   Everything runs through one smalxe solver (the augmented Lagrangian for the equality) whose
   feasible set has a lower bound 0 on each normal multiplier and a disk on each tangential pair:
   - frictionless: only bounds, so smalxe's inner solver is mprgp;
   - Tresca: disks of given radius, inner mpgp;
   - Coulomb, merged (the seed paper's Algorithm 2): smalxe with two Gauss-Seidel blocks, all
     non-tangential multipliers (mprgp) then the tangential ones (mpgp); before the tangential
     block the radii become F l_n of the normal multipliers just computed;
   - Coulomb, monolithic: one mpgp over everything; radii F l_n refreshed before each inner solve,
     and convergence only when the radii agree with F l_n (smalxe's consistency check);
   - Coulomb, MSA (Algorithm 1): a full smalxe Tresca solve per successive approximation. */
#include <conefeti/private/contactimpl.h>
#include <conefeti/private/operatortest.h>
#include <conefeti/private/reproduciblesum.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

PetscLogEvent CONTACT_Solve;

namespace {

ContactProblemData *Data(ContactProblem cp) { return cp->data; }

/* the set whose disk radii the friction law drives */
PetscErrorCode FrictionSet(ContactProblem cp, SeparableSet *set)
{
  ContactProblemData *d = Data(cp);

  PetscFunctionBegin;
  *set = d->set;
  if (d->pipeline == CONTACT_PIPELINE_COULOMB && d->algorithm == CONTACT_COULOMB_MERGED) {
    Tao sub;
    PetscCall(TaoSMALXEGetBlockSubsolver(d->tao, 1, &sub));
    PetscCall(TaoQPGetConstraints(sub, set));
    PetscCheck(*set, PetscObjectComm((PetscObject)cp), PETSC_ERR_PLIB, "ContactProblem: the tangential block has no set yet");
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The largest disk radius: a slip bound beyond it acts as an infinite one (the pair sticks). The solvers square
   radii (the disks' feasible steps, the radii's norms), so bounds near the largest real ended DIVERGED_NAN
   (F = 1e200, or a Tresca bound of 1e300); held below 1e150 they solve as the sticking friction they are. Forces
   as large as the cap overflow the solve's own norms anyway (a load of 1e150 converges, 1e200 does not). The cap is
   the largest radius a SeparableSet takes */
constexpr PetscReal CONTACT_RADIUS_MAX = SEPARABLESET_DISK_RADIUS_MAX;

/* the disk radius of contact node j under the normal multiplier l_n: its Tresca bound, or F l_n */
PetscReal DiskRadius(const ContactProblemData *d, PetscInt j, PetscReal ln)
{
  const PetscReal r = d->law[j] == CONTACT_COULOMB ? d->coef[j] * PetscMax(ln, 0.0) : d->coef[j];
  return r > CONTACT_RADIUS_MAX ? CONTACT_RADIUS_MAX : r; /* a NaN stays one (PetscMin would turn it into the cap) */
}

/* radii of the disks for the multipliers l */
PetscErrorCode TargetRadii(ContactProblem cp, Vec lambda, std::vector<PetscReal> &r)
{
  ContactProblemData *d = Data(cp);
  const PetscScalar  *l;

  PetscFunctionBegin;
  PetscCallCXX(r.resize(d->disk_node.size()));
  PetscCall(VecGetArrayRead(lambda, &l));
  for (size_t k = 0; k < d->disk_node.size(); k++) {
    const PetscInt j = d->disk_node[k];
    r[k]             = DiskRadius(d, j, PetscRealPart(l[d->normal[j] - d->rstart]));
  }
  PetscCall(VecRestoreArrayRead(lambda, &l));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* |a - b| / |a| over all ranks (0 when both vanish) */
PetscErrorCode RelativeChange(MPI_Comm comm, const std::vector<PetscReal> &a, const std::vector<PetscReal> &b, PetscReal *rel)
{
  DoubleDouble s[2];

  PetscFunctionBegin;
  for (size_t k = 0; k < a.size(); k++) {
    s[0].addProduct(a[k] - b[k], a[k] - b[k]);
    s[1].addProduct(a[k], a[k]);
  }
  PetscCall(ReproducibleAllreduce(s, 2, comm));
  *rel = s[1].value() > 0 ? PetscSqrtReal(s[0].value() / s[1].value()) : (s[0].value() > 0 ? 1.0 : 0.0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* max_k |a_k - b_k| over the largest contact force max(l_n, |l_t|) of l, over all ranks: a radius g used by
   a solve that differs from F l_n of its result by d leaves a slipping pair off the Coulomb cone, and
   off the slip rule, by d, and the mechanical residuals (ContactModelComputeResiduals()) measure both in
   the maximum norm against the largest contact force. The relative change in the 2-norm can be many
   times smaller: by the square root of the number of pressed nodes over F and more (the brick at F = 2:
   change 4.7e-7, slip rule 2.8e-6) */
PetscErrorCode LargestChange(ContactProblem cp, Vec lambda, const std::vector<PetscReal> &a, const std::vector<PetscReal> &b, PetscReal *rel)
{
  ContactProblemData *d = Data(cp);
  const PetscScalar  *l;
  PetscReal           m[2] = {0, 0}; /* largest change, largest force */

  PetscFunctionBegin;
  for (size_t k = 0; k < a.size(); k++) m[0] = PetscMax(m[0], PetscAbsReal(a[k] - b[k]));
  PetscCall(VecGetArrayRead(lambda, &l));
  for (size_t j = 0; j < d->normal.size(); j++) {
    m[1] = PetscMax(m[1], PetscAbsReal(PetscRealPart(l[d->normal[j] - d->rstart])));
    if (d->law[j] == CONTACT_FRICTIONLESS) continue;
    if (d->polygon) { /* the tangential force of the polygon's multipliers */
      std::vector<PetscReal> mu(d->polygon);
      PetscReal              lt[2];
      for (PetscInt q = 0; q < d->polygon; q++) mu[q] = PetscRealPart(l[d->tang[j * d->polygon + q] - d->rstart]);
      ContactPolygonTraction(d->polygon, mu.data(), lt);
      m[1] = PetscMax(m[1], std::hypot(lt[0], lt[1]));
    } else m[1] = PetscMax(m[1], PetscRealPart(PetscSqrtScalar(l[d->t1[j] - d->rstart] * l[d->t1[j] - d->rstart] + l[d->t2[j] - d->rstart] * l[d->t2[j] - d->rstart])));
  }
  PetscCall(VecRestoreArrayRead(lambda, &l));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, m, 2, MPIU_REAL, MPIU_MAX, PetscObjectComm((PetscObject)cp)));
  *rel = m[1] > 0 ? m[0] / m[1] : (m[0] > 0 ? 1.0 : 0.0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A tangential pair that slipped sits on its circle of radius r0 = F l_n. When the next radius r1 is
   larger, the projection leaves the pair inside the new disk, where it is free, and the inner solve spends
   one expansion step per few such pairs to bring them back to the circle they most likely still slip on.
   Scaling the pair by r1/|l_t| puts it there at once (a shrinking radius needs nothing: the projection
   does it). */
PetscErrorCode FollowGrownRadii(ContactProblem cp, const std::vector<PetscReal> &old, Vec lambda)
{
  ContactProblemData *d = Data(cp);
  PetscScalar        *l;

  PetscFunctionBegin;
  PetscCall(VecGetArray(lambda, &l));
  for (size_t k = 0; k < d->disk_node.size(); k++) {
    const PetscInt  j  = d->disk_node[k];
    const PetscReal r0 = old[k], r1 = d->radius[k];
    if (d->law[j] != CONTACT_COULOMB || !(r0 > 0) || !(r1 > r0)) continue;
    if (d->polygon) { /* a polygon's multipliers on their old bound c r0 move to the new one c r1 */
      const PetscReal c = ContactPolygonBoundFactor(d->polygon);
      for (PetscInt q = 0; q < d->polygon; q++) {
        PetscScalar &m = l[d->tang[j * d->polygon + q] - d->rstart];
        if (PetscAbsScalar(m) >= c * r0 * (1 - 1e-10)) m = PetscRealPart(m) > 0 ? c * r1 : -c * r1;
      }
      continue;
    }
    PetscScalar    &a = l[d->t1[j] - d->rstart], &b = l[d->t2[j] - d->rstart];
    const PetscReal t = PetscSqrtReal(PetscRealPart(a * a + b * b));
    if (t >= r0 * (1 - 1e-10)) { /* on the old circle (up to the projection's rounding) */
      a *= r1 / t;
      b *= r1 / t;
    }
  }
  PetscCall(VecRestoreArray(lambda, &l));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* pre-solve hook: set radii F l_n before the tangential block (merged) or every inner solve (monolithic) */
PetscErrorCode PreSolve(Tao, PetscInt block, Vec lambda, void *ctx)
{
  ContactProblem      cp = static_cast<ContactProblem>(ctx);
  ContactProblemData *d  = Data(cp);

  PetscFunctionBegin;
  if (d->algorithm == CONTACT_COULOMB_MERGED && block != 1) PetscFunctionReturn(PETSC_SUCCESS);
  const std::vector<PetscReal> old = d->radius;
  PetscReal                    change, largest;
  PetscCall(ContactProblemUpdateRadii_Private(cp, lambda, &change));
  PetscCall(LargestChange(cp, lambda, d->radius, old, &largest));
  PetscCall(PetscInfo(cp, "Coulomb radii F l_n before the inner solve: relative change %g, largest %g of the largest force\n", (double)change, (double)largest));
  if (d->follow_radii) PetscCall(FollowGrownRadii(cp, old, lambda));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* monolithic: converged only if the radii used agree with F l_n of the result */
PetscErrorCode Consistent(Tao, Vec lambda, PetscBool *ok, void *ctx)
{
  ContactProblem         cp = static_cast<ContactProblem>(ctx);
  ContactProblemData    *d  = Data(cp);
  std::vector<PetscReal> target;
  PetscReal              rel = 0, largest = 0;

  PetscFunctionBegin;
  PetscCall(TargetRadii(cp, lambda, target));
  PetscCall(RelativeChange(PetscObjectComm((PetscObject)cp), target, d->radius, &rel));
  PetscCall(LargestChange(cp, lambda, target, d->radius, &largest)); /* what the slip rule's residual sees */
  const PetscReal tol = d->fixed_point_rtol > 0 ? d->fixed_point_rtol : d->rtol;
  *ok                 = rel <= tol && largest <= tol ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscInfo(cp, "Coulomb radii used vs F l_n of the result: relative change %g, largest %g of the largest force (%s)\n", (double)rel, (double)largest, *ok ? "consistent" : "not yet"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The layer drives smalxe's API (sub-solvers, pre-solve hook, multiplier) and hands its inner solvers a
   QP (Hessian, linear term, separable set) rather than an objective: other TAO types would fail deep
   inside with messages about callbacks the user never set, so the types are checked here by option name */
static PetscErrorCode CheckSolverTypes(Tao tao, PetscInt nblocks)
{
  PetscBool   ok;
  const char *prefix, *type;

  PetscFunctionBegin;
  PetscCall(TaoGetOptionsPrefix(tao, &prefix));
  PetscCall(TaoGetType(tao, &type));
  PetscCall(PetscObjectTypeCompare((PetscObject)tao, TAOSMALXE, &ok));
  PetscCheck(ok, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONG,
             "-%stao_type %s: the contact solver is the augmented Lagrangian smalxe (its inner solvers are chosen by -%stao_smalxe_subsolver_tao_type)", prefix ? prefix : "", type,
             prefix ? prefix : "");
  for (PetscInt k = 0; k < PetscMax(nblocks, 1); k++) {
    Tao sub;
    if (nblocks > 1) PetscCall(TaoSMALXEGetBlockSubsolver(tao, k, &sub));
    else PetscCall(TaoSMALXEGetSubsolver(tao, &sub));
    PetscCall(TaoGetOptionsPrefix(sub, &prefix));
    PetscCall(TaoGetType(sub, &type));
    if (!type) continue; /* not chosen by the user: smalxe picks mprgp or mpgp from the set at the first solve */
    PetscCall(PetscObjectTypeCompareAny((PetscObject)sub, &ok, TAOMPRGP, TAOMPGP, ""));
    PetscCheck(ok, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONG,
               "-%stao_type %s: the inner solvers of the contact problem are conefeti's QP solvers, mprgp (bounds) or mpgp (bounds, disks and cones)", prefix ? prefix : "", type);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* friction polygons: the bounds -c g <= m_j <= c g of every tangential multiplier for the current slip bounds g */
PetscErrorCode SetPolygonBounds(ContactProblem cp, SeparableSet set)
{
  ContactProblemData *d = Data(cp);
  const PetscReal     c = ContactPolygonBoundFactor(d->polygon);
  PetscScalar        *lb, *ub;

  PetscFunctionBegin;
  PetscCall(VecGetArray(d->lb, &lb));
  PetscCall(VecGetArray(d->ub, &ub));
  for (size_t k = 0; k < d->disk_node.size(); k++) {
    const PetscInt j = d->disk_node[k];
    for (PetscInt q = 0; q < d->polygon; q++) {
      const PetscInt i = d->tang[j * d->polygon + q] - d->rstart;
      lb[i]            = -c * d->radius[k];
      ub[i]            = c * d->radius[k];
    }
  }
  PetscCall(VecRestoreArray(d->lb, &lb));
  PetscCall(VecRestoreArray(d->ub, &ub));
  PetscCall(SeparableSetSetBounds(set, d->lb, d->ub));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BuildSet(ContactProblem cp)
{
  ContactProblemData   *d = Data(cp);
  std::vector<PetscInt> idx;
  PetscScalar          *lb;
  PetscInt              N;

  PetscFunctionBegin;
  PetscCall(VecGetSize(d->h, &N));
  PetscCall(SeparableSetCreate(PetscObjectComm((PetscObject)cp), d->nlocal, N, &d->set));
  PetscCall(VecDuplicate(d->h, &d->lb));
  PetscCall(VecSet(d->lb, PETSC_NINFINITY));
  PetscCall(VecGetArray(d->lb, &lb));
  for (PetscInt n : d->normal) lb[n - d->rstart] = 0.0;
  PetscCall(VecRestoreArray(d->lb, &lb));
  if (d->polygon) {
    PetscCall(VecDuplicate(d->h, &d->ub));
    PetscCall(VecSet(d->ub, PETSC_INFINITY));
  }
  PetscCall(SeparableSetSetBounds(d->set, d->lb, d->ub));
  d->disk_node.clear();
  for (size_t j = 0; j < d->normal.size(); j++) {
    if (d->law[j] == CONTACT_FRICTIONLESS) continue;
    if (!d->polygon) PetscCallCXX(idx.insert(idx.end(), {d->t1[j], d->t2[j]}));
    PetscCallCXX(d->disk_node.push_back((PetscInt)j));
  }
  PetscCallCXX(d->radius.assign(d->disk_node.size(), 0.0));
  for (size_t k = 0; k < d->disk_node.size(); k++) d->radius[k] = DiskRadius(d, d->disk_node[k], 0.0); /* Coulomb's F l_n come with the first multipliers */
  if (d->polygon) PetscCall(SetPolygonBounds(cp, d->set));
  else PetscCall(SeparableSetAddDisks(d->set, (PetscInt)d->radius.size(), idx.data(), NULL, d->radius.data()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* merged: block 0 = all but the tangential multipliers, block 1 = the tangential pairs in node order */
PetscErrorCode SetBlocks(ContactProblem cp)
{
  ContactProblemData   *d = Data(cp);
  std::vector<char>     tangential(d->nlocal, 0);
  std::vector<PetscInt> c, t;
  IS                    is[2];

  PetscFunctionBegin;
  for (PetscInt k : d->disk_node) {
    tangential[d->t1[k] - d->rstart] = 1;
    tangential[d->t2[k] - d->rstart] = 1;
    PetscCallCXX(t.insert(t.end(), {d->t1[k], d->t2[k]}));
  }
  for (PetscInt i = 0; i < d->nlocal; i++)
    if (!tangential[i]) PetscCallCXX(c.push_back(d->rstart + i));
  PetscCall(ISCreateGeneral(PetscObjectComm((PetscObject)cp), (PetscInt)c.size(), c.data(), PETSC_COPY_VALUES, &is[0]));
  PetscCall(ISCreateGeneral(PetscObjectComm((PetscObject)cp), (PetscInt)t.size(), t.data(), PETSC_COPY_VALUES, &is[1]));
  PetscCall(TaoSMALXESetBlocks(d->tao, 2, is));
  PetscCall(ISDestroy(&is[0]));
  PetscCall(ISDestroy(&is[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the equality of the augmented Lagrangian: projector form, penalty form, or an empty one */
PetscErrorCode SetEquality(ContactProblem cp)
{
  ContactProblemData *d = Data(cp);

  PetscFunctionBegin;
  if (d->Q) PetscCall(TaoSMALXESetProjector(d->tao, d->Q, d->lt));
  else if (d->G) PetscCall(TaoSMALXESetEqualityConstraints(d->tao, d->G, d->e));
  else {
    PetscInt N;
    PetscCall(VecGetSize(d->h, &N));
    PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)cp), 0, d->nlocal, 0, N, 0, NULL, 0, NULL, &d->C0));
    PetscCall(MatAssemblyBegin(d->C0, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(d->C0, MAT_FINAL_ASSEMBLY));
    PetscCall(MatCreateVecs(d->C0, NULL, &d->d0));
    PetscCall(TaoSMALXESetEqualityConstraints(d->tao, d->C0, d->d0));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* G (or Q) acts on the multipliers of F: with another number of columns the solve failed in smalxe, with a message
   about C and "the solution", or in a product ("Mat mat,Vec x: global dim 8 9"), names the user never gave */
PetscErrorCode CheckEqualitySizes(ContactProblem cp)
{
  ContactProblemData *d = Data(cp);
  PetscInt            N, M, n, m;
  MPI_Comm            comm = PetscObjectComm((PetscObject)cp);

  PetscFunctionBegin;
  PetscCall(MatGetSize(d->F, &N, NULL));
  if (d->G) {
    PetscCall(MatGetSize(d->G, &M, &m));
    PetscCall(MatGetLocalSize(d->G, NULL, &n));
    PetscCheck(m == N, comm, PETSC_ERR_ARG_SIZ,
               "ContactProblem: the equality matrix G (ContactProblemSetEquality()) has %" PetscInt_FMT " columns, F (ContactProblemSetOperator()) is %" PetscInt_FMT " x %" PetscInt_FMT
               ": G must have a column for each multiplier",
               m, N, N);
    PetscCheck(n == d->nlocal, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
               "ContactProblem: the equality matrix G (ContactProblemSetEquality()) has %" PetscInt_FMT " local columns on this rank, h (ContactProblemSetOperator()) %" PetscInt_FMT
               " local entries: G's column layout must be that of the multipliers",
               n, d->nlocal);
  }
  if (d->Q) {
    PetscInt ltn;
    PetscCall(MatGetSize(d->Q, &M, &m));
    PetscCall(MatGetLocalSize(d->Q, NULL, &n));
    PetscCheck(M == N && m == N, comm, PETSC_ERR_ARG_SIZ,
               "ContactProblem: the projector Q (ContactProblemSetProjector()) is %" PetscInt_FMT " x %" PetscInt_FMT ", F (ContactProblemSetOperator()) is %" PetscInt_FMT " x %" PetscInt_FMT
               ": Q must be the size of F",
               M, m, N, N);
    PetscCheck(n == d->nlocal, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
               "ContactProblem: the projector Q (ContactProblemSetProjector()) has %" PetscInt_FMT " local columns on this rank, h (ContactProblemSetOperator()) %" PetscInt_FMT
               " local entries: Q's column layout must be that of the multipliers",
               n, d->nlocal);
    PetscCall(VecGetSize(d->lt, &ltn));
    PetscCheck(ltn == N, comm, PETSC_ERR_ARG_SIZ,
               "ContactProblem: the particular solution lt (ContactProblemSetProjector()) has %" PetscInt_FMT " entries, F (ContactProblemSetOperator()) is %" PetscInt_FMT " x %" PetscInt_FMT, ltn, N,
               N);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ValidateNodes(ContactProblem cp)
{
  ContactProblemData *d = Data(cp);
  std::vector<char>   used(d->nlocal, 0);

  PetscFunctionBegin;
  for (size_t j = 0; j < d->normal.size(); j++) {
    std::vector<PetscInt> ids = {d->normal[j]};
    if (d->law[j] != CONTACT_FRICTIONLESS && d->polygon) PetscCallCXX(ids.insert(ids.end(), d->tang.begin() + j * d->polygon, d->tang.begin() + (j + 1) * d->polygon));
    else if (d->law[j] != CONTACT_FRICTIONLESS) PetscCallCXX(ids.insert(ids.end(), {d->t1[j], d->t2[j]}));
    for (size_t q = 0; q < ids.size(); q++) {
      const PetscInt i = ids[q] - d->rstart;
      PetscCheck(i >= 0 && i < d->nlocal, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                 "ContactProblem: contact node %zu uses multiplier %" PetscInt_FMT ", not owned by this rank (range [%" PetscInt_FMT ", %" PetscInt_FMT "))", j, ids[q], d->rstart,
                 d->rstart + d->nlocal);
      PetscCheck(!used[i], PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "ContactProblem: multiplier %" PetscInt_FMT " belongs to two contact roles", ids[q]);
      used[i] = 1;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/* Sets the disk radii for the multipliers lambda; returns their relative change if asked. */
PetscErrorCode ContactProblemUpdateRadii_Private(ContactProblem cp, Vec lambda, PetscReal *change)
{
  ContactProblemData    *d = Data(cp);
  std::vector<PetscReal> target;
  SeparableSet           set;

  PetscFunctionBegin;
  PetscCall(TargetRadii(cp, lambda, target));
  if (change) PetscCall(RelativeChange(PetscObjectComm((PetscObject)cp), target, d->radius, change));
  d->radius = target;
  PetscCall(FrictionSet(cp, &set));
  if (d->polygon) PetscCall(SetPolygonBounds(cp, set));
  else PetscCall(SeparableSetSetDiskRadii(set, d->radius.data()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemSetFromOptions - Read the contact solver's options.

  Collective

  Input Parameter:
. cp - the problem

  Options Database Keys:
+ -contact_coulomb_algorithm <monolithic> - msa (Algorithm 1), merged (Algorithm 2), monolithic (one mpgp over all multipliers; the default: fewest products on the brick)
. -contact_rtol <1e-6>                  - projected gradient and equality residual relative to |h| (smalxe's gttol)
. -contact_msa_rtol <rtol>              - MSA: stop when the slip bounds change by less than this, relatively
. -contact_msa_max_it <100>             - MSA: most successive approximations
. -contact_msa_start_rtol <1e-2>        - MSA: tolerance of the first Tresca solve, whose slip bounds come from the initial multipliers (it only supplies the first bounds F l_n)
. -contact_msa_recycle <true>           - MSA: each Tresca solve after the first starts from the previous one's multiplier of the equality (`TaoSetRecycleHistory()`)
. -contact_fixed_point_rtol <rtol>      - monolithic: radii must agree with F l_n to this relative tolerance
. -contact_kkt_check <true>             - recompute the KKT residual before saying converged (a `ContactModel` turns it off: it judges by the mechanics)
. -contact_acceptance_factor <10>       - converged only when the KKT residual recomputed from the multipliers (`ContactProblemComputeKKTResidual()`) is at most this times -contact_rtol;
                                          without the option also at most 0.1 (or -contact_rtol, if larger)
. -contact_refine_max <3>              - tighter warm solves when the solver's test passes but the KKT check does not, at most this many (0: none; `ContactProblemSolve()`)
. -contact_coulomb_follow_radii <true>  - Coulomb: when F l_n grows between solves, tangential pairs on their old circle are scaled onto the new one (they most likely still slip)
. -contact_start_rtol <0.1>            - a cold solve first runs CG on the problem without the contact inequalities to this relative residual (0: off; see `ContactProblemSolve()`)
. -contact_start_max_it <100>           - most CG steps of that start
. -contact_start_compressive <0.6>      - the start is abandoned (the given multipliers kept) when less than this share of its sum |l_n| presses
. -contact_start_separated <0.6>        - below this share the solution without contact rows is tried too, and kept when it touches nothing (0: never)
. -contact_pc_type <none,lumped,dirichlet> - the preconditioner of F in the inner CG steps (default none; a `ContactModel` takes dirichlet when at most half its subdomains use dense K+ blocks in F;
                                          with one, the inner solvers default to the projected CG expansion; see `ContactProblemGetPC()`)
. -contact_tao_smalxe_anderson <depth>   - Anderson depth of the multiplier update (0: Dostal's plain update); 1 monolithic, 0 merged, 3 otherwise (`TaoSMALXESetAnderson()`)
- -contact_tao_smalxe_*, -contact_tao_smalxe_subsolver_tao_*, -contact_tao_smalxe_block<k>_tao_* - the solvers (see `TAOSMALXE`)

  Notes:
  After `ContactProblemSetUp()` the solvers' options (-contact_tao_*) and -contact_rtol still take effect; the
  Coulomb algorithm, which the setup built the solver for, can no longer change (an error), and -contact_pc_type
  is put in place at the setup only.

  Level: beginner

.seealso: `ContactProblemSolve()`
@*/
PetscErrorCode ContactProblemSetFromOptions(ContactProblem cp)
{
  ContactProblemData     *d;
  ContactCoulombAlgorithm built;
  const char             *prefix; /* the options the errors name are the user's, with the problem's prefix */
  PetscBool               set;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  d     = cp->data;
  built = d->algorithm;
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)cp, &prefix));
  if (!prefix) prefix = "";
  PetscObjectOptionsBegin((PetscObject)cp);
  PetscCall(PetscOptionsEnum("-contact_coulomb_algorithm", "Coulomb friction: msa (Algorithm 1), merged (Algorithm 2), monolithic", "ContactCoulombAlgorithm", ContactCoulombAlgorithms,
                             (PetscEnum)d->algorithm, (PetscEnum *)&d->algorithm, NULL));
  PetscCall(PetscOptionsReal("-contact_rtol", "Projected gradient and equality residual relative to |h|", "ContactProblemSolve", d->rtol, &d->rtol, NULL));
  PetscCall(PetscOptionsReal("-contact_msa_rtol", "MSA: relative change of the slip bounds at which the successive approximations stop (-1: -contact_rtol)", "ContactProblemSolve", d->msa_rtol,
                             &d->msa_rtol, NULL));
  PetscCall(PetscOptionsInt("-contact_msa_max_it", "MSA: most successive approximations", "ContactProblemSolve", d->msa_max_it, &d->msa_max_it, NULL));
  PetscCall(PetscOptionsReal("-contact_msa_start_rtol", "MSA: tolerance of the first Tresca solve, whose slip bounds come from the initial multipliers (it only supplies the first bounds F l_n)",
                             "ContactProblemSolve", d->msa_start_rtol, &d->msa_start_rtol, NULL));
  PetscCall(PetscOptionsBool("-contact_msa_recycle", "MSA: each Tresca solve after the first starts from the previous one's multiplier of the equality (TaoSetRecycleHistory())", "ContactProblemSolve",
                             d->msa_recycle, &d->msa_recycle, NULL));
  PetscCall(PetscOptionsBool("-contact_coulomb_follow_radii", "Coulomb: tangential pairs on their circle move onto the new circle when F l_n grows", "ContactProblemSolve", d->follow_radii,
                             &d->follow_radii, NULL));
  PetscCall(PetscOptionsBool("-contact_kkt_check", "Recompute the KKT residual from the multipliers before saying converged (default: on; off in a ContactModel, which judges by the mechanics)",
                             "ContactProblemComputeKKTResidual", d->kkt_check, &d->kkt_check, NULL));
  PetscCall(PetscOptionsReal("-contact_acceptance_factor",
                             "Converged only when the KKT residual (ContactProblem) or every mechanical residual (ContactModel) is at most this times -contact_rtol (by default also at most 0.1, or "
                             "-contact_rtol if that is larger; a factor given is taken as given)",
                             "ContactProblemComputeKKTResidual", d->acceptance_factor, &d->acceptance_factor, &set));
  if (set) d->acceptance_given = PETSC_TRUE; /* a later call without the option keeps it given */
  /* the model reads it too (for its mechanical residuals): the same text, so that -help lists one meaning */
  PetscCall(PetscOptionsInt("-contact_refine_max", "Tighter warm-started solves when the solver's test passes but a mechanical residual (or, with -contact_kkt_check, the KKT residual) does not",
                            "ContactProblemSolve", d->refine_max, &d->refine_max, NULL));
  PetscCall(PetscOptionsReal("-contact_fixed_point_rtol", "Monolithic: radii must agree with F l_n to this relative tolerance (-1: -contact_rtol)", "ContactProblemSolve", d->fixed_point_rtol,
                             &d->fixed_point_rtol, NULL));
  PetscCall(ContactProblemPCOptions_Private(cp, PetscOptionsObject));    /* -contact_pc_contact_scale ... (contactpc.cxx) */
  PetscCall(ContactProblemStartOptions_Private(cp, PetscOptionsObject)); /* -contact_start_rtol ... (contactstart.cxx) */
  PetscOptionsEnd();
  PetscCall(ContactProblemSetFromOptionsPC_Private(cp)); /* -contact_pc_type ... (contactpc.cxx) */
  PetscCheck(d->acceptance_factor >= 1 && d->acceptance_factor < PETSC_MAX_REAL, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE,
             "-%scontact_acceptance_factor must be finite and >= 1 (the residuals cannot be held below the solver's tolerance), got %g", prefix, (double)d->acceptance_factor);
  PetscCheck(d->refine_max >= 0, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE, "-%scontact_refine_max must be >= 0, got %" PetscInt_FMT " (0: no tighter solves)", prefix, d->refine_max);
  PetscCheck(d->rtol > 0 && d->rtol < 1, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE, "-%scontact_rtol must be in (0, 1), got %g", prefix, (double)d->rtol);
  PetscCheck((d->msa_rtol > 0 && d->msa_rtol < 1) || d->msa_rtol == -1, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE,
             "-%scontact_msa_rtol must be in (0, 1) (or -1: -%scontact_rtol), got %g", prefix, prefix, (double)d->msa_rtol);
  PetscCheck(d->msa_start_rtol > 0 && d->msa_start_rtol < 1, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE, "-%scontact_msa_start_rtol must be in (0, 1), got %g", prefix,
             (double)d->msa_start_rtol);
  PetscCheck(d->msa_max_it > 0, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE, "-%scontact_msa_max_it must be positive, got %" PetscInt_FMT, prefix, d->msa_max_it);
  PetscCheck((d->fixed_point_rtol > 0 && d->fixed_point_rtol < 1) || d->fixed_point_rtol == -1, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE,
             "-%scontact_fixed_point_rtol must be in (0, 1) (or -1: -%scontact_rtol), got %g", prefix, prefix, (double)d->fixed_point_rtol);
  if (d->setup) {
    /* the setup built the solver (blocks, hooks) for one algorithm: running it with another's fails half-way; the
       problem keeps the one it was built for */
    const ContactCoulombAlgorithm asked = d->algorithm;
    d->algorithm                        = built;
    PetscCheck(asked == built || d->pipeline != CONTACT_PIPELINE_COULOMB, PetscObjectComm((PetscObject)cp), PETSC_ERR_ORDER,
               "-%scontact_coulomb_algorithm %s after ContactProblemSetUp(), which built the solver for %s: set it before the setup", prefix, ContactCoulombAlgorithms[asked],
               ContactCoulombAlgorithms[built]);
    PetscCall(TaoSetTolerances(d->tao, 0.0, 0.0, d->rtol)); /* -contact_rtol, as the setup gave it */
  }
  if (d->tao) PetscCall(TaoSetFromOptions(d->tao));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemSetUp - Choose the pipeline from the problem, build the feasible set and the solver.

  Collective

  Input Parameter:
. cp - the problem

  Notes:
  Only the effects the problem contains are set up: no tangential multipliers enter the set for
  frictionless nodes, and the Coulomb machinery only exists when a Coulomb node does.
  G (`ContactProblemSetEquality()`) must have a column for each multiplier of F, Q (`ContactProblemSetProjector()`)
  must be the size of F, each with the column layout of h: otherwise the setup fails with an error naming both sizes.

  Level: intermediate

.seealso: `ContactProblemSolve()`, `ContactProblemGetPipeline()`
@*/
PetscErrorCode ContactProblemSetUp(ContactProblem cp)
{
  ContactProblemData *d;
  PetscInt            flags[3];
  const char         *prefix;
  char                taoprefix[256];

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  d = cp->data;
  if (d->setup) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)cp, &prefix));
  PetscCheck(d->F && d->h, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_WRONGSTATE, "ContactProblem: call ContactProblemSetOperator() first");
  PetscCheck(!(d->Q && d->G), PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_WRONGSTATE, "ContactProblem: give the equality once, as a projector or as G l = e");
  PetscCall(VecGetOwnershipRange(d->h, &d->rstart, NULL));
  PetscCall(VecGetLocalSize(d->h, &d->nlocal));
  PetscCall(CheckEqualitySizes(cp));
  PetscCall(ValidateNodes(cp));

  flags[0] = d->normal.empty() ? 0 : 1;
  flags[1] = std::count(d->law.begin(), d->law.end(), CONTACT_TRESCA) ? 1 : 0;
  flags[2] = std::count(d->law.begin(), d->law.end(), CONTACT_COULOMB) ? 1 : 0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, flags, 3, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)cp)));
  d->has_normal  = flags[0] ? PETSC_TRUE : PETSC_FALSE;
  d->has_tresca  = flags[1] ? PETSC_TRUE : PETSC_FALSE;
  d->has_coulomb = flags[2] ? PETSC_TRUE : PETSC_FALSE;
  d->pipeline    = d->has_coulomb ? CONTACT_PIPELINE_COULOMB : (d->has_tresca ? CONTACT_PIPELINE_TRESCA : (d->has_normal ? CONTACT_PIPELINE_FRICTIONLESS : CONTACT_PIPELINE_LINEAR));

  {
    PetscInt k = d->polygon;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &k, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)cp)));
    PetscCheck(d->polygon == k || d->normal.size() == 0 || std::count(d->law.begin(), d->law.end(), CONTACT_FRICTIONLESS) == (std::ptrdiff_t)d->law.size(), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
               "ContactProblem: the ranks' friction nodes differ: polygons of %" PetscInt_FMT " directions here, %" PetscInt_FMT " elsewhere", d->polygon, k);
    if (!d->polygon && k) { /* only frictionless nodes here: their tangential slots, for the code that walks the polygons */
      d->polygon = k;
      PetscCallCXX(d->tang.assign(d->normal.size() * k, -1));
    }
  }
  /* merged's tangential block gets a copy of the set that the pre-solve hook changes in place: disk radii only */
  PetscCheck(!(d->polygon && d->pipeline == CONTACT_PIPELINE_COULOMB && d->algorithm == CONTACT_COULOMB_MERGED), PetscObjectComm((PetscObject)cp), PETSC_ERR_SUP,
             "-%scontact_friction_polygon %" PetscInt_FMT ": friction polygons run with -%scontact_coulomb_algorithm monolithic or msa, not merged", prefix ? prefix : "", d->polygon,
             prefix ? prefix : "");
  PetscCall(BuildSet(cp));
  PetscCall(TaoCreate(PetscObjectComm((PetscObject)cp), &d->tao));
  PetscCall(PetscSNPrintf(taoprefix, sizeof(taoprefix), "%scontact_", prefix ? prefix : ""));
  PetscCall(TaoSetOptionsPrefix(d->tao, taoprefix));
  PetscCall(TaoSetType(d->tao, TAOSMALXE));
  PetscCall(TaoSetHessian(d->tao, d->F, d->F, NULL, NULL));
  PetscCall(TaoSMALXESetOperatorNames_Private(d->tao, "F (ContactProblemSetOperator())", "Q (ContactProblemSetProjector())"));
  PetscCall(TaoQPSetLinearTerm(d->tao, d->h));
  PetscCall(TaoQPSetConstraints(d->tao, d->set));
  PetscCall(SetEquality(cp));
  PetscCall(TaoSetTolerances(d->tao, 0.0, 0.0, d->rtol));
  /* a solve's answer is checked from scratch (the model's mechanics, or the KKT residual): no confirming product */
  PetscCall(TaoSMALXESetExactStop(d->tao, PETSC_FALSE));
  if (d->pipeline == CONTACT_PIPELINE_COULOMB) {
    if (d->algorithm == CONTACT_COULOMB_MERGED) PetscCall(SetBlocks(cp));
    if (d->algorithm != CONTACT_COULOMB_MSA) PetscCall(TaoSMALXESetPreSolve(d->tao, PreSolve, cp));
    if (d->algorithm == CONTACT_COULOMB_MONOLITHIC) {
      PetscCall(TaoSMALXESetConsistencyCheck(d->tao, Consistent, cp));
      /* the radii move before every inner solve, so the map from multiplier to residual changes with
         each outer iteration and older Anderson history describes a different map: mix only the last
         update (depth 1), which costs the brick fewer products than a deeper history
         (docs/brick-benchmark.md, 'Anderson acceleration of the multiplier update') */
      PetscCall(TaoSMALXESetAnderson(d->tao, 1, 3));
    }
  }
  PetscCall(TaoSetFromOptions(d->tao));
  PetscCall(CheckSolverTypes(d->tao, d->pipeline == CONTACT_PIPELINE_COULOMB && d->algorithm == CONTACT_COULOMB_MERGED ? 2 : 1));
  PetscCall(ContactProblemSetUpPC_Private(cp)); /* after the check: it asks smalxe for its inner solver */
  d->setup = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CollectStatistics(ContactProblem cp, PetscInt outer, PetscInt al)
{
  ContactProblemData *d = cp->data;
  QPCounters          total;
  ContactStatistics  &st = d->stats;

  PetscFunctionBegin;
  PetscCall(TaoQPGetCounters(d->tao, &total));
  st.pipeline          = d->pipeline;
  st.algorithm         = d->algorithm;
  st.outer_iterations  = outer;
  st.al_iterations     = al;
  st.products_other    = total.hessian_mults;
  st.products_estimate = total.estimate_mults;
  st.products_qpp = st.products_qpq = 0;
  if (d->pipeline == CONTACT_PIPELINE_COULOMB && d->algorithm == CONTACT_COULOMB_MERGED) {
    for (PetscInt k = 0; k < 2; k++) {
      Tao        sub;
      QPCounters c;
      PetscCall(TaoSMALXEGetBlockSubsolver(d->tao, k, &sub));
      PetscCall(TaoQPGetCounters(sub, &c));
      (k ? st.products_qpq : st.products_qpp) += c.hessian_mults;
    }
  } else {
    Tao       sub;
    PetscBool mprgp;
    PetscCall(TaoSMALXEGetSubsolver(d->tao, &sub));
    PetscCall(PetscObjectTypeCompare((PetscObject)sub, TAOMPRGP, &mprgp));
    (mprgp ? st.products_qpp : st.products_qpq) = total.nested_hessian_mults;
  }
  PetscCall(TaoSMALXEGetFeasibility(d->tao, &st.feasibility));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A sentence for how the augmented Lagrangian loop ended. */
static PetscErrorCode DescribeReason(ContactProblem cp, TaoConvergedReason reason, PetscInt its)
{
  ContactProblemData *d = cp->data;
  PetscBool           stagnated, stalled;
  PetscInt            limited;
  const char         *prefix; /* the options the sentences name are the user's, with the problem's prefix */

  PetscFunctionBegin;
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)cp, &prefix));
  if (!prefix) prefix = "";
  PetscCall(TaoSMALXEGetStagnated(d->tao, &stagnated));
  PetscCall(TaoSMALXEGetStalled(d->tao, &stalled));
  PetscCall(TaoSMALXEGetInnerLimited(d->tao, &limited));
  d->stats.converged = reason > 0 ? PETSC_TRUE : PETSC_FALSE;
  if (reason > 0) PetscCall(PetscSNPrintf(d->stats.reason, sizeof(d->stats.reason), "converged (%s) in %" PetscInt_FMT " outer iterations", TaoConvergedReasons[reason], its));
  else if (stagnated) {
    PetscReal feas; /* from the loop itself: msa describes its stopped Tresca solve before collecting the statistics */
    PetscCall(TaoSMALXEGetFeasibility(d->tao, &feas));
    PetscCall(PetscSNPrintf(
        d->stats.reason, sizeof(d->stats.reason),
        d->has_coulomb
            ? "no equilibrium found: |G l - e| stagnates at %.3g while the multiplier grows; the loads exceed what supports and friction carry, or the Coulomb radii F l_n lock the loop (large F)"
            : "no equilibrium: the equality (rigid-body equilibrium) cannot be met with admissible contact forces (|G l - e| stagnates at %.3g); the loads exceed what supports and friction can carry",
        (double)feas));
  } else if (stalled) {
    PetscReal gp, feas;
    PetscCall(TaoGetSolutionStatus(d->tao, NULL, NULL, &gp, &feas, NULL, NULL));
    /* the cause the loop's structure points to: merged's Gauss-Seidel sweep, whose blocks the penalty
       couples (the METIS bricks stalled so at rho = ||PFP||, at any F), or radii that lock the loop */
    char cause[160] = "";
    if (d->rtol < 1e-12) /* the relative residuals stop falling near the rounding of F's products, whatever the law */
      PetscCall(PetscSNPrintf(cause, sizeof(cause), ": the relative tolerance %g is below what rounding lets the residuals reach", (double)d->rtol));
    else if (d->has_coulomb && d->algorithm == CONTACT_COULOMB_MERGED)
      PetscCall(PetscSNPrintf(cause, sizeof(cause), ": merged's Gauss-Seidel sweep too slow (try -%scontact_coulomb_algorithm monolithic) or radii F l_n locking the loop (large F)", prefix));
    else if (d->has_coulomb) PetscCall(PetscSNPrintf(cause, sizeof(cause), ": the radii F l_n can lock the loop (large F); try a smaller F or msa"));
    PetscCall(PetscSNPrintf(d->stats.reason, sizeof(d->stats.reason), "stalled: %" PetscInt_FMT " outer iterations, the last ones without progress (|gP| %.3g, |G l - e| %.3g)%s", its, (double)gp,
                            (double)feas, cause));
  } else if (limited >= 0) {
    /* the inner solver that ran into its limit, by the option that names it (merged: block 0 the normal and
       gluing multipliers, block 1 the tangential pairs; otherwise one inner solver) */
    Tao       sub;
    PetscInt  maxit;
    char      inner[64];
    PetscBool blocks = (PetscBool)(d->pipeline == CONTACT_PIPELINE_COULOMB && d->algorithm == CONTACT_COULOMB_MERGED);
    if (blocks) PetscCall(TaoSMALXEGetBlockSubsolver(d->tao, limited, &sub));
    else PetscCall(TaoSMALXEGetSubsolver(d->tao, &sub));
    PetscCall(TaoGetMaximumIterations(sub, &maxit));
    if (blocks) PetscCall(PetscSNPrintf(inner, sizeof(inner), "block%" PetscInt_FMT "_tao", limited));
    else PetscCall(PetscSNPrintf(inner, sizeof(inner), "subsolver_tao"));
    PetscCall(PetscSNPrintf(d->stats.reason, sizeof(d->stats.reason),
                            "not converged: %" PetscInt_FMT " outer iterations, the inner solves at their limit of %" PetscInt_FMT
                            " steps in the last ones without 1%% progress (raise -%scontact_tao_smalxe_%s_max_it; -%scontact_tao_smalxe_inner_limit_its 0 goes on)",
                            its, maxit, prefix, inner, prefix));
  } else if (reason == TAO_DIVERGED_MAXITS) {
    PetscReal gp, feas, tol_g, tol_e, factor;
    PetscInt  fired, slow_its;
    PetscCall(TaoGetSolutionStatus(d->tao, NULL, NULL, &gp, &feas, NULL, NULL));
    PetscCall(TaoSMALXEGetOuterTolerances(d->tao, &tol_g, &tol_e));
    PetscCall(TaoSMALXEGetSlowLoop_Private(d->tao, &fired, &slow_its, &factor));
    /* a long loop (the scenes that converge take a few dozen outer iterations at most; as long as smalxe's slow-loop rule
       waits, -tao_smalxe_slow_its) that ends with |G l - e| the further from its tolerance: the multiplier of the
       equality converges slowly, which a larger penalty speeds up (docs/contact.md, "Nearly open zones": without the
       rule a bar of 48 one-cell cubes whose tip touches needs more than 1000 outer iterations, 161 at rho 10 from the
       start). A short limit set by the user says nothing about the rate */
    if (its >= (slow_its > 0 ? slow_its : 100) && tol_e > 0 && tol_g > 0 && feas > tol_e && feas / tol_e >= gp / tol_g) {
      char rule[96] = "";
      if (fired) PetscCall(PetscSNPrintf(rule, sizeof(rule), " (rho already times %g after %" PetscInt_FMT ")", (double)factor, fired));
      PetscCall(PetscSNPrintf(d->stats.reason, sizeof(d->stats.reason),
                              "not converged: %" PetscInt_FMT " outer iterations, |G l - e| still %.3g times its tolerance (|gP| %.3g): the equality's multiplier converges slowly, as "
                              "where a zone nearly stays open%s%s; try -%scontact_tao_smalxe_rho 10 or more, or raise -%scontact_tao_max_it",
                              its, (double)(feas / tol_e), (double)(gp / tol_g), d->has_coulomb ? " or Coulomb radii lock the loop (large F)" : "", rule, prefix, prefix));
    } else PetscCall(PetscSNPrintf(d->stats.reason, sizeof(d->stats.reason), "not converged: %" PetscInt_FMT " outer iterations (raise -%scontact_tao_max_it)", its, prefix));
  } else if (reason == TAO_DIVERGED_NAN)
    PetscCall(PetscSNPrintf(
        d->stats.reason, sizeof(d->stats.reason),
        "not converged: a quantity of the solve is not a finite number (DIVERGED_NAN) after %" PetscInt_FMT " outer iterations: an overflow from loads or gaps near the largest real?", its));
  else PetscCall(PetscSNPrintf(d->stats.reason, sizeof(d->stats.reason), "not converged: %s", TaoConvergedReasons[reason]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The solver's own test passed: converged only if the KKT residual, computed from scratch, is within the acceptance.
   worst: the larger of its two residuals (0 when it was not computed), which sets how much tighter a next solve aims.
   A tighter solve that stopped before its own test (tighter: its iteration limit, a stall below what it can reach)
   is judged by the KKT residual too, as a ContactModel judges such a solve by the mechanics: *stopped_ok says it
   passed (the first solve passed the solver's test at the user's tolerance; this one aimed lower) */
static PetscErrorCode CheckKKT(ContactProblem cp, Vec lambda, PetscReal acceptance, PetscBool tighter, PetscReal *worst, PetscBool *stopped_ok)
{
  ContactProblemData *d = cp->data;
  PetscReal           natural, equality;
  char                why[256];

  PetscFunctionBegin;
  *worst              = 0;
  *stopped_ok         = PETSC_FALSE;
  d->stats.acceptance = acceptance;
  if (!d->stats.converged) {
    PetscCall(PetscStrncpy(d->stats.failed_check, "solver", sizeof(d->stats.failed_check)));
    if (!tighter || !d->kkt_check) PetscFunctionReturn(PETSC_SUCCESS); /* (a residual that is not a number fails the test below) */
    PetscCall(ContactProblemComputeKKTResidual(cp, lambda, &natural, &equality));
    d->stats.products_other += 2;
    PetscCall(PetscInfo(cp, "a tighter solve stopped before its own test; KKT residual from scratch: natural %g, equality %g (acceptance %g)\n", (double)natural, (double)equality,
                        (double)d->stats.acceptance));
    if (natural <= d->stats.acceptance && equality <= d->stats.acceptance) {
      d->stats.converged = PETSC_TRUE;
      *stopped_ok        = PETSC_TRUE;
      PetscCall(PetscStrncpy(d->stats.failed_check, "", sizeof(d->stats.failed_check)));
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (!d->kkt_check) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(ContactProblemComputeKKTResidual(cp, lambda, &natural, &equality));
  d->stats.products_other += 2;
  *worst = PetscMax(natural, equality);
  PetscCall(PetscInfo(cp, "KKT residual from scratch: natural %g, equality %g (acceptance %g)\n", (double)natural, (double)equality, (double)d->stats.acceptance));
  if (natural <= d->stats.acceptance && equality <= d->stats.acceptance) PetscFunctionReturn(PETSC_SUCCESS);
  d->stats.converged = PETSC_FALSE;
  PetscCall(PetscStrncpy(d->stats.failed_check, natural > equality ? "dual_kkt" : "dual_equality", sizeof(d->stats.failed_check)));
  PetscCall(PetscSNPrintf(why, sizeof(why), "the solver's test passed (%s), but recomputed from the multipliers the %s residual is %.1e, above the acceptance %.1e", d->stats.reason,
                          natural > equality ? "KKT (natural)" : "equality", (double)PetscMax(natural, equality), (double)d->stats.acceptance));
  PetscCall(PetscStrncpy(d->stats.reason, why, sizeof(d->stats.reason)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A solve that did not converge: an F that is not symmetric or a Q that is not an orthogonal projector makes the
   inner Hessian PFP + rho Q non-symmetric, and the loop then stagnates or stalls with a reason that blames the loads
   or the friction. Test them with products (those of F counted in products_other; only here, after a failure, as the
   counts of successful solves are documented) and put the culprit first in the reason. */
static PetscErrorCode DiagnoseFailure(ContactProblem cp)
{
  ContactProblemData *d        = cp->data;
  char                why[256] = "", reason[sizeof(d->stats.reason)];

  PetscFunctionBegin;
  /* only the solver's own failure: a failed KKT check after the solver's test passed is not theirs */
  if (d->stats.converged || std::strcmp(d->stats.failed_check, "solver")) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(MatDiagnoseOperators_Private(d->F, 0, "F (ContactProblemSetOperator())", 'F', d->Q, "Q (ContactProblemSetProjector())", why, sizeof(why)));
  d->stats.products_other += 2;
  if (!why[0]) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscSNPrintf(reason, sizeof(reason), "not converged: %s; the solve ended: %s", why, d->stats.reason));
  PetscCall(PetscStrncpy(d->stats.reason, reason, sizeof(d->stats.reason)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the progress hook's view of an outer iteration: the larger of |gP| and |G l - e| against their tolerances,
   on the scale of the relative tolerance the solve runs at */
static PetscErrorCode ProgressMonitor(Tao tao, void *ctx)
{
  ContactProblemData &d = *static_cast<ContactProblem>(ctx)->data;
  PetscInt            its;
  PetscReal           gp, e, tol_g, tol_e, gttol;

  PetscFunctionBegin;
  if (!d.progress.fn) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(TaoGetSolutionStatus(tao, &its, NULL, &gp, &e, NULL, NULL));
  PetscCall(TaoSMALXEGetOuterTolerances(tao, &tol_g, &tol_e));
  PetscCall(TaoGetTolerances(tao, NULL, NULL, &gttol));
  const PetscReal ratio = PetscMax(tol_g > 0 ? gp / tol_g : 0, tol_e > 0 ? e / tol_e : 0);
  PetscCall(ConeFETIProgressIterate_Private(d.progress, d.progressstep, its + 1, ratio * gttol, gttol));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One run of the pipeline from lambda at the tolerances set: d->stats holds its counts and how it ended */
static PetscErrorCode SolveOnce(ContactProblem cp, Vec lambda)
{
  ContactProblemData *d = cp->data;
  TaoConvergedReason  reason;
  PetscInt            its = 0, outer = 0, al = 0;

  PetscFunctionBegin;
  PetscCall(TaoSetSolution(d->tao, lambda));
  PetscCall(TaoQPResetCounters(d->tao));
  d->stats             = ContactStatistics{};
  d->stats.fixed_point = 0;
  d->progressstep      = 0;

  if (d->pipeline == CONTACT_PIPELINE_COULOMB && d->algorithm == CONTACT_COULOMB_MSA) {
    PetscReal       change = 1, largest = 1;
    const PetscReal msa_rtol = d->msa_rtol > 0 ? d->msa_rtol : d->rtol;
    /* successive approximations: g from the current multipliers, a full Tresca solve, repeat */
    PetscCall(ContactProblemUpdateRadii_Private(cp, lambda, NULL));
    /* each Tresca solve a decade tighter than the test on the slip bounds, so the change is not noise */
    const PetscReal tresca_rtol = 0.1 * PetscMin(msa_rtol, d->rtol);
    /* The first Tresca solve has the bounds of the initial multipliers, a guess (0, or the particular
       solution of G l = e); it only supplies the first bounds F l_n of a solution, and the next solve
       starts from its l (and multiplier) and is done to full tolerance. So it is done to
       -contact_msa_start_rtol only, and the loop never stops after it. */
    PetscBool recycle;
    PetscCall(TaoGetRecycleHistory(d->tao, &recycle));
    for (outer = 0; outer < d->msa_max_it; outer++) {
      /* a Tresca solve after the first starts from the previous one's multiplier of G l = e, not only from its l */
      if (outer == 1 && d->msa_recycle) PetscCall(TaoSetRecycleHistory(d->tao, PETSC_TRUE));
      const bool loose = outer == 0 && d->msa_start_rtol > tresca_rtol;
      d->progressstep  = outer + 1;
      PetscCall(TaoSetTolerances(d->tao, 0.0, 0.0, loose ? d->msa_start_rtol : tresca_rtol));
      PetscCall(TaoSolve(d->tao));
      PetscCall(TaoGetConvergedReason(d->tao, &reason));
      PetscCall(TaoGetIterationNumber(d->tao, &its));
      al += its + 1;
      if (reason <= 0) break;
      const std::vector<PetscReal> old = d->radius;
      PetscCall(ContactProblemUpdateRadii_Private(cp, lambda, &change));
      /* the result is off the Coulomb law by the change of the bounds it was computed with: stop when that
         is small in the measure of the mechanical residuals too (largest change over the largest force) */
      PetscCall(LargestChange(cp, lambda, d->radius, old, &largest));
      PetscCall(PetscInfo(cp, "MSA step %" PetscInt_FMT ": %" PetscInt_FMT " outer iterations, relative change of the slip bounds %g, largest change over the largest contact force %g\n", outer + 1,
                          its + 1, (double)change, (double)largest));
      if (change <= msa_rtol && largest <= msa_rtol && !loose) {
        outer++;
        break;
      }
      if (d->follow_radii) PetscCall(FollowGrownRadii(cp, old, lambda));
    }
    d->stats.fixed_point = change;
    PetscCall(TaoSetRecycleHistory(d->tao, recycle));
    /* a Tresca solve that stopped is described at the tolerance it ran with (its residuals' ratios to it) */
    if (reason <= 0) PetscCall(DescribeReason(cp, reason, its + 1));
    PetscCall(TaoSetTolerances(d->tao, 0.0, 0.0, d->rtol));
    PetscCall(CollectStatistics(cp, outer, al));
    if (reason > 0 && change <= msa_rtol && largest <= msa_rtol) {
      d->stats.converged = PETSC_TRUE;
      PetscCall(PetscSNPrintf(d->stats.reason, sizeof(d->stats.reason), "converged: %" PetscInt_FMT " successive approximations, slip bounds change %.2e (largest %.2e of the largest force) <= %.2e",
                              outer, (double)change, (double)largest, (double)msa_rtol));
    } else if (reason > 0)
      PetscCall(PetscSNPrintf(d->stats.reason, sizeof(d->stats.reason),
                              "not converged: the successive approximations did not settle in %" PetscInt_FMT
                              " steps (slip bounds still change by %.2e, largest %.2e of the largest force; friction coefficient too large for a contractive fixed point?)",
                              d->msa_max_it, (double)change, (double)largest));
  } else {
    PetscCall(TaoSolve(d->tao));
    PetscCall(TaoGetConvergedReason(d->tao, &reason));
    PetscCall(TaoGetIterationNumber(d->tao, &its));
    PetscCall(CollectStatistics(cp, its + 1, its + 1));
    if (d->pipeline == CONTACT_PIPELINE_COULOMB) {
      std::vector<PetscReal> target;
      PetscCall(TargetRadii(cp, lambda, target));
      PetscCall(RelativeChange(PetscObjectComm((PetscObject)cp), target, d->radius, &d->stats.fixed_point));
    }
    PetscCall(DescribeReason(cp, reason, its + 1));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The tolerances the user gave: the tighter solves scale them, and the solve ends with them exactly */
struct UserTolerances {
  PetscReal rtol = 0, msa_rtol = 0, fixed_point_rtol = 0, gatol = 0, grtol = 0, gttol = 0;
};

/* A tighter solve's tolerances, as a ContactModel sets them (ContactModelSolve()): the solver's test at rtol, and the
   fixed-point tolerances the user gave scaled with it (those not given follow rtol). The acceptance is not scaled: it
   stays the user's, -contact_acceptance_factor times the first -contact_rtol (a tighter solve aims lower, it does not
   lower what is accepted) */
static PetscErrorCode SetTighterTolerances(ContactProblem cp, PetscReal rtol, const UserTolerances &t)
{
  ContactProblemData *d = cp->data;

  PetscFunctionBegin;
  d->rtol             = rtol;
  d->msa_rtol         = ContactScaledTolerance_Private(t.msa_rtol, rtol, t.rtol);
  d->fixed_point_rtol = ContactScaledTolerance_Private(t.fixed_point_rtol, rtol, t.rtol);
  PetscCall(TaoSetTolerances(d->tao, 0.0, 0.0, rtol));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RestoreTolerances(ContactProblem cp, const UserTolerances &t)
{
  ContactProblemData *d = cp->data;

  PetscFunctionBegin;
  d->rtol             = t.rtol;
  d->msa_rtol         = t.msa_rtol;
  d->fixed_point_rtol = t.fixed_point_rtol;
  PetscCall(TaoSetTolerances(d->tao, t.gatol, t.grtol, t.gttol));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The solver's state as the user left it (the tolerances, and whether a solve recycles the previous one's multiplier),
   put back when ContactProblemSolve() ends in an error: its tighter solves and the MSA loop change both while they
   run and restore them on their way out, which an error skips. A user who catches the error (PetscPushErrorHandler())
   and solves again would otherwise solve at a tighter tolerance than the one set, warm where a cold solve was asked.
   Restoring cannot report an error of its own from a destructor: it is tried, and the first error stands */
namespace {
class ProblemStateOnError {
public:
  explicit ProblemStateOnError(ContactProblem cp) : cp_(cp) {}
  PetscErrorCode Save()
  {
    ContactProblemData *d = cp_->data;

    PetscFunctionBegin;
    t_.rtol             = d->rtol;
    t_.msa_rtol         = d->msa_rtol;
    t_.fixed_point_rtol = d->fixed_point_rtol;
    PetscCall(TaoGetTolerances(d->tao, &t_.gatol, &t_.grtol, &t_.gttol));
    PetscCall(TaoGetRecycleHistory(d->tao, &recycle_));
    armed_ = true;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  void                  Disarm() { armed_ = false; }
  const UserTolerances &Tolerances() const { return t_; }
  ~ProblemStateOnError()
  {
    if (!armed_) return;
    (void)RestoreTolerances(cp_, t_);
    (void)TaoSetRecycleHistory(cp_->data->tao, recycle_);
  }

private:
  ContactProblem cp_;
  UserTolerances t_;
  PetscBool      recycle_ = PETSC_FALSE;
  bool           armed_   = false;
};
} // namespace

/* st.reason = head + st.reason + tail, the middle shortened so that neither end is cut */
static PetscErrorCode WrapReason(ContactStatistics &st, const char *head, const char *tail)
{
  std::string why;

  PetscFunctionBegin;
  PetscCallCXX(why = head + std::string(st.reason).substr(0, sizeof(st.reason) - 1 - std::min(sizeof(st.reason) - 1, std::strlen(head) + std::strlen(tail))) + tail);
  PetscCall(PetscStrncpy(st.reason, why.c_str(), sizeof(st.reason)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemSolve - Solve the contact problem: the pipeline its content calls for.

  Collective

  Input Parameters:
+ cp     - the problem
- lambda - initial guess on input (projected onto the set), the multipliers on output

  Options Database Keys:
+ -contact_kkt_check <true>       - recompute the KKT residual from the multipliers before saying converged (off in a `ContactModel`)
. -contact_acceptance_factor <10> - the KKT residual must be at most this times -contact_rtol (without the option also at most 0.1, or -contact_rtol)
- -contact_refine_max <3>         - when the solver's own test passes but the KKT residual does not, solve again warm at a tighter
                                    tolerance, at most this many times (0: the first verdict stands)

  Notes:
  The solve never ends with NaN: it stops with a stated reason (see `ContactProblemGetStatistics()`):
  converged; not converged after the iteration limit; or no equilibrium, when the equality cannot be
  met with admissible contact forces (e.g. a free body under a shear beyond the friction bound).
  Counters: Iter (outer iterations), n_A^QPP (mprgp products), n_A^QPQ (mpgp products), and products
  outside the inner solvers, each separately.

  A cold solve (one that does not recycle the previous solve's multiplier, `TaoSetRecycleHistory()`) with
  -contact_start_rtol r > 0 (default 0.1) first runs projected CG on the problem without the contact inequalities (every
  contact node bonded, projector form only) to the relative residual r, at most -contact_start_max_it steps,
  and starts from its multipliers: a contact pressure where the bodies press (docs/scale.md, "Lever: a bonded
  start"). When less than -contact_start_compressive of its sum |l_n| is compressive (checked from its second
  step on: curved bodies, whose bonded zone reaches far beyond the contact, are mostly in tension), the start is
  abandoned and the given multipliers kept. Its products with F are counted in products_other.
  When less than -contact_start_separated (0.6: whenever the start is abandoned) of it presses, the solve also tries the solution with every contact
  row left out (projected CG on the gluing rows, with their own coarse problem G D G'; FETI operators, no Tresca
  zone): when that touches nothing it is the solution, and the solve starts from it and from its equality's
  multiplier (one outer iteration confirms it, where the augmented Lagrangian alone needed tens to thousands: docs/contact.md,
  "Zones that stay open"); otherwise it is dropped. Its products are counted in products_other too.

  Before it says converged, the solve recomputes the KKT residual from the multipliers
  (`ContactProblemComputeKKTResidual()`, two products with F, counted in products_other): above
  -contact_acceptance_factor times -contact_rtol (without the option: at most 0.1, or -contact_rtol if larger) the solve has not converged (failed_check "dual_kkt" or
  "dual_equality"), whatever the solver's own test said. That test is relative to |P(h - F l~)|, which holds
  every gap: a gap far larger than the forces need (a separated node 1e9 from contact) leaves it passed by
  multipliers far from the solution. So when the solver's test passes and the KKT check does not, the solve
  continues warm (from lambda and from the equality's multiplier, `TaoSetRecycleHistory()`) at a tighter relative
  tolerance, as `ContactModelSolve()` does: the last one times 0.3 acceptance / residual, by a factor between 10 and
  10^4, not below 1e-13 (after a solve at 1e-13 missed, one last solve goes below it, at most to 1e-15), at most
  -contact_refine_max times. The statistics add up the solves (iterations, products) and `ContactStatistics`
  refinements says how many tighter solves ran; the reason says down to which tolerance. The acceptance stays
  the one of the first tolerances, and the tolerances (-contact_rtol, the solver's, and -contact_msa_rtol and
  -contact_fixed_point_rtol, which a tighter solve scales when they are given) are the user's again at the end,
  and so is the recycling of the multiplier, also when the solve ends in an error.
  If the KKT residual is still above the acceptance after them, the solve has not converged (failed_check
  "dual_kkt" or "dual_equality"). A tighter solve whose own test fails (its iteration limit, a stall below what it
  can reach) is judged by the KKT residual like the others: within the acceptance it has converged (the reason says
  the last solve stopped before its own test), else the solver's reason is the verdict.

  A `ContactModel` judges its solutions by the mechanical residuals of u and lambda instead, and runs the
  tighter solves itself (`ContactModelSolve()`): inside a model this solve is one solve.

  A solve whose solver did not converge tests whether F is symmetric and Q an orthogonal projector (two products with F,
  counted in products_other, and up to four with Q; never after a converged solve) and, when one is not, its
  reason says so first. An inner solve that fails on them ends in an error of smalxe that names F or Q.

  Level: beginner

.seealso: `ContactProblemGetStatistics()`, `ContactProblemSetFromOptions()`, `ContactProblemComputeKKTResidual()`
@*/
PetscErrorCode ContactProblemSolve(ContactProblem cp, Vec lambda)
{
  ContactProblemData *d;
  PetscInt            start_products = 0, round, refine_max;
  PetscBool           warm;
  PetscReal           acceptance, worst = 0, tol;
  PetscBool           stopped_ok = PETSC_FALSE;
  ContactStatistics   total      = {};
  ProblemStateOnError user(cp);

  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  PetscCheck(lambda, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_NULL, "ContactProblemSolve: lambda is NULL (give the initial multipliers, e.g. a zero vector from MatCreateVecs(F))");
  PetscValidHeaderSpecific(lambda, VEC_CLASSID, 2);
  {
    /* a NaN start came back as 4.5e307 or NaN with a reason that blamed the data near the largest real */
    PetscReal lmax;
    PetscCall(VecNorm(lambda, NORM_INFINITY, &lmax));
    PetscCheck(!PetscIsInfOrNanReal(lmax), PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_OUTOFRANGE, "ContactProblemSolve: the initial multipliers lambda have an entry that is not a finite number");
  }
  PetscCall(ContactProblemSetUp(cp));
  d = cp->data;
  PetscCall(user.Save());
  const UserTolerances &first = user.Tolerances();
  PetscCall(PetscLogEventBegin(CONTACT_Solve, cp, 0, 0, 0));
  /* a warm solve (the previous solve's multiplier recycled) starts where it is; a cold one may first solve the
     bonded problem loosely (-contact_start_rtol, contactstart.cxx) */
  PetscCall(TaoGetRecycleHistory(d->tao, &warm));
  if (!warm) PetscCall(ContactProblemStart_Private(cp, lambda, &start_products));
  if (d->progress.fn && !d->progressmonitor) {
    PetscCall(TaoMonitorSet(d->tao, ProgressMonitor, cp, NULL));
    d->progressmonitor = PETSC_TRUE;
  }
  PetscCall(ConeFETIProgressEnter_Private(d->progress, CONEFETI_PHASE_SOLVE));

  /* every solve is judged against the first tolerances' acceptance (inside a model: the model's, whose factor it
     scales as it tightens -contact_rtol) */
  acceptance = d->acceptance_outside > 0 ? d->acceptance_outside : ContactAcceptance_Private(d->acceptance_factor, d->acceptance_given, d->rtol);
  tol        = first.rtol;
  /* only a failed KKT check gets tighter solves here: without the check nothing judges the answer but the solver's
     test, and a ContactModel runs them itself (refine_outside) */
  refine_max = d->kkt_check && !d->refine_outside ? d->refine_max : 0;
  for (round = 0;; round++) {
    PetscCall(SolveOnce(cp, lambda));
    if (round == 0) d->stats.products_other += start_products;
    PetscCall(CheckKKT(cp, lambda, acceptance, (PetscBool)(round > 0), &worst, &stopped_ok));
    ContactStatisticsAccumulate_Private(total, d->stats);
    /* converged; or the solver's own test failed, which is the verdict (a tighter one's that also fails the KKT
       check too: it did not reach the tolerance asked, and its answer is the solver's last iterate) */
    if (d->stats.converged || !std::strcmp(d->stats.failed_check, "solver")) break;
    if (round >= refine_max || tol < CONTACT_REFINE_TIGHTEST) break;
    /* warm: from lambda and, for the equality, from the multiplier the solve ended with */
    if (round == 0) PetscCall(TaoSetRecycleHistory(d->tao, PETSC_TRUE));
    const PetscReal next = ContactTighterTolerance_Private(tol, acceptance, worst);
    PetscCall(PetscInfo(cp, "solve %" PetscInt_FMT " at relative tolerance %g: the KKT residual %g is above the acceptance %g; solving again warm at %g\n", round, (double)tol, (double)worst,
                        (double)acceptance, (double)next));
    tol = next;
    PetscCall(SetTighterTolerances(cp, tol, first));
  }
  if (round > 0) {
    char head[160] = "", tail[160] = "";
    PetscCall(TaoSetRecycleHistory(d->tao, warm));
    PetscCall(RestoreTolerances(cp, first));
    d->stats.outer_iterations  = total.outer_iterations;
    d->stats.al_iterations     = total.al_iterations;
    d->stats.products_qpp      = total.products_qpp;
    d->stats.products_qpq      = total.products_qpq;
    d->stats.products_other    = total.products_other;
    d->stats.products_estimate = total.products_estimate;
    d->stats.refinements       = round;
    if (stopped_ok) {
      PetscCall(PetscSNPrintf(head, sizeof(head),
                              "the KKT residual within the acceptance after %" PetscInt_FMT " tighter solve%s down to relative tolerance %.0e (the last stopped before its own test: ", round,
                              round > 1 ? "s" : "", (double)tol));
      PetscCall(PetscStrncpy(tail, ")", sizeof(tail)));
    } else if (d->stats.converged)
      PetscCall(PetscSNPrintf(tail, sizeof(tail), ", after %" PetscInt_FMT " tighter solve%s (down to relative tolerance %.0e) that brought the KKT residual within the acceptance", round,
                              round > 1 ? "s" : "", (double)tol));
    else if (!std::strcmp(d->stats.failed_check, "solver")) {
      PetscCall(PetscSNPrintf(head, sizeof(head), "tighter solve %" PetscInt_FMT " (relative tolerance %.0e, the KKT residual above the acceptance before it): ", round, (double)tol));
    } else PetscCall(PetscSNPrintf(tail, sizeof(tail), ", after %" PetscInt_FMT " solves down to relative tolerance %.0e", round + 1, (double)tol));
    PetscCall(WrapReason(d->stats, head, tail));
  }
  user.Disarm(); /* the user's state is back */
  PetscCall(DiagnoseFailure(cp));
  PetscCall(PetscLogEventEnd(CONTACT_Solve, cp, 0, 0, 0));
  PetscCall(PetscObjectViewFromOptions((PetscObject)cp, NULL, "-contact_view"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactProblemGetEqualityMultiplier - w = G'mu for the multiplier mu of the equality at the
  solution (A l - h + w in -N(l)); FETI's rigid-body amplitudes are alpha = -(GG')^{-1} G w.

  Collective

  Input Parameter:
. cp - the problem (after a solve)

  Output Parameter:
. w - the vector G'mu

  Level: intermediate

.seealso: `TaoSMALXEGetEqualityMultiplier()`
@*/
PetscErrorCode ContactProblemGetEqualityMultiplier(ContactProblem cp, Vec w)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(cp, CONTACTPROBLEM_CLASSID, 1);
  PetscCheck(cp->data->tao, PetscObjectComm((PetscObject)cp), PETSC_ERR_ARG_WRONGSTATE, "ContactProblem: solve first");
  PetscCall(TaoSMALXEGetEqualityMultiplier(cp->data->tao, w));
  PetscFunctionReturn(PETSC_SUCCESS);
}
