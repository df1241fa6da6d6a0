/* TAO types mprgp and mpgp: min 1/2 x'Ax - b'x over a SeparableSet, by the shared MPGP core. */
#include <conefeti.h>
#include <conefeti/private/mpgpcore.h>
#include <conefeti/private/reproduciblesum.h>
#include <conefeti/private/qpadopt.h>
#include <conefeti/private/errortext.h>
#include <petsc/private/taoimpl.h>
#include <cstring>
#include <string>

namespace {

enum QPBlockType {
  QP_BLOCK_SCALAR,
  QP_BLOCK_DISK,
  QP_BLOCK_CONE
};
const char *const QPBlockTypes[] = {"scalar", "disk", "cone", "QPBlockType", "QP_BLOCK_", NULL};

struct TAO_MPGP {
  MPGPCore               core;
  const char            *name     = nullptr; /* "mprgp" or "mpgp" */
  const MPGPOptionNames *options  = nullptr; /* -tao_mprgp_... or -tao_mpgp_... */
  SeparableSet           user_set = nullptr; /* from TaoQPSetConstraints() */
  SeparableSet           set      = nullptr; /* the set in use: user_set, or built from the variable bounds */
  Vec                    b        = nullptr; /* linear term */
  PetscBool              b_user   = PETSC_FALSE;
  PetscReal              bnorm    = 0;
  PetscReal              gref     = 0; /* what gttol is relative to: |b|, or |gP(x0)| when b = 0 */
  QPCounters             counters = {};

  QPNormSettings norm;

  QPBlockType block_type    = QP_BLOCK_SCALAR; /* how the variable bounds describe blocks (unmodified programs) */
  PetscReal   cone_mu       = 1.0;
  PetscBool   counters_view = PETSC_FALSE;
  Tao         tao           = nullptr;
  PC          pc            = nullptr; /* preconditioning in face, options -tao_mprgp_pc_* or -tao_mpgp_pc_*; PCNONE until a solve chooses from the Hessian */
  std::string pc_prefix;               /* the options prefix we gave pc (a prefix the user gives it instead is kept) */

  /* The PC type, the expansion and Gamma the user did not set follow the Hessian (mpgpdefaults.cxx) at each solve */
  MPGPHessianDefaults defaults;                   /* of the last solve's Hessian */
  PetscBool           solved       = PETSC_FALSE; /* defaults holds a choice */
  PetscBool           gamma_given  = PETSC_FALSE; /* by -tao_mprgp_gamma */
  PetscBool           projcg_given = PETSC_FALSE; /* by -tao_mprgp_expansion_projcg or TaoQPSetExpansionProjCG() */
  PetscBool           pc_given     = PETSC_FALSE; /* by -tao_mprgp_pc_type, or a type set through TaoQPGetPC() */
  PCType              pc_auto      = PCNONE;      /* the type the defaults last gave the PC: another type was set by someone else */
  PetscBool           from_options = PETSC_FALSE; /* TaoSetFromOptions() was called: a PC type chosen later reads its options too */
  PetscBool           pc_applied   = PETSC_FALSE; /* the PC was applied since its last setup (TaoQPPreconditionChecked()) */
};

TAO_MPGP *GetMPGP(Tao tao) { return static_cast<TAO_MPGP *>(tao->data); }

PetscErrorCode TaoQPReport(void *ctx, PetscInt it, PetscReal f, PetscReal gpnorm, PetscReal step, PetscBool *stop)
{
  Tao tao = static_cast<Tao>(ctx);

  PetscFunctionBegin;
  if (GetMPGP(tao)->core.provisional) { /* only whether the test would stop here: no monitor, no history, the state as it was */
    const PetscInt  niter = tao->niter;
    const PetscReal fc = tao->fc, residual = tao->residual;
    tao->niter    = it;
    tao->fc       = f;
    tao->residual = gpnorm;
    PetscUseTypeMethod(tao, convergencetest, tao->cnvP);
    *stop         = tao->reason != TAO_CONTINUE_ITERATING ? PETSC_TRUE : PETSC_FALSE;
    tao->reason   = TAO_CONTINUE_ITERATING;
    tao->niter    = niter;
    tao->fc       = fc;
    tao->residual = residual;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (it == 0) {
    TAO_MPGP *qp = GetMPGP(tao);
    qp->gref     = qp->bnorm > 0 ? qp->bnorm : gpnorm;
  }
  tao->niter = it;
  if (PetscIsInfOrNanReal(f) || PetscIsInfOrNanReal(gpnorm)) { /* TaoMonitor() would raise an error that blames a user function */
    tao->fc       = f;
    tao->residual = gpnorm;
    PetscCall(PetscInfo(tao, "TAO QP: the objective or the projected gradient is not a finite number at iteration %" PetscInt_FMT " (overflow: data near the largest real?)\n", it));
    PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_NAN));
    *stop = PETSC_TRUE;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(TaoLogConvergenceHistory(tao, f, gpnorm, 0.0, tao->ksp_its));
  PetscCall(TaoMonitor(tao, it, f, gpnorm, 0.0, step));
  PetscUseTypeMethod(tao, convergencetest, tao->cnvP);
  *stop = tao->reason != TAO_CONTINUE_ITERATING ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoQPPrecondition(void *ctx, Vec g, Vec z)
{
  PetscFunctionBegin;
  PetscCall(PCApply(static_cast<PC>(ctx), g, z));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Error ierr of setting up or applying the PC whose type an option gave, told with that option: a preconditioner that
   needs entries (jacobi, icc, ...) of a Hessian that has none (a MATSHELL: the FETI dual operator) fails deep in PETSc,
   at its setup or (jacobi) at its first application, without naming it. Called with PETSc's message not printed. */
static PetscErrorCode PCFailure(PC pc, PetscErrorCode ierr)
{
  const char *pcprefix, *pctype, *mattype;
  PetscBool   shell;
  Mat         P;

  PetscFunctionBegin;
  const std::string why = ConeFETIErrorText(ierr);
  PetscCall(PCGetOptionsPrefix(pc, &pcprefix));
  PetscCall(PCGetType(pc, &pctype));
  PetscCall(PCGetOperators(pc, NULL, &P));
  PetscCall(MatGetType(P, &mattype));
  PetscCall(PetscObjectTypeCompare((PetscObject)P, MATSHELL, &shell));
  SETERRQ(PetscObjectComm((PetscObject)pc), ierr, "-%spc_type %s: the preconditioner fails on the Hessian's preconditioning matrix, of type %s (%s)%s", pcprefix ? pcprefix : "", pctype, mattype,
          why.c_str(), shell ? "; a shell matrix has no entries: give the Hessian an assembled preconditioning matrix, or choose a preconditioner that needs none of them" : "");
}

/* TaoQPPrecondition() for a PC type given by an option: its first application after a setup is checked (PCFailure()) */
static PetscErrorCode TaoQPPreconditionChecked(void *ctx, Vec g, Vec z)
{
  TAO_MPGP      *qp = static_cast<TAO_MPGP *>(ctx);
  PetscErrorCode ierr;

  PetscFunctionBegin;
  if (qp->pc_applied) {
    PetscCall(PCApply(qp->pc, g, z));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = PCApply(qp->pc, g, z);
  PetscCall(PetscPopErrorHandler());
  if (ierr) PetscCall(PCFailure(qp->pc, ierr));
  qp->pc_applied = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The preconditioner, created on first use with the prefix -[tao prefix]tao_mprgp_ or tao_mpgp_ and type none. */
PetscErrorCode TaoQPGetPC_MPGP(Tao tao, PC *pc)
{
  TAO_MPGP *qp = GetMPGP(tao);

  PetscFunctionBegin;
  if (!qp->pc) {
    const char *tprefix;
    PetscCall(PCCreate(PetscObjectComm((PetscObject)tao), &qp->pc));
    PetscCall(PetscObjectIncrementTabLevel((PetscObject)qp->pc, (PetscObject)tao, 1));
    PetscCall(TaoGetOptionsPrefix(tao, &tprefix));
    PetscCall(PCSetOptionsPrefix(qp->pc, tprefix));
    PetscCall(PCAppendOptionsPrefix(qp->pc, qp->options->pc_prefix));
    PetscCallCXX(qp->pc_prefix = std::string(tprefix ? tprefix : "") + qp->options->pc_prefix);
    PetscCall(PCSetType(qp->pc, PCNONE));
  }
  *pc = qp->pc;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Default test of the QP types: |gP| <= max(gatol, gttol |b|). Relative to |b| rather than to the
   initial gradient, so that the result does not depend on the initial guess and is invariant under
   scaling of A and b; when b = 0 (the bounds alone make the problem) relative to |gP(x0)|. */
PetscErrorCode TaoQPConvergenceTest(Tao tao, void *)
{
  TAO_MPGP *qp = GetMPGP(tao);
  PetscReal g  = tao->residual;

  PetscFunctionBegin;
  if (tao->reason != TAO_CONTINUE_ITERATING) PetscFunctionReturn(PETSC_SUCCESS);
  if (PetscIsInfOrNanReal(g) || PetscIsInfOrNanReal(tao->fc)) PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_NAN));
  else if (g <= tao->gatol) PetscCall(TaoSetConvergedReason(tao, TAO_CONVERGED_GATOL));
  else if (g <= tao->gttol * qp->gref) PetscCall(TaoSetConvergedReason(tao, TAO_CONVERGED_GTTOL));
  else if (tao->grtol > 0 && g <= tao->grtol * PetscAbsReal(tao->fc)) PetscCall(TaoSetConvergedReason(tao, TAO_CONVERGED_GRTOL)); /* TAO's |g|/|f| test, off unless -tao_grtol is given */
  else if (tao->niter >= tao->max_it) PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_MAXITS));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* For programs that only know TaoSetVariableBounds(): consecutive pairs become disks inscribed in
   their box, consecutive triples become cones with a common coefficient. */
PetscErrorCode BuildBlocksFromBounds(Tao tao, TAO_MPGP *qp)
{
  PetscInt               n, rstart, bs = qp->block_type == QP_BLOCK_DISK ? 2 : 3;
  const PetscScalar     *l = NULL, *u = NULL;
  std::vector<PetscInt>  idx;
  std::vector<PetscReal> center, radius, mu;
  const char            *prefix;

  PetscFunctionBegin;
  PetscCall(TaoGetOptionsPrefix(tao, &prefix));
  if (!prefix) prefix = "";
  PetscCall(VecGetLocalSize(tao->solution, &n));
  PetscCall(VecGetOwnershipRange(tao->solution, &rstart, NULL));
  PetscCheck(n % bs == 0, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
             "-%stao_mpgp_block_type %s: the local length %" PetscInt_FMT " is not a multiple of the block length %" PetscInt_FMT " (a block never straddles MPI ranks)", prefix,
             QPBlockTypes[qp->block_type], n, bs);
  if (qp->block_type == QP_BLOCK_DISK) {
    PetscCheck(tao->XL && tao->XU, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE, "-%stao_mpgp_block_type disk needs variable bounds: each pair's box [l,u]^2 gives the inscribed disk",
               prefix);
    PetscCall(VecGetArrayRead(tao->XL, &l));
    PetscCall(VecGetArrayRead(tao->XU, &u));
    for (PetscInt k = 0; k < n; k += 2) {
      const PetscReal w0 = PetscRealPart(u[k] - l[k]), w1 = PetscRealPart(u[k + 1] - l[k + 1]);
      /* PETSC_INFINITY (a finite number, PETSC_MAX_REAL / 4) is how TAO says "no bound": its box gave a radius of 1e307,
         whose square overflowed, and the solve ended DIVERGED_NAN with 6.6e306 in every entry */
      for (PetscInt e = k; e < k + 2; e++)
        PetscCheck(PetscRealPart(l[e]) > PETSC_NINFINITY && PetscRealPart(u[e]) < PETSC_INFINITY, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                   "-%stao_mpgp_block_type disk: entry %" PetscInt_FMT " has no bound (%g, %g; PETSC_INFINITY means none): each pair's box [l,u]^2 must be finite to give its disk", prefix, rstart + e,
                   (double)PetscRealPart(l[e]), (double)PetscRealPart(u[e]));
      PetscCheck(PetscIsNormalReal(w0) || w0 == 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_mpgp_block_type disk: entry %" PetscInt_FMT " needs finite bounds l <= u", prefix, rstart + k);
      PetscCheck(w0 >= 0 && PetscAbsReal(w0 - w1) <= 1e-12 * PetscMax(PetscAbsReal(w0), PetscAbsReal(w1)), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                 "-%stao_mpgp_block_type disk: the box of entries %" PetscInt_FMT ",%" PetscInt_FMT " is not a square with l <= u (widths %g, %g)", prefix, rstart + k, rstart + k + 1, (double)w0,
                 (double)w1);
      PetscCallCXX(idx.insert(idx.end(), {rstart + k, rstart + k + 1}));
      PetscCallCXX(center.insert(center.end(), {PetscRealPart(l[k] + u[k]) / 2, PetscRealPart(l[k + 1] + u[k + 1]) / 2}));
      PetscCallCXX(radius.push_back(w0 / 2));
    }
    PetscCall(VecRestoreArrayRead(tao->XL, &l));
    PetscCall(VecRestoreArrayRead(tao->XU, &u));
    PetscCall(SeparableSetAddDisks(qp->set, (PetscInt)radius.size(), idx.data(), center.data(), radius.data()));
  } else {
    for (PetscInt k = 0; k < n; k += 3) {
      PetscCallCXX(idx.insert(idx.end(), {rstart + k, rstart + k + 1, rstart + k + 2}));
      PetscCallCXX(mu.push_back(qp->cone_mu));
    }
    PetscCall(SeparableSetAddCones(qp->set, (PetscInt)mu.size(), idx.data(), mu.data()));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoSetUp_MPGP(Tao tao)
{
  PetscFunctionBegin;
  if (!tao->gradient) PetscCall(VecDuplicate(tao->solution, &tao->gradient));
  if (!tao->stepdirection) PetscCall(VecDuplicate(tao->solution, &tao->stepdirection));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The set in use for this solve: the user's, or one built from the current variable bounds. */
PetscErrorCode TaoMPGPPrepareSet(Tao tao, TAO_MPGP *qp)
{
  PetscInt n, N;

  PetscFunctionBegin;
  PetscCall(TaoComputeVariableBounds(tao));
  if (qp->user_set) {
    PetscCall(SeparableSetCheckCompatible_Private(qp->user_set, tao->solution));
    if (qp->set != qp->user_set) {
      PetscCall(SeparableSetDestroy(&qp->set));
      PetscCall(PetscObjectReference((PetscObject)qp->user_set));
      qp->set = qp->user_set;
    }
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (qp->block_type != QP_BLOCK_SCALAR) PetscCall(SeparableSetDestroy(&qp->set)); /* disks and cones from the bounds of this solve */
  if (!qp->set) {
    PetscCall(VecGetLocalSize(tao->solution, &n));
    PetscCall(VecGetSize(tao->solution, &N));
    PetscCall(SeparableSetCreate(PetscObjectComm((PetscObject)tao), n, N, &qp->set));
    if (qp->block_type != QP_BLOCK_SCALAR) PetscCall(BuildBlocksFromBounds(tao, qp));
  }
  if (qp->block_type == QP_BLOCK_SCALAR) PetscCall(SeparableSetSetBounds(qp->set, tao->XL, tao->XU));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether -<pc prefix><name> is in the options database (the PC's prefix is the solver's plus tao_mprgp_). */
PetscErrorCode TaoMPGPHasPCOption(TAO_MPGP *qp, const char *name, PetscBool *has)
{
  const char *pcprefix;

  PetscFunctionBegin;
  PetscCall(PCGetOptionsPrefix(qp->pc, &pcprefix));
  PetscCall(PetscOptionsHasName(((PetscObject)qp->pc)->options, pcprefix, name, has));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The block Jacobi chosen on several ranks gets ICC in its blocks (PETSc's default there is ILU, whose
   inverse is not symmetric and would not make [M^-1]_FF a preconditioner for CG), unless
   -tao_mprgp_sub_pc_type says otherwise. Called after PCSetUp(), which creates the blocks' solvers but does
   not factor them yet. */
PetscErrorCode TaoMPGPBlockICC(TAO_MPGP *qp)
{
  KSP      *sub;
  PetscInt  nlocal;
  PetscBool given;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)qp->pc, PCBJACOBI, &given));
  if (!given) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(TaoMPGPHasPCOption(qp, "-sub_pc_type", &given));
  if (given) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PCBJacobiGetSubKSP(qp->pc, &nlocal, NULL, &sub));
  for (PetscInt k = 0; k < nlocal; k++) {
    PC        subpc;
    PetscBool icc;
    PetscCall(KSPGetPC(sub[k], &subpc));
    PetscCall(PetscObjectTypeCompare((PetscObject)subpc, PCICC, &icc));
    if (icc) continue;
    PetscCall(PCSetType(subpc, PCICC));
    if (qp->from_options) PetscCall(PCSetFromOptions(subpc)); /* -tao_mprgp_sub_pc_factor_levels ... */
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The PC type, the expansion and Gamma that the user did not choose follow the preconditioning matrix P and the
   set (MPGPHessianDefaultsGet()). A PC whose type is no longer the one given here was set by the user (or by
   the caller, e.g. smalxe's penalty preconditioner) through TaoQPGetPC(), and is kept. */
PetscErrorCode TaoMPGPApplyHessianDefaults(Tao tao, TAO_MPGP *qp, Mat P)
{
  PC        pc;
  PetscBool same;

  PetscFunctionBegin;
  PetscCall(MPGPHessianDefaultsGet(P, qp->set, &qp->defaults));
  qp->solved = PETSC_TRUE;
  if (!qp->gamma_given) qp->core.gamma = qp->defaults.gamma;
  if (!qp->projcg_given) qp->core.projcg = qp->defaults.projcg;
  PetscCall(TaoQPGetPC_MPGP(tao, &pc));
  if (!qp->pc_given) {
    PetscCall(PetscObjectTypeCompare((PetscObject)pc, qp->pc_auto, &same));
    if (!same) qp->pc_given = PETSC_TRUE;
  }
  if (qp->pc_given) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, qp->defaults.pc, &same));
  if (same) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PCSetType(pc, qp->defaults.pc));
  qp->pc_auto = qp->defaults.pc;
  if (qp->from_options) PetscCall(PCSetFromOptions(pc)); /* the options of the type now chosen (-tao_mprgp_pc_factor_levels ...) */
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoSolve_MPGP(Tao tao)
{
  TAO_MPGP   *qp = GetMPGP(tao);
  Mat         A;
  PetscInt    m, n, N;
  PetscBool   curved;
  const char *prefix;

  PetscFunctionBegin;
  PetscCall(TaoGetOptionsPrefix(tao, &prefix));
  if (!prefix) prefix = "";
  PetscCall(TaoQPCheckTolerances_Private(tao, PETSC_FALSE));
  PetscCall(TaoQPCheckMaxIt_Private(tao));
  PetscCall(TaoMPGPPrepareSet(tao, qp));
  if (qp->core.variant == MPGPVariant::MPRGP) {
    PetscCall(SeparableSetHasCurvedBlocks(qp->set, &curved));
    PetscCheck(!curved, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONG, "TAO mprgp handles bounds only, but the set has disk or cone blocks; use -%stao_type mpgp", prefix);
  }

  /* the Hessian: from the user's routine if there is one, else the Mat given to TaoSetHessian() */
  if (tao->ops->computehessian) PetscCall(TaoComputeHessian(tao, tao->solution, tao->hessian, tao->hessian_pre));
  A = tao->hessian;
  PetscCheck(A, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE, "TAO %s: no Hessian; call TaoSetHessian()", qp->name);
  PetscCall(MatGetSize(A, &m, &n));
  PetscCall(VecGetSize(tao->solution, &N));
  PetscCheck(m == n && n == N, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_SIZ,
             "TAO %s: the Hessian must be square with the solution's size %" PetscInt_FMT ", it is %" PetscInt_FMT " x %" PetscInt_FMT, qp->name, N, m, n);
  if (tao->ops->convergencetest == TaoQPConvergenceTest) {
    /* a user's start: the projection of a NaN or an infinity onto the set is a huge finite number, and the solve
       ended DIVERGED_NAN with the user's x overwritten by it; name it instead (an inner solve of smalxe starts from
       smalxe's iterate, whose NaN smalxe reports as DIVERGED_NAN itself) */
    PetscReal xmax;
    PetscCall(VecNorm(tao->solution, NORM_INFINITY, &xmax));
    PetscCheck(!PetscIsInfOrNanReal(xmax), PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE,
               "TAO %s: the initial guess (the solution vector, TaoSetSolution()) has an entry that is not a finite number", qp->name);
  }

  /* the linear term: given, or minus the gradient at 0 (one call) */
  if (!qp->b_user) {
    if (!qp->b) PetscCall(VecDuplicate(tao->solution, &qp->b));
    PetscCall(VecSet(tao->stepdirection, 0.0));
    PetscCheck(tao->ops->computegradient || tao->ops->computeobjectiveandgradient, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE,
               "TAO %s: no linear term; call TaoQPSetLinearTerm() or set a gradient routine (b = -gradient at 0)", qp->name);
    PetscCall(TaoComputeGradient(tao, tao->stepdirection, qp->b));
    PetscCall(VecScale(qp->b, -1.0));
  }
  PetscCall(ReproducibleDot(qp->b, qp->b, &qp->bnorm));
  qp->bnorm = PetscSqrtReal(qp->bnorm);

  /* the norm estimate for the fixed step length */
  PetscCall(QPNormSettingsApply(&qp->norm, A, prefix, qp->options, &qp->counters));

  qp->core.A          = A;
  qp->core.b          = qp->b;
  qp->core.set        = qp->set;
  qp->core.normA      = qp->norm.used;
  qp->core.counters   = &qp->counters;
  qp->core.report     = TaoQPReport;
  qp->core.report_ctx = tao;
  PetscCall(TaoMPGPApplyHessianDefaults(tao, qp, tao->hessian_pre ? tao->hessian_pre : A));
  {
    PetscBool none = PETSC_TRUE;
    if (qp->pc) PetscCall(PetscObjectTypeCompare((PetscObject)qp->pc, PCNONE, &none));
    PetscBool named = PETSC_FALSE; /* the type came from -..._pc_type (smalxe's shell, the FETI preconditioner, did not) */
    if (!none) {
      PetscBool shell;
      PetscCall(TaoMPGPHasPCOption(qp, "-pc_type", &named));
      PetscCall(PetscObjectTypeCompare((PetscObject)qp->pc, PCSHELL, &shell));
      named = (PetscBool)(named && !shell);
    }
    qp->core.precondition     = none ? nullptr : (named ? TaoQPPreconditionChecked : TaoQPPrecondition);
    qp->core.precondition_ctx = named ? static_cast<void *>(qp) : static_cast<void *>(qp->pc);
    qp->pc_applied            = PETSC_FALSE;
    if (!none) {
      PetscCall(PCSetOperators(qp->pc, A, tao->hessian_pre ? tao->hessian_pre : A));
      if (named) {
        PetscErrorCode ierr;
        PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
        ierr = PCSetUp(qp->pc);
        PetscCall(PetscPopErrorHandler());
        if (ierr) PetscCall(PCFailure(qp->pc, ierr));
      } else PetscCall(PCSetUp(qp->pc));
      if (!qp->pc_given) PetscCall(TaoMPGPBlockICC(qp));
    }
  }
  tao->reason = TAO_CONTINUE_ITERATING;
  /* with TAO's QP test (a solve of the user's, not an inner solve of smalxe, whose own test follows) the solver stops
     only on an exact gradient: CG's recurred one drifts from A x - b where A is ill conditioned, and met the test
     while the exact |gP| was 5.6 times the tolerance (tests/qp/exact_stop.cxx) */
  qp->core.verify = (PetscBool)(tao->ops->convergencetest == TaoQPConvergenceTest);
  PetscCall(MPGPCoreSolve(&qp->core, tao->solution));
  if (qp->core.status == MPGPStatus::NORM_TOO_SMALL && qp->norm.user <= 0) {
    /* the cached estimate belongs to an operator that has changed behind the same state: estimate
       again and go on from the current iterate (once) */
    PetscCall(PetscInfo(tao, "TAO %s: q rose with ||A|| = %g: estimating ||A|| again\n", qp->name, (double)qp->norm.used));
    PetscCall(MatQPClearNormEstimate(A));
    PetscCall(QPNormSettingsApply(&qp->norm, A, prefix, qp->options, &qp->counters));
    qp->core.normA  = qp->norm.used;
    qp->core.resume = PETSC_TRUE; /* the stopping reference (gref) stays that of the first start */
    tao->reason     = TAO_CONTINUE_ITERATING;
    PetscCall(MPGPCoreSolve(&qp->core, tao->solution));
    qp->core.resume = PETSC_FALSE;
  }
  PetscCall(VecCopy(qp->core.g, tao->gradient));
  PetscCall(MPGPCoreDiagnose(&qp->core));
  if (qp->core.status == MPGPStatus::NOT_SYMMETRIC) {
    PetscCall(PetscInfo(tao, "TAO %s: the Hessian is not symmetric (x'Ay - y'Ax = %g for random x, y, against ||A|| |x| |y| = %g)\n", qp->name, (double)qp->core.asymmetry,
                        (double)qp->core.asymmetry_scale));
    PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_USER));
  } else if (qp->core.status == MPGPStatus::INDEFINITE) {
    PetscCall(PetscInfo(tao, "TAO %s: p'Ap < 0, the Hessian is not positive semidefinite\n", qp->name));
    PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_USER));
  } else if (qp->core.status == MPGPStatus::UNBOUNDED) {
    PetscCall(PetscInfo(tao, "TAO %s: p'Ap = 0 along a descent direction no constraint stops: q is unbounded below\n", qp->name));
    PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_USER));
  } else if (qp->core.status == MPGPStatus::NORM_TOO_SMALL) {
    PetscCall(PetscInfo(tao, "TAO %s: q rose: the estimate ||A|| = %g is too small; a MATSHELL Hessian whose action changed needs PetscObjectStateIncrease(), or give -%s%s\n", qp->name,
                        (double)qp->norm.used, prefix, qp->options->norm + 1));
    PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_USER));
  } else if (qp->core.status == MPGPStatus::ACCURACY_FLOOR) {
    PetscCall(PetscInfo(tao, "TAO %s: the exact projected gradient stays at %g, above the tolerance the recurred one met: rounding limits the accuracy (an ill-conditioned Hessian); ask for less\n",
                        qp->name, (double)qp->core.gpnorm));
    PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_USER));
  } else if (qp->core.status == MPGPStatus::NOT_A_NUMBER) PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_NAN));
  if (qp->counters_view) {
    PetscViewer viewer;
    PetscCall(PetscViewerASCIIGetStdout(PetscObjectComm((PetscObject)tao), &viewer));
    PetscCall(QPCountersViewJSON(&qp->counters, qp->name, viewer));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoSetFromOptions_MPGP(Tao tao, CONEFETI_OPTIONS_ITEMS PetscOptionsObject)
{
  TAO_MPGP   *qp = GetMPGP(tao);
  const char *prefix;

  PetscFunctionBegin;
  PetscCall(TaoGetOptionsPrefix(tao, &prefix));
  if (!prefix) prefix = "";
  {
    /* an option given, even with the value of a default, is the user's choice (mpgpdefaults.cxx) */
    PetscBool given;
    PetscCall(PetscOptionsHasName(((PetscObject)tao)->options, prefix, qp->options->gamma, &given));
    if (given) qp->gamma_given = PETSC_TRUE;
    PetscCall(PetscOptionsHasName(((PetscObject)tao)->options, prefix, qp->options->expansion_projcg, &given));
    if (given) qp->projcg_given = PETSC_TRUE;
  }
  PetscCall(TaoQPCheckMaxIt_Private(tao));
  PetscCall(MPGPCoreSetFromOptions(PetscOptionsObject, PetscObjectComm((PetscObject)tao), prefix, qp->options, &qp->core, &qp->norm, &qp->counters_view));
  {
    PC          pc;
    PetscBool   given;
    const char *pcprefix;
    char        want[256];
    PetscCall(TaoQPGetPC_MPGP(tao, &pc));
    /* under the Tao's prefix as it is now (TaoSetOptionsPrefix() after the PC was made does not reach it), unless
       the user gave the PC a prefix of their own */
    PetscCall(PetscSNPrintf(want, sizeof(want), "%s%s", prefix ? prefix : "", qp->options->pc_prefix));
    PetscCall(PCGetOptionsPrefix(pc, &pcprefix));
    if (qp->pc_prefix == (pcprefix ? pcprefix : "") && qp->pc_prefix != want) {
      PetscCall(PCSetOptionsPrefix(pc, want));
      PetscCallCXX(qp->pc_prefix = want);
    }
    PetscCall(TaoMPGPHasPCOption(qp, "-pc_type", &given));
    if (given) qp->pc_given = PETSC_TRUE;
    PetscCall(PCSetFromOptions(pc));
    qp->from_options = PETSC_TRUE;
  }
  if (qp->core.variant == MPGPVariant::MPRGP) { /* bounds only: no block description to choose, so none in -help */
    PetscEnum type = (PetscEnum)QP_BLOCK_SCALAR;
    PetscBool set;
    PetscCall(PetscOptionsGetEnum(((PetscObject)tao)->options, prefix, "-tao_mprgp_block_type", QPBlockTypes, &type, &set));
    PetscCheck(!set || type == (PetscEnum)QP_BLOCK_SCALAR, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONG, "-%stao_mprgp_block_type %s: mprgp handles bounds only; use -%stao_type mpgp",
               prefix, QPBlockTypes[type], prefix);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscOptionsHeadBegin(PetscOptionsObject, "mpgp: block description from the variable bounds");
  PetscCall(PetscOptionsEnum("-tao_mpgp_block_type", "Without TaoQPSetConstraints(): scalar (bounds), disk (pairs in their bound boxes) or cone (triples)", "TaoQPSetConstraints", QPBlockTypes,
                             (PetscEnum)qp->block_type, (PetscEnum *)&qp->block_type, NULL));
  PetscCall(PetscOptionsReal("-tao_mpgp_cone_mu", "Cone coefficient for -tao_mpgp_block_type cone", "TaoQPSetConstraints", qp->cone_mu, &qp->cone_mu, NULL));
  PetscOptionsHeadEnd();
  PetscCheck(qp->block_type != QP_BLOCK_CONE || (qp->cone_mu >= 0 && !PetscIsInfOrNanReal(qp->cone_mu)), PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE,
             "-%stao_mpgp_cone_mu must be finite and >= 0, got %g", prefix, (double)qp->cone_mu);
  if (qp->block_type != QP_BLOCK_SCALAR && qp->core.variant == MPGPVariant::MPRGP)
    SETERRQ(PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONG, "-%stao_mprgp_block_type %s: mprgp handles bounds only; use -%stao_type mpgp", prefix, QPBlockTypes[qp->block_type], prefix);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* What the preconditioner in face, Gamma and the expansion are, and who chose them: the user, or the
   defaults from the Hessian (with the reason). */
PetscErrorCode TaoMPGPViewChoices(TAO_MPGP *qp, PetscViewer viewer)
{
  char        why[256], chosen[300];
  const char *pctype = PCNONE;
  PetscBool   blocks;

  PetscFunctionBegin;
  PetscCall(MPGPHessianDefaultsReason(&qp->defaults, why, sizeof(why)));
  PetscCall(PetscSNPrintf(chosen, sizeof(chosen), qp->solved ? "chosen %s" : "to be chosen %s", why));
  if (qp->pc) PetscCall(PCGetType(qp->pc, &pctype));
  PetscCall(PetscStrcmp(pctype, PCBJACOBI, &blocks));
  if (qp->pc_given) PetscCall(PetscViewerASCIIPrintf(viewer, "pc: %s (set by an option or through TaoQPGetPC())\n", pctype ? pctype : "unset"));
  else if (qp->solved && blocks) {
    KSP     *sub;
    PC       subpc;
    PCType   subtype = nullptr;
    PetscInt nlocal;
    PetscCall(PCBJacobiGetSubKSP(qp->pc, &nlocal, NULL, &sub));
    if (nlocal > 0) {
      PetscCall(KSPGetPC(sub[0], &subpc));
      PetscCall(PCGetType(subpc, &subtype));
    }
    PetscCall(PetscViewerASCIIPrintf(viewer, "pc: bjacobi with %s in each rank's block (%s)\n", subtype ? subtype : "a default", chosen));
  } else PetscCall(PetscViewerASCIIPrintf(viewer, "pc: %s (%s)\n", qp->solved ? pctype : "none until the first solve", chosen));
  PetscCall(PetscViewerASCIIPrintf(viewer, "Gamma: %g (%s)\n", (double)qp->core.gamma, qp->gamma_given ? "set by an option" : chosen));
  PetscCall(PetscViewerASCIIPrintf(viewer, "expansion chosen: %s (%s)\n", qp->core.projcg ? "projected full CG step first" : "Dostal's (feasible half step and fixed-length projected step)",
                                   qp->projcg_given ? "set by an option or TaoQPSetExpansionProjCG()" : chosen));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoView_MPGP(Tao tao, PetscViewer viewer)
{
  TAO_MPGP *qp = GetMPGP(tao);
  PetscBool iascii;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (!iascii) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%s: Gamma %g, step length %g/||A||, ||A|| %s %g\n", qp->name, (double)qp->core.gamma, (double)qp->core.alpha_scale,
                                   qp->norm.user > 0 ? "given" : "estimated", (double)qp->norm.used));
  PetscCall(MPGPCoreViewExpansion(&qp->core, viewer));
  PetscCall(TaoMPGPViewChoices(qp, viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "stopping: |projected gradient| <= max(gatol %g, gttol %g * %s = %g)%s\n", (double)tao->gatol, (double)tao->gttol,
                                   qp->bnorm > 0 ? "|b|" : "|gP(x0)| (b = 0)", (double)(tao->gttol * qp->gref), tao->grtol > 0 ? ", or <= grtol |f|" : ""));
  PetscCall(QPCountersView(&qp->counters, NULL, viewer));
  if (qp->core.precondition) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "preconditioning in face (the PC restricted to the free entries):\n"));
    PetscCall(PCView(qp->pc, viewer));
  }
  if (qp->core.status == MPGPStatus::NOT_SYMMETRIC)
    PetscCall(PetscViewerASCIIPrintf(viewer, "stopped: the Hessian is not symmetric (x'Ay - y'Ax = %g for random x, y, against ||A|| |x| |y| = %g)\n", (double)qp->core.asymmetry,
                                     (double)qp->core.asymmetry_scale));
  if (qp->core.status == MPGPStatus::INDEFINITE) PetscCall(PetscViewerASCIIPrintf(viewer, "stopped: the Hessian is not positive semidefinite (p'Ap < 0)\n"));
  if (qp->core.status == MPGPStatus::UNBOUNDED) PetscCall(PetscViewerASCIIPrintf(viewer, "stopped: q is unbounded below (p'Ap = 0 along a descent direction no constraint stops)\n"));
  if (qp->core.status == MPGPStatus::NORM_TOO_SMALL)
    PetscCall(PetscViewerASCIIPrintf(viewer, "stopped: q rose, the estimate of ||A|| is too small (a MATSHELL whose action changed needs PetscObjectStateIncrease())\n"));
  if (qp->core.status == MPGPStatus::ACCURACY_FLOOR)
    PetscCall(PetscViewerASCIIPrintf(viewer, "stopped: the exact projected gradient stays at %g, above the tolerance the recurred one met (rounding: an ill-conditioned Hessian)\n",
                                     (double)qp->core.gpnorm));
  if (qp->core.verified)
    PetscCall(PetscViewerASCIIPrintf(viewer, "stops confirmed on the exact gradient: %" PetscInt_FMT " (one product each), %" PetscInt_FMT " refused\n", qp->core.verified, qp->core.verify_failed));
  if (qp->set) PetscCall(SeparableSetView(qp->set, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoDestroy_MPGP(Tao tao)
{
  TAO_MPGP *qp = GetMPGP(tao);

  PetscFunctionBegin;
  PetscCall(MPGPCoreReset(&qp->core));
  PetscCall(SeparableSetDestroy(&qp->user_set));
  PetscCall(SeparableSetDestroy(&qp->set));
  PetscCall(VecDestroy(&qp->b));
  PetscCall(PCDestroy(&qp->pc));
  /* a later TaoSetType() keeps tao->ops->convergencetest: give the next type TAO's default, which it replaces by its own */
  if (tao->ops->convergencetest == TaoQPConvergenceTest) tao->ops->convergencetest = TaoDefaultConvergenceTest;
  for (const char *fn : {"TaoQPSetConstraints_C", "TaoQPGetConstraints_C", "TaoQPSetLinearTerm_C", "TaoQPSetNormEstimate_C", "TaoQPGetNormEstimate_C", "TaoQPGetCounters_C", "TaoQPResetCounters_C",
                         "TaoQPGetPC_C", "TaoQPSetExpansionProjCG_C", "TaoQPSetExpansionLagged_C"})
    PetscCall(PetscObjectComposeFunction((PetscObject)tao, fn, NULL));
  delete qp;
  tao->data = NULL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoQPSetConstraints_MPGP(Tao tao, SeparableSet set)
{
  TAO_MPGP *qp = GetMPGP(tao);

  PetscFunctionBegin;
  PetscCall(PetscObjectReference((PetscObject)set));
  PetscCall(SeparableSetDestroy(&qp->user_set));
  qp->user_set = set;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoQPGetConstraints_MPGP(Tao tao, SeparableSet *set)
{
  PetscFunctionBegin;
  *set = GetMPGP(tao)->set ? GetMPGP(tao)->set : GetMPGP(tao)->user_set;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoQPSetLinearTerm_MPGP(Tao tao, Vec b)
{
  TAO_MPGP *qp = GetMPGP(tao);

  PetscFunctionBegin;
  PetscCall(PetscObjectReference((PetscObject)b));
  PetscCall(VecDestroy(&qp->b));
  qp->b      = b;
  qp->b_user = b ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoQPSetNormEstimate_MPGP(Tao tao, PetscReal norm)
{
  PetscFunctionBegin;
  PetscCheck(norm >= 0 && !PetscIsInfOrNanReal(norm), PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE, "TaoQPSetNormEstimate: ||A|| must be finite and > 0 (0 to estimate), got %g",
             (double)norm);
  GetMPGP(tao)->norm.user = norm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoQPGetNormEstimate_MPGP(Tao tao, PetscReal *norm)
{
  PetscFunctionBegin;
  *norm = GetMPGP(tao)->norm.used;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoQPSetExpansionProjCG_MPGP(Tao tao, PetscBool flg)
{
  PetscFunctionBegin;
  GetMPGP(tao)->core.projcg  = flg;
  GetMPGP(tao)->projcg_given = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoQPSetExpansionLagged_MPGP(Tao tao, PetscBool flg)
{
  PetscFunctionBegin;
  GetMPGP(tao)->core.lagged = flg;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoQPGetCounters_MPGP(Tao tao, QPCounters *c)
{
  PetscFunctionBegin;
  *c = GetMPGP(tao)->counters;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoQPResetCounters_MPGP(Tao tao)
{
  PetscFunctionBegin;
  GetMPGP(tao)->counters = QPCounters{};
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoCreate_MPGPCommon(Tao tao, MPGPVariant variant, const char *name)
{
  TAO_MPGP *qp;

  PetscFunctionBegin;
  PetscCallCXX(qp = new TAO_MPGP);
  qp->core.variant = variant;
  qp->core.bb      = PETSC_FALSE;
  qp->name         = name;
  qp->options      = variant == MPGPVariant::MPRGP ? &MPGPOptionsTaoMPRGP : &MPGPOptionsTaoMPGP;
  qp->tao          = tao;
  tao->data        = qp;

  tao->ops->setup          = TaoSetUp_MPGP;
  tao->ops->solve          = TaoSolve_MPGP;
  tao->ops->setfromoptions = TaoSetFromOptions_MPGP;
  tao->ops->view           = TaoView_MPGP;
  tao->ops->destroy        = TaoDestroy_MPGP;
  if (tao->ops->convergencetest == TaoDefaultConvergenceTest) tao->ops->convergencetest = TaoQPConvergenceTest;

  /* tolerances relative to |b| (see TaoQPConvergenceTest); no absolute floor by default, so that
     problems scaled by 1e-12 or 1e+12 behave alike */
  if (!tao->gatol_changed) tao->gatol = 0.0;
  if (!tao->grtol_changed) tao->grtol = 0.0;
  if (!tao->gttol_changed) tao->gttol = 1e-8;
  if (!tao->max_it_changed) tao->max_it = 10000;

  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPSetConstraints_C", TaoQPSetConstraints_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPGetConstraints_C", TaoQPGetConstraints_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPSetLinearTerm_C", TaoQPSetLinearTerm_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPSetNormEstimate_C", TaoQPSetNormEstimate_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPGetNormEstimate_C", TaoQPGetNormEstimate_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPGetCounters_C", TaoQPGetCounters_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPResetCounters_C", TaoQPResetCounters_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPGetPC_C", TaoQPGetPC_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPSetExpansionProjCG_C", TaoQPSetExpansionProjCG_MPGP));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPSetExpansionLagged_C", TaoQPSetExpansionLagged_MPGP));
  PetscCall(TaoQPAdoptComposed_Private(tao));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/* For an outer solver (smalxe) about to stop on this solver's last result: its projected gradient from the exact
   gradient (*confirmed false, nothing done, for a TAO that is not mprgp/mpgp) */
PetscErrorCode TaoQPConfirmGradient_Private(Tao tao, PetscReal *gpnorm, PetscBool *confirmed)
{
  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompareAny((PetscObject)tao, confirmed, TAOMPRGP, TAOMPGP, ""));
  if (!*confirmed) PetscFunctionReturn(PETSC_SUCCESS);
  TAO_MPGP *qp = GetMPGP(tao);
  PetscCall(MPGPCoreConfirmGradient(&qp->core, tao->solution, gpnorm));
  PetscCall(VecCopy(qp->core.g, tao->gradient));
  tao->residual = *gpnorm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*MC
  TAOMPRGP - "mprgp": Modified Proportioning with Reduced Gradient Projections (Dostal and Schoberl)
  for min 1/2 x'Ax - b'x subject to l <= x <= u.

  Options Database Keys:
+ -tao_mprgp_gamma <1 or 2>      - proportioning parameter Gamma (default from the Hessian: 2 when assembled, else 1)
. -tao_mprgp_alpha <1.95>        - fixed step length (expansion steps) in units of 1/||A||, in (0, 2]
. -tao_mprgp_norm <value>        - ||A|| given, not estimated
. -tao_mprgp_norm_method <slepc> - slepc or power
. -tao_mprgp_norm_margin         - safety margin on the estimate
. -tao_mprgp_expansion_projcg <bool> - expansion steps first try the projected full CG step (`TaoQPSetExpansionProjCG()`; default from the Hessian: true when assembled)
. -tao_mprgp_expansion_lagged <false> - projected CG expansions first try the last expansion's length, without a product of their own (`TaoQPSetExpansionLagged()`)
. -tao_mprgp_expansion_lookahead <0> - projected CG expansions project the point this many more CG steps down the face, past the set (kept when q is no higher than at the feasible half step)
. -tao_mprgp_expansion_gradient <false> - projected CG expansions try P(y - alpha g(y)), y the CG point, instead of P(y)
. -tao_mprgp_pc_type <icc or none> - preconditioner of the CG steps on the free entries (in face; default from the Hessian: icc when assembled, bjacobi + icc on several ranks, else none)
- -tao_mprgp_counters_view       - print the counters as one JSON line after each solve

  Notes:
  A is the Hessian (`TaoSetHessian()`, a MATSHELL works; without a Hessian routine the given Mat is
  used as is), b is minus the gradient at 0 (one gradient call) or set by `TaoQPSetLinearTerm()`.
  Bounds come from `TaoSetVariableBounds()` (infinite or absent entries allowed) or from
  `TaoQPSetConstraints()`. The initial guess is projected. The solver stops when the projected
  gradient satisfies |gP| <= max(gatol, gttol |b|) (`-tao_gatol`, `-tao_gttol`, defaults 0 and 1e-8),
  or after `-tao_max_it` iterations. Each iteration costs one Hessian product (expansion steps two).
  With a preconditioner M (`-tao_mprgp_pc_type`, `TaoQPGetPC()`; it is set up with the Hessian and the
  Hessian's preconditioning matrix) the CG steps use z = [M^-1]_FF g_F on the free set F, a principal
  submatrix of M^-1, hence symmetric positive definite on the face; the proportioning test, the
  expansion and proportioning steps and the stopping test stay unpreconditioned.
  Defaults from the Hessian: when ICC can factor the Hessian's preconditioning matrix (an assembled sparse
  matrix; on several ranks each rank's diagonal block), the PC is ICC(0) (block Jacobi with ICC(0) on several
  ranks), the expansion tries the projected CG step and Gamma is 2; otherwise (a MATSHELL, a dense matrix) no
  PC, Dostal's expansion and Gamma 1. Each of the three options given wins over its default; -tao_view says
  which was chosen and why.
  A must be symmetric. A solve that fails (q rises, a direction of curvature p'Ap <= 0, or an exact gradient that
  stays above the tolerance) tests A with two products (counted in hessian_mults; a successful solve does not): when
  x'Ay - y'Ax for random x, y exceeds 1e-8 ||A|| |x| |y| it ends with `TAO_DIVERGED_USER` and -tao_view says
  "stopped: the Hessian is not symmetric". A negative -tao_max_it is an error.
  The algorithm and what conefeti adds to it: docs/algorithms.md, 'MPRGP and MPGP'.

  References:
+ * - Z. Dostal, J. Schoberl, Minimizing quadratic functions over non-negative cone with the rate of convergence and finite termination, Computational Optimization and Applications (2005)
- * - Z. Dostal, Optimal Quadratic Programming Algorithms, with Applications to Variational Inequalities, Springer (2009)

  Level: beginner

.seealso: `TAOMPGP`, `TAOSMALXE`, `KSPMPRGP`, `TaoQPGetCounters()`
M*/
PETSC_INTERN PetscErrorCode TaoCreate_MPRGP(Tao tao)
{
  PetscFunctionBegin;
  PetscCall(TaoCreate_MPGPCommon(tao, MPGPVariant::MPRGP, TAOMPRGP));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*MC
  TAOMPGP - "mpgp": Modified Proportioning with Gradient Projections (Kucera) for min 1/2 x'Ax - b'x
  over a separable convex set: bounds, 2D disks, 3D second-order cones, free entries.

  Options Database Keys:
+ -tao_mpgp_gamma <1 or 2>      - proportioning parameter Gamma (default from the Hessian, as for mprgp; 1 when the set has cones)
. -tao_mpgp_alpha <1.95>        - fixed step length in units of 1/||A||, in (0, 2]
. -tao_mpgp_norm <value>        - ||A|| given, not estimated
. -tao_mpgp_norm_method <slepc> - slepc or power
. -tao_mpgp_norm_margin         - safety margin on the estimate
. -tao_mpgp_bb <false>          - try Barzilai-Borwein lengths in gradient projection steps, kept only when q decreases
. -tao_mpgp_arc <1>            - CG steps also move a disk block on its circle along the circle while alpha |g.nu|/r <= this; 0 turns arc steps off
. -tao_mpgp_block_type <scalar> - without `TaoQPSetConstraints()`: scalar (bounds), disk (consecutive pairs, each the disk inscribed in its bound box), cone (consecutive triples)
. -tao_mpgp_cone_mu <1>         - the cone coefficient with -tao_mpgp_block_type cone
. -tao_mpgp_expansion_projcg <bool> - expansion steps first try the projected full CG step (`TaoQPSetExpansionProjCG()`; default from the Hessian, as for mprgp; off when the set has cones)
. -tao_mpgp_expansion_lagged <false> - projected CG expansions first try the last expansion's length, without a product of their own (`TaoQPSetExpansionLagged()`)
. -tao_mpgp_expansion_lookahead <0> - projected CG expansions project the point this many more CG steps down the face, past the set (kept when q is no higher than at the feasible half step)
. -tao_mpgp_expansion_gradient <false> - projected CG expansions try P(y - alpha g(y)), y the CG point, instead of P(y)
. -tao_mpgp_pc_type <icc or none> - preconditioner of the CG steps, restricted to the free entries and interior blocks (default from the Hessian, as for mprgp; none when the set has cones)
- -tao_mpgp_counters_view       - print the counters as one JSON line after each solve

  Notes:
  The set is given by `TaoQPSetConstraints()` (a `SeparableSet`); otherwise by the variable bounds
  as described by -tao_mpgp_block_type. Otherwise as `TAOMPRGP`, except that a set with cone blocks keeps no
  PC, Dostal's expansion and Gamma 1 whatever the Hessian (a cone block on its surface moves by projected
  gradient steps only, so such solves are nearly all proportioning steps: src/qp/impls/mpgp/mpgpdefaults.cxx). Arc steps are conefeti's addition:
  docs/algorithms.md, 'MPRGP and MPGP'.

  References:
+ * - R. Kucera, Convergence rate of an optimization algorithm for minimizing quadratic functions with separable convex constraints, SIAM J. Optim. (2008)
- * - R. Kucera, A new algorithm for solving 3D contact problems with Coulomb friction (the seed paper of conefeti: MPGP on friction disks)

  Level: beginner

.seealso: `TAOMPRGP`, `TAOSMALXE`, `KSPMPGP`, `SeparableSet`
M*/
PETSC_INTERN PetscErrorCode TaoCreate_MPGP(Tao tao)
{
  PetscFunctionBegin;
  PetscCall(TaoCreate_MPGPCommon(tao, MPGPVariant::MPGP, TAOMPGP));
  PetscFunctionReturn(PETSC_SUCCESS);
}
