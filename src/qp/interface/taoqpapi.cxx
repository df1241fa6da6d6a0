/* Public setters/getters of the TAO QP types (mprgp, mpgp, smalxe), dispatched to the type. */
#include <conefeti/qp.h>
#include <conefeti/compat.h>
#include <conefeti/private/qpadopt.h>
#include <petsc/private/taoimpl.h>

/*@C
  TaoQPSetConstraints - Give a TAO QP solver (`TAOMPGP`, `TAOMPRGP`, `TAOSMALXE`) its feasible set.

  Logically Collective

  Input Parameters:
+ tao - the solver
- set - the separable set; referenced, so later in-place changes (e.g. `SeparableSetSetDiskRadii()`) are seen by the next solve

  Notes:
  Without a set the solvers use the variable bounds (`TaoSetVariableBounds()`). `TAOMPRGP` accepts
  only sets without disks and cones. Ignored by other TAO types, but kept on the Tao: a QP type set
  later (e.g. `-tao_type mpgp` read by `TaoSetFromOptions()`) uses it.

  Level: beginner

.seealso: `SeparableSet`, `TaoQPSetLinearTerm()`, `KSPQPSetConstraints()`
@*/
PetscErrorCode TaoQPSetConstraints(Tao tao, SeparableSet set)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 2);
  /* kept on the Tao too, so that a later change of type (-tao_type mpgp after TaoSetType(tao, TAOMPRGP)) keeps the set */
  PetscCall(PetscObjectCompose((PetscObject)tao, "TaoQPConstraints", (PetscObject)set));
  PetscTryMethod(tao, "TaoQPSetConstraints_C", (Tao, SeparableSet), (tao, set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoQPGetConstraints - The feasible set a TAO QP solver uses (NULL before the first solve if none was given).

  Not Collective

  Input Parameter:
. tao - the solver

  Output Parameter:
. set - the set (not a new reference)

  Level: intermediate

.seealso: `TaoQPSetConstraints()`
@*/
PetscErrorCode TaoQPGetConstraints(Tao tao, SeparableSet *set)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  *set = NULL;
  PetscTryMethod(tao, "TaoQPGetConstraints_C", (Tao, SeparableSet *), (tao, set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoQPSetLinearTerm - Give the linear term b of q(x) = 1/2 x'Ax - b'x directly.

  Logically Collective

  Input Parameters:
+ tao - the solver
- b   - the linear term (referenced; its values are read at each solve), or NULL to go back to b = -gradient(0)

  Notes:
  Without it the QP types call the gradient routine once at x = 0.

  Level: intermediate

.seealso: `TaoQPSetConstraints()`, `TaoSetHessian()`
@*/
PetscErrorCode TaoQPSetLinearTerm(Tao tao, Vec b)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  if (b) PetscValidHeaderSpecific(b, VEC_CLASSID, 2);
  PetscCall(PetscObjectCompose((PetscObject)tao, "TaoQPLinearTerm", (PetscObject)b));
  PetscTryMethod(tao, "TaoQPSetLinearTerm_C", (Tao, Vec), (tao, b));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoQPSetNormEstimate - Give ||A|| (for the fixed step length) instead of letting the solver estimate it.

  Logically Collective

  Input Parameters:
+ tao  - the solver
- norm - an upper bound of the largest eigenvalue of A (0 to estimate again)

  Options Database Key:
. -tao_mpgp_norm <value> - (or -tao_mprgp_norm, -tao_smalxe_norm)

  Level: intermediate

.seealso: `MatQPEstimateNorm()`, `TaoQPGetNormEstimate()`
@*/
PetscErrorCode TaoQPSetNormEstimate(Tao tao, PetscReal norm)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidLogicalCollectiveReal(tao, norm, 2);
  PetscCall(QPComposeReal_Private((PetscObject)tao, "TaoQPNormEstimate", norm)); /* for a QP type chosen later */
  PetscTryMethod(tao, "TaoQPSetNormEstimate_C", (Tao, PetscReal), (tao, norm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoQPGetNormEstimate - The value of ||A|| the last solve used.

  Not Collective

  Input Parameter:
. tao - the solver

  Output Parameter:
. norm - the value (0 before the first solve)

  Level: intermediate

.seealso: `TaoQPSetNormEstimate()`
@*/
PetscErrorCode TaoQPGetNormEstimate(Tao tao, PetscReal *norm)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidRealPointer(norm, 2);
  *norm = 0;
  PetscTryMethod(tao, "TaoQPGetNormEstimate_C", (Tao, PetscReal *), (tao, norm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoQPGetCounters - Work a TAO QP solver did since creation or the last reset: Hessian products
  (own, nested, norm estimate), iterations and steps by kind.

  Not Collective

  Input Parameter:
. tao - the solver

  Output Parameter:
. counters - the counters (all zero for a TAO type that is not a conefeti QP type)

  Level: beginner

.seealso: `QPCounters`, `TaoQPResetCounters()`, `QPCountersViewJSON()`
@*/
PetscErrorCode TaoQPGetCounters(Tao tao, QPCounters *counters)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscAssertPointer(counters, 2);
  *counters = QPCounters{};
  PetscTryMethod(tao, "TaoQPGetCounters_C", (Tao, QPCounters *), (tao, counters));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoQPResetCounters - Zero the counters of a TAO QP solver (and of its nested solvers).

  Logically Collective

  Input Parameter:
. tao - the solver

  Level: intermediate

.seealso: `TaoQPGetCounters()`
@*/
PetscErrorCode TaoQPResetCounters(Tao tao)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscTryMethod(tao, "TaoQPResetCounters_C", (Tao), (tao));
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {

/* the value kept on obj under name (in a container composed with it), or NULL */
template <typename T> PetscErrorCode KeptValue(PetscObject obj, const char *name, T **value)
{
  PetscObject composed;
  void       *p = NULL;

  PetscFunctionBegin;
  PetscCall(PetscObjectQuery(obj, name, &composed));
  if (composed) PetscCall(PetscContainerGetPointer((PetscContainer)composed, &p));
  *value = static_cast<T *>(p);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* keep v on obj under name: the container made on the first call is reused (smalxe gives its inner solver a norm
   estimate at every change of the penalty) */
template <typename T> PetscErrorCode ComposeValue(PetscObject obj, const char *name, T v)
{
  PetscContainer container;
  T             *value = NULL;

  PetscFunctionBegin;
  PetscCall(KeptValue(obj, name, &value));
  if (value) {
    *value = v;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscNew(&value));
  *value = v;
  PetscCall(PetscContainerCreate(PetscObjectComm(obj), &container));
  PetscCall(PetscContainerSetPointer(container, value));
  PetscCall(PetscContainerSetUserDestroy(container, PetscContainerUserDestroyDefault));
  PetscCall(PetscObjectCompose(obj, name, (PetscObject)container));
  PetscCall(PetscContainerDestroy(&container));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the value kept on obj under name, if any */
template <typename T> PetscErrorCode QueryValue(PetscObject obj, const char *name, T *v, PetscBool *found)
{
  T *value = NULL;

  PetscFunctionBegin;
  *found = PETSC_FALSE;
  PetscCall(KeptValue(obj, name, &value));
  if (value) {
    *found = PETSC_TRUE;
    *v     = *value;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/* Called at the end of each QP type's TaoCreate_XXX(): adopts the set, the linear term, the norm estimate and the
   expansion flags given while the Tao had another type (their setters keep them on the Tao). */
PetscErrorCode TaoQPAdoptComposed_Private(Tao tao)
{
  PetscObject set, b;
  PetscReal   norm = 0;
  PetscBool   hasnorm, projcg, hasprojcg, lagged, haslagged;

  PetscFunctionBegin;
  PetscCall(PetscObjectQuery((PetscObject)tao, "TaoQPConstraints", &set));
  PetscCall(QPQueryReal_Private((PetscObject)tao, "TaoQPNormEstimate", &norm, &hasnorm));
  PetscCall(PetscObjectQuery((PetscObject)tao, "TaoQPLinearTerm", &b));
  PetscCall(QueryValue((PetscObject)tao, "TaoQPExpansionProjCG", &projcg, &hasprojcg));
  PetscCall(QueryValue((PetscObject)tao, "TaoQPExpansionLagged", &lagged, &haslagged));
  if (set) PetscTryMethod(tao, "TaoQPSetConstraints_C", (Tao, SeparableSet), (tao, (SeparableSet)set));
  if (b) PetscTryMethod(tao, "TaoQPSetLinearTerm_C", (Tao, Vec), (tao, (Vec)b));
  if (hasprojcg) PetscTryMethod(tao, "TaoQPSetExpansionProjCG_C", (Tao, PetscBool), (tao, projcg));
  if (haslagged) PetscTryMethod(tao, "TaoQPSetExpansionLagged_C", (Tao, PetscBool), (tao, lagged));
  if (hasnorm) PetscTryMethod(tao, "TaoQPSetNormEstimate_C", (Tao, PetscReal), (tao, norm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode QPComposeReal_Private(PetscObject obj, const char name[], PetscReal v)
{
  PetscFunctionBegin;
  PetscCall(ComposeValue(obj, name, v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode QPQueryReal_Private(PetscObject obj, const char name[], PetscReal *v, PetscBool *found)
{
  PetscFunctionBegin;
  PetscCall(QueryValue(obj, name, v, found));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoQPSetExpansionProjCG - Whether the expansion steps of TAO `mprgp` / `mpgp` first try the projected
  full conjugate gradient step P(x - a_cg p).

  Logically Collective

  Input Parameters:
+ tao - the solver (of any type: a QP type chosen later adopts the setting)
- flg - `PETSC_TRUE` to try the projected CG step, `PETSC_FALSE` for Dostal's expansion only

  Options Database Key:
. -tao_mprgp_expansion_projcg <bool> - (or -tao_mpgp_expansion_projcg) overrides the setting

  Notes:
  An expansion step starts when the CG step would leave the set. Dostal's expansion goes to the
  boundary along p (the feasible half step) and then takes a projected gradient step of fixed
  length; it adds a few constraints at a time, and its R-linear rate of convergence is proven. The
  projected full CG step is kept when q there is no higher than at the feasible half step (else the
  fixed-length step follows, one Hessian product later); it adds many constraints at once. It saves
  products on discretized PDE problems (the obstacle, the journal bearing, the friction disks, the brick's
  dual contact problems) and costs more on random ill-conditioned QPs (docs/qp-benchmark.md,
  docs/brick-benchmark.md); mixed on the brick's friction problems (fewer products at
  -contact_rtol 1e-3 and 1e-4, more at the other tolerances), where it stays off. Without this call or the
  option the default follows the Hessian: on for an assembled sparse one (with ICC in face), off for a
  MATSHELL (FETI's dual operator) or a dense one.

  Level: intermediate

.seealso: `TAOMPRGP`, `TAOMPGP`, `TaoQPGetPC()`
@*/
PetscErrorCode TaoQPSetExpansionProjCG(Tao tao, PetscBool flg)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidLogicalCollectiveBool(tao, flg, 2);
  PetscCall(ComposeValue((PetscObject)tao, "TaoQPExpansionProjCG", flg)); /* for a QP type chosen later */
  PetscTryMethod(tao, "TaoQPSetExpansionProjCG_C", (Tao, PetscBool), (tao, flg));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoQPSetExpansionLagged - Whether the projected CG expansion steps of TAO `mprgp` / `mpgp` first try the
  projected step with a lagged length, without a Hessian product of their own.

  Logically Collective

  Input Parameters:
+ tao - the solver (of any type: a QP type chosen later adopts the setting)
- flg - `PETSC_TRUE` to try lagged lengths, `PETSC_FALSE` (the default) not to

  Options Database Key:
. -tao_mprgp_expansion_lagged <bool> - (or -tao_mpgp_expansion_lagged) overrides the setting

  Notes:
  Only with the projected CG expansion (`TaoQPSetExpansionProjCG()`). A projected CG expansion takes two
  products: A p for the CG length g'p/p'Ap and the gradient at the projected point. While the active set grows,
  expansions follow one another and their CG lengths vary little; a lagged expansion reuses the last length
  (scaled by the exact line minimum along the step it took, within [1/2, 2]) for P(x - a p), one product, and is
  kept when q falls, else the ordinary expansion follows. It is tried only where the step crosses the boundary
  (an expansion would follow anyway). It saves products on the dual contact problems with FETI's Dirichlet
  preconditioner in face (the contact layer turns it on there) and costs products on the obstacle and journal
  bearing QPs with ICC in face (bearing 316^2: 719 -> 923), where it stays off: docs/scale.md, "Lever: the early
  outer iterations".

  Level: intermediate

.seealso: `TAOMPRGP`, `TAOMPGP`, `TaoQPSetExpansionProjCG()`
@*/
PetscErrorCode TaoQPSetExpansionLagged(Tao tao, PetscBool flg)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidLogicalCollectiveBool(tao, flg, 2);
  PetscCall(ComposeValue((PetscObject)tao, "TaoQPExpansionLagged", flg)); /* for a QP type chosen later */
  PetscTryMethod(tao, "TaoQPSetExpansionLagged_C", (Tao, PetscBool), (tao, flg));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoQPGetPC - The preconditioner of a TAO `mprgp` or `mpgp` solver's CG steps (preconditioning in face).

  Not Collective

  Input Parameter:
. tao - the solver

  Output Parameter:
. pc - the preconditioner (NULL for a TAO type that is not mprgp or mpgp)

  Notes:
  The PC has the options prefix of the solver followed by `tao_mprgp_` or `tao_mpgp_` (so
  `-tao_mprgp_pc_type icc`) and type `PCNONE` until a solve chooses the default from the Hessian: `PCICC`
  when ICC can factor the Hessian's preconditioning matrix (an assembled sparse matrix; `PCBJACOBI` with
  `PCICC` in each rank's block on several ranks), else `PCNONE`. A type set on it (or by
  -tao_mprgp_pc_type) is kept; `PCNONE` set through this PC before the first solve cannot be told from the
  default, so give the option -tao_mprgp_pc_type none to keep an assembled Hessian unpreconditioned. At each solve it gets the Hessian and the
  Hessian's preconditioning matrix as operators. A CG step uses z = [M^-1]_FF g_F, the preconditioned
  free gradient restricted to the free entries (interior blocks): a principal submatrix of M^-1, hence
  a symmetric positive definite preconditioner of the face's Hessian A_FF. Other steps and the
  stopping test are unpreconditioned, so the result and its accuracy do not depend on M. A PC that
  needs an assembled matrix does not work with a MATSHELL Hessian.

  With a long prefix, PETSc 3.18's -help may print the PC's options with the prefix cut short (e.g.
  -contact_tao_smalxe_subsolvpc_type); the option that works is the full prefix, here
  -contact_tao_smalxe_subsolver_tao_mpgp_pc_type.

  Level: intermediate

.seealso: `TAOMPRGP`, `TAOMPGP`, `QPCounters`
@*/
PetscErrorCode TaoQPGetPC(Tao tao, PC *pc)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscAssertPointer(pc, 2);
  *pc = NULL;
  PetscTryMethod(tao, "TaoQPGetPC_C", (Tao, PC *), (tao, pc));
  PetscFunctionReturn(PETSC_SUCCESS);
}
