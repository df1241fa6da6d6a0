/* Primal recovery and the linear ("no contact") FETI solve.

   With L(u, l) = 1/2 u'K u - u'f + l'(B u - c), stationarity gives K u = f - B'l, solvable iff
   R'(f - B'l) = 0, i.e. G l = e; then u = K+(f - B'l) + R alpha. On every row where B u = c holds
   with equality, B K+ f - F l + B R alpha = c, i.e.
       G' alpha = F l - h      (G' = B R, h = B K+ f - c),
   which determines alpha by least squares over those rows. */
#include <conefeti/private/fetiimpl.h>

/*@C
  FETIComputeAlphaFromEquality - The rigid-body amplitudes alpha from the multiplier of the equality G lambda = e, as the
  augmented Lagrangian solvers carry it: alpha = -(G G')^{-1} G w.

  Collective

  Input Parameters:
+ feti - the FETI problem, set up
- w    - dual vector: G' mu, with mu the multiplier of G lambda = e (`ContactProblemGetEqualityMultiplier()` gives w)

  Output Parameter:
. alpha - coarse vector (untouched when the problem has no rigid modes)

  Notes:
  At a solution of the dual problem, F lambda - h + w lies in the normal cone of the constraints at lambda, so on the
  rows holding with equality G' alpha = F lambda - h with alpha = -(G G')^{-1} G w: the least squares of
  `FETIComputeAlpha()` without its own factorization of G_A G_A'.

  Level: intermediate

.seealso: `FETIComputeAlpha()`, `FETIRecoverPrimal()`
@*/
PetscErrorCode FETIComputeAlphaFromEquality(FETI feti, Vec w, Vec alpha)
{
  Mat      G;
  Vec      Gw;
  PetscInt ncoarse;

  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscValidHeaderSpecific(w, VEC_CLASSID, 2);
  PetscValidHeaderSpecific(alpha, VEC_CLASSID, 3);
  PetscCheck(feti->impl->setupcalled, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER, "Call FETISetUp() first");
  PetscCall(FETICheckVec_Private(feti, w, FETI_VEC_DUAL, "FETIComputeAlphaFromEquality", "w"));
  PetscCall(FETICheckVec_Private(feti, alpha, FETI_VEC_COARSE, "FETIComputeAlphaFromEquality", "alpha"));
  PetscCall(VecGetSize(alpha, &ncoarse));
  if (!ncoarse) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(FETIGetOperators(feti, NULL, &G, NULL, NULL));
  PetscCall(VecDuplicate(alpha, &Gw));
  PetscCall(MatMult(G, w, Gw));
  PetscCall(FETIApplyCoarseInverse(feti, Gw, alpha));
  PetscCall(VecScale(alpha, -1.0));
  PetscCall(VecDestroy(&Gw));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIComputeAlpha - The rigid-body amplitudes alpha of the primal solution, by least squares of G' alpha = F lambda - h over the rows where the constraint holds with equality.

  Collective

  Input Parameters:
+ feti   - the FETI problem, set up
. lambda - the multipliers
- mask   - dual vector: 1 on rows holding with equality (gluing, Dirichlet, contact in contact, stick), 0 elsewhere; NULL means all rows

  Output Parameter:
. alpha - coarse vector

  Notes:
  With all rows this uses the coarse factorization; with a mask it assembles and factors
  G_A G_A' once per call (as small as G G'). The rows in the mask must determine alpha
  (G_A of full row rank), otherwise this is an error. The augmented Lagrangian solvers carry
  alpha as (minus) the multiplier of G lambda = e, which is cheaper when available.

  Level: intermediate

.seealso: `FETIRecoverPrimal()`, `FETIGetOperators()`
@*/
PetscErrorCode FETIComputeAlpha(FETI feti, Vec lambda, Vec mask, Vec alpha)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  FETI_Impl &impl = *feti->impl;
  PetscValidHeaderSpecific(lambda, VEC_CLASSID, 2);
  PetscValidHeaderSpecific(alpha, VEC_CLASSID, 4);
  PetscCheck(impl.setupcalled, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER, "Call FETISetUp() first");
  PetscCall(FETICheckVec_Private(feti, lambda, FETI_VEC_DUAL, "FETIComputeAlpha", "lambda"));
  if (mask) PetscCall(FETICheckVec_Private(feti, mask, FETI_VEC_DUAL, "FETIComputeAlpha", "mask"));
  PetscCall(FETICheckVec_Private(feti, alpha, FETI_VEC_COARSE, "FETIComputeAlpha", "alpha"));
  if (!impl.ncoarse) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(MatMult(impl.F, lambda, impl.residual));
  PetscCall(VecAXPY(impl.residual, -1.0, impl.h));
  if (!mask) {
    PetscCall(FETIApplyG(feti, impl.residual, impl.wc1));
    PetscCall(FETIApplyCoarseInverse(feti, impl.wc1, alpha));
  } else { /* G_A = G diag(mask): (G_A G_A') alpha = G_A (mask .* residual) */
    Mat              M;
    FETICoarseSolver cs;
    PetscBool        failed;
    PetscCall(FETICreateCoarseMatrix(feti, mask, &M));
    PetscCall(VecPointwiseMult(impl.wd3, mask, impl.residual));
    PetscCall(VecPointwiseMult(impl.wd3, mask, impl.wd3));
    PetscCall(FETIApplyG(feti, impl.wd3, impl.wc1));
    PetscCall(FETICoarseSolverCreate(feti, M, cs, &failed));
    PetscCheck(!failed, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_WRONG,
               "FETIComputeAlpha(): the rows in the mask do not determine the rigid-body amplitudes (G_A G_A' is singular); include rows that fix every floating subdomain");
    PetscCall(PetscLogEventBegin(FETI_CoarseSolve, feti, 0, 0, 0));
    PetscCall(FETICoarseSolverApply(cs, impl.wc1, alpha));
    PetscCall(PetscLogEventEnd(FETI_CoarseSolve, feti, 0, 0, 0));
    PetscCall(FETICoarseSolverDestroy(cs));
    PetscCall(MatDestroy(&M));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIRecoverPrimal - The primal solution u = K+(f - B' lambda) + R alpha (and the prescribed values of `FETISetSubdomainDirichletValues()` at the Dirichlet dofs kept in the primal).

  Collective

  Input Parameters:
+ feti   - the FETI problem, set up
. lambda - the multipliers
- alpha  - the rigid-body amplitudes, or NULL to compute them by `FETIComputeAlpha()` over all rows
           (right when every constraint holds with equality, as in the linear problem)

  Output Parameter:
. u - primal vector (subdomain copies concatenated)

  Notes:
  A wrong alpha moves subdomains by rigid motions while every dual residual looks fine: check the
  primal (B u = c on equality rows, equilibrium K u = f - B' lambda with `FETIApplyK()`).

  Level: beginner

.seealso: `FETIComputeAlpha()`, `FETISolveLinear()`, `FETIApplyK()`
@*/
PetscErrorCode FETIRecoverPrimal(FETI feti, Vec lambda, Vec alpha, Vec u)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  FETI_Impl &impl = *feti->impl;
  PetscValidHeaderSpecific(lambda, VEC_CLASSID, 2);
  PetscValidHeaderSpecific(u, VEC_CLASSID, 4);
  PetscCheck(impl.setupcalled, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER, "Call FETISetUp() first");
  PetscCall(FETICheckVec_Private(feti, lambda, FETI_VEC_DUAL, "FETIRecoverPrimal", "lambda"));
  if (alpha) PetscCall(FETICheckVec_Private(feti, alpha, FETI_VEC_COARSE, "FETIRecoverPrimal", "alpha"));
  PetscCall(FETICheckVec_Private(feti, u, FETI_VEC_PRIMAL, "FETIRecoverPrimal", "u"));
  if (!alpha) {
    PetscCall(FETIComputeAlpha(feti, lambda, NULL, impl.alpha));
    alpha = impl.alpha;
  }
  PetscCall(PetscLogEventBegin(FETI_PrimalRecovery, feti, 0, 0, 0));
  PetscCall(FETIRowSumApply(impl.Btsum, lambda, impl.wp1));
  PetscCall(VecAYPX(impl.wp1, -1.0, impl.f));
  PetscCall(FETIApplyKplus(feti, impl.wp1, u, PETSC_TRUE));
  if (impl.ncoarse) PetscCall(MatMultAdd(impl.R, alpha, u, u));
  { /* prescribed values of Dirichlet dofs kept in the primal (K+ and R vanish there) */
    PetscScalar *ua;
    PetscCall(VecGetArray(u, &ua));
    for (FETISubdomain &sd : impl.sub)
      for (size_t k = 0; k < sd.dirichletvalues.size(); k++) ua[sd.localoffset + sd.dirichletdofs[k]] = sd.dirichletvalues[k];
    PetscCall(VecRestoreArray(u, &ua));
  }
  PetscCall(PetscLogEventEnd(FETI_PrimalRecovery, feti, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the progress hook's view of the projected CG: iteration k, the residual relative to the first one (the
   KSP's default test with a zero initial guess), against -feti_ksp_rtol */
static PetscErrorCode ProgressMonitor(KSP ksp, PetscInt k, PetscReal rnorm, void *ctx)
{
  FETI_Impl &impl = *static_cast<FETI>(ctx)->impl;
  PetscReal  rtol;

  PetscFunctionBegin;
  if (k == 0) impl.progressrnorm0 = rnorm;
  if (k == 0 || !impl.progress.fn) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(KSPGetTolerances(ksp, &rtol, NULL, NULL, NULL));
  PetscCall(ConeFETIProgressIterate_Private(impl.progress, 0, k, impl.progressrnorm0 > 0 ? rnorm / impl.progressrnorm0 : rnorm, rtol));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETISolveLinear - Solve the FETI problem when every constraint is an equality (gluing and Dirichlet):
  projected CG on P F P, then primal recovery.

  Collective

  Input Parameter:
. feti - the FETI problem (set up here if needed)

  Output Parameters:
+ lambda - the multipliers (dual vector)
- u      - the primal solution (may be NULL)

  Notes:
  lambda = lambda~ + mu with mu in Ker G solving P F P mu = P(h - F lambda~) by the KSP of
  `FETIGetKSP()` (prefix feti_: -feti_ksp_type, -feti_ksp_rtol, -feti_ksp_monitor, -feti_pc_type
  dirichlet|lumped|none). The iterates stay in Ker G because the preconditioner is applied as
  P M^-1 P. Check `KSPGetConvergedReason()` on that KSP.

  Level: beginner

.seealso: `FETIGetKSP()`, `FETIRecoverPrimal()`, `FETISetFromOptions()`
@*/
PetscErrorCode FETISolveLinear(FETI feti, Vec lambda, Vec u)
{
  KSP ksp;

  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  FETI_Impl &impl = *feti->impl;
  PetscValidHeaderSpecific(lambda, VEC_CLASSID, 2);
  if (impl.B) { /* projected CG solves equalities: a contact row would be treated as one, and the answer called converged */
    PetscInt lo, first = PETSC_MAX_INT, kind = -1;
    PetscCall(MatGetOwnershipRange(impl.B, &lo, NULL));
    for (size_t r = 0; r < impl.kinds.size(); r++)
      if (impl.kinds[r] == FETI_ROW_CONTACT_NORMAL || impl.kinds[r] == FETI_ROW_CONTACT_TANGENTIAL) {
        first = lo + (PetscInt)r;
        break;
      }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &first, 1, MPIU_INT, MPI_MIN, PetscObjectComm((PetscObject)feti)));
    if (first != PETSC_MAX_INT && first >= lo && first - lo < (PetscInt)impl.kinds.size()) kind = (PetscInt)impl.kinds[first - lo];
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &kind, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)feti)));
    PetscCheck(first == PETSC_MAX_INT, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_WRONG,
               "FETISolveLinear(): row %" PetscInt_FMT " of B has kind %s; the linear solve takes gluing and Dirichlet rows (equalities) only, contact rows need the contact solver (ContactProblem)",
               first, FETIRowKinds[kind]);
  }
  PetscCall(FETISetUp(feti));
  PetscCall(FETICheckVec_Private(feti, lambda, FETI_VEC_DUAL, "FETISolveLinear", "lambda"));
  if (u) PetscCall(FETICheckVec_Private(feti, u, FETI_VEC_PRIMAL, "FETISolveLinear", "u"));
  PetscCall(FETIGetKSP(feti, &ksp));
  PetscCall(KSPSetOperators(ksp, impl.PFP, impl.PFP));
  if (impl.progress.fn && !impl.progressmonitor) {
    PetscCall(KSPMonitorSet(ksp, ProgressMonitor, feti, NULL));
    impl.progressmonitor = PETSC_TRUE;
  }
  PetscCall(ConeFETIProgressEnter_Private(impl.progress, CONEFETI_PHASE_SOLVE));
  PetscCall(MatMult(impl.F, impl.lambdatilde, impl.rhs));
  PetscCall(VecAYPX(impl.rhs, -1.0, impl.h));
  PetscCall(FETIApplyP(feti, impl.rhs, impl.rhs));
  PetscCall(VecSet(lambda, 0.0));
  PetscCall(KSPSolve(ksp, impl.rhs, lambda));
  PetscCall(VecAXPY(lambda, 1.0, impl.lambdatilde));
  if (u) PetscCall(FETIRecoverPrimal(feti, lambda, NULL, u));
  PetscFunctionReturn(PETSC_SUCCESS);
}
