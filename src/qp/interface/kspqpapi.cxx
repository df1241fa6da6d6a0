/* Public setters/getters of the KSP QP types (mprgp, mpgp), dispatched to the type. */
#include <conefeti/qp.h>
#include <conefeti/compat.h>
#include <conefeti/private/qpadopt.h>
#include <petsc/private/kspimpl.h>

/*@C
  KSPQPSetConstraints - Give a KSP QP solver (`KSPMPGP`, `KSPMPRGP`) its feasible set.

  Logically Collective

  Input Parameters:
+ ksp - the solver
- set - the separable set (referenced)

  Level: beginner

  Notes:
  Ignored by other KSP types, but kept on the KSP: a QP type set later (e.g. `-ksp_type mpgp` read by
  `KSPSetFromOptions()`) uses it; so do `KSPMPRGPSetBounds()`'s bounds.

.seealso: `SeparableSet`, `KSPMPRGPSetBounds()`, `TaoQPSetConstraints()`
@*/
PetscErrorCode KSPQPSetConstraints(KSP ksp, SeparableSet set)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(ksp, KSP_CLASSID, 1);
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 2);
  PetscCall(PetscObjectCompose((PetscObject)ksp, "KSPQPConstraints", (PetscObject)set));
  PetscTryMethod(ksp, "KSPQPSetConstraints_C", (KSP, SeparableSet), (ksp, set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  KSPQPGetConstraints - The feasible set a KSP QP solver uses (NULL before the first solve if none was given).

  Not Collective

  Input Parameter:
. ksp - the solver

  Output Parameter:
. set - the set (not a new reference)

  Level: intermediate

.seealso: `KSPQPSetConstraints()`
@*/
PetscErrorCode KSPQPGetConstraints(KSP ksp, SeparableSet *set)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(ksp, KSP_CLASSID, 1);
  *set = NULL;
  PetscTryMethod(ksp, "KSPQPGetConstraints_C", (KSP, SeparableSet *), (ksp, set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  KSPMPRGPSetBounds - Bounds l <= x <= u for `KSPMPRGP` (and `KSPMPGP`).

  Logically Collective

  Input Parameters:
+ ksp - the solver
. lb  - lower bounds (entries may be `PETSC_NINFINITY`), or NULL
- ub  - upper bounds (entries may be `PETSC_INFINITY`), or NULL

  Notes:
  The vectors are referenced and read at each solve. Ignored when a set was given by
  `KSPQPSetConstraints()`.

  Level: beginner

.seealso: `KSPMPRGP`, `KSPQPSetConstraints()`
@*/
PetscErrorCode KSPMPRGPSetBounds(KSP ksp, Vec lb, Vec ub)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(ksp, KSP_CLASSID, 1);
  if (lb) PetscValidHeaderSpecific(lb, VEC_CLASSID, 2);
  if (ub) PetscValidHeaderSpecific(ub, VEC_CLASSID, 3);
  PetscCall(PetscObjectCompose((PetscObject)ksp, "KSPMPRGPLowerBounds", (PetscObject)lb));
  PetscCall(PetscObjectCompose((PetscObject)ksp, "KSPMPRGPUpperBounds", (PetscObject)ub));
  PetscTryMethod(ksp, "KSPMPRGPSetBounds_C", (KSP, Vec, Vec), (ksp, lb, ub));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  KSPQPSetNormEstimate - Give ||A|| instead of letting the KSP QP solver estimate it.

  Logically Collective

  Input Parameters:
+ ksp  - the solver
- norm - an upper bound of the largest eigenvalue of A (0 to estimate)

  Level: intermediate

.seealso: `MatQPEstimateNorm()`
@*/
PetscErrorCode KSPQPSetNormEstimate(KSP ksp, PetscReal norm)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(ksp, KSP_CLASSID, 1);
  PetscCall(QPComposeReal_Private((PetscObject)ksp, "KSPQPNormEstimate", norm)); /* for a QP type chosen later */
  PetscTryMethod(ksp, "KSPQPSetNormEstimate_C", (KSP, PetscReal), (ksp, norm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  KSPQPGetCounters - Work a KSP QP solver did since creation or the last reset.

  Not Collective

  Input Parameter:
. ksp - the solver

  Output Parameter:
. counters - the counters (all zero for other KSP types)

  Level: beginner

.seealso: `QPCounters`, `TaoQPGetCounters()`
@*/
PetscErrorCode KSPQPGetCounters(KSP ksp, QPCounters *counters)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(ksp, KSP_CLASSID, 1);
  PetscAssertPointer(counters, 2);
  *counters = QPCounters{};
  PetscTryMethod(ksp, "KSPQPGetCounters_C", (KSP, QPCounters *), (ksp, counters));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  KSPQPResetCounters - Zero the counters of a KSP QP solver.

  Logically Collective

  Input Parameter:
. ksp - the solver

  Level: intermediate

.seealso: `KSPQPGetCounters()`
@*/
PetscErrorCode KSPQPResetCounters(KSP ksp)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(ksp, KSP_CLASSID, 1);
  PetscTryMethod(ksp, "KSPQPResetCounters_C", (KSP), (ksp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Called at the end of each KSP QP type's create function: adopts the set, bounds and norm estimate given while
   the KSP had another type (the setters keep them on the KSP, see qpadopt.h). */
PetscErrorCode KSPQPAdoptComposed_Private(KSP ksp)
{
  PetscObject set, lb, ub;
  PetscReal   norm;
  PetscBool   hasnorm;

  PetscFunctionBegin;
  PetscCall(PetscObjectQuery((PetscObject)ksp, "KSPQPConstraints", &set));
  PetscCall(QPQueryReal_Private((PetscObject)ksp, "KSPQPNormEstimate", &norm, &hasnorm));
  PetscCall(PetscObjectQuery((PetscObject)ksp, "KSPMPRGPLowerBounds", &lb));
  PetscCall(PetscObjectQuery((PetscObject)ksp, "KSPMPRGPUpperBounds", &ub));
  if (set) PetscTryMethod(ksp, "KSPQPSetConstraints_C", (KSP, SeparableSet), (ksp, (SeparableSet)set));
  if (lb || ub) PetscTryMethod(ksp, "KSPMPRGPSetBounds_C", (KSP, Vec, Vec), (ksp, (Vec)lb, (Vec)ub));
  if (hasnorm) PetscTryMethod(ksp, "KSPQPSetNormEstimate_C", (KSP, PetscReal), (ksp, norm));
  PetscFunctionReturn(PETSC_SUCCESS);
}
