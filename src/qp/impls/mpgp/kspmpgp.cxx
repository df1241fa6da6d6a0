/* KSP types mprgp and mpgp: KSPSolve(A x = b) minimizes 1/2 x'Ax - b'x over a SeparableSet,
   by the shared MPGP core. Without constraints the iterates are those of CG (PCG with a PC). */
#include <conefeti.h>
#include <conefeti/private/mpgpcore.h>
#include <conefeti/private/qpadopt.h>
#include <petsc/private/kspimpl.h>

namespace {

struct KSP_MPGP {
  MPGPCore               core;
  const char            *name     = nullptr;
  const MPGPOptionNames *options  = nullptr;         /* -ksp_mprgp_... or -ksp_mpgp_... */
  SeparableSet           user_set = nullptr;         /* from KSPQPSetConstraints() */
  SeparableSet           set      = nullptr;         /* in use for the current solve */
  Vec                    lb = nullptr, ub = nullptr; /* from KSPMPRGPSetBounds() */
  Vec                    dm_lb = nullptr, dm_ub = nullptr;
  QPCounters             counters = {};

  QPNormSettings norm;
  PetscBool      counters_view = PETSC_FALSE;
  PetscBool      unconstrained = PETSC_TRUE;
};

KSP_MPGP *GetMPGP(KSP ksp) { return static_cast<KSP_MPGP *>(ksp->data); }

PetscErrorCode KSPQPReport(void *ctx, PetscInt it, PetscReal, PetscReal gpnorm, PetscReal, PetscBool *stop)
{
  KSP ksp = static_cast<KSP>(ctx);

  PetscFunctionBegin;
  if (GetMPGP(ksp)->core.provisional) { /* only whether the test would stop here: no monitor, no history, the state as it was */
    const PetscInt     its    = ksp->its;
    const PetscReal    rnorm  = ksp->rnorm;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    ksp->its                  = it;
    ksp->rnorm                = gpnorm;
    PetscCall((*ksp->converged)(ksp, it, gpnorm, &reason, ksp->cnvP));
    *stop      = (reason || it >= ksp->max_it) ? PETSC_TRUE : PETSC_FALSE;
    ksp->its   = its;
    ksp->rnorm = rnorm;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  ksp->its   = it;
  ksp->rnorm = gpnorm;
  PetscCall(KSPLogResidualHistory(ksp, gpnorm));
  PetscCall(KSPMonitor(ksp, it, gpnorm));
  PetscCall((*ksp->converged)(ksp, it, gpnorm, &ksp->reason, ksp->cnvP));
  if (!ksp->reason && it >= ksp->max_it) ksp->reason = KSP_DIVERGED_ITS;
  *stop = ksp->reason ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPQPPrecondition(void *ctx, Vec g, Vec z)
{
  KSP ksp = static_cast<KSP>(ctx);

  PetscFunctionBegin;
  PetscCall(KSP_PCApply(ksp, g, z));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The set for this solve: the user's set, the bounds of KSPMPRGPSetBounds(), the DM's variable
   bounds, or none. */
PetscErrorCode KSPMPGPPrepareSet(KSP ksp, KSP_MPGP *qp)
{
  PetscInt n, N;

  PetscFunctionBegin;
  if (qp->user_set) {
    PetscCall(SeparableSetCheckCompatible_Private(qp->user_set, ksp->vec_sol));
    if (qp->set != qp->user_set) {
      PetscCall(PetscObjectReference((PetscObject)qp->user_set));
      PetscCall(SeparableSetDestroy(&qp->set));
      qp->set = qp->user_set;
    }
  } else {
    if (!qp->set) {
      PetscCall(VecGetLocalSize(ksp->vec_sol, &n));
      PetscCall(VecGetSize(ksp->vec_sol, &N));
      PetscCall(SeparableSetCreate(PetscObjectComm((PetscObject)ksp), n, N, &qp->set));
    }
    if (qp->lb || qp->ub) PetscCall(SeparableSetSetBounds(qp->set, qp->lb, qp->ub));
    else {
      PetscBool has = PETSC_FALSE;
      if (ksp->dm) PetscCall(DMHasVariableBounds(ksp->dm, &has));
      if (has) {
        if (!qp->dm_lb) PetscCall(VecDuplicate(ksp->vec_sol, &qp->dm_lb));
        if (!qp->dm_ub) PetscCall(VecDuplicate(ksp->vec_sol, &qp->dm_ub));
        PetscCall(DMComputeVariableBounds(ksp->dm, qp->dm_lb, qp->dm_ub));
        PetscCall(SeparableSetSetBounds(qp->set, qp->dm_lb, qp->dm_ub));
      } else PetscCall(SeparableSetSetBounds(qp->set, NULL, NULL));
    }
  }
  PetscCall(SeparableSetIsUnconstrained(qp->set, &qp->unconstrained));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPSetUp_MPGP(KSP ksp)
{
  PetscFunctionBegin;
  if (ksp->vec_sol) PetscCall(MPGPCoreSetUp(&GetMPGP(ksp)->core, ksp->vec_sol));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* KSPSetFromOptions() and KSPSetTolerances() take a negative -ksp_max_it, and the solve then ran as with 0: checked
   in KSPSetFromOptions_MPGP() (the option) and when a solve starts (KSPSetTolerances()) */
static PetscErrorCode KSPCheckMaxIt(KSP ksp)
{
  const char *prefix;

  PetscFunctionBegin;
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  PetscCheck(ksp->max_it >= 0, PetscObjectComm((PetscObject)ksp), PETSC_ERR_ARG_OUTOFRANGE, "-%sksp_max_it must be >= 0, got %" PetscInt_FMT, prefix ? prefix : "", ksp->max_it);
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPSolve_MPGP(KSP ksp)
{
  KSP_MPGP   *qp = GetMPGP(ksp);
  Mat         A;
  PCType      pctype;
  PetscBool   pcnone, curved;
  const char *prefix;

  PetscFunctionBegin;
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  if (!prefix) prefix = "";
  /* KSPSetFromOptions() takes a NaN tolerance, with which the test never holds and the solve ends in a
     misleading reason (an indefinite operator) */
  PetscCheck(ksp->rtol >= 0 && !PetscIsInfOrNanReal(ksp->rtol), PetscObjectComm((PetscObject)ksp), PETSC_ERR_ARG_OUTOFRANGE, "-%sksp_rtol must be finite and >= 0, got %g", prefix, (double)ksp->rtol);
  PetscCheck(ksp->abstol >= 0 && !PetscIsInfOrNanReal(ksp->abstol), PetscObjectComm((PetscObject)ksp), PETSC_ERR_ARG_OUTOFRANGE, "-%sksp_atol must be finite and >= 0, got %g", prefix,
             (double)ksp->abstol);
  PetscCall(KSPCheckMaxIt(ksp));
  PetscCall(PCGetOperators(ksp->pc, &A, NULL));
  PetscCall(KSPMPGPPrepareSet(ksp, qp));
  if (qp->core.variant == MPGPVariant::MPRGP) {
    PetscCall(SeparableSetHasCurvedBlocks(qp->set, &curved));
    PetscCheck(!curved, PetscObjectComm((PetscObject)ksp), PETSC_ERR_ARG_WRONG, "KSP mprgp handles bounds only, but the set has disk or cone blocks; use -%sksp_type mpgp", prefix);
  }
  PetscCall(PCGetType(ksp->pc, &pctype));
  PetscCall(PetscStrcmp(pctype, PCNONE, &pcnone));
  if (ksp->guess_zero) PetscCall(VecSet(ksp->vec_sol, 0.0));

  /* the fixed step length matters only when there are constraints: without them every step is CG */
  if (qp->unconstrained) qp->norm.used = qp->norm.user > 0 ? qp->norm.user : 1.0;
  else PetscCall(QPNormSettingsApply(&qp->norm, A, prefix, qp->options, &qp->counters));

  qp->core.A                = A;
  qp->core.b                = ksp->vec_rhs;
  qp->core.set              = qp->set;
  qp->core.normA            = qp->norm.used;
  qp->core.counters         = &qp->counters;
  qp->core.report           = KSPQPReport;
  qp->core.report_ctx       = ksp;
  qp->core.precondition     = pcnone ? nullptr : KSPQPPrecondition; /* in face: restricted to the free entries */
  qp->core.precondition_ctx = ksp;
  ksp->reason               = KSP_CONVERGED_ITERATING;
  /* with PETSc's default test the solve stops only on an exact residual, as the TAO types do: CG's recurred residual
     drifts from b - A x where the operator is applied inexactly (FETI's P F P with an ill-conditioned coarse problem: a
     chain of 96 subdomains stopped at a recurred 1e-11 while b - A x was 2e-4 of b, and its answer was 1e8 off) */
  qp->core.verify = (PetscBool)(ksp->converged == KSPConvergedDefault);
  PetscCall(MPGPCoreSolve(&qp->core, ksp->vec_sol));
  if (qp->core.status == MPGPStatus::NORM_TOO_SMALL && qp->norm.user <= 0 && !qp->unconstrained) {
    /* the cached estimate belongs to an operator that has changed behind the same state: estimate
       again and go on from the current iterate (once) */
    PetscCall(PetscInfo(ksp, "KSP %s: q rose with ||A|| = %g: estimating ||A|| again\n", qp->name, (double)qp->norm.used));
    PetscCall(MatQPClearNormEstimate(A));
    PetscCall(QPNormSettingsApply(&qp->norm, A, prefix, qp->options, &qp->counters));
    qp->core.normA  = qp->norm.used;
    qp->core.resume = PETSC_TRUE; /* the convergence test keeps the tolerance it set at the first iteration 0 */
    ksp->reason     = KSP_CONVERGED_ITERATING;
    PetscCall(MPGPCoreSolve(&qp->core, ksp->vec_sol));
    qp->core.resume = PETSC_FALSE;
  }
  PetscCall(MPGPCoreDiagnose(&qp->core));
  if (qp->core.status == MPGPStatus::NOT_SYMMETRIC) {
    PetscCall(PetscInfo(ksp, "KSP %s: the operator is not symmetric (x'Ay - y'Ax = %g for random x, y, against ||A|| |x| |y| = %g)\n", qp->name, (double)qp->core.asymmetry,
                        (double)qp->core.asymmetry_scale));
    ksp->reason = KSP_DIVERGED_NONSYMMETRIC;
  } else if (qp->core.status == MPGPStatus::INDEFINITE) ksp->reason = KSP_DIVERGED_INDEFINITE_MAT;
  else if (qp->core.status == MPGPStatus::NORM_TOO_SMALL) {
    PetscCall(PetscInfo(ksp, "KSP %s: q rose: the estimate ||A|| = %g is too small; a MATSHELL operator whose action changed needs PetscObjectStateIncrease(), or give -%s%s\n", qp->name,
                        (double)qp->norm.used, prefix, qp->options->norm + 1));
    ksp->reason = KSP_DIVERGED_BREAKDOWN;
  } else if (qp->core.status == MPGPStatus::UNBOUNDED) { /* as KSPCG on p'Ap = 0 */
    PetscCall(PetscInfo(ksp, "KSP %s: p'Ap = 0 along a descent direction no constraint stops: the problem is unbounded below (a singular operator with an inconsistent right-hand side?)\n", qp->name));
    ksp->reason = KSP_DIVERGED_INDEFINITE_MAT;
  } else if (qp->core.status == MPGPStatus::ACCURACY_FLOOR) {
    PetscCall(PetscInfo(
        ksp, "KSP %s: the exact residual stays at %g, above the tolerance the recurred one met: rounding limits the accuracy (an ill-conditioned or inexactly applied operator); ask for less\n",
        qp->name, (double)qp->core.gpnorm));
    ksp->reason = KSP_DIVERGED_BREAKDOWN;
  } else if (qp->core.status == MPGPStatus::NOT_A_NUMBER) ksp->reason = KSP_DIVERGED_NANORINF;
  if (qp->counters_view) {
    PetscViewer viewer;
    PetscCall(PetscViewerASCIIGetStdout(PetscObjectComm((PetscObject)ksp), &viewer));
    PetscCall(QPCountersViewJSON(&qp->counters, qp->name, viewer));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPSetFromOptions_MPGP(KSP ksp, CONEFETI_OPTIONS_ITEMS PetscOptionsObject)
{
  KSP_MPGP   *qp = GetMPGP(ksp);
  const char *prefix;

  PetscFunctionBegin;
  PetscCall(KSPCheckMaxIt(ksp));
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  PetscCall(MPGPCoreSetFromOptions(PetscOptionsObject, PetscObjectComm((PetscObject)ksp), prefix, qp->options, &qp->core, &qp->norm, &qp->counters_view));
  {
    /* KSPSetFromOptions() gives the PC PETSc's default type (ILU, block Jacobi) before -ksp_type makes
       this KSP one of ours: that PC was not chosen, and ours is none unless chosen (-pc_type) */
    PetscBool kspset, pcset, dflt;
    PetscCall(PetscOptionsHasName(((PetscObject)ksp)->options, prefix, "-ksp_type", &kspset));
    PetscCall(PetscOptionsHasName(((PetscObject)ksp)->options, prefix, "-pc_type", &pcset));
    PetscCall(PetscObjectTypeCompareAny((PetscObject)ksp->pc, &dflt, PCILU, PCBJACOBI, PCICC, ""));
    if (kspset && !pcset && dflt) {
      PetscCall(PetscInfo(ksp, "KSP %s: the PC of type %s was PETSc's default, not chosen: none\n", qp->name, ((PetscObject)ksp->pc)->type_name));
      PetscCall(PCSetType(ksp->pc, PCNONE));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPView_MPGP(KSP ksp, PetscViewer viewer)
{
  KSP_MPGP *qp = GetMPGP(ksp);
  PetscBool iascii;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (!iascii) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscViewerASCIIPrintf(viewer, "  %s: Gamma %g, step length %g/||A||, ||A|| %s %g\n", qp->name, (double)qp->core.gamma, (double)qp->core.alpha_scale,
                                   qp->norm.user > 0 ? "given" : "estimated", (double)qp->norm.used));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(MPGPCoreViewExpansion(&qp->core, viewer));
  PetscCall(QPCountersView(&qp->counters, NULL, viewer));
  if (qp->core.status == MPGPStatus::NOT_SYMMETRIC)
    PetscCall(PetscViewerASCIIPrintf(viewer, "stopped: the operator is not symmetric (x'Ay - y'Ax = %g for random x, y, against ||A|| |x| |y| = %g)\n", (double)qp->core.asymmetry,
                                     (double)qp->core.asymmetry_scale));
  if (qp->set) PetscCall(SeparableSetView(qp->set, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPReset_MPGP(KSP ksp)
{
  KSP_MPGP *qp = GetMPGP(ksp);

  PetscFunctionBegin;
  PetscCall(MPGPCoreReset(&qp->core));
  PetscCall(SeparableSetDestroy(&qp->set));
  PetscCall(VecDestroy(&qp->dm_lb));
  PetscCall(VecDestroy(&qp->dm_ub));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPDestroy_MPGP(KSP ksp)
{
  KSP_MPGP *qp = GetMPGP(ksp);

  PetscFunctionBegin;
  PetscCall(KSPReset_MPGP(ksp));
  PetscCall(SeparableSetDestroy(&qp->user_set));
  PetscCall(VecDestroy(&qp->lb));
  PetscCall(VecDestroy(&qp->ub));
  for (const char *fn : {"KSPQPSetConstraints_C", "KSPQPGetConstraints_C", "KSPMPRGPSetBounds_C", "KSPQPSetNormEstimate_C", "KSPQPGetCounters_C", "KSPQPResetCounters_C"})
    PetscCall(PetscObjectComposeFunction((PetscObject)ksp, fn, NULL));
  delete qp;
  ksp->data = NULL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPQPSetConstraints_MPGP(KSP ksp, SeparableSet set)
{
  KSP_MPGP *qp = GetMPGP(ksp);

  PetscFunctionBegin;
  PetscCall(PetscObjectReference((PetscObject)set));
  PetscCall(SeparableSetDestroy(&qp->user_set));
  qp->user_set = set;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPQPGetConstraints_MPGP(KSP ksp, SeparableSet *set)
{
  PetscFunctionBegin;
  *set = GetMPGP(ksp)->set ? GetMPGP(ksp)->set : GetMPGP(ksp)->user_set;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPMPRGPSetBounds_MPGP(KSP ksp, Vec lb, Vec ub)
{
  KSP_MPGP *qp = GetMPGP(ksp);

  PetscFunctionBegin;
  if (lb) PetscCall(PetscObjectReference((PetscObject)lb));
  if (ub) PetscCall(PetscObjectReference((PetscObject)ub));
  PetscCall(VecDestroy(&qp->lb));
  PetscCall(VecDestroy(&qp->ub));
  qp->lb = lb;
  qp->ub = ub;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPQPSetNormEstimate_MPGP(KSP ksp, PetscReal norm)
{
  PetscFunctionBegin;
  PetscCheck(norm >= 0 && !PetscIsInfOrNanReal(norm), PetscObjectComm((PetscObject)ksp), PETSC_ERR_ARG_OUTOFRANGE, "KSPQPSetNormEstimate: ||A|| must be finite and > 0 (0 to estimate), got %g",
             (double)norm);
  GetMPGP(ksp)->norm.user = norm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPQPGetCounters_MPGP(KSP ksp, QPCounters *c)
{
  PetscFunctionBegin;
  *c = GetMPGP(ksp)->counters;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPQPResetCounters_MPGP(KSP ksp)
{
  PetscFunctionBegin;
  GetMPGP(ksp)->counters = QPCounters{};
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode KSPCreate_MPGPCommon(KSP ksp, MPGPVariant variant, const char *name)
{
  KSP_MPGP *qp;
  PC        pc;

  PetscFunctionBegin;
  PetscCallCXX(qp = new KSP_MPGP);
  qp->core.variant = variant;
  qp->core.bb      = PETSC_FALSE;
  qp->name         = name;
  qp->options      = variant == MPGPVariant::MPRGP ? &MPGPOptionsKSPMPRGP : &MPGPOptionsKSPMPGP;
  ksp->data        = qp;
  PetscCall(KSPSetSupportedNorm(ksp, KSP_NORM_UNPRECONDITIONED, PC_LEFT, 3));
  /* a preconditioner (in face, with constraints) only when the user chooses one */
  PetscCall(KSPGetPC(ksp, &pc));
  if (!((PetscObject)pc)->type_name) PetscCall(PCSetType(pc, PCNONE));

  ksp->ops->setup          = KSPSetUp_MPGP;
  ksp->ops->solve          = KSPSolve_MPGP;
  ksp->ops->setfromoptions = KSPSetFromOptions_MPGP;
  ksp->ops->view           = KSPView_MPGP;
  ksp->ops->reset          = KSPReset_MPGP;
  ksp->ops->destroy        = KSPDestroy_MPGP;
  ksp->ops->buildsolution  = KSPBuildSolutionDefault;
  ksp->ops->buildresidual  = KSPBuildResidualDefault;

  PetscCall(PetscObjectComposeFunction((PetscObject)ksp, "KSPQPSetConstraints_C", KSPQPSetConstraints_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)ksp, "KSPQPGetConstraints_C", KSPQPGetConstraints_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)ksp, "KSPMPRGPSetBounds_C", KSPMPRGPSetBounds_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)ksp, "KSPQPSetNormEstimate_C", KSPQPSetNormEstimate_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)ksp, "KSPQPGetCounters_C", KSPQPGetCounters_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)ksp, "KSPQPResetCounters_C", KSPQPResetCounters_MPGP));
  PetscCall(KSPQPAdoptComposed_Private(ksp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/*MC
  KSPMPRGP - "mprgp": KSPSolve(A x = b) as min 1/2 x'Ax - b'x subject to l <= x <= u (Dostal-Schoberl
  MPRGP); without bounds it is CG (PCG with a preconditioner), with the same iterates as `KSPCG` until it stops.

  Options Database Keys:
+ -ksp_mprgp_gamma <1>           - proportioning parameter Gamma
. -ksp_mprgp_alpha <1.95>        - fixed step length in units of 1/||A||, in (0, 2]
. -ksp_mprgp_norm <value>        - ||A|| given, not estimated (only used with bounds)
. -ksp_mprgp_norm_method <slepc> - slepc or power
. -ksp_mprgp_norm_margin         - safety margin on the estimate
. -ksp_mprgp_expansion_projcg, -ksp_mprgp_expansion_lagged, -ksp_mprgp_expansion_lookahead, -ksp_mprgp_expansion_gradient - the expansion steps, as -tao_mprgp_expansion_* of `TAOMPRGP`
- -ksp_mprgp_counters_view       - print the counters as one JSON line after each solve

  Notes:
  Bounds come from `KSPMPRGPSetBounds()`, `KSPQPSetConstraints()`, or the variable bounds of the KSP's DM
  (`DMSetVariableBounds()`), so an unmodified program with a DM that has bounds can use it. The
  initial guess is projected. The residual norm reported to monitors and to the convergence test is
  the norm of the projected gradient (the KKT residual); `-ksp_rtol` is relative to |b|. The PC is
  none unless chosen; with bounds a PC M preconditions the CG steps in face, z = [M^-1]_FF g_F on the
  free entries F (see `TaoQPGetPC()`).
  A must be symmetric: a solve that fails tests it as `TAOMPRGP` does and, when it is not, ends with
  `KSP_DIVERGED_NONSYMMETRIC` (-ksp_view: "stopped: the operator is not symmetric"). A negative -ksp_max_it is an error.
  With PETSc's default convergence test the solve stops only on an exact residual: when the recurred one meets the
  test, b - A x is computed (one product) and must meet it too, else the solve goes on from it with a restarted
  direction; three such refusals that do not halve it end the solve with `KSP_DIVERGED_BREAKDOWN` (rounding limits
  the accuracy: an ill-conditioned or inexactly applied operator, -info says so). Where `KSPCG` would stop on a
  drifted residual the iterates then differ.

  References:
. * - Z. Dostal, J. Schoberl, Minimizing quadratic functions over non-negative cone with the rate of convergence and finite termination, Computational Optimization and Applications (2005)

  Level: beginner

.seealso: `KSPMPGP`, `TAOMPRGP`, `KSPMPRGPSetBounds()`
M*/
PETSC_INTERN PetscErrorCode KSPCreate_MPRGP(KSP ksp)
{
  PetscFunctionBegin;
  PetscCall(KSPCreate_MPGPCommon(ksp, MPGPVariant::MPRGP, KSPMPRGP));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*MC
  KSPMPGP - "mpgp": KSPSolve(A x = b) as min 1/2 x'Ax - b'x over a `SeparableSet` (bounds, disks,
  cones; Kucera's MPGP); without constraints it is CG.

  Options Database Keys:
  Those of `KSPMPRGP`, with the prefix -ksp_mpgp_, and -ksp_mpgp_arc <1> as -tao_mpgp_arc of `TAOMPGP`.

  Notes:
  The set comes from `KSPQPSetConstraints()`; bounds as for `KSPMPRGP`.

  References:
. * - R. Kucera, Convergence rate of an optimization algorithm for minimizing quadratic functions with separable convex constraints, SIAM J. Optim. (2008)

  Level: beginner

.seealso: `KSPMPRGP`, `TAOMPGP`, `KSPQPSetConstraints()`
M*/
PETSC_INTERN PetscErrorCode KSPCreate_MPGP(KSP ksp)
{
  PetscFunctionBegin;
  PetscCall(KSPCreate_MPGPCommon(ksp, MPGPVariant::MPGP, KSPMPGP));
  PetscFunctionReturn(PETSC_SUCCESS);
}
