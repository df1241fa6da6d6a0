/* MPRGP (Dostal-Schoberl) and MPGP (Kucera): one implementation for both the TAO and KSP types.

   Minimizes q(x) = 1/2 x'Ax - b'x over a separable set. Each iteration does exactly one kind of step:
   - CG step on the free set when the iterate is proportional (|beta|^2 <= Gamma^2 phi~.phi) and the
     CG step stays feasible;
   - expansion step otherwise in the proportional case: to the boundary by the largest feasible step
     along p, then a projected step of fixed length alpha along the free gradient, and CG restarts.
     With -tao_mprgp_expansion_projcg (TaoQPSetExpansionProjCG())
     the projected full CG step P(x - a_cg p) is tried first and kept when q there is no higher than
     at the feasible half step (q's change at the half step is known from g'p and p'Ap, so the test
     is free; a rejected try costs one product). It adds many constraints at once where the
     fixed-length step adds a few: fewer products on discretized PDE problems (obstacle 1051 -> 783),
     more on random ill-conditioned QPs, where Dostal's proven expansion stays the default. With a
     preconditioner the CG directions hit the boundary more often and the projected CG step matters
     more;
   - proportioning step when not proportional: along the chopped gradient with exact line search
     (MPRGP; cut at the opposite bound of a box), or a projected gradient step (MPGP, which is what curved
     boundaries need), of Kucera's fixed length alpha. With -tao_mpgp_bb the proportioning step
     first tries the Barzilai-Borwein length s's/s'(As) of the last step (free: As = g - g_prev for
     a QP) and keeps it only if q decreased. Measured: BB shortens long runs of proportioning steps
     on random cone problems (docs/qp-benchmark.md) but costs products on the brick's friction disks,
     so it is off by default.
   Math: ../shared/ALGORITHMS.md section 3. */
#include <conefeti/private/mpgpcore.h>
#include <conefeti/private/reproduciblesum.h>

PetscLogEvent QP_HessianMult, QP_Solve, QP_NormEstimate;

static PetscErrorCode MPGPCoreMult(MPGPCore *c, Vec x, Vec y)
{
  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(QP_HessianMult, c->A, x, y, 0));
  PetscCall(MatMult(c->A, x, y));
  PetscCall(PetscLogEventEnd(QP_HessianMult, c->A, x, y, 0));
  c->counters->hessian_mults++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* g = A x - b */
static PetscErrorCode MPGPCoreGradient(MPGPCore *c, Vec x)
{
  PetscFunctionBegin;
  PetscCall(MPGPCoreMult(c, x, c->g));
  PetscCall(VecAXPY(c->g, -1.0, c->b));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MPGPCoreSetUp(MPGPCore *c, Vec x)
{
  PetscFunctionBegin;
  if (c->g) {
    PetscInt n, N, n0, N0;
    PetscCall(VecGetLocalSize(x, &n));
    PetscCall(VecGetSize(x, &N));
    PetscCall(VecGetLocalSize(c->g, &n0));
    PetscCall(VecGetSize(c->g, &N0));
    if (n == n0 && N == N0) PetscFunctionReturn(PETSC_SUCCESS);
    PetscCall(MPGPCoreReset(c));
  }
  PetscCall(VecDuplicate(x, &c->g));
  PetscCall(VecDuplicate(x, &c->p));
  PetscCall(VecDuplicate(x, &c->Ap));
  PetscCall(VecDuplicate(x, &c->phi));
  PetscCall(VecDuplicate(x, &c->beta));
  PetscCall(VecDuplicate(x, &c->xprev));
  PetscCall(VecDuplicate(x, &c->gprev));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MPGPCoreReset(MPGPCore *c)
{
  PetscFunctionBegin;
  PetscCall(VecDestroy(&c->g));
  PetscCall(VecDestroy(&c->p));
  PetscCall(VecDestroy(&c->Ap));
  PetscCall(VecDestroy(&c->phi));
  PetscCall(VecDestroy(&c->beta));
  PetscCall(VecDestroy(&c->z));
  PetscCall(VecDestroy(&c->dx));
  PetscCall(VecDestroy(&c->xprev));
  PetscCall(VecDestroy(&c->gprev));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Computes phi, beta and the sums at (x, g); Ap may be NULL. */
static PetscErrorCode MPGPCoreSplit(MPGPCore *c, Vec x, PetscReal alpha, Vec Ap, SeparableSplit *s)
{
  PetscFunctionBegin;
  PetscCall(SeparableSetSplitGradient_Private(c->set, x, c->g, alpha, c->phi, c->beta, Ap, c->b, s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* z = [M^-1]_FF phi_F at the point of the last split (preconditioning in face) */
static PetscErrorCode MPGPCorePrecondition(MPGPCore *c)
{
  PetscFunctionBegin;
  PetscCall(c->precondition(c->precondition_ctx, c->phi, c->z));
  PetscCall(SeparableSetMaskFree_Private(c->set, c->z));
  c->counters->pc_applications++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A direction d with d'Ad <= 0. Zero curvature up to rounding (|d'Ad| <= 1e-10 ||A|| |d|^2: a
   semicoercive problem, e.g. a floating body, with d in the kernel of A) is fine as long as a constraint
   stops the step (af finite): *status STOPPED, the caller steps to the boundary. Otherwise the solve
   ends: NaN, negative curvature (INDEFINITE), or a flat descent direction nothing stops (UNBOUNDED). */
static PetscErrorCode MPGPCoreFlatDirection(MPGPCore *c, Vec d, PetscReal dAd, PetscReal af, MPGPStatus *status)
{
  PetscReal dd;

  PetscFunctionBegin;
  if (PetscIsInfOrNanReal(dAd)) {
    *status = MPGPStatus::NOT_A_NUMBER;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(ReproducibleDot(d, d, &dd));
  if (dAd < -1e-10 * c->normA * dd) *status = MPGPStatus::INDEFINITE;
  else if (af >= PETSC_INFINITY) *status = MPGPStatus::UNBOUNDED;
  else *status = MPGPStatus::STOPPED;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Search direction after a restart: the free gradient, or its preconditioned version. */
static PetscErrorCode MPGPCoreRestartDirection(MPGPCore *c)
{
  PetscFunctionBegin;
  if (c->precondition) {
    PetscCall(MPGPCorePrecondition(c));
    PetscCall(VecCopy(c->z, c->p));
  } else PetscCall(VecCopy(c->phi, c->p));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MPGPCoreSolve(MPGPCore *c, Vec x)
{
  SeparableSplit s;
  PetscReal      alpha;
  PetscInt       it   = 0;
  PetscBool      stop = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCheck(c->normA > 0 && !PetscIsInfOrNanReal(c->normA), PetscObjectComm((PetscObject)x), PETSC_ERR_ARG_OUTOFRANGE, "MPGP: the norm estimate of A must be positive and finite, got %g",
             (double)c->normA);
  PetscCheck(c->alpha_scale > 0 && c->alpha_scale <= 2, PetscObjectComm((PetscObject)x), PETSC_ERR_ARG_OUTOFRANGE, "MPGP: step length factor %g is outside (0, 2]", (double)c->alpha_scale);
  PetscCheck(c->gamma > 0, PetscObjectComm((PetscObject)x), PETSC_ERR_ARG_OUTOFRANGE, "MPGP: proportioning parameter Gamma = %g must be positive", (double)c->gamma);
  PetscCall(MPGPCoreSetUp(c, x));
  if (c->precondition && !c->z) PetscCall(VecDuplicate(x, &c->z));
  if (c->projcg && !c->dx) PetscCall(VecDuplicate(x, &c->dx));
  PetscCall(PetscLogEventBegin(QP_Solve, 0, 0, 0, 0));
  alpha = c->alpha_scale / c->normA;
  if (!c->resume) c->counters->solves++;

  /* the initial guess is projected */
  PetscCall(SeparableSetProjectedStep_Private(c->set, x, 0.0, NULL, x));
  PetscCall(MPGPCoreGradient(c, x));
  PetscCall(MPGPCoreSplit(c, x, alpha, NULL, &s));
  PetscCall(MPGPCoreRestartDirection(c));
  c->status = MPGPStatus::STOPPED;
  c->f      = 0.5 * (s.xg - s.xb);
  c->gpnorm = PetscSqrtReal(s.gp2);
  if (!c->resume) PetscCall(c->report(c->report_ctx, it, c->f, c->gpnorm, 0.0, &stop));

  while (!stop) {
    PetscReal step;
    if (PetscIsInfOrNanReal(c->gpnorm) || PetscIsInfOrNanReal(c->f)) {
      c->status = MPGPStatus::NOT_A_NUMBER;
      break;
    }
    if (s.beta2 <= c->gamma * c->gamma * s.phitphi) { /* proportional: CG or expansion */
      if (c->bb) {                                    /* the iterate before this step, for the next Barzilai-Borwein length */
        PetscCall(VecCopy(x, c->xprev));
        PetscCall(VecCopy(c->g, c->gprev));
      }
      PetscReal pAp, gp, acg, af;
      PetscCall(MPGPCoreMult(c, c->p, c->Ap));
      PetscCall(ReproducibleDot2(c->Ap, c->p, c->g, c->p, &pAp, &gp));
      PetscCall(SeparableSetFeasibleStep_Private(c->set, x, c->p, &af));
      if (!(pAp > 0)) {
        MPGPStatus flat;
        PetscCall(MPGPCoreFlatDirection(c, c->p, pAp, af, &flat));
        if (flat != MPGPStatus::STOPPED) {
          c->status = flat;
          break;
        }
        acg = PETSC_INFINITY; /* q falls linearly along -p: go to the boundary (expansion) */
      } else acg = gp / pAp;
      if (acg <= af) { /* conjugate gradient step */
        PetscReal gamma_cg;
        PetscCall(ReproducibleAXPY(x, -acg, c->p));
        PetscCall(ReproducibleAXPY(c->g, -acg, c->Ap));
        PetscCall(MPGPCoreSplit(c, x, alpha, c->Ap, &s));
        if (c->precondition) {
          PetscReal zAp;
          PetscCall(MPGPCorePrecondition(c));
          PetscCall(ReproducibleDot(c->z, c->Ap, &zAp));
          gamma_cg = zAp / pAp;
          PetscCall(ReproducibleAYPX(c->p, -gamma_cg, c->z));
        } else {
          gamma_cg = s.phiAp / pAp;
          PetscCall(ReproducibleAYPX(c->p, -gamma_cg, c->phi));
        }
        step = acg;
        c->counters->cg_steps++;
      } else { /* expansion: feasible half step, then a projected step along the free gradient */
        PetscBool projected = PETSC_FALSE;
        if (c->projcg && acg < PETSC_INFINITY &&
            !PetscIsNanReal(acg)) { /* PETSC_INFINITY (a flat direction) is finite */ /* first try the projected full CG step; keep it if it beats the feasible half step */
          if (!c->bb) {
            PetscCall(VecCopy(x, c->xprev));
            PetscCall(VecCopy(c->g, c->gprev));
          }
          PetscCall(SeparableSetProjectedStep_Private(c->set, c->xprev, acg, c->p, x));
          PetscCall(MPGPCoreGradient(c, x));
          PetscCall(MPGPCoreSplit(c, x, alpha, NULL, &s));
          /* the changes of q, not q itself, are compared: late in a solve they are far below q's rounding.
             Step d: q(x + d) - q(x) = d'(g + g_new)/2; a tie (e.g. the same point) keeps the half step */
          PetscReal dg0, dg1;
          PetscCall(VecWAXPY(c->dx, -1.0, c->xprev, x));
          PetscCall(ReproducibleDot2(c->dx, c->gprev, c->dx, c->g, &dg0, &dg1));
          const PetscReal dnew = 0.5 * (dg0 + dg1), dhalf = 0.5 * af * af * pAp - af * gp;
          projected = (dnew <= dhalf * (1 + 1e-10) && !PetscIsInfOrNanReal(dnew) && !PetscIsInfOrNanReal(s.gp2)) ? PETSC_TRUE : PETSC_FALSE;
          PetscCall(PetscInfo(NULL, "expansion: projected CG step %g (to the boundary %g) changes q by %g, the half step by %g: %s\n", (double)acg, (double)af, (double)dnew, (double)dhalf,
                              projected ? "kept" : "not kept"));
          if (!projected) {
            c->projcg_rejected++;
            PetscCall(VecCopy(c->xprev, x));
            PetscCall(VecCopy(c->gprev, c->g));
          }
        }
        if (projected) step = acg;
        else {
          PetscCall(ReproducibleAXPY(x, -af, c->p));
          PetscCall(ReproducibleAXPY(c->g, -af, c->Ap));
          PetscCall(MPGPCoreSplit(c, x, alpha, NULL, &s));
          PetscCall(SeparableSetProjectedStep_Private(c->set, x, alpha, c->phi, x));
          PetscCall(MPGPCoreGradient(c, x));
          PetscCall(MPGPCoreSplit(c, x, alpha, NULL, &s));
          step = af;
        }
        PetscCall(MPGPCoreRestartDirection(c));
        c->counters->expansion_steps++;
      }
    } else { /* proportioning */
      if (c->variant == MPGPVariant::MPRGP) {
        PetscReal bAb, gb;
        PetscCall(MPGPCoreMult(c, c->beta, c->Ap));
        PetscCall(ReproducibleDot2(c->Ap, c->beta, c->g, c->beta, &bAb, &gb));
        /* the exact line search step leaves lower bounds inward, but with both bounds on an entry it
           can cross the opposite one: stop there (q still decreases, the step is shorter) */
        PetscReal af;
        PetscCall(SeparableSetFeasibleStep_Private(c->set, x, c->beta, &af));
        if (!(bAb > 0)) {
          MPGPStatus flat;
          PetscCall(MPGPCoreFlatDirection(c, c->beta, bAb, af, &flat));
          if (flat != MPGPStatus::STOPPED) {
            c->status = flat;
            break;
          }
        }
        step = bAb > 0 ? PetscMin(gb / bAb, af) : af;
        PetscCall(ReproducibleAXPY(x, -step, c->beta));
        PetscCall(ReproducibleAXPY(c->g, -step, c->Ap));
      } else {
        PetscReal abb = 0;
        if (c->bb && it > 0) { /* BB length from the last step s = x - x_prev: s's / s'y, y = g - g_prev = A s */
          PetscReal ss, sy;
          PetscCall(VecWAXPY(c->p, -1.0, c->xprev, x));
          PetscCall(VecWAXPY(c->Ap, -1.0, c->gprev, c->g));
          PetscCall(ReproducibleDot2(c->p, c->p, c->p, c->Ap, &ss, &sy));
          if (sy > 0 && ss > 0) abb = ss / sy;
        }
        PetscCall(VecCopy(x, c->xprev));
        PetscCall(VecCopy(c->g, c->gprev));
        step = alpha;
        if (abb > alpha) { /* keep the longer step only if it decreases q */
          const PetscReal f0 = c->f;
          PetscCall(SeparableSetProjectedStep_Private(c->set, c->xprev, abb, c->gprev, x));
          PetscCall(MPGPCoreGradient(c, x));
          PetscCall(MPGPCoreSplit(c, x, alpha, NULL, &s));
          if (0.5 * (s.xg - s.xb) < f0) step = abb;
          else c->bb_rejected++;
        }
        if (step == alpha) {
          PetscCall(SeparableSetProjectedStep_Private(c->set, c->xprev, alpha, c->gprev, x));
          PetscCall(MPGPCoreGradient(c, x));
        }
      }
      if (step == alpha || c->variant == MPGPVariant::MPRGP) PetscCall(MPGPCoreSplit(c, x, alpha, NULL, &s));
      PetscCall(MPGPCoreRestartDirection(c));
      c->counters->proportioning_steps++;
    }
    it++;
    c->counters->iterations++;
    {
      /* every step lowers q when alpha <= 2/||A||: a rise beyond the rounding of q's terms means the
         estimate of ||A|| is too small (e.g. a MATSHELL whose action changed without a new object state) */
      const PetscReal fnew = 0.5 * (s.xg - s.xb), noise = 1e-10 * (PetscAbsReal(s.xg) + PetscAbsReal(s.xb));
      if (fnew > c->f + noise) {
        PetscCall(PetscInfo(NULL, "MPGP: q rose from %g to %g in iteration %" PetscInt_FMT ": the norm estimate %g of A is too small\n", (double)c->f, (double)fnew, it, (double)c->normA));
        c->f      = fnew;
        c->gpnorm = PetscSqrtReal(s.gp2);
        c->status = MPGPStatus::NORM_TOO_SMALL;
        break;
      }
    }
    c->f      = 0.5 * (s.xg - s.xb);
    c->gpnorm = PetscSqrtReal(s.gp2);
    PetscCall(c->report(c->report_ctx, it, c->f, c->gpnorm, step, &stop));
  }
  c->its = it;
  PetscCall(PetscLogEventEnd(QP_Solve, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
