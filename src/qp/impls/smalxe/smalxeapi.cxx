/* Public functions of the TAO type smalxe, dispatched to the type. */
#include <conefeti/qp.h>
#include <conefeti/compat.h>
#include <petsc/private/taoimpl.h>

/*@C
  TaoSMALXESetEqualityConstraints - The equality C x = d of a `TAOSMALXE` problem.

  Logically Collective

  Input Parameters:
+ tao - the solver
. C   - the constraint matrix (any Mat with MatMult and MatMultTranspose, MATSHELL included), full row rank
- d   - the right-hand side

  Notes:
  With `-tao_smalxe_projector` the rows of C must be orthonormal (C C' = I); the solver then uses
  Q = C'C and x~ = C'd. Alternatively give TAO's equality routines (see `TAOSMALXE`).

  Level: beginner

.seealso: `TAOSMALXE`, `TaoSMALXESetProjector()`
@*/
PetscErrorCode TaoSMALXESetEqualityConstraints(Tao tao, Mat C, Vec d)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidHeaderSpecific(C, MAT_CLASSID, 2);
  PetscValidHeaderSpecific(d, VEC_CLASSID, 3);
  PetscTryMethod(tao, "TaoSMALXESetEqualityConstraints_C", (Tao, Mat, Vec), (tao, C, d));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXESetProjector - Projector form of the equality: Q is the orthogonal projector onto the
  range of C' and xt any particular solution (C xt = d).

  Logically Collective

  Input Parameters:
+ tao - the solver
. Q   - the projector (typically a MATSHELL: FETI's Q = G'(GG')^{-1}G)
- xt  - a particular solution (copied; the solver uses Q xt)

  Notes:
  The inner Hessian becomes PAP + rho Q with P = I - Q; feasibility is measured as |Q x - Q xt| = |C x - d|
  for C with orthonormal rows spanning range(Q).

  Level: intermediate

.seealso: `TAOSMALXE`, `TaoSMALXESetEqualityConstraints()`
@*/
PetscErrorCode TaoSMALXESetProjector(Tao tao, Mat Q, Vec xt)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidHeaderSpecific(Q, MAT_CLASSID, 2);
  PetscValidHeaderSpecific(xt, VEC_CLASSID, 3);
  PetscTryMethod(tao, "TaoSMALXESetProjector_C", (Tao, Mat, Vec), (tao, Q, xt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXEGetSubsolver - The nested TAO of monolithic inner solves (options prefix -tao_smalxe_subsolver_).

  Not Collective

  Input Parameter:
. tao - the solver

  Output Parameter:
. sub - the nested solver

  Level: intermediate

.seealso: `TAOSMALXE`, `TaoSMALXEGetBlockSubsolver()`
@*/
PetscErrorCode TaoSMALXEGetSubsolver(Tao tao, Tao *sub)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscAssertPointer(sub, 2);
  PetscUseMethod(tao, "TaoSMALXEGetSubsolver_C", (Tao, Tao *), (tao, sub));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXESetBlocks - Split the inner minimization into a block Gauss-Seidel sweep: each block is
  minimized in turn with the others fixed, by its own nested TAO.

  Logically Collective

  Input Parameters:
+ tao - the solver
. n   - number of blocks
- is  - index sets of global indices owned by this rank; together a partition of the local entries,
        each disk or cone of the set entirely inside one block

  Notes:
  Block k's nested solver has the options prefix -tao_smalxe_block<k>_ (`TaoSMALXEGetBlockSubsolver()`);
  its default type is mprgp if its part of the set has only bounds, else mpgp. Each block solve
  costs one extra product with the Hessian for its linear term, and each sweep one more for the
  gradient at its end. `-tao_smalxe_sweeps` sets the number of sweeps per outer iteration. This is
  the seed paper's Algorithm 2 split: normal and gluing multipliers by MPRGP, tangential by MPGP.

  Level: advanced

.seealso: `TAOSMALXE`, `TaoSMALXEGetBlockSubsolver()`, `TaoSMALXESetPreSolve()`
@*/
PetscErrorCode TaoSMALXESetBlocks(Tao tao, PetscInt n, const IS is[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscTryMethod(tao, "TaoSMALXESetBlocks_C", (Tao, PetscInt, const IS[]), (tao, n, is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXEGetBlockSubsolver - The nested TAO of block k (see `TaoSMALXESetBlocks()`).

  Not Collective

  Input Parameters:
+ tao - the solver
- k   - the block

  Output Parameter:
. sub - its nested solver

  Level: advanced

.seealso: `TaoSMALXESetBlocks()`
@*/
PetscErrorCode TaoSMALXEGetBlockSubsolver(Tao tao, PetscInt k, Tao *sub)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscAssertPointer(sub, 3);
  PetscUseMethod(tao, "TaoSMALXEGetBlockSubsolver_C", (Tao, PetscInt, Tao *), (tao, k, sub));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXESetPreSolve - A function called before every inner (block) solve with the current full
  iterate, e.g. to change disk radii in place (the Coulomb friction loop sets radius = F lambda_n).

  Logically Collective

  Input Parameters:
+ tao - the solver
. fn  - fn(tao, block, x, ctx): block is the index of the block about to be solved (0 when monolithic)
- ctx - context for fn

  Level: advanced

.seealso: `TaoSMALXESetBlocks()`, `SeparableSetSetDiskRadii()`
@*/
PetscErrorCode TaoSMALXESetPreSolve(Tao tao, PetscErrorCode (*fn)(Tao, PetscInt, Vec, void *), void *ctx)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscTryMethod(tao, "TaoSMALXESetPreSolve_C", (Tao, PetscErrorCode(*)(Tao, PetscInt, Vec, void *), void *), (tao, fn, ctx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXEGetEqualityMultiplier - w = C'mu for the multiplier mu of C x = d at the last solution,
  with the sign convention A x - b + C'mu in -N(x) (minus the normal cone of the set).

  Collective

  Input Parameter:
. tao - the solver

  Output Parameter:
. w - the vector C'mu (same layout as the solution)

  Notes:
  In projector form this costs one product with A. For FETI, alpha = -(GG')^{-1} G w gives the
  rigid-body amplitudes of the primal solution u = K+(f - B'lambda) + R alpha.

  Level: intermediate

.seealso: `TAOSMALXE`
@*/
PetscErrorCode TaoSMALXEGetEqualityMultiplier(Tao tao, Vec w)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidHeaderSpecific(w, VEC_CLASSID, 2);
  PetscUseMethod(tao, "TaoSMALXEGetEqualityMultiplier_C", (Tao, Vec), (tao, w));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXEGetFeasibility - |C x - d| at the last iterate.

  Not Collective

  Input Parameter:
. tao - the solver

  Output Parameter:
. e - the norm of the equality residual

  Level: intermediate

.seealso: `TAOSMALXE`
@*/
PetscErrorCode TaoSMALXEGetFeasibility(Tao tao, PetscReal *e)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidRealPointer(e, 2);
  PetscUseMethod(tao, "TaoSMALXEGetFeasibility_C", (Tao, PetscReal *), (tao, e));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXEGetMultiplierGrowth - How the multiplier of C x = d grew over the last outer iterations, C'(mu_k - mu_j):
  where the loop stagnates because C x = d cannot be met over the set, the direction in which it cannot.

  Collective

  Input Parameter:
. tao - the solver, after a solve

  Output Parameters:
+ w   - vector of the solution's layout: C'(mu_k - mu_j), with k the last outer iteration and j the latest outer
        iteration j > 0, a multiple of h = -tao_smalxe_stagnation_its / 2 (at least 1), with k - j >= h; the zero vector
        when the solve had no such j
- its - k - j, the outer iterations the growth spans (h to 2h - 1), or 0 when the solve had no such j (fewer than
        2h outer iterations, or -tao_smalxe_stagnation_its 0)

  Notes:
  An equality that cannot be met makes the multiplier grow without bound, by about the same step in every outer
  iteration: by Farkas' lemma, along a direction y with C'y pointing out of the set (every x of the set has
  y'(C x - d) < 0). Its growth over the last outer iterations is nearly free of the part that converges, unlike the
  multiplier itself (or its growth since the start). In FETI terms (w = G'mu) it gives the rigid-body motion that the
  load drives and the constraints do not stop (`FETIComputeAlphaFromEquality()`). Two copies of the multiplier are
  kept, made only in solves of at least h outer iterations.

  Level: advanced

.seealso: `TAOSMALXE`, `TaoSMALXEGetStagnated()`, `TaoSMALXEGetEqualityMultiplier()`
@*/
PetscErrorCode TaoSMALXEGetMultiplierGrowth(Tao tao, Vec w, PetscInt *its)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidHeaderSpecific(w, VEC_CLASSID, 2);
  PetscValidIntPointer(its, 3);
  PetscUseMethod(tao, "TaoSMALXEGetMultiplierGrowth_C", (Tao, Vec, PetscInt *), (tao, w, its));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXEGetOuterTolerances - The absolute tolerances the outer loop stops on in the current (or last) solve:
  |gP| <= tol_g and |C x - d| <= tol_e.

  Not Collective

  Input Parameter:
. tao - the solver (inside a solve, e.g. in a `TaoMonitor` routine, or after one)

  Output Parameters:
+ tol_g - the tolerance on the projected gradient (or NULL)
- tol_e - the tolerance on the equality residual (or NULL)

  Notes:
  Both come from the relative tolerance (-tao_gttol) and the size of the linear term, so a monitor can put the
  residuals on the scale of the relative tolerance: max(|gP| / tol_g, |C x - d| / tol_e) times gttol.

  Level: advanced

.seealso: `TAOSMALXE`, `TaoSMALXEGetFeasibility()`
@*/
PetscErrorCode TaoSMALXEGetOuterTolerances(Tao tao, PetscReal *tol_g, PetscReal *tol_e)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscUseMethod(tao, "TaoSMALXEGetOuterTolerances_C", (Tao, PetscReal *, PetscReal *), (tao, tol_g, tol_e));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXESetConsistencyCheck - A function that can veto convergence: when the tolerances hold,
  smalxe asks fn whether the iterate is also consistent with whatever the pre-solve hook keeps in
  step with it (e.g. disk radii F lambda_n of a Coulomb problem), and iterates on if not.

  Logically Collective

  Input Parameters:
+ tao - the solver
. fn  - fn(tao, x, &consistent, ctx)
- ctx - context for fn

  Level: advanced

.seealso: `TaoSMALXESetPreSolve()`
@*/
PetscErrorCode TaoSMALXESetConsistencyCheck(Tao tao, PetscErrorCode (*fn)(Tao, Vec, PetscBool *, void *), void *ctx)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscTryMethod(tao, "TaoSMALXESetConsistencyCheck_C", (Tao, PetscErrorCode(*)(Tao, Vec, PetscBool *, void *), void *), (tao, fn, ctx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXEGetStalled - Whether the last solve stopped because the outer loop made no progress: the
  best |Cx - d| of the last stagnation_its outer iterations was not 1% below the best before them, while
  the multiplier did not grow (so not `TaoSMALXEGetStagnated()`). More iterations would not help; with
  a consistency check (Coulomb radii) the loop may be locked between a few states.

  Not Collective

  Input Parameter:
. tao - the solver

  Output Parameter:
. flag - `PETSC_TRUE` if the solve stopped for it (reason `TAO_DIVERGED_USER`)

  Options Database Key:
. -tao_smalxe_stagnation_its <30> - the window (0 turns both tests off)

  Level: intermediate

.seealso: `TAOSMALXE`, `TaoSMALXEGetStagnated()`, `TaoSMALXEGetFeasibility()`
@*/
PetscErrorCode TaoSMALXEGetStalled(Tao tao, PetscBool *flag)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidBoolPointer(flag, 2);
  PetscUseMethod(tao, "TaoSMALXEGetStalled_C", (Tao, PetscBool *), (tao, flag));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXEGetInnerLimited - Whether the last solve stopped because its inner solves kept running into their
  iteration limit: in each of the last -tao_smalxe_inner_limit_its outer iterations an inner solve ended at its
  iteration limit, and the best distance from convergence, max(|gP| / tol, |Cx - d| / tol), among them was not
  1% below the best before them (tested from 2 -tao_smalxe_inner_limit_its outer iterations on, as the stall test
  of `TaoSMALXEGetStalled()` with its own window). Each outer iteration then costs the inner limit in Hessian
  products for little gain; raising the inner solver's -tao_max_it, or choosing an inner solver that suits the set,
  may help.

  Not Collective

  Input Parameter:
. tao - the solver

  Output Parameter:
. block - the block (0 when there are no blocks) whose inner solve ran into its limit in the last outer
          iteration, if the solve stopped for it (reason `TAO_DIVERGED_USER`); -1 otherwise

  Options Database Key:
. -tao_smalxe_inner_limit_its <5> - the window (0 turns the test off)

  Level: intermediate

.seealso: `TAOSMALXE`, `TaoSMALXEGetStalled()`, `TaoSMALXEGetBlockSubsolver()`
@*/
PetscErrorCode TaoSMALXEGetInnerLimited(Tao tao, PetscInt *block)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidIntPointer(block, 2);
  PetscUseMethod(tao, "TaoSMALXEGetInnerLimited_C", (Tao, PetscInt *), (tao, block));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  TaoSMALXEGetStagnated - Whether the last solve stopped because |Cx - d| stagnated, which means
  that C x = d cannot be met over the set (or that rho is far too small).

  Not Collective

  Input Parameter:
. tao - the solver

  Output Parameter:
. flag - `PETSC_TRUE` if the solve stopped for stagnation (reason `TAO_DIVERGED_USER`)

  Options Database Key:
. -tao_smalxe_stagnation_its <30> - the window: less than 1% progress in this many outer iterations

  Level: intermediate

.seealso: `TAOSMALXE`, `TaoSMALXEGetFeasibility()`, `TaoSMALXEGetMultiplierGrowth()`
@*/
PetscErrorCode TaoSMALXEGetStagnated(Tao tao, PetscBool *flag)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidBoolPointer(flag, 2);
  PetscUseMethod(tao, "TaoSMALXEGetStagnated_C", (Tao, PetscBool *), (tao, flag));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  TaoSMALXESetAnderson - Accelerates the augmented Lagrangian's multiplier update by Anderson mixing.

  Logically Collective

  Input Parameters:
+ tao   - the solver
. depth - how many previous updates enter the mixing (0: the plain update mu += rho (Cx - d), Dostal's SMALBE;
          `PETSC_DECIDE` (-1, the default): 3 with one inner solver, 0 with `TaoSMALXESetBlocks()`)
- start - the first outer iteration (counted from 0, at least 1) whose update is accelerated

  Options Database Keys:
+ -tao_smalxe_anderson <-1>      - the depth
- -tao_smalxe_anderson_start <3> - the first accelerated outer iteration

  Notes:
  The outer loop is the fixed-point iteration mu <- mu + rho (C x(mu) - d), which converges linearly;
  with contact and friction |Cx - d| typically falls by a factor 3-5 per outer iteration. The
  multiplier lives in range(C'), whose dimension is the number of equality rows (the rigid modes in
  FETI), so a short history captures the map well. Anderson mixing of depth m replaces the update by
  mu + f - sum_j gamma_j (dmu_j + df_j), f = rho (Cx - d), with gamma minimizing |f - sum_j gamma_j df_j|
  over the last m differences dmu_j, df_j of multipliers and updates. The history restarts when rho
  changes or |Cx - d| grows, and a nearly singular mixing problem falls back to the plain update.
  The first inner solves are loose (their precision follows |Cx - d|), which makes poor history;
  hence `start`. The semi-monotonicity updates of M (or rho) are unchanged; the theory of SMALBE
  (bounded outer iterations) covers the plain update only. All dot products are reproducible sums,
  so the iterates do not depend on the number of ranks.

  With Gauss-Seidel blocks the sweeps make the map from multiplier to residual too irregular, and
  mixing costs outer iterations instead of saving them, hence no acceleration there by default. When
  something else changes the map between outer iterations (the friction radii of the monolithic
  algorithm of `ContactProblemSolve()`), older history describes a different map and depth 1 is the
  better choice; the contact solver sets it there. On the brick the acceleration saves outer iterations
  and products of the Coulomb solves and barely changes the frictionless and Tresca solves, which need
  few outer iterations anyway (docs/brick-benchmark.md, 'Anderson acceleration of the multiplier update').

  Level: advanced

.seealso: `TAOSMALXE`, `TaoSMALXEGetEqualityMultiplier()`
@*/
PetscErrorCode TaoSMALXESetAnderson(Tao tao, PetscInt depth, PetscInt start)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidLogicalCollectiveInt(tao, depth, 2);
  PetscValidLogicalCollectiveInt(tao, start, 3);
  PetscTryMethod(tao, "TaoSMALXESetAnderson_C", (Tao, PetscInt, PetscInt), (tao, depth, start));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  TaoSMALXESetPenaltyPreconditioner - Preconditions the CG steps of the inner solves by the inverse of the
  penalty term's shape (projector form).

  Logically Collective

  Input Parameters:
+ tao  - the solver
- flag - `PETSC_TRUE` (the default) to precondition, `PETSC_FALSE` for plain CG steps

  Options Database Key:
. -tao_smalxe_penalty_pc <true> - the flag

  Notes:
  In projector form the inner Hessian is PAP + rho Q, Q the orthogonal projector onto range(C'): a term of
  rank m (the equality rows; the rigid modes in FETI) at the top of the spectrum. On the free set of the
  inner solve the active constraints mix it with PAP, and CG pays for it with extra steps. The
  preconditioner is M^-1 = I - theta Q with theta = rho/(||PAP|| + rho), the inverse of
  (||PAP|| I + rho Q)/||PAP||, applied in face (the principal submatrix on the free set, as
  `TaoQPGetPC()` describes): one product with Q per CG step, no product with A. Expansion,
  proportioning and the stopping tests stay unpreconditioned, so the solution and its accuracy do not
  change, only the path.

  It is used with one inner solver of type `TAOMPRGP` or `TAOMPGP` whose PC is `PCNONE` (the default); a
  PC chosen for the inner solver (its -tao_mpgp_pc_type) is kept. Gauss-Seidel blocks
  (`TaoSMALXESetBlocks()`) and the penalty form (general C) have no such preconditioner.
  It saves products with A on the Coulomb, Tresca and frictionless bricks (docs/brick-benchmark.md, 'The
  penalty preconditioner').

  Level: advanced

.seealso: `TAOSMALXE`, `TaoSMALXESetProjector()`, `TaoQPGetPC()`
@*/
PetscErrorCode TaoSMALXESetPenaltyPreconditioner(Tao tao, PetscBool flag)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidLogicalCollectiveBool(tao, flag, 2);
  PetscTryMethod(tao, "TaoSMALXESetPenaltyPreconditioner_C", (Tao, PetscBool), (tao, flag));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  TaoSMALXESetExactStop - Whether a stop is confirmed on the inner solver's exact gradient.

  Logically Collective

  Input Parameters:
+ tao  - the solver
- flag - `PETSC_TRUE` (the default) to confirm, `PETSC_FALSE` to stop on the inner solver's last |gP|

  Options Database Key:
. -tao_smalxe_exact_stop <true> - the same

  Notes:
  The inner solvers update their gradient by CG's recurrence g - a A p, which drifts from A x - b where A is
  ill conditioned: a QP of condition 1e12 was called converged with an exact |gP| 280 times the tolerance. When
  the outer test passes, the exact gradient of the last inner solve is computed (one product with A; the inner
  solver must be `TAOMPRGP` or `TAOMPGP`, without Gauss-Seidel blocks) and must pass the gradient test too, or
  the loop goes on. The contact layer turns it off (`ContactProblemSolve()`): its answers are checked from
  scratch (the mechanical residuals of a `ContactModel`, the KKT residual of a `ContactProblem`), and the
  confirmation would add a product to every solve.

  Level: advanced

.seealso: `TAOSMALXE`, `TAOMPRGP`
@*/
PetscErrorCode TaoSMALXESetExactStop(Tao tao, PetscBool flag)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscValidLogicalCollectiveBool(tao, flag, 2);
  PetscTryMethod(tao, "TaoSMALXESetExactStop_C", (Tao, PetscBool), (tao, flag));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  TaoSMALXESetProjectedPreconditioner - Gives a preconditioner M of the Hessian A, which the inner solves of the
  projector form use in face as P M P + (s/rho) Q instead of the penalty preconditioner.

  Logically Collective

  Input Parameters:
+ tao - the solver
- pc  - an SPD approximation of the inverse of A on range(P) = ker(C) (referenced; set up by the solver before
        each solve), or `NULL` to go back to the penalty preconditioner

  Options Database Key:
. -tao_smalxe_pc_q_scale <1> - s

  Notes:
  In projector form the inner Hessian H = PAP + rho Q is block diagonal in range(P) + range(Q), with the
  inverse (PAP)^+ + Q/rho. M approximates the first block, P M P keeps it in range(P) whatever M does to
  range(Q), and 1/rho is the second block exactly (s = 1); s moves the rank-m block's eigenvalue among those of
  the preconditioned PAP. The inner CG steps are preconditioned in face (the principal submatrix on the free
  set, as `TaoQPGetPC()` describes), so the iterates stay feasible; expansion, proportioning and the stopping
  tests stay unpreconditioned, and the solution and its accuracy do not change, only the path. Each CG step
  costs one application of M and two products with Q more. A FETI dual (A = F = B K+ B') takes the lumped
  B K B' or the Dirichlet preconditioner B S B' (`PCFETILUMPED`, `PCFETIDIRICHLET`); the contact layer
  sets one (`ContactProblemGetPC()`).

  It is used only in projector form with one inner solver of type `TAOMPRGP` or `TAOMPGP` whose PC is `PCNONE`
  (the default); a PC chosen for the inner solver is kept, and Gauss-Seidel blocks (`TaoSMALXESetBlocks()`) and
  the penalty form have none.

  Level: advanced

.seealso: `TAOSMALXE`, `TaoSMALXESetPenaltyPreconditioner()`, `TaoSMALXEGetProjectedPreconditioner()`, `TaoQPGetPC()`
@*/
PetscErrorCode TaoSMALXESetProjectedPreconditioner(Tao tao, PC pc)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  if (pc) PetscValidHeaderSpecific(pc, PC_CLASSID, 2);
  PetscTryMethod(tao, "TaoSMALXESetProjectedPreconditioner_C", (Tao, PC), (tao, pc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  TaoSMALXEGetProjectedPreconditioner - The preconditioner of A given by `TaoSMALXESetProjectedPreconditioner()`.

  Not Collective

  Input Parameter:
. tao - the solver

  Output Parameter:
. pc - the preconditioner (borrowed), or `NULL`

  Level: advanced

.seealso: `TAOSMALXE`, `TaoSMALXESetProjectedPreconditioner()`
@*/
PetscErrorCode TaoSMALXEGetProjectedPreconditioner(Tao tao, PC *pc)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(tao, TAO_CLASSID, 1);
  PetscAssertPointer(pc, 2);
  *pc = NULL;
  PetscTryMethod(tao, "TaoSMALXEGetProjectedPreconditioner_C", (Tao, PC *), (tao, pc));
  PetscFunctionReturn(PETSC_SUCCESS);
}
