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
     fixed-length step adds a few: it pays on discretized PDE problems and not on random
     ill-conditioned QPs, where Dostal's proven expansion stays the default (docs/qp-benchmark.md). With
     a preconditioner the CG directions hit the boundary more often and the projected CG step matters
     more. With -tao_mpgp_expansion_lagged (TaoQPSetExpansionLagged()) a projected step with the last
     expansion's length is tried first, without the product A p (MPGPCoreLaggedExpansion()). With
     -tao_mpgp_expansion_lookahead k the projected CG step is taken from the point k more CG steps down the face,
     past the set, instead, and with -tao_mpgp_expansion_gradient from P(y - alpha g(y)) for the CG point y
     (MPGPCoreLookahead(); both off by default);
   - proportioning step when not proportional: along the chopped gradient with exact line search
     (MPRGP; cut at the opposite bound of a box), or a projected gradient step (MPGP, which is what curved
     boundaries need), of Kucera's fixed length alpha.
   Arc steps (MPGP, -tao_mpgp_arc a, default 1; 0 turns them off): a disk block on its circle with the gradient pushing
   outward (a slipping friction node) has a free direction too, along the circle. Kucera's split puts its
   whole projected gradient into the chopped gradient, so only the fixed-length projected steps move it
   (on the brick the slipping friction nodes then cost many proportioning steps; docs/brick-benchmark.md,
   'Arc steps'). Here such a block counts as free along the circle (its tangential gradient is in phi,
   see SeparableSetSplitGradient_Private()) and CG steps move it: the direction is made tangent there, the step x - a p is retracted onto the circle by the
   projection, and its second derivative in a is p'Ap + p'Wp, W the circle's curvature 1/r times the outward
   push |g.nu| (conjugate gradients on the curved face, with the step length and conjugacy of A + W). A
   block held much more firmly than ||A|| (alpha |g.nu|/r > arc) stays with the projected steps, which
   already scale its move by 1/(1 + alpha |g.nu|/r), and would make A + W ill conditioned. The gradient
   after an arc step is updated, g - a Ap, and misses A d for the retraction d (second order in the step):
   its error is bounded by drift = ||A|| sum |d|. With that bound every step keeps q from rising: an arc
   step whose upper bound on q's change is not negative is replaced by a projected gradient step, and a
   fixed-length step taken from an updated gradient is certified afterwards (or taken again from the exact
   gradient); the stopping test only ever accepts the exact gradient (a provisional test first, then one
   product). Arc steps save products on the brick and on the disks QP and can cost some on random
   ill-conditioned disk QPs (docs/brick-benchmark.md, 'Arc steps'; docs/qp-benchmark.md).
   With -tao_mpgp_bb the proportioning step first tries the Barzilai-Borwein length s's/s'(As) of the last
     step (free: As = g - g_prev for a QP) and keeps it only if q decreased. BB shortens long runs of
     proportioning steps on random cone problems but costs products on the brick's friction disks
     (docs/qp-benchmark.md), so it is off by default.
   Math: docs/algorithms.md, 'MPRGP and MPGP'. */
#include <conefeti/private/mpgpcore.h>
#include <conefeti/private/operatortest.h>
#include <conefeti/private/reproduciblesum.h>

PetscLogEvent QP_HessianMult, QP_Solve, QP_NormEstimate, QP_Precondition, QP_Feasibility, QP_MultiplierUpdate, QP_VecReproducible;

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
  c->updated  = PETSC_FALSE;
  c->drift    = 0;
  c->recurred = 0;
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

/* After a solve that failed in a way a non-symmetric A explains: CG's recurrences, its step lengths and the
   decrease of q all assume A = A', and with a non-symmetric A the solve ended with a curvature, an unbounded
   direction, a rise of q or a drifted gradient that blamed semidefiniteness or the norm estimate. Two products
   test A (counted as products); if it is not symmetric that is the cause (NOT_SYMMETRIC). Never after a
   successful solve, whose counts are documented. */
PetscErrorCode MPGPCoreDiagnose(MPGPCore *c)
{
  MatSymmetryTest t;

  PetscFunctionBegin;
  if (c->status != MPGPStatus::INDEFINITE && c->status != MPGPStatus::UNBOUNDED && c->status != MPGPStatus::NORM_TOO_SMALL && c->status != MPGPStatus::ACCURACY_FLOOR)
    PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(MatTestSymmetry_Private(c->A, c->normA, &t));
  if (c->counters) c->counters->hessian_mults += 2;
  if (!t.symmetric) {
    c->status          = MPGPStatus::NOT_SYMMETRIC;
    c->asymmetry       = t.asymmetry;
    c->asymmetry_scale = t.scale;
  }
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
  PetscCall(VecDestroy(&c->Wp));
  PetscCall(VecDestroy(&c->ApW));
  PetscCall(VecDestroy(&c->xsave));
  PetscCall(VecDestroy(&c->gsave));
  PetscCall(VecDestroy(&c->psave));
  PetscCall(VecDestroy(&c->Apsave));
  PetscCall(VecDestroy(&c->wt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Computes phi, beta and the sums at (x, g); Ap may be NULL. keep: after a CG step, the arc blocks stay those
   of the last split (the face of a CG run is fixed, as for MPRGP's free set) */
static PetscErrorCode MPGPCoreSplitKeep(MPGPCore *c, Vec x, PetscReal alpha, Vec Ap, PetscBool keep, SeparableSplit *s)
{
  PetscFunctionBegin;
  PetscCall(SeparableSetSplitGradient_Private(c->set, x, c->g, alpha, c->variant == MPGPVariant::MPGP ? c->arc : 0.0, keep, c->phi, c->beta, Ap, c->b, s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode MPGPCoreSplit(MPGPCore *c, Vec x, PetscReal alpha, Vec Ap, SeparableSplit *s)
{
  PetscFunctionBegin;
  PetscCall(MPGPCoreSplitKeep(c, x, alpha, Ap, PETSC_FALSE, s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* z = [M^-1]_FF phi_F at the point of the last split (preconditioning in face) */
static PetscErrorCode MPGPCorePrecondition(MPGPCore *c)
{
  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(QP_Precondition, 0, 0, 0, 0));
  PetscCall(c->precondition(c->precondition_ctx, c->phi, c->z));
  PetscCall(SeparableSetMaskFree_Private(c->set, c->z));
  PetscCall(PetscLogEventEnd(QP_Precondition, 0, 0, 0, 0));
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

/* Whether the curvature d'Ad of a direction is zero up to rounding (<= 1e-13 ||A|| |d|^2: rounding leaves about
   1e-16 on a kernel vector, a condition number of 1e12 leaves 1e-12) or negative. A tiny positive d'Ad (b outside the range of a singular A) gave a step
   of 1e30 and then "the norm estimate is too small" instead of "unbounded below". |d|^2 costs a reduction, so
   it is computed only for a step longer than 1e8 / ||A|| (the ratio a condition number below 1e8 keeps under) */
static PetscErrorCode MPGPCoreIsFlat(MPGPCore *c, Vec d, PetscReal dAd, PetscReal gd, PetscBool *flat)
{
  PetscReal dd;

  PetscFunctionBegin;
  *flat = (PetscBool) !(dAd > 0);
  if (*flat || !(PetscAbsReal(gd) > 1e8 / c->normA * dAd)) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(ReproducibleDot(d, d, &dd));
  *flat = (PetscBool)(dAd <= 1e-13 * c->normA * dd);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Search direction after a restart: the free gradient, or its preconditioned version. The preconditioned one is
   left pending: a proportioning step or the stop may follow, which do not use it, and an application can cost
   as much as a product with A (a FETI Dirichlet preconditioner). The split (phi) does not change before the next
   step, which computes it (MPGPCoreDirection()): the same direction, fewer applications. */
static PetscErrorCode MPGPCoreRestartDirection(MPGPCore *c)
{
  PetscFunctionBegin;
  if (c->precondition) c->pending = PETSC_TRUE;
  else PetscCall(VecCopy(c->phi, c->p));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The search direction before a CG or expansion step uses it */
static PetscErrorCode MPGPCoreDirection(MPGPCore *c)
{
  PetscFunctionBegin;
  if (c->pending) {
    PetscCall(MPGPCorePrecondition(c));
    PetscCall(VecCopy(c->z, c->p));
    c->pending = PETSC_FALSE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The exact gradient after steps along arcs (MPGPCoreSolve()), with the split, q and a new CG direction. */
static PetscErrorCode MPGPCoreRefreshGradient(MPGPCore *c, Vec x, PetscReal alpha, SeparableSplit *s, PetscInt *count)
{
  PetscFunctionBegin;
  PetscCall(MPGPCoreGradient(c, x));
  PetscCall(MPGPCoreSplit(c, x, alpha, NULL, s));
  PetscCall(MPGPCoreRestartDirection(c));
  c->f      = 0.5 * (s->xg - s->xb);
  c->gpnorm = PetscSqrtReal(s->gp2);
  (*count)++; /* arc_refreshed, or verified: a stop confirmed */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Kucera's projected gradient step x = P(x - alpha g) from the gradient in c->g, then the exact gradient,
   the split and a new CG direction at the new x (the fallback of arc steps that may raise q). */
static PetscErrorCode MPGPCoreProjectedGradientStep(MPGPCore *c, Vec x, PetscReal alpha, SeparableSplit *s)
{
  PetscFunctionBegin;
  PetscCall(SeparableSetProjectedStep_Private(c->set, x, alpha, c->g, x));
  PetscCall(MPGPCoreGradient(c, x));
  PetscCall(MPGPCoreSplit(c, x, alpha, NULL, s));
  PetscCall(MPGPCoreRestartDirection(c));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Lagged expansion (-tao_mpgp_expansion_lagged, with the projected CG expansion): the projected step P(x - a p)
   along the (preconditioned) direction p with a length a from the last expansion instead of its own CG length
   g'p/p'Ap, so without the product A p: one product per step instead of two. While the active set is being
   found, successive expansions are steepest descent steps in the preconditioner's metric, whose CG lengths vary
   little (on the brick's dual contact problem 0.1-0.2 of c/||F|| for tens of steps), and a lagged length is what
   Barzilai and Borwein use for steepest descent. Tried only where it crosses the boundary (the feasible step along
   p is shorter than a: an expansion would follow anyway; a CG run stops the lagging) and kept when q falls: the
   change of q along the step d is d'(g + g_new)/2, and its exact line minimum t = -d'g/d'(g_new - g) of d (a QP)
   scales the next length, within [1/2, 2]. Otherwise x and g are restored and the ordinary expansion follows
   (one product lost). Measurements: docs/scale.md, "Lever: the early outer iterations". */
static PetscErrorCode MPGPCoreLaggedExpansion(MPGPCore *c, Vec x, PetscReal alpha, PetscReal qnoise, SeparableSplit *s, PetscBool *kept)
{
  PetscReal af, dg0, dg1;

  PetscFunctionBegin;
  *kept = PETSC_FALSE;
  PetscCall(SeparableSetFeasibleStep_Private(c->set, x, c->p, &af));
  if (!(af < c->lag)) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecCopy(x, c->xprev));
  PetscCall(VecCopy(c->g, c->gprev));
  PetscCall(SeparableSetProjectedStep_Private(c->set, c->xprev, c->lag, c->p, x));
  PetscCall(MPGPCoreGradient(c, x));
  PetscCall(MPGPCoreSplit(c, x, alpha, NULL, s));
  PetscCall(VecWAXPY(c->dx, -1.0, c->xprev, x));
  PetscCall(ReproducibleDot2(c->dx, c->gprev, c->dx, c->g, &dg0, &dg1));
  const PetscReal dq = 0.5 * (dg0 + dg1);
  *kept              = (dq < -qnoise && !PetscIsInfOrNanReal(dq) && !PetscIsInfOrNanReal(s->gp2)) ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscInfo(NULL, "expansion: lagged projected step %g (to the boundary %g) changes q by %g: %s\n", (double)c->lag, (double)af, (double)dq, *kept ? "kept" : "not kept"));
  c->lag_used = c->lag;
  if (*kept) {
    c->lagged_steps++;
    if (dg1 > dg0) { /* the next length: the exact line minimum along the step taken is at t = -dg0/(dg1 - dg0) of it */
      const PetscReal t = -dg0 / (dg1 - dg0);
      c->lag *= PetscMin(PetscMax(t, 0.5), 2.0);
    }
  } else {
    c->lagged_rejected++;
    c->lag = 0;
    PetscCall(VecCopy(c->xprev, x));
    PetscCall(VecCopy(c->gprev, c->g));
    PetscCall(MPGPCoreSplit(c, x, alpha, NULL, s));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Look-ahead expansion (-tao_mpgp_expansion_lookahead k, with the projected CG expansion): where the CG step along p
   would leave the set, the projected CG step P(x - a_cg p) is replaced by P(y), y the point k more CG steps down
   the face from x - a_cg p, the set ignored on the way (the free entries of the last split stay free, the others
   fixed). Why: near a moving contact boundary a single projected step adds the row of multipliers that the
   step pushes out of the set, then CG restarts in the new face and pushes out the next row; on the frictionless
   brick the number of such expansions doubled when h halved (docs/scale.md, "Lever: a look-ahead expansion").
   k CG steps that ignore the set solve the face problem further before the projection cuts it, and can
   cut several rows at once, as a primal-dual active-set step would. The caller keeps P(y) only when q
   there is no higher than at the feasible half step (the same test as the projected CG step's), so q never rises;
   a rejected look-ahead costs its k + 1 products. Arc blocks (slipping disk blocks, free along their circle) move
   along the tangent of their circle at x, with the circle's curvature in the step lengths (as in arc CG steps),
   and the projection retracts them. With -tao_mpgp_expansion_gradient the projection is P(y - alpha g(y)), g(y)
   updated along the steps without a product (also with k = 0: the gradient step alone). On entry x = xprev,
   g = gprev, p and Ap (and Wp for arcs) are those of the rejected CG step of length acg, pHp its curvature; on
   return x is the tried point and g its exact gradient, and for k > 0 psave and Apsave hold p and Ap for the half
   step of a rejection. */
static PetscErrorCode MPGPCoreLookahead(MPGPCore *c, Vec x, PetscReal acg, PetscReal pHp, PetscBool arcs, PetscReal alpha)
{
  Vec             Aq            = c->Ap;                            /* the conjugacy's product: A p, or (A + W) p with arcs */
  const PetscReal gradient_step = c->projcg_gradient ? alpha : 0.0; /* -tao_mpgp_expansion_gradient: P(y - alpha g(y)) */
  PetscReal       unused;

  PetscFunctionBegin;
  if (c->lookahead > 0) {
    PetscCall(VecCopy(c->p, c->psave));
    PetscCall(VecCopy(c->Ap, c->Apsave));
  }
  PetscCall(ReproducibleAXPY(x, -acg, c->p));
  PetscCall(ReproducibleAXPY(c->g, -acg, c->Ap));
  c->recurred++;
  if (arcs) {
    PetscCall(VecWAXPY(c->ApW, 1.0, c->Ap, c->Wp));
    Aq = c->ApW;
  }
  for (PetscInt j = 0; j < c->lookahead; j++) {
    PetscReal gamma_cg, pAp, gp, pWp = 0;
    /* the face's gradient at the current point: its free entries, tangential on arc blocks */
    PetscCall(VecCopy(c->g, c->phi));
    PetscCall(SeparableSetMaskFree_Private(c->set, c->phi));
    if (arcs) PetscCall(SeparableSetArcTangent_Private(c->set, c->xprev, c->phi, c->wt, &unused));
    if (c->precondition) {
      PetscReal zAq;
      PetscCall(MPGPCorePrecondition(c));
      if (arcs) PetscCall(SeparableSetArcTangent_Private(c->set, c->xprev, c->z, c->wt, &unused));
      PetscCall(ReproducibleDot(c->z, Aq, &zAq));
      gamma_cg = zAq / pHp;
      PetscCall(ReproducibleAYPX(c->p, -gamma_cg, c->z));
    } else {
      PetscReal rAq;
      PetscCall(ReproducibleDot(c->phi, Aq, &rAq));
      gamma_cg = rAq / pHp;
      PetscCall(ReproducibleAYPX(c->p, -gamma_cg, c->phi));
    }
    if (arcs) PetscCall(SeparableSetArcTangent_Private(c->set, c->xprev, c->p, c->Wp, &pWp));
    PetscCall(MPGPCoreMult(c, c->p, c->Ap));
    PetscCall(ReproducibleDot2(c->Ap, c->p, c->g, c->p, &pAp, &gp));
    if (!(pAp + pWp > 0) || PetscIsInfOrNanReal(gp)) break; /* flat or broken: project what there is (the caller's test decides) */
    pHp = pAp + pWp;
    PetscCall(ReproducibleAXPY(x, -gp / pHp, c->p));
    PetscCall(ReproducibleAXPY(c->g, -gp / pHp, c->Ap));
    c->recurred++;
    if (arcs) PetscCall(VecWAXPY(c->ApW, 1.0, c->Ap, c->Wp));
  }
  PetscCall(SeparableSetProjectedStep_Private(c->set, x, gradient_step, c->projcg_gradient ? c->g : NULL, x));
  PetscCall(MPGPCoreGradient(c, x));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* After a solve: the projected gradient of x from the exact gradient A x - b, recomputed (one product) when the
   solve ended on a recurred or updated one; the owner's test decides whether that one is small enough */
PetscErrorCode MPGPCoreConfirmGradient(MPGPCore *c, Vec x, PetscReal *gpnorm)
{
  PetscFunctionBegin;
  if (c->recurred > 0 || c->updated) {
    SeparableSplit s;
    PetscCall(MPGPCoreRefreshGradient(c, x, c->alpha_scale / c->normA, &s, &c->verified));
  }
  *gpnorm = c->gpnorm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MPGPCoreSolve(MPGPCore *c, Vec x)
{
  SeparableSplit s;
  PetscReal      alpha;
  PetscInt       it   = 0;
  PetscBool      stop = PETSC_FALSE;
  QPRefusedStops refused; /* verify: the stops the exact gradient refused */

  PetscFunctionBegin;
  PetscCheck(c->normA > 0 && !PetscIsInfOrNanReal(c->normA), PetscObjectComm((PetscObject)x), PETSC_ERR_ARG_OUTOFRANGE, "MPGP: the norm estimate of A must be positive and finite, got %g",
             (double)c->normA);
  PetscCheck(c->alpha_scale > 0 && c->alpha_scale <= 2, PetscObjectComm((PetscObject)x), PETSC_ERR_ARG_OUTOFRANGE, "MPGP: step length factor %g is outside (0, 2]", (double)c->alpha_scale);
  PetscCheck(c->gamma > 0, PetscObjectComm((PetscObject)x), PETSC_ERR_ARG_OUTOFRANGE, "MPGP: proportioning parameter Gamma = %g must be positive", (double)c->gamma);
  PetscCheck(c->arc >= 0 && !PetscIsInfOrNanReal(c->arc), PetscObjectComm((PetscObject)x), PETSC_ERR_ARG_OUTOFRANGE, "MPGP: the curvature bound of arc steps must be finite and >= 0, got %g",
             (double)c->arc);
  PetscCall(MPGPCoreSetUp(c, x));
  c->pending = PETSC_FALSE;
  if (c->precondition && !c->z) PetscCall(VecDuplicate(x, &c->z));
  if (c->projcg && !c->dx) PetscCall(VecDuplicate(x, &c->dx));
  PetscCheck(c->lookahead >= 0, PetscObjectComm((PetscObject)x), PETSC_ERR_ARG_OUTOFRANGE, "MPGP: the look-ahead of projected CG expansions must be >= 0 CG steps, got %" PetscInt_FMT, c->lookahead);
  if (c->projcg && c->lookahead > 0 && !c->psave) {
    PetscCall(VecDuplicate(x, &c->psave));
    PetscCall(VecDuplicate(x, &c->Apsave));
    PetscCall(VecDuplicate(x, &c->wt));
  }
  if (c->variant == MPGPVariant::MPGP && c->arc > 0 && !c->Wp) {
    PetscCall(VecDuplicate(x, &c->Wp));
    PetscCall(VecDuplicate(x, &c->ApW));
    PetscCall(VecDuplicate(x, &c->xsave));
    PetscCall(VecDuplicate(x, &c->gsave));
  }
  PetscCall(PetscLogEventBegin(QP_Solve, 0, 0, 0, 0));
  alpha  = c->alpha_scale / c->normA;
  c->lag = 0;
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
    const PetscReal qnoise  = 1e-10 * (PetscAbsReal(s.xg) + PetscAbsReal(s.xb)); /* the rounding of q's terms at x (below: changes of q smaller than that say nothing) */
    const PetscBool updated = c->updated;                                        /* this step starts from an updated gradient (after steps along arcs) */
    const PetscReal drift   = c->drift;
    PetscBool       cg_step = PETSC_FALSE, arc_half = PETSC_FALSE, exact = PETSC_FALSE; /* exact: a projected step from the exact gradient */
    if (updated || s.narc > 0) {                                                        /* for the certificate of a fixed-length step (below) */
      PetscCall(VecCopy(x, c->xsave));
      PetscCall(VecCopy(c->g, c->gsave));
    }
    if (s.beta2 <= c->gamma * c->gamma * s.phitphi) { /* proportional: CG or expansion */
      if (c->bb) {                                    /* the iterate before this step, for the next Barzilai-Borwein length */
        PetscCall(VecCopy(x, c->xprev));
        PetscCall(VecCopy(c->g, c->gprev));
      }
      PetscReal pAp, pWp = 0, gp, acg, af;
      PetscBool lagged = PETSC_FALSE;
      PetscCall(MPGPCoreDirection(c));
      if (s.narc > 0) PetscCall(SeparableSetArcTangent_Private(c->set, x, c->p, c->Wp, &pWp));
      if (c->lag > 0 && !updated) PetscCall(MPGPCoreLaggedExpansion(c, x, alpha, qnoise, &s, &lagged));
      if (lagged) {
        step = c->lag_used;
        PetscCall(MPGPCoreRestartDirection(c));
        c->counters->expansion_steps++;
      } else {
        PetscCall(MPGPCoreMult(c, c->p, c->Ap));
        PetscCall(ReproducibleDot2(c->Ap, c->p, c->g, c->p, &pAp, &gp));
        PetscCall(SeparableSetFeasibleStep_Private(c->set, x, c->p, &af));
        const PetscReal pHp = pAp + pWp; /* the second derivative of q along the (retracted) step */
        PetscBool       flat_p;
        PetscCall(MPGPCoreIsFlat(c, c->p, pHp, gp, &flat_p));
        if (flat_p) {
          MPGPStatus flat;
          PetscCall(MPGPCoreFlatDirection(c, c->p, pHp, af, &flat));
          if (flat != MPGPStatus::STOPPED) {
            c->status = flat;
            break;
          }
          acg = PETSC_INFINITY; /* q falls linearly along -p: go to the boundary (expansion) */
        } else acg = gp / pHp;
        /* with arc blocks p is tangent there and af ignores them: every step along p is retracted (also where W is 0) */
        const PetscBool along_arcs = s.narc > 0 ? PETSC_TRUE : PETSC_FALSE;
        PetscReal       dd_arc     = 0;
        PetscBool       rejected   = (s.narc > 0 && !(gp > 0)) ? PETSC_TRUE : PETSC_FALSE; /* made tangent, -p does not descend (rounding, an updated gradient) */
        if (acg <= af && along_arcs && !rejected) {
          /* q at the retracted point P(x - a p) = x - a p + d is bounded above by the second-order expansion with
             ||A|| for d'Ad (SeparableSetArcRetraction_Private()), plus |e| |d - a p| for the error e of an updated
             gradient: a step that may not lower q (the arc too long for the model) is not taken */
          PetscReal dg, dd, pp;
          PetscCall(SeparableSetArcRetraction_Private(c->set, x, acg, c->p, c->g, c->Ap, &dg, &dd));
          dd_arc = dd;
          PetscCall(ReproducibleDot(c->p, c->p, &pp));
          const PetscReal dq = -acg * gp + 0.5 * acg * acg * pAp + dg + 0.5 * c->normA * dd + drift * (acg * PetscSqrtReal(pp) + PetscSqrtReal(dd));
          rejected           = dq <= qnoise ? PETSC_FALSE : PETSC_TRUE;
          if (rejected) PetscCall(PetscInfo(NULL, "MPGP: a CG step along arcs may raise q (bound %g): a projected gradient step instead\n", (double)dq));
          else c->drift += c->normA * PetscSqrtReal(dd); /* the gradient update below misses A d, |A d| <= ||A|| |d| */
        }
        if (rejected) c->arc_rejected++;
        if (acg <= af && !rejected) { /* conjugate gradient step */
          PetscReal gamma_cg;
          Vec       Aq = along_arcs ? c->ApW : c->Ap; /* conjugacy with respect to A + W */
          PetscCall(ReproducibleAXPY(x, -acg, c->p));
          PetscCall(ReproducibleAXPY(c->g, -acg, c->Ap));
          c->recurred++;
          if (along_arcs) { /* back onto the circles: the gradient is now updated, not exact */
            PetscCall(SeparableSetProjectedStep_Private(c->set, x, 0.0, NULL, x));
            PetscCall(VecWAXPY(c->ApW, 1.0, c->Ap, c->Wp));
            if (dd_arc > 0) c->updated = PETSC_TRUE;
            c->arc_steps++;
          }
          PetscCall(MPGPCoreSplitKeep(c, x, alpha, Aq, PETSC_TRUE, &s));
          if (c->precondition) {
            PetscReal zAp, unused;
            PetscCall(MPGPCorePrecondition(c));
            /* the next direction is made tangent on the arc blocks (SeparableSetArcTangent_Private() before the next
               step), so its conjugacy must be that of the tangent part of z: with z itself, the part of z across the
               circles entered gamma and the directions lost their conjugacy (PCG stalled for 10^4 steps per inner
               solve on a stiff block pressed on a thin slab: scripts/fuzz-scenes.py --seed 1, scene 241) */
            if (s.narc > 0) PetscCall(SeparableSetArcTangent_Private(c->set, x, c->z, c->Wp, &unused));
            PetscCall(ReproducibleDot(c->z, Aq, &zAp));
            gamma_cg = zAp / pHp;
            PetscCall(ReproducibleAYPX(c->p, -gamma_cg, c->z));
          } else {
            gamma_cg = s.phiAp / pHp;
            PetscCall(ReproducibleAYPX(c->p, -gamma_cg, c->phi));
          }
          step    = acg;
          cg_step = PETSC_TRUE;
          c->lag  = 0; /* a CG run: the face holds, no lagged expansion until the next expansion */
          c->counters->cg_steps++;
        } else if (rejected) { /* Kucera's projected gradient step, from the exact gradient */
          if (c->updated) PetscCall(MPGPCoreRefreshGradient(c, x, alpha, &s, &c->arc_refreshed));
          PetscCall(MPGPCoreProjectedGradientStep(c, x, alpha, &s));
          step  = alpha;
          exact = PETSC_TRUE;
          c->counters->proportioning_steps++;
        } else { /* expansion: feasible half step, then a projected step along the free gradient */
          PetscBool projected = PETSC_FALSE;
          if (c->projcg && acg < PETSC_INFINITY &&
              !PetscIsNanReal(acg)) { /* PETSC_INFINITY (a flat direction) is finite */ /* first try the projected full CG step; keep it if it beats the feasible half step */
            if (!c->bb) {
              PetscCall(VecCopy(x, c->xprev));
              PetscCall(VecCopy(c->g, c->gprev));
            }
            const PetscBool lookahead = c->lookahead > 0 ? PETSC_TRUE : PETSC_FALSE;
            if (lookahead || c->projcg_gradient) PetscCall(MPGPCoreLookahead(c, x, acg, pHp, along_arcs, alpha));
            else {
              PetscCall(SeparableSetProjectedStep_Private(c->set, c->xprev, acg, c->p, x));
              PetscCall(MPGPCoreGradient(c, x));
            }
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
            if (lookahead) {
              PetscCall(PetscInfo(NULL, "expansion: the projected CG step looked %" PetscInt_FMT " CG steps ahead: %s\n", c->lookahead, projected ? "kept" : "not kept"));
              if (projected) c->lookahead_kept++;
              else {
                c->lookahead_rejected++;
                PetscCall(VecCopy(c->psave, c->p)); /* the half step below goes along the first direction */
                PetscCall(VecCopy(c->Apsave, c->Ap));
              }
            }
            if (!projected) {
              c->projcg_rejected++;
              PetscCall(VecCopy(c->xprev, x));
              PetscCall(VecCopy(c->gprev, c->g));
            }
          }
          if (projected) {
            step = acg;
            if (c->lagged && af < acg) c->lag = acg; /* the next expansions may reuse this length without its product (also after a kept look-ahead: a lagged try has its own q test) */
          } else {
            PetscCall(ReproducibleAXPY(x, -af, c->p));
            PetscCall(ReproducibleAXPY(c->g, -af, c->Ap));
            c->recurred++;
            if (along_arcs) { /* the half step moved arc blocks along their tangent: back onto the circles (g is updated) */
              PetscCall(SeparableSetProjectedStep_Private(c->set, x, 0.0, NULL, x));
              arc_half = PETSC_TRUE;
            }
            PetscCall(MPGPCoreSplit(c, x, alpha, NULL, &s));
            PetscCall(SeparableSetProjectedStep_Private(c->set, x, alpha, c->phi, x));
            PetscCall(MPGPCoreGradient(c, x));
            PetscCall(MPGPCoreSplit(c, x, alpha, NULL, &s));
            step = af;
          }
          PetscCall(MPGPCoreRestartDirection(c));
          c->counters->expansion_steps++;
        }
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
        PetscBool flat_b;
        PetscCall(MPGPCoreIsFlat(c, c->beta, bAb, gb, &flat_b));
        if (flat_b) {
          MPGPStatus flat;
          PetscCall(MPGPCoreFlatDirection(c, c->beta, bAb, af, &flat));
          if (flat != MPGPStatus::STOPPED) {
            c->status = flat;
            break;
          }
        }
        step = !flat_b ? PetscMin(gb / bAb, af) : af;
        PetscCall(ReproducibleAXPY(x, -step, c->beta));
        PetscCall(ReproducibleAXPY(c->g, -step, c->Ap));
        c->recurred++;
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
    PetscBool fallback = PETSC_FALSE;
    if (!cg_step && !exact && (updated || arc_half)) {
      /* a fixed-length step from an updated gradient g~ (error e, |e| <= drift), or whose half step was retracted
         onto circles, ends at the exact gradient g1. Its step d changes q by d.(g~ + e + g1)/2 <= d.(g~ + g1)/2 +
         |d| drift/2: unless that bound is not positive, the step is undone and Kucera's projected gradient step
         from the exact gradient taken instead */
      PetscReal t1, t0, dd;
      PetscCall(VecAYPX(c->xsave, -1.0, x)); /* d */
      PetscCall(ReproducibleDot2(c->xsave, c->g, c->xsave, c->gsave, &t1, &t0));
      PetscCall(ReproducibleDot(c->xsave, c->xsave, &dd));
      const PetscReal dq = 0.5 * (t0 + t1) + 0.5 * PetscSqrtReal(dd) * drift;
      if (!(dq <= qnoise)) {
        PetscCall(PetscInfo(NULL, "MPGP: a step from an updated gradient or along arcs may have raised q (bound %g): a projected gradient step instead\n", (double)dq));
        PetscCall(VecAXPY(x, -1.0, c->xsave));
        if (updated) PetscCall(MPGPCoreRefreshGradient(c, x, alpha, &s, &c->arc_refreshed));
        else {
          PetscCall(VecCopy(c->gsave, c->g));
          PetscCall(MPGPCoreSplit(c, x, alpha, NULL, &s));
          c->f = 0.5 * (s.xg - s.xb);
        }
        PetscCall(MPGPCoreProjectedGradientStep(c, x, alpha, &s));
        c->arc_rejected++;
        fallback = PETSC_TRUE;
      }
    }
    it++;
    c->counters->iterations++;
    {
      /* every step lowers q when alpha <= 2/||A||: a rise beyond the rounding of q's terms means the
         estimate of ||A|| is too small (e.g. a MATSHELL whose action changed without a new object state).
         Steps from or to an updated gradient know q only to second order: the certificates above watch them */
      const PetscReal fnew = 0.5 * (s.xg - s.xb), noise = 1e-10 * (PetscAbsReal(s.xg) + PetscAbsReal(s.xb));
      if (((!updated && !arc_half) || exact || fallback) && !c->updated && fnew > c->f + noise) {
        PetscCall(PetscInfo(NULL, "MPGP: q rose from %g to %g in iteration %" PetscInt_FMT ": the norm estimate %g of A is too small\n", (double)c->f, (double)fnew, it, (double)c->normA));
        c->f      = fnew;
        c->gpnorm = PetscSqrtReal(s.gp2);
        c->status = MPGPStatus::NORM_TOO_SMALL;
        break;
      }
    }
    c->f                = 0.5 * (s.xg - s.xb);
    c->gpnorm           = PetscSqrtReal(s.gp2);
    PetscBool verifying = PETSC_FALSE;
    if (c->updated || (c->verify && c->recurred > 0)) { /* the solve stops only on the exact gradient: ask whether it may, and if so recompute it */
      PetscBool may_stop;
      c->provisional = PETSC_TRUE;
      PetscCall(c->report(c->report_ctx, it, c->f, c->gpnorm, step, &may_stop));
      c->provisional = PETSC_FALSE;
      if (may_stop) {
        verifying = (PetscBool)!c->updated;
        PetscCall(MPGPCoreRefreshGradient(c, x, alpha, &s, verifying ? &c->verified : &c->arc_refreshed));
      }
    }
    PetscCall(c->report(c->report_ctx, it, c->f, c->gpnorm, step, &stop));
    if (verifying && !stop) {
      /* the recurred gradient met the test, the exact one did not: go on from the exact one (a restarted direction).
         Where rounding sets a floor (A ill conditioned), the exact |gP| stops falling: after three refusals without
         halving it, say so rather than run to the iteration limit */
      c->verify_failed++;
      if (refused.AtFloor(c->gpnorm)) {
        c->status = MPGPStatus::ACCURACY_FLOOR;
        break;
      }
    }
  }
  /* a stop other than the convergence test (a flat direction, a rise of q) may leave an updated gradient */
  if (c->updated && c->status != MPGPStatus::NOT_A_NUMBER) PetscCall(MPGPCoreRefreshGradient(c, x, alpha, &s, &c->arc_refreshed));
  c->its = it;
  PetscCall(PetscLogEventEnd(QP_Solve, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
