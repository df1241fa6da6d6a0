/* TAO type smalxe: min 1/2 x'Ax - b'x over a SeparableSet subject to C x = d, by Dostal's
   semi-monotonic augmented Lagrangian (SMALBE) with adaptive precision of the inner solves.

   L(x, mu, rho) = q(x) + mu'(Cx - d) + rho/2 |Cx - d|^2.
   Outer iteration k: minimize L(., mu_k, rho_k) over the set until |gP| <= min(M_k |Cx - d|, eta);
   mu_{k+1} = mu_k + rho_k (Cx - d); if L did not grow by at least rho_k/2 |Cx - d|^2, lower M
   (SMALBE-M, default) or raise rho (SMALBE).

   Projector form (C with orthonormal rows, Q = C'C, P = I - Q, x~ = Q x~ with C x~ = d): the
   inner Hessian is PAP + rho Q, whose norm is max(|PAP|, rho) and which is well conditioned on
   the feasible affine space (FETI: Farhat-Mandel-Roux). In that form the inner problem is written
   in x directly: min 1/2 x'Hx - x'(rho x~ + P(b - A x~) - nu), nu = C'mu, so the feasible set
   needs no translation.

   The inner minimization is one nested TAO (mprgp/mpgp), or a block Gauss-Seidel sweep over
   index sets, each block with its own nested TAO (the seed paper's Algorithm 2 splits the
   multipliers this way). A pre-solve hook runs before every inner solve (the Coulomb friction
   loop updates disk radii there). Math: docs/algorithms.md, 'SMALXE: the semi-monotonic augmented Lagrangian'.

   Penalty preconditioner (projector form, one inner solver): the CG steps of the inner solve are
   preconditioned in face by M^-1 = I - theta Q, theta = rho/(||PAP|| + rho), the inverse of
   (||PAP|| I + rho Q)/||PAP|| restricted to the free set. rho Q adds a rank-m term (m equality rows,
   the rigid modes in FETI) at the top of the spectrum that the active set mixes with PAP's; M^-1
   pulls it back for the price of one product with Q. */
#include <conefeti.h>
#include <conefeti/private/mpgpcore.h>
#include <conefeti/private/operatortest.h>
#include <conefeti/private/qpadopt.h>
#include <conefeti/private/reproduciblesum.h>
#include <petsc/private/taoimpl.h>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace {

enum SMALXEUpdate {
  SMALXE_UPDATE_M,
  SMALXE_UPDATE_RHO,
  SMALXE_UPDATE_NONE
};
const char *const SMALXEUpdates[] = {"M", "rho", "none", "SMALXEUpdate", "SMALXE_UPDATE_", NULL};

struct SMALXEBlock {
  IS          is      = nullptr; /* NULL: the whole vector (monolithic inner solve) */
  Tao         sub     = nullptr;
  Mat         H       = nullptr; /* this block of the inner Hessian (owned only when is != NULL) */
  Vec         x       = nullptr; /* block of the solution (owned only when is != NULL) */
  Vec         b       = nullptr; /* linear term of the block problem */
  VecScatter  scatter = nullptr; /* full vector -> block */
  std::string suffix;            /* of its options prefix after ours */
  std::string prefix;            /* the options prefix we gave it (a prefix the user gives it instead is kept) */

  PetscObjectState set_version = 0; /* of the parent set when the block's subset was copied from it */
};

struct TaoSMALXE {
  Tao tao = nullptr;

  /* the problem */
  Vec          b         = nullptr; /* linear term */
  PetscBool    b_user    = PETSC_FALSE;
  SeparableSet set       = nullptr; /* the user's set, or NULL: the variable bounds */
  Mat          C         = nullptr; /* equality C x = d */
  Vec          d         = nullptr;
  Mat          Q         = nullptr; /* projector form: orthogonal projector onto range(C') */
  Vec          xt        = nullptr; /* projector form: particular solution, in range(Q) */
  PetscBool    projector = PETSC_FALSE, Q_from_C = PETSC_FALSE;
  std::string  hessian_name   = "the Hessian"; /* as failures name them (TaoSMALXESetOperatorNames_Private()) */
  std::string  projector_name = "the projector Q";

  /* augmented Lagrangian state */
  Vec              mu       = nullptr; /* general form: the multiplier (m-vector) */
  Vec              nu       = nullptr; /* projector form: C'mu */
  Vec              nu_start = nullptr; /* projector form: the next solve's first C'mu (TaoSMALXESetStartMultiplier_Private()), used once */
  Vec              bx       = nullptr; /* linear term of the inner problem */
  Vec              bconst   = nullptr; /* projector form: P(b - A x~) */
  Vec              g        = nullptr; /* gradient of L at the current x */
  PetscReal        rho = 0, M = 0, eta = 0, feas = 0, gpnorm = 0, beff = 0;
  PetscReal        normA = 0, normC2 = 1, normH = 0;
  PetscReal        dnorm2 = 0, qxt = 0;            /* |d|^2 or |x~|^2, and q(x~): constants of L */
  PetscObjectState hessian_state = 0, q_state = 0; /* of the operators the norm estimate belongs to */
  PetscObjectState c_state         = 0;            /* of the C whose |C|^2 is normC2 */
  PetscBool        C_from_routines = PETSC_FALSE;  /* C and d from TAO's equality routines: evaluated again at every solve */

  /* parameters */
  PetscReal    rho_rel = 1.0, M_rel = 0.1, M_min_rel = 1e-4, eta_rel = 0.1, beta = 10.0;
  PetscReal    rho_first    = 1.0; /* the first outer iteration's penalty relative to rho (see TaoSolve_SMALXE()) */
  PetscInt     repeat_first = 0;   /* the inner solves of this many first outer iterations run twice, the pre-solve hook before each */
  SMALXEUpdate update       = SMALXE_UPDATE_M;
  PetscInt     sweeps       = 1;
  PetscReal    block_rtol   = 0.0; /* > 0: a block solve of a sweep also stops at this reduction of its projected gradient */
  PetscReal    inner_floor  = 0.5; /* inner solves stop at this fraction of the final |gP| tolerance (0: only the adaptive precision) */
  PetscReal    norm_user = 0, norm_margin = -1;
  QPNormMethod norm_method     = QP_NORM_SLEPC;
  PetscBool    counters_view   = PETSC_FALSE;
  PetscBool    penalty_pc      = PETSC_TRUE; /* projector form: precondition the inner CG steps by I - theta Q */
  PetscBool    exact_stop      = PETSC_TRUE; /* confirm a stop on the inner solver's exact gradient (TaoSMALXESetExactStop()) */
  PetscInt     stops_confirmed = 0, stops_refused = 0;
  PetscBool    accuracy_floor = PETSC_FALSE; /* the last solve stopped because the exact |gP| did not reach its tolerance */
  PC           projected_pc   = nullptr;     /* projector form: a preconditioner M of A (TaoSMALXESetProjectedPreconditioner()), used as P M P + (q_scale/rho) Q instead */
  PetscReal    pc_q_scale     = 1.0;         /* -tao_smalxe_pc_q_scale */
  Vec          pcq = nullptr, pcp = nullptr; /* its work vectors */
  PetscReal    rho_balance = -1;             /* > 1: residual balancing of rho (see BalancePenalty()); 0: off; -1: 2 with blocks, 0 without */
  PetscInt     rho_changes = 0;              /* by the balancing, over all solves, for TaoView */

  /* inner solves */
  std::vector<SMALXEBlock> blocks; /* one block with is = NULL: monolithic */
  Mat                      H                                  = nullptr;
  PetscInt                 current_block                      = 0;
  PetscErrorCode (*presolve)(Tao, PetscInt, Vec, void *)      = nullptr;
  void *presolve_ctx                                          = nullptr;
  PetscErrorCode (*consistent)(Tao, Vec, PetscBool *, void *) = nullptr; /* may veto convergence */
  void *consistent_ctx                                        = nullptr;

  /* feasibility history: an equality that cannot be met over the set makes |Cx - d| level off */
  std::vector<PetscReal> feas_history, mult_history; /* |Cx - d| and |C'mu| per outer iteration */
  std::vector<PetscReal> gp_history;                 /* |gP| per outer iteration */
  PetscInt               stagnation_its = 30;
  PetscBool              stagnated      = PETSC_FALSE;
  /* the multiplier (nu, or mu in the general form) at the two last outer iterations k > 0 that are multiples of
     stagnation_its / 2, newest second: where the loop stagnates, its growth since the older one is the direction in
     which C x = d cannot be met (TaoSMALXEGetMultiplierGrowth()) */
  Vec       growth_snap[2] = {nullptr, nullptr};
  PetscInt  growth_k[2]    = {-1, -1};
  PetscBool stalled        = PETSC_FALSE; /* |Cx - d| made no progress while the multiplier settled */
  /* a stall first raises rho (by beta) this many times, each followed by a full stall window, before it stops */
  PetscInt stall_rho_growths = 1, stall_rho_done = 0, stall_base = 0;
  PetscInt slow_its = 100, slow_done = 0; /* a long loop whose |Cx - d| lags: rho times slow_factor, once per solve (OuterConvergenceTest()); slow_done: after how many outer iterations (0: not yet) */
  PetscReal slow_factor = 10;
  /* inner solves at their iteration limit: the block that ran into it in each outer iteration (-1: none), the one
     that made the loop stop (-1: it did not stop for it), and the window of that stop */
  std::vector<PetscInt> limited_history;
  PetscInt              limited_now = -1, inner_limited = -1, inner_limit_its = 5;

  /* Anderson acceleration of the multiplier update (depth 0: the plain update mu += rho (Cx - d)) */
  PetscInt         anderson = -1, anderson_start = 3; /* depth -1: automatic (AndersonDepth()) */
  std::vector<Vec> aDX, aDF;                          /* differences of the multipliers and of the increments, oldest first */
  Vec              aX = nullptr, aF = nullptr;        /* the previous multiplier and increment */
  PetscInt         aCount       = 0;                  /* how many of aDX, aDF hold history */
  PetscReal        aRho         = 0;                  /* rho of the previous update */
  PetscInt         aAccelerated = 0, aRestarts = 0;   /* over all solves, for TaoView */

  /* work: hq, hp, hr for products with H; bin, bout for block products; wf for feasibility; w for the rest */
  Vec hq = nullptr, hp = nullptr, hr = nullptr, r = nullptr, bin = nullptr, bout = nullptr, wf = nullptr, w = nullptr;

  /* projector form: which vector (object id and state) hq holds Q of (the last product with H), and wf Q - x~ of
     with its norm: |Qx - x~| of an iterate whose gradient was just computed (an expansion or proportioning step,
     the end of an inner solve) then costs no product with Q, and gives the same bits (Q's own product, reused) */
  PetscInt64       hq_id = -1, wf_id = -1;
  PetscObjectState hq_state = 0, wf_state = 0;
  PetscReal        wf_norm = 0;

  QPCounters counters = {};
  PetscBool  setup    = PETSC_FALSE;
};

TaoSMALXE *Get(Tao tao) { return static_cast<TaoSMALXE *>(tao->data); }

/* one inner solver over all of x (no Gauss-Seidel blocks) */
bool Monolithic(const TaoSMALXE *s) { return s->blocks.size() == 1 && !s->blocks[0].is; }

/* 2-norm summed the same way on any number of ranks (see reproduciblesum.h) */
PetscErrorCode Norm(Vec v, PetscReal *n)
{
  PetscFunctionBegin;
  PetscCall(ReproducibleDot(v, v, n));
  *n = PetscSqrtReal(*n);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---------- operators ---------- */

/* y = H x, H = A + rho C'C, or PAP + rho Q in projector form: one product with A. */
PetscErrorCode MultH(TaoSMALXE *s, Vec x, Vec y)
{
  Mat A = s->tao->hessian;

  PetscFunctionBegin;
  if (s->projector) {
    PetscCall(MatMult(s->Q, x, s->hq));
    PetscCall(PetscObjectGetId((PetscObject)x, &s->hq_id));
    PetscCall(PetscObjectStateGet((PetscObject)x, &s->hq_state));
    PetscCall(VecWAXPY(s->hp, -1.0, s->hq, x)); /* P x */
    PetscCall(MatMult(A, s->hp, y));
    PetscCall(MatMult(s->Q, y, s->hp));
    PetscCall(VecAXPY(y, -1.0, s->hp)); /* P A P x */
    PetscCall(ReproducibleAXPY(y, s->rho, s->hq));
  } else {
    PetscCall(MatMult(A, x, y));
    PetscCall(MatMult(s->C, x, s->hr));
    PetscCall(VecScale(s->hr, s->rho));
    PetscCall(MatMultTransposeAdd(s->C, s->hr, y, y));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ShellMultH(Mat H, Vec x, Vec y)
{
  TaoSMALXE *s;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(H, &s));
  PetscCall(MultH(s, x, y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

struct BlockShellCtx {
  TaoSMALXE *s;
  PetscInt   k;
};

/* y_b = R_b H R_b' x_b */
PetscErrorCode ShellMultHBlock(Mat Hb, Vec xb, Vec yb)
{
  BlockShellCtx *c;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(Hb, &c));
  TaoSMALXE   *s   = c->s;
  SMALXEBlock &blk = s->blocks[c->k];
  PetscCall(VecSet(s->bin, 0.0));
  PetscCall(VecScatterBegin(blk.scatter, xb, s->bin, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(blk.scatter, xb, s->bin, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(MultH(s, s->bin, s->bout));
  PetscCall(VecScatterBegin(blk.scatter, s->bout, yb, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(blk.scatter, s->bout, yb, INSERT_VALUES, SCATTER_FORWARD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BlockShellDestroy(Mat Hb)
{
  BlockShellCtx *c;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(Hb, &c));
  delete c;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Q x = C'(C x) when the projector form comes from C with orthonormal rows */
PetscErrorCode QFromCMult(Mat Qm, Vec x, Vec y)
{
  TaoSMALXE *s;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(Qm, &s));
  PetscCall(MatMult(s->C, x, s->hr));
  PetscCall(MatMultTranspose(s->C, s->hr, y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* e = |C x - d| (projector form: |Q x - x~|). Leaves C x - d in r, or Q x - x~ in wf. */
PetscErrorCode Feasibility(TaoSMALXE *s, Vec x, PetscReal *e)
{
  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(QP_Feasibility, 0, 0, 0, 0));
  if (s->projector) {
    PetscInt64       id;
    PetscObjectState state;
    PetscCall(PetscObjectGetId((PetscObject)x, &id));
    PetscCall(PetscObjectStateGet((PetscObject)x, &state));
    if (id == s->wf_id && state == s->wf_state) *e = s->wf_norm; /* wf holds Q x - x~ already */
    else {
      if (id == s->hq_id && state == s->hq_state) PetscCall(VecCopy(s->hq, s->wf)); /* Q x from the last product with H */
      else PetscCall(MatMult(s->Q, x, s->wf));
      PetscCall(VecAXPY(s->wf, -1.0, s->xt));
      PetscCall(Norm(s->wf, e));
      s->wf_id    = id;
      s->wf_state = state;
      s->wf_norm  = *e;
    }
  } else {
    PetscCall(MatMult(s->C, x, s->r));
    PetscCall(VecAXPY(s->r, -1.0, s->d));
    PetscCall(Norm(s->r, e));
  }
  PetscCall(PetscLogEventEnd(QP_Feasibility, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the linear term of the inner problem for the current multiplier */
PetscErrorCode UpdateInnerLinearTerm(TaoSMALXE *s)
{
  PetscFunctionBegin;
  if (s->projector) { /* rho x~ + P(b - A x~) - nu */
    PetscCall(VecWAXPY(s->bx, -1.0, s->nu, s->bconst));
    PetscCall(ReproducibleAXPY(s->bx, s->rho, s->xt));
  } else {                           /* b + C'(rho d - mu) */
    PetscCall(VecCopy(s->mu, s->r)); /* rho d - mu, rounded alike everywhere */
    PetscCall(VecScale(s->r, -1.0));
    PetscCall(ReproducibleAXPY(s->r, s->rho, s->d));
    PetscCall(MatMultTransposeAdd(s->C, s->r, s->b, s->bx));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Anderson acceleration of the multiplier update. The outer loop is the fixed-point iteration
   mu <- mu + f(mu), f = rho (Cx(mu) - d); it converges linearly (|Cx - d| falls by a constant factor
   per outer iteration, about 3-5 on the brick), and the multiplier lives in range(C'), a space of
   dimension rank(C) (12 for the brick) however large the problem. Anderson mixing of depth m takes
   mu+ = mu + f - sum_j gamma_j (dmu_j + df_j), gamma = argmin |f - sum_j gamma_j df_j|, over the last
   m differences. Safeguards: the history restarts when rho changed or |Cx - d| grew, and the plain
   update is taken when the small least-squares problem is ill conditioned. The dot products are
   reproducible sums, so every rank solves the same small system and the iterates do not depend on
   the number of ranks. */
PetscErrorCode AndersonDestroyHistory(TaoSMALXE *s)
{
  PetscFunctionBegin;
  for (Vec *v : {&s->aX, &s->aF}) PetscCall(VecDestroy(v));
  for (auto &v : s->aDX) PetscCall(VecDestroy(&v));
  for (auto &v : s->aDF) PetscCall(VecDestroy(&v));
  s->aDX.clear();
  s->aDF.clear();
  s->aCount = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Solves the m x m symmetric positive semidefinite system A g = c by Cholesky; *ok is false when a
   pivot is below tol times the largest diagonal entry (the differences are nearly dependent) or not
   above floor (a difference too small to be more than rounding, see UpdateMultiplier()). */
void SmallCholeskySolve(PetscInt m, std::vector<PetscReal> &A, std::vector<PetscReal> &c, PetscReal tol, PetscReal floor, PetscBool *ok)
{
  PetscReal dmax = 0;
  for (PetscInt i = 0; i < m; i++) dmax = PetscMax(dmax, A[i * m + i]);
  *ok = dmax > 0 ? PETSC_TRUE : PETSC_FALSE;
  for (PetscInt j = 0; j < m && *ok; j++) {
    PetscReal d = A[j * m + j];
    for (PetscInt k = 0; k < j; k++) d -= A[j * m + k] * A[j * m + k];
    if (d <= tol * dmax || d <= floor) {
      *ok = PETSC_FALSE;
      break;
    }
    A[j * m + j] = PetscSqrtReal(d);
    for (PetscInt i = j + 1; i < m; i++) {
      PetscReal v = A[i * m + j];
      for (PetscInt k = 0; k < j; k++) v -= A[i * m + k] * A[j * m + k];
      A[i * m + j] = v / A[j * m + j];
    }
  }
  if (!*ok) return;
  for (PetscInt i = 0; i < m; i++) { /* L y = c */
    for (PetscInt k = 0; k < i; k++) c[i] -= A[i * m + k] * c[k];
    c[i] /= A[i * m + i];
  }
  for (PetscInt i = m - 1; i >= 0; i--) { /* L' g = y */
    for (PetscInt k = i + 1; k < m; k++) c[i] -= A[k * m + i] * c[k];
    c[i] /= A[i * m + i];
  }
}

/* The depth in effect: -1 (the default) is 3 with one inner solver and 0 with Gauss-Seidel blocks,
   whose sweeps make the map from multiplier to residual too irregular for mixing (more outer
   iterations, not fewer, on the tests' block problems and on the brick's merged algorithm). */
PetscInt AndersonDepth(TaoSMALXE *s)
{
  if (s->anderson >= 0) return s->anderson;
  return s->blocks.size() > 1 ? 0 : 3;
}

/* mu (projector form: nu = C'mu) += rho (Cx - d), accelerated when AndersonDepth() > 0.
   Expects Feasibility() to have left Cx - d in r (Qx - x~ in wf); e = |Cx - d| = feas_history[k]. */
PetscErrorCode UpdateMultiplier(TaoSMALXE *s, PetscInt k, PetscReal e)
{
  Vec            mult = s->projector ? s->nu : s->mu, res = s->projector ? s->wf : s->r;
  const PetscInt depth = AndersonDepth(s);

  PetscFunctionBegin;
  s->wf_id = -1; /* res is scaled below: no longer Q x - x~ */
  if (depth <= 0) {
    PetscCall(ReproducibleAXPY(mult, s->rho, res));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (s->aX && (PetscInt)s->aDX.size() != depth) PetscCall(AndersonDestroyHistory(s)); /* the depth changed since the history was allocated */
  if (!s->aX) {
    PetscCall(VecDuplicate(mult, &s->aX));
    PetscCall(VecDuplicate(mult, &s->aF));
    s->aDX.assign(depth, nullptr);
    s->aDF.assign(depth, nullptr);
    for (PetscInt j = 0; j < depth; j++) {
      PetscCall(VecDuplicate(mult, &s->aDX[j]));
      PetscCall(VecDuplicate(mult, &s->aDF[j]));
    }
  }
  /* the increment f = rho (Cx - d), kept in res (res is not used again before the next Feasibility()) */
  PetscCall(VecScale(res, s->rho));
  if (k < s->anderson_start || s->rho != s->aRho || e > s->feas_history[k - 1]) { /* restart */
    if (k >= s->anderson_start) s->aRestarts++;
    s->aCount = 0;
  } else { /* append (mult - aX, res - aF), dropping the oldest pair when full */
    if (s->aCount == depth) {
      Vec dx = s->aDX[0], df = s->aDF[0];
      for (PetscInt j = 1; j < depth; j++) {
        s->aDX[j - 1] = s->aDX[j];
        s->aDF[j - 1] = s->aDF[j];
      }
      s->aDX[depth - 1] = dx;
      s->aDF[depth - 1] = df;
      s->aCount--;
    }
    PetscCall(VecWAXPY(s->aDX[s->aCount], -1.0, s->aX, mult));
    PetscCall(VecWAXPY(s->aDF[s->aCount], -1.0, s->aF, res));
    s->aCount++;
  }
  PetscCall(VecCopy(mult, s->aX));
  PetscCall(VecCopy(res, s->aF));
  s->aRho = s->rho;
  PetscCall(ReproducibleAXPY(mult, 1.0, res)); /* the plain update; corrected below */
  if (s->aCount > 0) {
    const PetscInt         m = s->aCount;
    std::vector<PetscReal> A(m * m), c(m);
    PetscBool              ok;
    PetscReal              ff;
    /* a difference of the increments below 1e-4 |f| says nothing the rounding does not: an inner solve that
       took no step (its gradient already within the final tolerance) returns the same Cx - d, and the
       difference of two equal increments is rounding. A relative pivot test alone passes it when it is the
       only one (m = 1), and its coefficient, about |f| / |df|, then threw the multiplier 10^15 times too far
       (a random scene of scripts/fuzz-scenes.py: a clamped body declared to have no equilibrium) */
    PetscCall(ReproducibleDot(res, res, &ff));
    for (PetscInt i = 0; i < m; i++) {
      PetscCall(ReproducibleDot(s->aDF[i], res, &c[i]));
      for (PetscInt j = 0; j <= i; j++) {
        PetscCall(ReproducibleDot(s->aDF[i], s->aDF[j], &A[i * m + j]));
        A[j * m + i] = A[i * m + j];
      }
    }
    SmallCholeskySolve(m, A, c, 1e-12, 1e-8 * ff, &ok);
    if (ok) {
      for (PetscInt i = 0; i < m; i++) {
        PetscCall(ReproducibleAXPY(mult, -c[i], s->aDX[i]));
        PetscCall(ReproducibleAXPY(mult, -c[i], s->aDF[i]));
      }
      s->aAccelerated++;
    } else {
      PetscCall(PetscInfo(s->tao, "Anderson: nearly dependent differences, plain multiplier update and restart\n"));
      s->aRestarts++;
      s->aCount = 0;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The spacing of the multiplier's snapshots: half the stagnation window, so that the growth spans h to 2h outer
   iterations when the window ends (and does not reach back to the start, whose multiplier still holds most of the
   part that converges) */
PetscInt GrowthSpacing(const TaoSMALXE *s) { return PetscMax(1, s->stagnation_its / 2); }

/* Keep the multiplier of outer iteration k > 0 when k is a multiple of GrowthSpacing(), in the older slot's vector
   (two copies at most, made only in loops that long) */
PetscErrorCode SnapshotMultiplier(TaoSMALXE *s, PetscInt k)
{
  Vec mult = s->projector ? s->nu : s->mu;

  PetscFunctionBegin;
  if (s->stagnation_its <= 0 || k == 0 || k % GrowthSpacing(s)) PetscFunctionReturn(PETSC_SUCCESS);
  std::swap(s->growth_snap[0], s->growth_snap[1]);
  std::swap(s->growth_k[0], s->growth_k[1]);
  if (!s->growth_snap[1]) PetscCall(VecDuplicate(mult, &s->growth_snap[1]));
  PetscCall(VecCopy(mult, s->growth_snap[1]));
  s->growth_k[1] = k;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* With TaoSetRecycleHistory() a solve starts from the multiplier of the previous one (the iterate is
   the user's warm start anyway). Without it, the multiplier starts at 0 and the first inner solve drives
   a warm-started iterate back to the solution of the problem without the equality's forces, which
   undoes the warm start: a sequence of nearby problems (the Tresca solves of successive
   approximations, load steps) then pays the whole outer loop each time. Called before the histories are
   cleared: mult_history.back() is |multiplier| at the end of the previous solve (none: no solve yet). */
bool RecycleMultiplier(Tao tao, TaoSMALXE *s) { return tao->recycle && !s->mult_history.empty() && !PetscIsInfOrNanReal(s->mult_history.back()); }

/* |Cx - d| is measured against ||C|| |b| over ||H|| at the default penalty (rho = ||A|| / ||C||^2, so ||H|| is
   ||PAP|| in projector form and 2 ||A|| otherwise), not over the current ||H||: the accuracy a tolerance
   asks for must not depend on rho, which -tao_smalxe_rho sets and SMALBE's rho updates raise, nor on the
   scale of C and d (C x = d and 10 C x = 10 d are one constraint; without ||C|| the second was held 10 times
   tighter, beyond what the inner solves' floor of 0.5 tol_g leaves, and stalled). Unless crtol is given, the
   tolerance follows tol_g, so that a gradient tolerance relaxed by -tao_gatol relaxes the equality's too */
PetscErrorCode Tolerances(Tao tao, TaoSMALXE *s, PetscReal *tol_g, PetscReal *tol_e)
{
  const PetscReal scale = s->projector ? s->normA : 2 * s->normA, normC = s->projector ? 1.0 : PetscSqrtReal(s->normC2);

  PetscFunctionBegin;
  *tol_g = PetscMax(tao->gatol, tao->gttol * s->beff);
  *tol_e = PetscMax(tao->catol, (tao->crtol_changed ? tao->crtol * s->beff : *tol_g) * normC / scale);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---------- stopping rules ---------- */

/* Inner solves stop at the adaptive precision |gP| <= min(M |Cx - d|, eta), or when the final
   tolerances already hold. */
PetscErrorCode InnerConvergenceTest(Tao sub, void *ctx)
{
  TaoSMALXE *s   = static_cast<TaoSMALXE *>(ctx);
  Tao        tao = s->tao;
  PetscReal  gp  = sub->residual, e, tol_g, tol_e;
  Vec        xfull;

  PetscFunctionBegin;
  if (sub->reason != TAO_CONTINUE_ITERATING) PetscFunctionReturn(PETSC_SUCCESS);
  if (PetscIsInfOrNanReal(gp) || PetscIsInfOrNanReal(sub->fc)) {
    PetscCall(TaoSetConvergedReason(sub, TAO_DIVERGED_NAN));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  SMALXEBlock &blk = s->blocks[s->current_block];
  if (blk.is) { /* the full iterate: the block's current values in place */
    PetscCall(VecCopy(tao->solution, s->w));
    PetscCall(VecScatterBegin(blk.scatter, sub->solution, s->w, INSERT_VALUES, SCATTER_REVERSE));
    PetscCall(VecScatterEnd(blk.scatter, sub->solution, s->w, INSERT_VALUES, SCATTER_REVERSE));
    xfull = s->w;
  } else xfull = sub->solution;
  PetscCall(Tolerances(tao, s, &tol_g, &tol_e));
  /* blocks of a Gauss-Seidel sweep are only worth a relative reduction: the next sweep moves their data.
     No inner solve needs to go below a fraction of the final gradient tolerance: the outer loop ends on
     |gP| <= tol_g, which such an iterate meets, and the adaptive precision M |Cx - d| would otherwise
     demand far more than that once M has been lowered (with friction the moving radii lower it often) */
  /* the floor scales with rho below its default: an inner solve to |gP| leaves |Cx - d| near |gP| / rho,
     which must stay below tol_e */
  const PetscReal rho_default = s->normA / (s->projector ? 1.0 : s->normC2), floor = s->inner_floor * tol_g * PetscMin(1.0, s->rho / rho_default);
  PetscBool       stop = (gp <= floor || (blk.is && s->block_rtol > 0 && sub->niter > 0 && gp <= s->block_rtol * sub->gnorm0)) ? PETSC_TRUE : PETSC_FALSE;
  /* |Cx - d| (a product with Q or C) only when it can decide: both tests that use it need gp <= eta or gp <= tol_g */
  if (!stop && (gp <= s->eta || gp <= tol_g)) {
    PetscCall(Feasibility(s, xfull, &e));
    stop = (gp <= PetscMin(s->M * e, s->eta) || (gp <= tol_g && e <= tol_e)) ? PETSC_TRUE : PETSC_FALSE;
  }
  if (stop) PetscCall(TaoSetConvergedReason(sub, TAO_CONVERGED_USER));
  else if (sub->niter >= sub->max_it) PetscCall(TaoSetConvergedReason(sub, TAO_DIVERGED_MAXITS));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Whether the best distance from convergence, max(|gP| / tol_g, |Cx - d| / tol_e), of the last `window` outer
   iterations up to k fell by 1% below the best before them (a minimum over a window, so that a loop cycling between
   a few states does not count as progress): the stall tests below */
bool Progressed(const TaoSMALXE *s, PetscInt k, PetscInt window, PetscReal tol_g, PetscReal tol_e)
{
  PetscReal recent = PETSC_MAX_REAL, before = PETSC_MAX_REAL;
  for (PetscInt i = 0; i <= k; i++) {
    const PetscReal merit = PetscMax(s->gp_history[i] / tol_g, s->feas_history[i] / tol_e);
    if (i > k - window) recent = PetscMin(recent, merit);
    else before = PetscMin(before, merit);
  }
  return !(recent > 0.99 * before);
}

/* Outer: |gP| <= tol_g and |Cx - d| <= tol_e (Tolerances()); both relative, so scaling A and b, or C and d,
   does not change the iterations. */
PetscErrorCode UpdateNormH(TaoSMALXE *s);

PetscErrorCode OuterConvergenceTest(Tao tao, void *)
{
  TaoSMALXE *s = Get(tao);
  PetscReal  tol_g, tol_e;
  PetscInt   k = (PetscInt)s->feas_history.size() - 1;

  bool grew = false; /* rho grown by the stall test in this outer iteration */

  PetscFunctionBegin;
  if (tao->reason != TAO_CONTINUE_ITERATING) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(Tolerances(tao, s, &tol_g, &tol_e));
  PetscCall(PetscInfo(tao, "TAO smalxe outer %" PetscInt_FMT ": |gP| = %g (tol %g), |Cx - d| = %g (tol %g), M = %g, rho = %g\n", tao->niter, (double)tao->residual, (double)tol_g, (double)tao->cnorm,
                      (double)tol_e, (double)s->M, (double)s->rho));
  if (PetscIsInfOrNanReal(tao->residual) || PetscIsInfOrNanReal(tao->cnorm) || PetscIsInfOrNanReal(tao->fc)) PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_NAN));
  else if (tao->residual <= tol_g && tao->cnorm <= tol_e) {
    PetscBool consistent = PETSC_TRUE;
    if (s->consistent) PetscCall(s->consistent(tao, tao->solution, &consistent, s->consistent_ctx));
    if (consistent) PetscCall(TaoSetConvergedReason(tao, tao->gttol * s->beff >= tao->gatol ? TAO_CONVERGED_GTTOL : TAO_CONVERGED_GATOL));
  }
  if (tao->reason == TAO_CONTINUE_ITERATING && s->stagnation_its > 0 && k >= s->stagnation_its && tao->cnorm > tol_e && s->feas_history[k] > 0.99 * s->feas_history[k - s->stagnation_its] &&
      s->mult_history[k] > 1.25 * s->mult_history[k - s->stagnation_its]) {
    /* |Cx - d| did not fall by 1% in stagnation_its outer iterations while the multiplier kept growing
       (by a quarter at least): the signature of an equality that cannot be met, where the multiplier
       grows without bound; a slowly converging loop has a settling multiplier instead */
    s->stagnated = PETSC_TRUE;
    PetscCall(PetscInfo(tao, "TAO smalxe: |Cx - d| = %g stagnates (%" PetscInt_FMT " iterations without 1%% progress): C x = d cannot be met over the set, or rho is far too small\n",
                        (double)tao->cnorm, s->stagnation_its));
    PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_USER));
  }
  if (tao->reason == TAO_CONTINUE_ITERATING && s->stagnation_its > 0 && k - s->stall_base >= 2 * s->stagnation_its && (tao->cnorm > tol_e || tao->residual > tol_g)) {
    /* the best distance from convergence, max(|gP| / tol_g, |Cx - d| / tol_e), of the last stagnation_its
       outer iterations is not 1% below the best before them (a minimum over a window, so that a loop
       cycling between a few states counts too), while the multiplier does not grow: the iteration is
       stuck, more of it will not help. Both parts count: a loop whose |Cx - d| sits at its tolerance while
       |gP| still falls steadily (a slow Gauss-Seidel sweep between blocks) is not stuck */
    const bool stuck = !Progressed(s, k, s->stagnation_its, tol_g, tol_e) && s->mult_history[k] <= 1.25 * s->mult_history[k - s->stagnation_its];
    if (stuck && s->stall_rho_done < s->stall_rho_growths && s->update == SMALXE_UPDATE_M && tao->cnorm > 10 * tol_e) {
      /* a penalty far too small for the coupling the set puts between range(Q) and the rest (a clamped block whose
         Tresca disks, large, sit on nodes far from their foundation: fuzz boxes seed 106, scene 2189, stuck at |gP| of
         2e-4 of its reference at rho = ||PFP||, converged in 5 outer iterations at 2 ||PFP||): grow rho as SMALBE does,
         and give the loop a full window again before the stall test may stop it. Only when |Cx - d| is stuck far
         (10 times) above its tolerance, the part a penalty enforces: a loop stuck near it is at rounding's floor (the
         brick at -contact_rtol 1e-15: 2.3 times), where a larger rho only makes each inner solve dearer */
      const PetscReal rho0 = s->rho;
      s->rho *= s->beta;
      PetscCall(UpdateNormH(s));
      s->stall_rho_done++;
      s->stall_base = k;
      grew          = true;
      PetscCall(PetscInfo(tao,
                          "TAO smalxe: stuck at |gP| = %g (tol %g), |Cx - d| = %g (tol %g) for %" PetscInt_FMT " outer iterations: rho %g -> %g (-tao_smalxe_stall_rho_growths %" PetscInt_FMT ")\n",
                          (double)tao->residual, (double)tol_g, (double)tao->cnorm, (double)tol_e, s->stagnation_its, (double)rho0, (double)s->rho, s->stall_rho_growths));
    } else if (stuck) {
      s->stalled = PETSC_TRUE;
      PetscCall(PetscInfo(tao,
                          "TAO smalxe: stalls at |gP| = %g (tol %g), |Cx - d| = %g (tol %g): the best of max(|gP| / tol, |Cx - d| / tol) did not fall by 1%% in %" PetscInt_FMT " outer iterations\n",
                          (double)tao->residual, (double)tol_g, (double)tao->cnorm, (double)tol_e, s->stagnation_its));
      PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_USER));
    }
  }
  if (tao->reason == TAO_CONTINUE_ITERATING && s->slow_its > 0 && s->slow_factor > 1 && !s->slow_done && !grew && k + 1 >= s->slow_its && s->projector && s->update == SMALXE_UPDATE_M &&
      tao->cnorm > tol_e && tao->cnorm / tol_e >= tao->residual / tol_g && !PetscIsInfOrNanReal(s->rho * s->slow_factor)) {
    /* a long loop (the shipped scenes take at most a few dozen outer iterations) whose |Cx - d| is the residual further
       from its tolerance: the multiplier of the equality converges slowly, at a rate of about 1/(1 + rho sigma) with
       sigma the share of Q's curvature that the face leaves (docs/contact.md, "Nearly open zones"). A larger rho speeds
       it up, for dearer inner solves, which a long loop can afford: a bar of 48 one-cell cubes whose tip touches
       converged in 174 outer iterations instead of not in 1000; on 942 random scenes of scripts/fuzz-scenes.py it
       acted on 19, of which 4 converged that had not, and the others took 22% (boxes) and 1.8% (meshes) fewer
       products (docs/contact.md, "Stopping"). Not in an outer iteration where a stall just grew rho (the two at once
       would multiply it by beta times the factor) */
    const PetscReal rho0 = s->rho;
    s->rho *= s->slow_factor;
    PetscCall(UpdateNormH(s));
    s->slow_done = k + 1; /* the outer iterations run */
    /* the stall test waits a full window again, unless a stall already grew rho: a loop stuck since then (the radii of
       a large F locking it) ends as 'stalled' about when it did before (the brick with F = 8: after 131 outer iterations
       instead of 121), rather than a full window later */
    if (!s->stall_rho_done) s->stall_base = k;
    PetscCall(PetscInfo(tao, "TAO smalxe: %" PetscInt_FMT " outer iterations, |Cx - d| = %g still %g times its tolerance (|gP| %g times its): rho %g -> %g (-tao_smalxe_slow_its)\n", k + 1,
                        (double)tao->cnorm, (double)(tao->cnorm / tol_e), (double)(tao->residual / tol_g), (double)rho0, (double)s->rho));
  }
  if (tao->reason == TAO_CONTINUE_ITERATING && s->inner_limit_its > 0 && k >= 2 * s->inner_limit_its && (tao->cnorm > tol_e || tao->residual > tol_g)) {
    /* the stall test below with a short window, for a loop whose every outer iteration costs the inner limit in
       products: an inner solve ran into its iteration limit in each of the last inner_limit_its outer iterations,
       and the best distance from convergence among them is not 1% below the best before them (Kucera's projected
       steps alone, -tao_mpgp_arc 0, move slipping friction nodes on small circles a little per step: 10^4 steps
       for 1e-3 of |gP| on a fuzz scene, whose tighter solve ran for more than 300 s before the stall test's window
       of 30 outer iterations was full). A loop that converges with its inner solves at their limit gains more than
       1% per window: stack.opts, twobodies.opts and the merged brick at -scene_refine 6 with inner limits of 5 steps
       converge as before (a window of 3 that asked for a halving stopped them) */
    PetscBool all = PETSC_TRUE;
    for (PetscInt i = k - s->inner_limit_its + 1; i <= k; i++)
      if (s->limited_history[i] < 0) all = PETSC_FALSE;
    if (all && !Progressed(s, k, s->inner_limit_its, tol_g, tol_e)) {
      s->inner_limited = s->limited_history[k];
      PetscCall(PetscInfo(tao,
                          "TAO smalxe: the inner solves reached their iteration limit in %" PetscInt_FMT " outer iterations in a row (block %" PetscInt_FMT
                          " last) and max(|gP| / tol, |Cx - d| / tol) did not fall by 1%%\n",
                          s->inner_limit_its, s->inner_limited));
      PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_USER));
    }
  }
  /* niter counts from 0 (the first inner solve), so niter + 1 outer iterations are done: -tao_max_it N allows N */
  if (tao->reason == TAO_CONTINUE_ITERATING && tao->niter + 1 >= tao->max_it) PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_MAXITS));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---------- setup ---------- */

/* what TaoSetFromOptions_SMALXE() compares with: the prefix the nested solver has now, which we gave it */
PetscErrorCode RememberPrefix(SMALXEBlock &blk)
{
  const char *prefix;

  PetscFunctionBegin;
  PetscCall(TaoGetOptionsPrefix(blk.sub, &prefix));
  PetscCallCXX(blk.prefix = prefix ? prefix : "");
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode CreateSubsolver(Tao tao, const char *suffix, Tao *sub)
{
  const char *prefix;

  PetscFunctionBegin;
  PetscCall(TaoCreate(PetscObjectComm((PetscObject)tao), sub));
  PetscCall(PetscObjectIncrementTabLevel((PetscObject)*sub, (PetscObject)tao, 1));
  PetscCall(TaoGetOptionsPrefix(tao, &prefix));
  PetscCall(TaoSetOptionsPrefix(*sub, prefix));
  PetscCall(TaoAppendOptionsPrefix(*sub, suffix));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DestroyBlocks(TaoSMALXE *s)
{
  PetscFunctionBegin;
  for (auto &blk : s->blocks) {
    PetscCall(TaoDestroy(&blk.sub));
    PetscCall(VecDestroy(&blk.b));
    if (blk.is) {
      PetscCall(ISDestroy(&blk.is));
      PetscCall(VecScatterDestroy(&blk.scatter));
      PetscCall(MatDestroy(&blk.H));
      PetscCall(VecDestroy(&blk.x));
    }
  }
  s->blocks.clear();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The equality from TaoSMALXESetEqualityConstraints(), or from TAO's equality-constraint routines. */
PetscErrorCode PrepareEquality(Tao tao, TaoSMALXE *s)
{
  PetscFunctionBegin;
  if (s->C || (s->Q && s->xt)) PetscFunctionReturn(PETSC_SUCCESS);
  if (!tao->ops->computeequalityconstraints && !tao->ops->computejacobianequality) {
    /* no equality at all: an empty C (0 rows), so that a bound-constrained program can select smalxe;
       the outer loop then ends after its first inner solve */
    PetscInt n, N;
    PetscCall(PetscInfo(tao, "TAO smalxe: no equality constraint given, solving with an empty one\n"));
    PetscCall(VecGetLocalSize(tao->solution, &n));
    PetscCall(VecGetSize(tao->solution, &N));
    PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)tao), 0, n, 0, N, 0, NULL, 0, NULL, &s->C));
    PetscCall(MatAssemblyBegin(s->C, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(s->C, MAT_FINAL_ASSEMBLY));
    PetscCall(MatCreateVecs(s->C, NULL, &s->d));
    s->projector = PETSC_FALSE; /* a projector onto an empty range would be the zero matrix: penalty form */
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCheck(tao->ops->computeequalityconstraints && tao->ops->computejacobianequality, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE,
             "TAO smalxe: an equality needs both TaoSetEqualityConstraintsRoutine() and TaoSetJacobianEqualityRoutine() (or TaoSMALXESetEqualityConstraints(), TaoSMALXESetProjector())");
  PetscCall(TaoComputeJacobianEquality(tao, tao->solution, tao->jacobian_equality, tao->jacobian_equality_pre));
  PetscCall(VecSet(tao->stepdirection, 0.0));
  PetscCall(TaoComputeEqualityConstraints(tao, tao->stepdirection, tao->constraints_equality));
  PetscCall(PetscObjectReference((PetscObject)tao->jacobian_equality));
  s->C = tao->jacobian_equality;
  PetscCall(VecDuplicate(tao->constraints_equality, &s->d));
  PetscCall(VecAXPY(s->d, -1.0, tao->constraints_equality)); /* ce(x) = C x - d, so d = -ce(0) */
  s->C_from_routines = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A later solve with TAO's equality routines: the user may have changed the constraint since, as for
   any TAO solver they are evaluated again (C in place, d = -ce(0), and x~ = C'd in projector form). */
PetscErrorCode RefreshEquality(Tao tao, TaoSMALXE *s)
{
  PetscFunctionBegin;
  if (!s->C_from_routines) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(TaoComputeJacobianEquality(tao, tao->solution, tao->jacobian_equality, tao->jacobian_equality_pre));
  PetscCheck(tao->jacobian_equality == s->C, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE,
             "TAO smalxe: the equality Jacobian was replaced by another matrix between solves; create a new Tao");
  PetscCall(VecSet(tao->stepdirection, 0.0));
  PetscCall(TaoComputeEqualityConstraints(tao, tao->stepdirection, tao->constraints_equality));
  PetscCall(VecAXPBY(s->d, -1.0, 0.0, tao->constraints_equality));
  if (s->Q_from_C) {
    PetscCall(MatMultTranspose(s->C, s->d, s->xt));
    PetscCall(PetscObjectStateIncrease((PetscObject)s->Q)); /* Q = C'C changed with C: its norm estimates are stale */
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A later solve: a block's set is a copy of a part of the set, made again when the set changed since
   (e.g. new values in its bound vectors) */
PetscErrorCode RefreshBlockSets(TaoSMALXE *s)
{
  PetscFunctionBegin;
  if (!s->set) PetscFunctionReturn(PETSC_SUCCESS);
  for (auto &blk : s->blocks) {
    PetscObjectState version;
    SeparableSet     bset;
    if (!blk.is) continue;
    PetscCall(SeparableSetGetVersion_Private(s->set, &version));
    if (version == blk.set_version) continue;
    PetscCall(SeparableSetCreateSubset(s->set, blk.is, &bset));
    PetscCall(TaoQPSetConstraints(blk.sub, bset));
    PetscCall(SeparableSetDestroy(&bset));
    blk.set_version = version;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetUpOnce(Tao tao, TaoSMALXE *s)
{
  PetscInt n, N;
  MPI_Comm comm = PetscObjectComm((PetscObject)tao);

  PetscFunctionBegin;
  if (s->setup) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PrepareEquality(tao, s));
  PetscCall(VecGetLocalSize(tao->solution, &n));
  PetscCall(VecGetSize(tao->solution, &N));
  if (s->set) PetscCall(SeparableSetCheckCompatible_Private(s->set, tao->solution));
  if (s->C) {
    PetscInt cm, cn, cM, cN, dM;
    PetscCall(MatGetLocalSize(s->C, &cm, &cn));
    PetscCall(MatGetSize(s->C, &cM, &cN));
    PetscCheck(cN == N && cn == n, comm, PETSC_ERR_ARG_SIZ,
               "TAO smalxe: C has %" PetscInt_FMT " columns (local %" PetscInt_FMT "), the solution has %" PetscInt_FMT " entries (local %" PetscInt_FMT ")", cN, cn, N, n);
    PetscCall(VecGetSize(s->d, &dM));
    PetscCheck(dM == cM, comm, PETSC_ERR_ARG_SIZ, "TAO smalxe: d has %" PetscInt_FMT " entries, C has %" PetscInt_FMT " rows", dM, cM);
    PetscCall(MatCreateVecs(s->C, NULL, &s->r));
    PetscCall(VecDuplicate(s->r, &s->hr));
    PetscCall(VecDuplicate(s->r, &s->mu));
  }
  if (s->projector && !s->Q) { /* projector form from C with orthonormal rows: Q = C'C, x~ = C'd */
    const char *prefix;
    PetscCall(TaoGetOptionsPrefix(tao, &prefix));
    PetscCheck(s->C, comm, PETSC_ERR_ARG_WRONGSTATE, "TAO smalxe: -%stao_smalxe_projector needs C", prefix ? prefix : "");
    PetscCall(MatCreateShell(comm, n, n, N, N, s, &s->Q));
    PetscCall(MatShellSetOperation(s->Q, MATOP_MULT, (void (*)(void))QFromCMult));
    PetscCall(VecDuplicate(tao->solution, &s->xt));
    PetscCall(MatMultTranspose(s->C, s->d, s->xt));
    s->Q_from_C = PETSC_TRUE;
  }
  if (s->Q) {
    PetscInt qm, qn;
    PetscCall(MatGetSize(s->Q, &qm, &qn));
    PetscCheck(qm == N && qn == N, comm, PETSC_ERR_ARG_SIZ, "TAO smalxe: the projector is %" PetscInt_FMT " x %" PetscInt_FMT ", it must be %" PetscInt_FMT " x %" PetscInt_FMT, qm, qn, N, N);
    s->projector = PETSC_TRUE;
    PetscCall(VecDuplicate(tao->solution, &s->nu));
    PetscCall(VecDuplicate(tao->solution, &s->bconst));
    PetscCall(VecDuplicate(tao->solution, &s->hq));
    PetscCall(VecDuplicate(tao->solution, &s->hp));
    PetscCall(VecDuplicate(tao->solution, &s->wf));
  }
  for (Vec *v : {&s->bx, &s->g, &s->bin, &s->bout, &s->w}) PetscCall(VecDuplicate(tao->solution, v));
  PetscCall(MatCreateShell(comm, n, n, N, N, s, &s->H));
  PetscCall(MatShellSetOperation(s->H, MATOP_MULT, (void (*)(void))ShellMultH));
  PetscCall(MatSetOption(s->H, MAT_SYMMETRIC, PETSC_TRUE));

  for (size_t k = 0; k < s->blocks.size(); k++) {
    SMALXEBlock &blk  = s->blocks[k];
    SeparableSet bset = nullptr;
    if (blk.is) {
      PetscInt       nb, Nb;
      BlockShellCtx *ctx;
      PetscCall(ISGetLocalSize(blk.is, &nb));
      PetscCall(VecCreateMPI(comm, nb, PETSC_DETERMINE, &blk.x));
      PetscCall(VecGetSize(blk.x, &Nb));
      PetscCall(VecScatterCreate(tao->solution, blk.is, blk.x, NULL, &blk.scatter));
      PetscCallCXX(ctx = new BlockShellCtx{s, (PetscInt)k});
      PetscCall(MatCreateShell(comm, nb, nb, Nb, Nb, ctx, &blk.H));
      PetscCall(MatShellSetOperation(blk.H, MATOP_MULT, (void (*)(void))ShellMultHBlock));
      PetscCall(MatShellSetOperation(blk.H, MATOP_DESTROY, (void (*)(void))BlockShellDestroy));
      PetscCall(MatSetOption(blk.H, MAT_SYMMETRIC, PETSC_TRUE));
      if (s->set) {
        PetscCall(SeparableSetCreateSubset(s->set, blk.is, &bset));
        PetscCall(SeparableSetGetVersion_Private(s->set, &blk.set_version));
      }
    } else {
      blk.H = s->H;
      blk.x = tao->solution;
      if (s->set) {
        PetscCall(PetscObjectReference((PetscObject)s->set));
        bset = s->set;
      }
    }
    PetscCall(VecDuplicate(blk.x, &blk.b));
    /* default inner type: mprgp on bounds only (its exact line search beats a fixed step), mpgp otherwise */
    if (!((PetscObject)blk.sub)->type_name) {
      PetscBool curved = PETSC_FALSE;
      if (bset) PetscCall(SeparableSetHasCurvedBlocks(bset, &curved));
      PetscCall(TaoSetType(blk.sub, curved ? TAOMPGP : TAOMPRGP));
      PetscCall(TaoSetFromOptions(blk.sub));
    }
    if (bset) PetscCall(TaoQPSetConstraints(blk.sub, bset));
    PetscCall(SeparableSetDestroy(&bset));
    PetscCall(TaoSetSolution(blk.sub, blk.x));
    PetscCall(TaoSetHessian(blk.sub, blk.H, blk.H, NULL, NULL));
    PetscCall(TaoQPSetLinearTerm(blk.sub, blk.b));
    PetscCall(TaoSetConvergenceTest(blk.sub, InnerConvergenceTest, s));
  }
  s->setup = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Variable bounds (when no set was given) reach the nested solvers, per block. */
PetscErrorCode PassVariableBounds(Tao tao, TaoSMALXE *s)
{
  PetscFunctionBegin;
  if (s->set || (!tao->XL && !tao->XU)) PetscFunctionReturn(PETSC_SUCCESS);
  for (auto &blk : s->blocks) {
    if (!blk.is) {
      PetscCall(TaoSetVariableBounds(blk.sub, tao->XL, tao->XU));
      continue;
    }
    Vec bounds[2] = {tao->XL, tao->XU}, sub[2] = {NULL, NULL};
    for (int i = 0; i < 2; i++) {
      if (!bounds[i]) continue;
      PetscCall(VecDuplicate(blk.x, &sub[i]));
      PetscCall(VecScatterBegin(blk.scatter, bounds[i], sub[i], INSERT_VALUES, SCATTER_FORWARD));
      PetscCall(VecScatterEnd(blk.scatter, bounds[i], sub[i], INSERT_VALUES, SCATTER_FORWARD));
    }
    PetscCall(TaoSetVariableBounds(blk.sub, sub[0], sub[1]));
    PetscCall(VecDestroy(&sub[0]));
    PetscCall(VecDestroy(&sub[1]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode UpdateNormH(TaoSMALXE *s)
{
  PetscFunctionBegin;
  /* |PAP + rho Q| = max(|PAP|, rho): the two parts act on orthogonal subspaces */
  s->normH = s->projector ? PetscMax(s->normA, s->rho) : s->normA + s->rho * s->normC2;
  for (auto &blk : s->blocks) PetscCall(TaoQPSetNormEstimate(blk.sub, s->normH));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode EstimateNorms(Tao tao, TaoSMALXE *s)
{
  PetscInt    products = 0;
  char        prefix[256];
  const char *tprefix;
  PetscReal   margin = s->norm_margin >= 0 ? s->norm_margin : (s->norm_method == QP_NORM_SLEPC ? 0.01 : 0.05);

  PetscFunctionBegin;
  /* |C|^2 = |C'C| (penalty form), once per state of C: no product with A (an empty C: a problem without equality) */
  if (!s->projector) {
    PetscObjectState sc;
    PetscCall(PetscObjectStateGet((PetscObject)s->C, &sc));
    if (sc != s->c_state || s->normA <= 0) {
      Mat      CtC;
      PetscInt rows;
      s->c_state = sc;
      PetscCall(MatGetSize(s->C, &rows, NULL));
      if (!rows) s->normC2 = 1;
      else {
        PetscCall(MatCreateNormal(s->C, &CtC));
        PetscCall(MatQPEstimateNorm(CtC, QP_NORM_POWER, 0.05, NULL, &s->normC2, NULL));
        PetscCall(MatDestroy(&CtC));
      }
    }
  }
  /* once per operator: repeated solves (successive approximations) reuse the estimate */
  {
    PetscObjectState sa, sq = 0;
    PetscCall(PetscObjectStateGet((PetscObject)tao->hessian, &sa));
    if (s->Q) PetscCall(PetscObjectStateGet((PetscObject)s->Q, &sq));
    if (s->normA > 0 && s->norm_user <= 0 && sa == s->hessian_state && sq == s->q_state) PetscFunctionReturn(PETSC_SUCCESS);
    s->hessian_state = sa;
    s->q_state       = sq;
  }
  PetscCall(TaoGetOptionsPrefix(tao, &tprefix));
  PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "%stao_smalxe_norm_", tprefix ? tprefix : ""));
  if (s->norm_user > 0) s->normA = s->norm_user;
  else if (s->projector) { /* |PAP|: H with rho = 0, each product one product with A */ s->rho = 0;
    PetscCall(MatQPClearNormEstimate(s->H));
    PetscCall(MatQPEstimateNorm(s->H, s->norm_method, margin, prefix, &s->normA, &products));
    PetscCall(MatQPClearNormEstimate(s->H));
  } else PetscCall(MatQPEstimateNorm(tao->hessian, s->norm_method, margin, prefix, &s->normA, &products));
  s->counters.estimate_mults += products;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -tao_max_it: checked in TaoSetFromOptions_SMALXE() (the option; -1 was accepted there) and when a solve starts
   (TaoSetMaximumIterations()) */
PetscErrorCode CheckMaxIt(Tao tao)
{
  const char *prefix;

  PetscFunctionBegin;
  PetscCall(TaoGetOptionsPrefix(tao, &prefix));
  PetscCheck(tao->max_it >= 1, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE, "-%stao_max_it %" PetscInt_FMT ": smalxe needs at least one outer iteration", prefix ? prefix : "",
             tao->max_it);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* An inner solve failed. A Hessian that is not symmetric, or a Q that is not an orthogonal projector, makes the
   inner Hessian (A + rho C'C, or PAP + rho Q) non-symmetric, and the inner solver then fails as on an indefinite
   one ("is the Hessian positive semidefinite?"). Test them with products (counted; only here, after a failure)
   and write the culprit to why, or "" when both pass. */
PetscErrorCode DiagnoseInnerFailure(Tao tao, TaoSMALXE *s, char why[], size_t len)
{
  PetscFunctionBegin;
  /* a Q built from C is C'C: C's rows are the user's to make orthonormal */
  PetscCall(MatDiagnoseOperators_Private(tao->hessian, s->normA, s->hessian_name.c_str(), 'A', s->Q && !s->Q_from_C ? s->Q : nullptr, s->projector_name.c_str(), why, len));
  s->counters.hessian_mults += 2;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One inner minimization: `sweeps` block Gauss-Seidel sweeps (one solve when monolithic).
   Leaves the gradient of L at the new x in s->g and returns the norm of its projected gradient. */
PetscErrorCode InnerSolve(Tao tao, TaoSMALXE *s, PetscReal *gp)
{
  const bool monolithic = Monolithic(s);

  PetscFunctionBegin;
  for (PetscInt sweep = 0; sweep < s->sweeps; sweep++) {
    for (size_t k = 0; k < s->blocks.size(); k++) {
      SMALXEBlock       &blk = s->blocks[k];
      QPCounters         before, after;
      TaoConvergedReason reason;
      s->current_block = (PetscInt)k;
      if (s->presolve) PetscCall(s->presolve(tao, (PetscInt)k, tao->solution, s->presolve_ctx));
      if (blk.is) { /* block linear term R_b (bx - H x_{-b}), x_{-b} = x with the block zeroed */
        PetscCall(VecCopy(tao->solution, s->w));
        PetscCall(VecISSet(s->w, blk.is, 0.0));
        PetscCall(MultH(s, s->w, s->g));
        s->counters.hessian_mults++;
        PetscCall(VecAYPX(s->g, -1.0, s->bx));
        PetscCall(VecScatterBegin(blk.scatter, s->g, blk.b, INSERT_VALUES, SCATTER_FORWARD));
        PetscCall(VecScatterEnd(blk.scatter, s->g, blk.b, INSERT_VALUES, SCATTER_FORWARD));
        PetscCall(VecScatterBegin(blk.scatter, tao->solution, blk.x, INSERT_VALUES, SCATTER_FORWARD));
        PetscCall(VecScatterEnd(blk.scatter, tao->solution, blk.x, INSERT_VALUES, SCATTER_FORWARD));
      } else PetscCall(VecCopy(s->bx, blk.b));
      PetscCall(TaoQPGetCounters(blk.sub, &before));
      PetscCall(TaoSolve(blk.sub));
      PetscCall(TaoQPGetCounters(blk.sub, &after));
      PetscCall(PetscInfo(tao,
                          "TAO smalxe outer %" PetscInt_FMT " block %zu: %" PetscInt_FMT " products, %" PetscInt_FMT " CG + %" PetscInt_FMT " expansion + %" PetscInt_FMT
                          " proportioning steps, |gP| %g (M |Cx - d| with M %g, eta %g), rho %g\n",
                          (PetscInt)s->feas_history.size(), k, after.hessian_mults - before.hessian_mults, after.cg_steps - before.cg_steps, after.expansion_steps - before.expansion_steps,
                          after.proportioning_steps - before.proportioning_steps, (double)blk.sub->residual, (double)s->M, (double)s->eta, (double)s->rho));
      s->counters.nested_hessian_mults += after.hessian_mults - before.hessian_mults;
      s->counters.nested_iterations += after.iterations - before.iterations;
      s->counters.estimate_mults += after.estimate_mults - before.estimate_mults;
      PetscCall(TaoGetConvergedReason(blk.sub, &reason));
      if (reason == TAO_DIVERGED_MAXITS) s->limited_now = (PetscInt)k;
      if (reason == TAO_DIVERGED_NAN) { /* overflow: the outer loop ends with DIVERGED_NAN, a reason, not an error */
        *gp = std::numeric_limits<PetscReal>::quiet_NaN();
        PetscFunctionReturn(PETSC_SUCCESS);
      }
      if (reason == TAO_DIVERGED_USER) {
        char why[256];
        PetscCall(DiagnoseInnerFailure(tao, s, why, sizeof(why)));
        PetscCheck(!why[0], PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONG, "TAO smalxe: %s; the inner solve of block %zu failed (%s)", why, k, TaoConvergedReasons[reason]);
        SETERRQ(PetscObjectComm((PetscObject)tao), PETSC_ERR_NOT_CONVERGED,
                "TAO smalxe: the inner solve of block %zu failed (%s); is the Hessian positive semidefinite on the feasible set, and q bounded below?", k, TaoConvergedReasons[reason]);
      }
      if (blk.is) {
        PetscCall(VecScatterBegin(blk.scatter, blk.x, tao->solution, INSERT_VALUES, SCATTER_REVERSE));
        PetscCall(VecScatterEnd(blk.scatter, blk.x, tao->solution, INSERT_VALUES, SCATTER_REVERSE));
      }
    }
  }
  if (monolithic && s->sweeps == 1) { /* the nested solver's final gradient is the gradient of L */
    Vec g;
    PetscCall(TaoGetGradient(s->blocks[0].sub, &g, NULL, NULL));
    PetscCall(VecCopy(g, s->g));
    *gp = s->blocks[0].sub->residual;
  } else { /* after a sweep the earlier blocks' gradients are stale: one fresh product */
    SeparableSet set = s->set;
    PetscCall(MultH(s, tao->solution, s->g));
    s->counters.hessian_mults++;
    PetscCall(VecAXPY(s->g, -1.0, s->bx));
    if (set) PetscCall(PetscObjectReference((PetscObject)set));
    else {
      PetscInt n, N;
      PetscCall(VecGetLocalSize(tao->solution, &n));
      PetscCall(VecGetSize(tao->solution, &N));
      PetscCall(SeparableSetCreate(PetscObjectComm((PetscObject)tao), n, N, &set));
      PetscCall(SeparableSetSetBounds(set, tao->XL, tao->XU));
    }
    PetscCall(SeparableSetProjectedGradient(set, tao->solution, s->g, s->w));
    PetscCall(SeparableSetDestroy(&set));
    PetscCall(Norm(s->w, gp));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* z = (I - theta Q) g, theta = rho/(||PAP|| + rho): see the penalty preconditioner at the top */
PetscErrorCode PenaltyPCApply(PC pc, Vec g, Vec z)
{
  TaoSMALXE *s;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &s));
  PetscCall(MatMult(s->Q, g, z));
  PetscCall(VecAYPX(z, -s->rho / (s->normA + s->rho), g));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* z = P M P g + (q_scale/rho) Q g, M the preconditioner of A given by TaoSMALXESetProjectedPreconditioner().
   H = PAP + rho Q is block diagonal in range(P) + range(Q), so its inverse is (PAP)^+ + Q/rho: M
   approximates the first block (P M P keeps it there, whatever M does to range(Q)), 1/rho the second
   exactly. Two products with Q, one application of M. */
PetscErrorCode ProjectedPCApply(PC pc, Vec g, Vec z)
{
  TaoSMALXE *s;

  PetscFunctionBegin;
  PetscCall(PCShellGetContext(pc, &s));
  PetscCall(MatMult(s->Q, g, s->pcq));
  PetscCall(VecWAXPY(s->pcp, -1.0, s->pcq, g)); /* P g */
  PetscCall(PCApply(s->projected_pc, s->pcp, z));
  PetscCall(MatMult(s->Q, z, s->pcp));
  PetscCall(VecAXPY(z, -1.0, s->pcp)); /* P M P g (a subtraction: no multiply to fuse) */
  PetscCall(ReproducibleAXPY(z, s->pc_q_scale / s->rho, s->pcq));
  PetscFunctionReturn(PETSC_SUCCESS);
}

const char kPenaltyPCName[]   = "smalxe penalty preconditioner I - rho/(||PAP|| + rho) Q";
const char kProjectedPCName[] = "smalxe projected preconditioner P M P + Q/rho";

/* Puts the projected preconditioner (when a PC of A was given) or the penalty preconditioner into the
   inner solver's PC when that is PCNONE or one of ours (a PC the user chose stays), or takes it out again
   when neither is wanted. Only the projector form with one inner solver has them: a Gauss-Seidel block
   would need Q's block, the penalty form (C C')^-1. */
PetscErrorCode UpdatePenaltyPC(TaoSMALXE *s)
{
  PC          pc;
  PetscBool   none, shell;
  const char *name = nullptr;

  PetscFunctionBegin;
  if (!Monolithic(s)) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(TaoQPGetPC(s->blocks[0].sub, &pc));
  if (!pc) PetscFunctionReturn(PETSC_SUCCESS); /* not a QP type of ours */
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCNONE, &none));
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCSHELL, &shell));
  if (shell) PetscCall(PCShellGetName(pc, &name));
  const bool  ours      = shell && name && (!std::strcmp(name, kPenaltyPCName) || !std::strcmp(name, kProjectedPCName));
  const bool  projected = s->projector && s->projected_pc;
  const bool  want      = s->projector && (s->penalty_pc || s->projected_pc);
  const char *wanted    = projected ? kProjectedPCName : kPenaltyPCName;
  if (want && (none || (ours && std::strcmp(name, wanted)))) {
    PetscCall(PCSetType(pc, PCSHELL));
    PetscCall(PCShellSetContext(pc, s));
    PetscCall(PCShellSetApply(pc, projected ? ProjectedPCApply : PenaltyPCApply));
    PetscCall(PCShellSetName(pc, wanted));
  } else if (!want && ours) PetscCall(PCSetType(pc, PCNONE));
  if (want && projected) {
    if (!s->pcq) {
      PetscCall(VecDuplicate(s->tao->solution, &s->pcq));
      PetscCall(VecDuplicate(s->tao->solution, &s->pcp));
    }
    PetscCall(PCSetUp(s->projected_pc));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The balancing factor in effect: -1 (the default) is 2 with Gauss-Seidel blocks and 0 (off) with one inner solver */
PetscReal BalanceFactor(const TaoSMALXE *s)
{
  if (s->rho_balance >= 0) return s->rho_balance;
  return s->blocks.size() > 1 ? 2.0 : 0.0;
}

/* Residual balancing of the penalty (as for ADMM), for Gauss-Seidel blocks: rho Q (rho C'C) couples the
   blocks, since C mixes the variables of several blocks (in the contact problem the tangential multipliers
   enter the rigid-body equilibrium with the gluing ones), and one sweep per outer iteration then leaves a
   projected gradient that falls only as fast as the sweep converges. When |gP| is further from its
   tolerance than |Cx - d| from its own by the factor, rho is halved (weaker coupling: the sweep converges
   faster, the multiplier update is slower); in the opposite case it is doubled, never above its default
   (-tao_smalxe_rho) nor below 1% of it. On the METIS bricks of docs/contact.md this takes merged from 86
   to 46 (16 parts) and from 372 to 94 (48 parts) outer iterations; the three cubes keep their counts at
   F = 0.1 (the two residuals stay balanced there). */
PetscErrorCode BalancePenalty(Tao tao, TaoSMALXE *s, PetscReal gp, PetscReal e, PetscReal rho_top)
{
  const PetscReal mu = BalanceFactor(s);
  PetscReal       tol_g, tol_e;

  PetscFunctionBegin;
  if (!(mu > 1)) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(Tolerances(tao, s, &tol_g, &tol_e));
  const PetscReal rg = gp / tol_g, re = e / tol_e, rho0 = s->rho;
  if (rg > mu * re && s->rho > 0.01 * rho_top) s->rho /= 2;
  else if (re > mu * rg && s->rho < rho_top) s->rho = PetscMin(2 * s->rho, rho_top);
  if (s->rho != rho0) {
    s->rho_changes++;
    PetscCall(PetscInfo(tao, "TAO smalxe: |gP| / tol %g, |Cx - d| / tol %g: rho %g -> %g\n", (double)rg, (double)re, (double)rho0, (double)s->rho));
    PetscCall(UpdateNormH(s));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoSolve_SMALXE(Tao tao)
{
  TaoSMALXE *s     = Get(tao);
  PetscReal  Lprev = 0;

  PetscFunctionBegin;
  if (tao->ops->computehessian) PetscCall(TaoComputeHessian(tao, tao->solution, tao->hessian, tao->hessian_pre));
  PetscCheck(tao->hessian, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE, "TAO smalxe: no Hessian; call TaoSetHessian()");
  {
    PetscInt m, n, N;
    PetscCall(MatGetSize(tao->hessian, &m, &n));
    PetscCall(VecGetSize(tao->solution, &N));
    PetscCheck(m == n && n == N, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_SIZ,
               "TAO smalxe: the Hessian must be square with the solution's size %" PetscInt_FMT ", it is %" PetscInt_FMT " x %" PetscInt_FMT, N, m, n);
  }
  PetscCall(TaoQPCheckTolerances_Private(tao, PETSC_TRUE));
  PetscCall(CheckMaxIt(tao));
  PetscCall(TaoComputeVariableBounds(tao));
  if (s->setup) {
    PetscCall(RefreshEquality(tao, s));
    PetscCall(RefreshBlockSets(s));
  }
  PetscCall(SetUpOnce(tao, s));
  PetscCall(PassVariableBounds(tao, s));
  if (!s->b_user) {
    if (!s->b) PetscCall(VecDuplicate(tao->solution, &s->b));
    PetscCheck(tao->ops->computegradient || tao->ops->computeobjectiveandgradient, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE,
               "TAO smalxe: no linear term; call TaoQPSetLinearTerm() or set a gradient routine (b = -gradient at 0)");
    PetscCall(VecSet(tao->stepdirection, 0.0));
    PetscCall(TaoComputeGradient(tao, tao->stepdirection, s->b));
    PetscCall(VecScale(s->b, -1.0));
  }

  /* norms, penalty, and the constant part of the linear term */
  PetscCall(EstimateNorms(tao, s));
  const PetscReal rho_later = s->rho_rel * s->normA / (s->projector ? 1.0 : s->normC2);
  s->rho                    = s->rho_first * rho_later;
  if (s->projector) {
    if (!s->Q_from_C) { /* a particular solution in range(Q), then P(b - A x~) */
      PetscCall(MatMult(s->Q, s->xt, s->w));
      PetscCall(VecCopy(s->w, s->xt));
    }
    PetscCall(MatMult(tao->hessian, s->xt, s->w));
    s->counters.hessian_mults++;
    {
      PetscReal xAx, xb;
      PetscCall(ReproducibleDot2(s->xt, s->w, s->xt, s->b, &xAx, &xb));
      PetscCall(ReproducibleDot(s->xt, s->xt, &s->dnorm2));
      s->qxt = 0.5 * xAx - xb;
    }
    PetscCall(VecAYPX(s->w, -1.0, s->b));
    PetscCall(MatMult(s->Q, s->w, s->hq));
    s->hq_id = s->wf_id = -1; /* a new solve: x~ may have changed, and hq is not Q of an iterate */
    PetscCall(VecWAXPY(s->bconst, -1.0, s->hq, s->w));
    PetscCall(Norm(s->bconst, &s->beff));
    {
      /* |P(b - A x~)| = 0 (uniform gaps under a total-force equality: x~ already balances b in range(P)) made every
         tolerance 0, and the inner solve chased rounding until a direction of zero curvature ended it with "is the
         Hessian positive semidefinite?". The unprojected |b - A x~| is the scale then */
      PetscReal unprojected;
      PetscCall(Norm(s->w, &unprojected));
      s->beff = PetscMax(s->beff, 1e-8 * unprojected);
    }
    if (s->nu_start) { /* given for this solve (a start that knows its multiplier): used once */
      PetscCall(VecCopy(s->nu_start, s->nu));
      PetscCall(VecDestroy(&s->nu_start));
    } else if (!RecycleMultiplier(tao, s)) PetscCall(VecSet(s->nu, 0.0));
  } else {
    PetscCall(Norm(s->b, &s->beff));
    {
      /* b = 0 with d != 0 (no load, a prescribed resultant): the gradient's scale is that of the multipliers C x = d
         needs, ||A|| |d| / ||C||, as 0 tolerances make the inner solves chase rounding */
      PetscReal dn;
      PetscCall(Norm(s->d, &dn));
      s->beff = PetscMax(s->beff, 1e-8 * s->normA * dn / PetscSqrtReal(PetscMax(s->normC2, PETSC_SMALL)));
    }
    PetscCall(ReproducibleDot(s->d, s->d, &s->dnorm2));
    s->qxt = 0;
    if (!RecycleMultiplier(tao, s)) PetscCall(VecSet(s->mu, 0.0));
  }
  PetscCall(UpdateNormH(s));
  PetscCall(UpdatePenaltyPC(s));
  s->M   = s->M_rel * s->normH;
  s->eta = s->eta_rel * s->beff;

  tao->reason = TAO_CONTINUE_ITERATING;
  s->counters.solves++;
  s->feas_history.clear();
  s->mult_history.clear();
  s->growth_k[0] = s->growth_k[1] = -1;
  s->gp_history.clear();
  s->limited_history.clear();
  s->stagnated      = PETSC_FALSE;
  s->stalled        = PETSC_FALSE;
  s->inner_limited  = -1;
  s->stall_rho_done = 0;
  s->slow_done      = 0;
  s->stall_base     = 0;
  QPRefusedStops refused; /* exact stop: the stops the inner solver's exact gradient refused */
  s->accuracy_floor = PETSC_FALSE;
  for (PetscInt k = 0;; k++) {
    PetscReal gp, e, L;
    PetscReal xg, xb, md;
    PetscCall(UpdateInnerLinearTerm(s));
    s->limited_now = -1;
    PetscCall(InnerSolve(tao, s, &gp));
    /* a pre-solve hook that moves the set from the iterate (the Coulomb radii F l_n) hands the first inner solve
       a set computed from the starting point, which may be far from any solution (the particular solution of
       C x = d: its normal multipliers are no contact pressure); the multiplier update after that solve then
       meets a set that moves again by half its size. A second pass from the solved iterate, the hook between,
       lets the first update see a set near its fixed point (-tao_smalxe_repeat_first; docs/scale.md) */
    if (k < s->repeat_first && s->presolve && !PetscIsInfOrNanReal(gp)) PetscCall(InnerSolve(tao, s, &gp));
    PetscCall(Feasibility(s, tao->solution, &e));
    /* L(x, mu, rho) = 1/2 x'(g - bx) - mu'd + rho/2 |d|^2 (general form), or
       1/2 x'(g - bx) - nu'x~ + rho/2 |x~|^2 + q(x~) (projector form) */
    PetscCall(ReproducibleDot2(tao->solution, s->g, tao->solution, s->bx, &xg, &xb));
    if (s->projector) PetscCall(ReproducibleDot(s->nu, s->xt, &md));
    else PetscCall(ReproducibleDot(s->mu, s->d, &md));
    L = 0.5 * (xg - xb) - md + 0.5 * s->rho * s->dnorm2 + s->qxt;
    /* L sums terms that cancel: a change of L below their rounding says nothing (late in a solve
       the semi-monotonicity test would otherwise decide by rounding, differently for A and 1e12 A) */
    const PetscReal Lnoise = 1e-12 * (0.5 * (PetscAbsReal(xg) + PetscAbsReal(xb)) + PetscAbsReal(md) + 0.5 * s->rho * s->dnorm2 + PetscAbsReal(s->qxt));
    s->gpnorm              = gp;
    s->feas                = e;
    PetscCallCXX(s->feas_history.push_back(e));
    PetscCallCXX(s->gp_history.push_back(gp));
    PetscCallCXX(s->limited_history.push_back(s->limited_now));
    PetscCall(VecCopy(s->g, tao->gradient));
    tao->niter = k;
    s->counters.iterations++;
    if (PetscIsInfOrNanReal(L) || PetscIsInfOrNanReal(gp) || PetscIsInfOrNanReal(e)) { /* TaoMonitor() would blame a user function */
      tao->fc       = L;
      tao->residual = gp;
      tao->cnorm    = e;
      PetscCall(PetscInfo(tao, "TAO smalxe: L, |gP| or |Cx - d| is not a finite number at outer iteration %" PetscInt_FMT " (overflow: data near the largest real?)\n", k));
      PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_NAN));
      break;
    }
    PetscCall(TaoLogConvergenceHistory(tao, L, gp, e, tao->ksp_its));
    PetscCall(TaoMonitor(tao, k, L, gp, e, 0.0));
    /* the multiplier update comes before the test: the returned multiplier is the updated one */
    PetscCall(PetscLogEventBegin(QP_MultiplierUpdate, 0, 0, 0, 0));
    PetscCall(UpdateMultiplier(s, k, e));
    {
      PetscReal mn;
      PetscCall(Norm(s->projector ? s->nu : s->mu, &mn));
      PetscCallCXX(s->mult_history.push_back(mn));
    }
    PetscCall(SnapshotMultiplier(s, k));
    PetscCall(PetscLogEventEnd(QP_MultiplierUpdate, 0, 0, 0, 0));
    PetscUseTypeMethod(tao, convergencetest, tao->cnvP);
    if (tao->reason > 0 && s->exact_stop && Monolithic(s)) {
      /* the inner solver's |gP| may come from CG's recurred gradient, which drifts from the exact one where A is
         ill conditioned (a QP of condition 1e12 was called converged at 280 times the tolerance): confirm it */
      PetscReal exact, tol_g, tol_e;
      PetscBool confirmed;
      PetscCall(TaoQPConfirmGradient_Private(s->blocks[0].sub, &exact, &confirmed));
      PetscCall(Tolerances(tao, s, &tol_g, &tol_e));
      if (confirmed) s->stops_confirmed++;
      if (confirmed && exact > tol_g) {
        PetscCall(
            PetscInfo(tao, "TAO smalxe outer %" PetscInt_FMT ": the inner solver's exact |gP| = %g is above the tolerance %g that its recurred one met: going on\n", k, (double)exact, (double)tol_g));
        s->stops_refused++;
        s->gpnorm            = exact;
        s->gp_history.back() = exact;
        tao->residual        = exact;
        tao->reason          = TAO_CONTINUE_ITERATING;
        /* where rounding sets a floor, say so (as mpgp does) rather than run to the iteration limit */
        if (refused.AtFloor(exact)) {
          s->accuracy_floor = PETSC_TRUE;
          PetscCall(PetscInfo(tao, "TAO smalxe: the exact |gP| stays at %g above the tolerance %g: rounding limits the accuracy (an ill-conditioned Hessian)\n", (double)exact, (double)tol_g));
          PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_USER));
        }
      } else if (confirmed) refused.Accepted();
    }
    if (tao->reason != TAO_CONTINUE_ITERATING) break;
    /* semi-monotonicity: if L did not grow enough, tighten the inner precision (M) or raise rho.
       M stops at a floor: when a pre-solve hook moves the set (the radii of a friction law), L may
       drop for that reason alone, and without a floor M would collapse and with it the inner
       tolerances (thousands of useless inner iterations) */
    if (k > 0 && L < Lprev + 0.5 * s->rho * e * e - Lnoise) {
      if (s->update == SMALXE_UPDATE_M) s->M = PetscMax(s->M / s->beta, s->M_min_rel * s->normH);
      else if (s->update == SMALXE_UPDATE_RHO) {
        s->rho *= s->beta;
        PetscCall(UpdateNormH(s));
      }
    }
    Lprev = L;
    /* a smaller penalty for the first inner solve, which finds the active set from the multiplier 0: its
       expansion steps have the fixed length 1.95/||H||, so they pay for a large rho; the later solves mostly follow the
       multiplier, and a larger rho speeds the multiplier's convergence up (-tao_smalxe_rho_first) */
    if (k == 0 && s->rho_first != 1) {
      s->rho = rho_later;
      PetscCall(UpdateNormH(s));
    }
    /* the balancing's ceiling is the default penalty, times the slow-loop rule's factor once that rule raised it */
    if (k > 0) PetscCall(BalancePenalty(tao, s, gp, e, s->slow_done ? s->slow_factor * rho_later : rho_later));
  }
  if (s->counters_view) {
    PetscViewer viewer;
    PetscCall(PetscViewerASCIIGetStdout(PetscObjectComm((PetscObject)tao), &viewer));
    PetscCall(QPCountersViewJSON(&s->counters, TAOSMALXE, viewer));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoSetUp_SMALXE(Tao tao)
{
  PetscFunctionBegin;
  if (!tao->gradient) PetscCall(VecDuplicate(tao->solution, &tao->gradient));
  if (!tao->stepdirection) PetscCall(VecDuplicate(tao->solution, &tao->stepdirection));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoSetFromOptions_SMALXE(Tao tao, CONEFETI_OPTIONS_ITEMS PetscOptionsObject)
{
  TaoSMALXE  *s = Get(tao);
  PetscReal   value;
  PetscBool   set;
  const char *p; /* the options prefix, for the messages */
  MPI_Comm    comm = PetscObjectComm((PetscObject)tao);

  PetscFunctionBegin;
  PetscCall(CheckMaxIt(tao));
  PetscCall(TaoGetOptionsPrefix(tao, &p));
  if (!p) p = "";
  PetscOptionsHeadBegin(PetscOptionsObject, "smalxe: semi-monotonic augmented Lagrangian for C x = d (conefeti)");
  PetscCall(PetscOptionsReal("-tao_smalxe_rho", "Penalty rho relative to ||A|| (||PAP|| in projector form, ||A||/||C||^2 otherwise)", "TaoSMALXE", s->rho_rel, &s->rho_rel, NULL));
  PetscCall(PetscOptionsReal("-tao_smalxe_rho_first", "Penalty of the first outer iteration relative to -tao_smalxe_rho (the later ones use -tao_smalxe_rho)", "TaoSMALXE", s->rho_first, &s->rho_first,
                             NULL));
  PetscCall(PetscOptionsInt("-tao_smalxe_repeat_first", "With a pre-solve hook: the inner solves of this many first outer iterations run twice, the hook before each (0: never)",
                            "TaoSMALXESetPreSolve", s->repeat_first, &s->repeat_first, NULL));
  PetscCall(PetscOptionsReal("-tao_smalxe_M", "Initial M relative to ||H||: inner solves stop when |gP| <= min(M |Cx - d|, eta)", "TaoSMALXE", s->M_rel, &s->M_rel, NULL));
  PetscCall(PetscOptionsReal("-tao_smalxe_M_min", "Floor of M relative to ||H|| (the semi-monotonicity updates stop there)", "TaoSMALXE", s->M_min_rel, &s->M_min_rel, NULL));
  PetscCall(PetscOptionsReal("-tao_smalxe_eta", "eta relative to |b| (|P(b - A x~)| in projector form)", "TaoSMALXE", s->eta_rel, &s->eta_rel, NULL));
  PetscCall(PetscOptionsReal("-tao_smalxe_beta", "Factor > 1 by which M falls (or rho grows) when the Lagrangian did not grow enough", "TaoSMALXE", s->beta, &s->beta, NULL));
  PetscCall(PetscOptionsEnum("-tao_smalxe_update", "What the semi-monotonicity test updates: M (SMALBE-M), rho (SMALBE) or none", "TaoSMALXE", SMALXEUpdates, (PetscEnum)s->update,
                             (PetscEnum *)&s->update, NULL));
  PetscCall(PetscOptionsBool("-tao_smalxe_projector", "Projector form: C has orthonormal rows; inner Hessian PAP + rho Q", "TaoSMALXESetProjector", s->projector, &s->projector, NULL));
  PetscCall(
      PetscOptionsReal("-tao_smalxe_block_rtol", "With blocks: a block solve also stops when its projected gradient fell by this factor", "TaoSMALXESetBlocks", s->block_rtol, &s->block_rtol, NULL));
  PetscCall(PetscOptionsInt("-tao_smalxe_sweeps", "Block Gauss-Seidel sweeps per outer iteration (with TaoSMALXESetBlocks())", "TaoSMALXESetBlocks", s->sweeps, &s->sweeps, NULL));
  PetscCall(PetscOptionsReal("-tao_smalxe_norm", "Use this ||A|| (||PAP|| in projector form) instead of estimating it", "TaoQPSetNormEstimate", s->norm_user, &value, &set));
  if (set) {
    /* checked here so that the message names the option, not TaoQPSetNormEstimate() */
    PetscCheck(value >= 0 && !PetscIsInfOrNanReal(value), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_norm must be finite and > 0 (0 to estimate), got %g", p, (double)value);
    PetscCall(TaoQPSetNormEstimate(tao, value));
  }
  PetscCall(PetscOptionsEnum("-tao_smalxe_norm_method", "How ||A|| is estimated", "MatQPEstimateNorm", QPNormMethods, (PetscEnum)s->norm_method, (PetscEnum *)&s->norm_method, NULL));
  PetscCall(PetscOptionsReal("-tao_smalxe_norm_margin", "Relative safety margin of the norm estimate", "MatQPEstimateNorm", s->norm_margin, &s->norm_margin, NULL));
  PetscCall(PetscOptionsReal("-tao_smalxe_inner_floor", "Inner solves also stop when |gP| <= this fraction of the final tolerance max(gatol, gttol |b|) (0: never; at most 1)", "TaoSMALXE",
                             s->inner_floor, &s->inner_floor, NULL));
  PetscCheck(s->inner_floor >= 0 && s->inner_floor <= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_inner_floor must be in [0, 1], got %g", p, (double)s->inner_floor);
  PetscCall(PetscOptionsInt("-tao_smalxe_anderson", "Anderson acceleration of the multiplier update: depth (0: the plain update mu += rho (Cx - d); -1: 3, or 0 with Gauss-Seidel blocks)",
                            "TaoSMALXESetAnderson", s->anderson, &s->anderson, NULL));
  PetscCheck(s->anderson >= -1 && s->anderson <= 20, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_anderson: the depth must be in [0, 20] (or -1: automatic), got %" PetscInt_FMT, p, s->anderson);
  PetscCall(PetscOptionsInt("-tao_smalxe_anderson_start",
                            "First outer iteration (counted from 0, at least 1) whose multiplier update is accelerated (the first inner solves are loose and make poor history)",
                            "TaoSMALXESetAnderson", s->anderson_start, &s->anderson_start, NULL));
  PetscCheck(s->anderson_start >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_anderson_start: must be >= 1, got %" PetscInt_FMT, p, s->anderson_start);
  PetscCall(PetscOptionsInt("-tao_smalxe_stagnation_its",
                            "Stop when |Cx - d| makes less than 1% progress in this many outer iterations: infeasible if the multiplier grew by a quarter meanwhile, stalled if it settled (0: never)",
                            "TaoSMALXEGetStagnated", s->stagnation_its, &s->stagnation_its, NULL));
  PetscCall(PetscOptionsInt("-tao_smalxe_slow_its",
                            "Projector form, with -tao_smalxe_update M: after this many outer iterations, the first time |Cx - d| is the residual further from its tolerance, rho is multiplied by "
                            "-tao_smalxe_slow_rho_factor (once per solve; 0: never)",
                            "TaoSMALXE", s->slow_its, &s->slow_its, NULL));
  PetscCall(PetscOptionsReal("-tao_smalxe_slow_rho_factor", "The factor (>= 1) by which -tao_smalxe_slow_its multiplies rho (1: off)", "TaoSMALXE", s->slow_factor, &s->slow_factor, NULL));
  PetscCheck(s->slow_its >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_slow_its must be >= 0 (0: never), got %" PetscInt_FMT, p, s->slow_its);
  PetscCheck(s->slow_factor >= 1 && !PetscIsInfOrNanReal(s->slow_factor), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_slow_rho_factor must be finite and >= 1, got %g", p, (double)s->slow_factor);
  PetscCall(PetscOptionsInt("-tao_smalxe_stall_rho_growths",
                            "A stall (no 1% progress in -tao_smalxe_stagnation_its outer iterations) with |Cx - d| above 10 times its tolerance first multiplies rho by -tao_smalxe_beta this many "
                            "times, each with a full window again (with -tao_smalxe_update M)",
                            "TaoSMALXEGetStalled", s->stall_rho_growths, &s->stall_rho_growths, NULL));
  PetscCheck(s->stall_rho_growths >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_stall_rho_growths must be >= 0 (0: a stall stops the loop), got %" PetscInt_FMT, p, s->stall_rho_growths);
  PetscCall(PetscOptionsInt("-tao_smalxe_inner_limit_its", "Stop when the inner solves reach their iteration limit in this many outer iterations in a row without 1% progress (0: never)",
                            "TaoSMALXEGetInnerLimited", s->inner_limit_its, &s->inner_limit_its, NULL));
  PetscCheck(s->inner_limit_its >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_inner_limit_its must be >= 0 (0: never), got %" PetscInt_FMT, p, s->inner_limit_its);
  PetscCall(PetscOptionsBool("-tao_smalxe_exact_stop", "Confirm a stop on the inner solver's exact gradient (one product; off in the contact solves, which check their answer from scratch)",
                             "TaoSMALXESetExactStop", s->exact_stop, &s->exact_stop, NULL));
  PetscCall(PetscOptionsBool("-tao_smalxe_penalty_pc", "Projector form: precondition the inner CG steps by I - rho/(||PAP|| + rho) Q in face (unless the inner solver has a PC of its own)",
                             "TaoSMALXESetPenaltyPreconditioner", s->penalty_pc, &s->penalty_pc, NULL));
  PetscCall(PetscOptionsReal("-tao_smalxe_pc_q_scale", "Projector form with TaoSMALXESetProjectedPreconditioner(): the inner CG steps use P M P + (this/rho) Q", "TaoSMALXESetProjectedPreconditioner",
                             s->pc_q_scale, &s->pc_q_scale, NULL));
  PetscCall(PetscOptionsReal("-tao_smalxe_rho_balance",
                             "With blocks: halve rho when |gP| is further from its tolerance than |Cx - d| by this factor (> 1), double it (up to -tao_smalxe_rho) in the opposite case (0: off; -1: 2 "
                             "with blocks, 0 without)",
                             "TaoSMALXESetBlocks", s->rho_balance, &s->rho_balance, NULL));
  PetscCall(PetscOptionsBool("-tao_smalxe_counters_view", "Print the counters as one JSON line after each solve", "QPCountersViewJSON", s->counters_view, &s->counters_view, NULL));
  PetscOptionsHeadEnd();
  /* "x > 0" alone lets inf through: an infinite rho reaches the nested solver as an infinite ||H|| (an
     error blaming TaoQPSetNormEstimate()), an infinite M or eta never tightens the inner solves (the
     outer loop then stagnates and is diagnosed as an equality that cannot be met), an infinite beta
     sends M straight to its floor */
  PetscCheck(s->rho_rel > 0 && !PetscIsInfOrNanReal(s->rho_rel), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_rho must be finite and > 0, got %g", p, (double)s->rho_rel);
  PetscCheck(s->rho_first > 0 && !PetscIsInfOrNanReal(s->rho_first), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_rho_first must be finite and > 0, got %g", p, (double)s->rho_first);
  PetscCheck(s->repeat_first >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_repeat_first must be >= 0 (0: never), got %" PetscInt_FMT, p, s->repeat_first);
  PetscCheck(s->M_rel > 0 && !PetscIsInfOrNanReal(s->M_rel), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_M must be finite and > 0, got %g", p, (double)s->M_rel);
  PetscCheck(s->M_min_rel >= 0 && !PetscIsInfOrNanReal(s->M_min_rel), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_M_min must be finite and >= 0 (0: no floor), got %g", p, (double)s->M_min_rel);
  PetscCheck(s->eta_rel > 0 && !PetscIsInfOrNanReal(s->eta_rel), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_eta must be finite and > 0, got %g", p, (double)s->eta_rel);
  PetscCheck(s->beta > 1 && !PetscIsInfOrNanReal(s->beta), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_beta must be finite and > 1, got %g", p, (double)s->beta);
  PetscCheck(s->block_rtol >= 0 && s->block_rtol < 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_block_rtol must be in [0, 1) (0: off), got %g", p, (double)s->block_rtol);
  /* a negative margin stands for the method's default; a NaN would silently become that default too */
  PetscCheck(!PetscIsInfOrNanReal(s->norm_margin), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_norm_margin must be finite (>= 0, or negative for the method's default), got %g", p,
             (double)s->norm_margin);
  PetscCheck(s->stagnation_its >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_stagnation_its must be >= 0 (0: never), got %" PetscInt_FMT, p, s->stagnation_its);
  PetscCheck(s->rho_balance == -1 || s->rho_balance == 0 || (s->rho_balance > 1 && !PetscIsInfOrNanReal(s->rho_balance)), comm, PETSC_ERR_ARG_OUTOFRANGE,
             "-%stao_smalxe_rho_balance must be a finite factor > 1 (0: off, -1: automatic), got %g", p, (double)s->rho_balance);
  PetscCheck(s->pc_q_scale > 0 && !PetscIsInfOrNanReal(s->pc_q_scale), comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_pc_q_scale must be finite and > 0, got %g", p, (double)s->pc_q_scale);
  PetscCheck(s->sweeps >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%stao_smalxe_sweeps must be >= 1, got %" PetscInt_FMT, p, s->sweeps);
  PetscCheck(s->norm_method != QP_NORM_USER || s->norm_user > 0, comm, PETSC_ERR_ARG_WRONG, "-%stao_smalxe_norm_method user needs -%stao_smalxe_norm <value>", p, p);
  /* the nested solvers read their options with ours (their type: from the options, else decided at setup), under
     our prefix as it is now: TaoSetOptionsPrefix() after TaoSetType() does not reach them (KSPSetOptionsPrefix()
     passes it to the PC; TAO has no such hook); a prefix the user gave one of them is kept */
  for (auto &blk : s->blocks) {
    PetscBool   typed;
    const char *subprefix;
    char        want[256];
    PetscCall(PetscSNPrintf(want, sizeof(want), "%s%s", p, blk.suffix.c_str()));
    PetscCall(TaoGetOptionsPrefix(blk.sub, &subprefix));
    if (blk.prefix == (subprefix ? subprefix : "") && blk.prefix != want) { /* ours, not one the user gave it */
      PetscCall(TaoSetOptionsPrefix(blk.sub, want));
      PetscCallCXX(blk.prefix = want);
    }
    PetscCall(PetscOptionsHasName(((PetscObject)blk.sub)->options, ((PetscObject)blk.sub)->prefix, "-tao_type", &typed));
    if (typed || ((PetscObject)blk.sub)->type_name) PetscCall(TaoSetFromOptions(blk.sub));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoView_SMALXE(Tao tao, PetscViewer viewer)
{
  TaoSMALXE *s = Get(tao);
  PetscBool  iascii;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (!iascii) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "smalxe: %s form, %s update (beta %g), rho %g, M %g, eta %g, ||%s|| %s %g\n", s->projector ? "projector" : "penalty", SMALXEUpdates[s->update],
                                   (double)s->beta, (double)s->rho, (double)s->M, (double)s->eta, s->projector ? "PAP" : "A", s->norm_user > 0 ? "given" : "estimated", (double)s->normA));
  if (s->normA > 0) { /* the tolerances exist once a solve has estimated the norm */
    PetscReal tol_g, tol_e;
    PetscCall(Tolerances(tao, s, &tol_g, &tol_e));
    PetscCall(PetscViewerASCIIPrintf(viewer, "stops when |projected gradient| <= %g and |Cx - d| <= %g\n", (double)tol_g, (double)tol_e));
  }
  PetscCall(PetscViewerASCIIPrintf(viewer, "last iterate: |projected gradient| %g, |Cx - d| %g\n", (double)s->gpnorm, (double)s->feas));
  if (s->rho_first != 1) PetscCall(PetscViewerASCIIPrintf(viewer, "the first outer iteration runs at %g rho\n", (double)s->rho_first));
  if (s->repeat_first > 0 && s->presolve)
    PetscCall(PetscViewerASCIIPrintf(viewer, "the inner solves of the first %" PetscInt_FMT " outer iteration(s) run twice, the pre-solve hook before each\n", s->repeat_first));
  if (AndersonDepth(s) > 0)
    PetscCall(PetscViewerASCIIPrintf(
        viewer, "Anderson acceleration of the multiplier, depth %" PetscInt_FMT " from outer iteration %" PetscInt_FMT ": %" PetscInt_FMT " accelerated updates, %" PetscInt_FMT " restarts\n",
        AndersonDepth(s), s->anderson_start, s->aAccelerated, s->aRestarts));
  else PetscCall(PetscViewerASCIIPrintf(viewer, "plain multiplier update (no Anderson acceleration)\n"));
  if (s->projected_pc && s->projector && Monolithic(s)) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "inner CG steps preconditioned in face by P M P + %g/rho Q, unless the inner solver has a PC of its own; M:\n", (double)s->pc_q_scale));
    PetscCall(PetscViewerASCIIPushTab(viewer));
    PetscCall(PCView(s->projected_pc, viewer));
    PetscCall(PetscViewerASCIIPopTab(viewer));
  } else if (s->penalty_pc && s->projector && Monolithic(s))
    PetscCall(PetscViewerASCIIPrintf(viewer, "inner CG steps preconditioned in face by I - rho/(||PAP|| + rho) Q, unless the inner solver has a PC of its own\n"));
  if (BalanceFactor(s) > 1) PetscCall(PetscViewerASCIIPrintf(viewer, "rho balanced between |gP| and |Cx - d| (factor %g): %" PetscInt_FMT " changes\n", (double)BalanceFactor(s), s->rho_changes));
  if (s->slow_done)
    PetscCall(PetscViewerASCIIPrintf(viewer, "a slow loop: rho multiplied by %g after %" PetscInt_FMT " outer iterations (-tao_smalxe_slow_its %" PetscInt_FMT ")\n", (double)s->slow_factor,
                                     s->slow_done, s->slow_its));
  if (tao->recycle) PetscCall(PetscViewerASCIIPrintf(viewer, "recycles the multiplier: a solve starts from the previous solve's multiplier\n"));
  if (s->stops_confirmed)
    PetscCall(PetscViewerASCIIPrintf(viewer, "stops confirmed on the inner solver's exact gradient: %" PetscInt_FMT " (one product each), %" PetscInt_FMT " refused\n", s->stops_confirmed,
                                     s->stops_refused));
  if (s->stagnated) PetscCall(PetscViewerASCIIPrintf(viewer, "stopped: |Cx - d| stagnated: the equality cannot be met over the set (or rho is far too small)\n"));
  if (s->accuracy_floor)
    PetscCall(PetscViewerASCIIPrintf(viewer, "stopped: the inner solver's exact projected gradient stays above the tolerance its recurred one met (rounding: an ill-conditioned Hessian)\n"));
  if (s->stalled) PetscCall(PetscViewerASCIIPrintf(viewer, "stopped: |Cx - d| stalled: no progress in %" PetscInt_FMT " outer iterations, the multiplier settled\n", s->stagnation_its));
  if (s->inner_limited >= 0)
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "stopped: the inner solves (block %" PetscInt_FMT " last) reached their iteration limit in %" PetscInt_FMT " outer iterations in a row without 1%% progress\n",
                                     s->inner_limited, s->inner_limit_its));
  PetscCall(QPCountersView(&s->counters, NULL, viewer));
  /* TaoView() prints tao->niter, the index of the last outer iteration counted from 0: one less than the
     outer iterations run, which the contact summaries report as Iter */
  if (tao->reason != TAO_CONTINUE_ITERATING)
    PetscCall(
        PetscViewerASCIIPrintf(viewer, "last solve: %" PetscInt_FMT " outer iterations (inner solves and multiplier updates; \"total number of iterations\" below counts from 0)\n", tao->niter + 1));
  if (s->blocks.size() > 1) PetscCall(PetscViewerASCIIPrintf(viewer, "inner solves: %zu blocks, %" PetscInt_FMT " Gauss-Seidel sweep(s) per outer iteration\n", s->blocks.size(), s->sweeps));
  for (auto &blk : s->blocks) PetscCall(TaoView(blk.sub, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ResetWork(TaoSMALXE *s)
{
  PetscFunctionBegin;
  for (Vec *v : {&s->mu, &s->nu, &s->nu_start, &s->bx, &s->bconst, &s->g, &s->hq, &s->hp, &s->hr, &s->r, &s->bin, &s->bout, &s->wf, &s->w, &s->pcq, &s->pcp, &s->growth_snap[0], &s->growth_snap[1]})
    PetscCall(VecDestroy(v));
  s->growth_k[0] = s->growth_k[1] = -1;
  PetscCall(AndersonDestroyHistory(s));
  PetscCall(MatDestroy(&s->H));
  if (s->Q_from_C) {
    PetscCall(MatDestroy(&s->Q));
    PetscCall(VecDestroy(&s->xt));
    s->Q_from_C = PETSC_FALSE;
  }
  s->setup = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

const char *const kComposed[] = {"TaoQPSetConstraints_C",
                                 "TaoQPGetConstraints_C",
                                 "TaoQPSetLinearTerm_C",
                                 "TaoQPSetNormEstimate_C",
                                 "TaoQPGetNormEstimate_C",
                                 "TaoQPGetCounters_C",
                                 "TaoQPResetCounters_C",
                                 "TaoSMALXESetEqualityConstraints_C",
                                 "TaoSMALXESetProjector_C",
                                 "TaoSMALXEGetSubsolver_C",
                                 "TaoSMALXESetBlocks_C",
                                 "TaoSMALXEGetBlockSubsolver_C",
                                 "TaoSMALXESetPreSolve_C",
                                 "TaoSMALXEGetEqualityMultiplier_C",
                                 "TaoSMALXEGetFeasibility_C",
                                 "TaoSMALXEGetMultiplierGrowth_C",
                                 "TaoSMALXESetConsistencyCheck_C",
                                 "TaoSMALXEGetOuterTolerances_C",
                                 "TaoSMALXEGetStagnated_C",
                                 "TaoSMALXEGetStalled_C",
                                 "TaoSMALXEGetInnerLimited_C",
                                 "TaoSMALXESetAnderson_C",
                                 "TaoSMALXESetPenaltyPreconditioner_C",
                                 "TaoSMALXESetExactStop_C",
                                 "TaoSMALXESetProjectedPreconditioner_C",
                                 "TaoSMALXEGetProjectedPreconditioner_C"};

PetscErrorCode TaoDestroy_SMALXE(Tao tao)
{
  TaoSMALXE *s = Get(tao);

  PetscFunctionBegin;
  PetscCall(ResetWork(s));
  PetscCall(DestroyBlocks(s));
  PetscCall(VecDestroy(&s->b));
  PetscCall(SeparableSetDestroy(&s->set));
  PetscCall(MatDestroy(&s->C));
  PetscCall(VecDestroy(&s->d));
  PetscCall(MatDestroy(&s->Q));
  PetscCall(VecDestroy(&s->xt));
  PetscCall(PCDestroy(&s->projected_pc));
  /* a later TaoSetType() keeps tao->ops->convergencetest: give the next type TAO's default, which it replaces by its own */
  if (tao->ops->convergencetest == OuterConvergenceTest) tao->ops->convergencetest = TaoDefaultConvergenceTest;
  for (const char *fn : kComposed) PetscCall(PetscObjectComposeFunction((PetscObject)tao, fn, NULL));
  delete s;
  tao->data = NULL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ---------- type-specific functions ---------- */

PetscErrorCode SetConstraints_SMALXE(Tao tao, SeparableSet set)
{
  TaoSMALXE *s = Get(tao);

  PetscFunctionBegin;
  PetscCheck(!s->setup, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE, "TAO smalxe: set the constraints before the first solve (change radii in place instead)");
  PetscCall(PetscObjectReference((PetscObject)set));
  PetscCall(SeparableSetDestroy(&s->set));
  s->set = set;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetConstraints_SMALXE(Tao tao, SeparableSet *set)
{
  PetscFunctionBegin;
  *set = Get(tao)->set;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetLinearTerm_SMALXE(Tao tao, Vec b)
{
  TaoSMALXE *s = Get(tao);

  PetscFunctionBegin;
  if (b) PetscCall(PetscObjectReference((PetscObject)b));
  PetscCall(VecDestroy(&s->b));
  s->b      = b;
  s->b_user = b ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetNormEstimate_SMALXE(Tao tao, PetscReal norm)
{
  PetscFunctionBegin;
  PetscCheck(norm >= 0 && !PetscIsInfOrNanReal(norm), PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE, "TaoQPSetNormEstimate: ||A|| must be finite and > 0 (0 to estimate), got %g",
             (double)norm);
  Get(tao)->norm_user = norm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetNormEstimate_SMALXE(Tao tao, PetscReal *norm)
{
  PetscFunctionBegin;
  *norm = Get(tao)->normA;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetCounters_SMALXE(Tao tao, QPCounters *c)
{
  PetscFunctionBegin;
  *c = Get(tao)->counters;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ResetCounters_SMALXE(Tao tao)
{
  TaoSMALXE *s = Get(tao);

  PetscFunctionBegin;
  s->counters = QPCounters{};
  for (auto &blk : s->blocks) PetscCall(TaoQPResetCounters(blk.sub));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetEqualityConstraints_SMALXE(Tao tao, Mat C, Vec d)
{
  TaoSMALXE *s = Get(tao);

  PetscFunctionBegin;
  PetscCheck(!s->setup, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE, "TAO smalxe: set the equality before the first solve");
  PetscCall(PetscObjectReference((PetscObject)C));
  PetscCall(PetscObjectReference((PetscObject)d));
  PetscCall(MatDestroy(&s->C));
  PetscCall(VecDestroy(&s->d));
  s->C = C;
  s->d = d;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetProjector_SMALXE(Tao tao, Mat Q, Vec xt)
{
  TaoSMALXE *s = Get(tao);

  PetscFunctionBegin;
  PetscCheck(!s->setup, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE, "TAO smalxe: set the projector before the first solve");
  PetscCall(PetscObjectReference((PetscObject)Q));
  PetscCall(MatDestroy(&s->Q));
  s->Q = Q;
  PetscCall(VecDestroy(&s->xt));
  PetscCall(VecDuplicate(xt, &s->xt)); /* a copy: it is replaced by Q x~ at each solve */
  PetscCall(VecCopy(xt, s->xt));
  s->projector = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetSubsolver_SMALXE(Tao tao, Tao *sub)
{
  TaoSMALXE *s = Get(tao);

  PetscFunctionBegin;
  PetscCheck(Monolithic(s), PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE, "TAO smalxe: with blocks, use TaoSMALXEGetBlockSubsolver()");
  *sub = s->blocks[0].sub;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetBlocks_SMALXE(Tao tao, PetscInt n, const IS is[])
{
  TaoSMALXE *s     = Get(tao);
  PetscInt   total = 0, nlocal = -1;

  PetscFunctionBegin;
  PetscCheck(!s->setup, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE, "TAO smalxe: set the blocks before the first solve");
  PetscCheck(n >= 1, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE, "TaoSMALXESetBlocks: need at least one block, got %" PetscInt_FMT, n);
  if (tao->solution) PetscCall(VecGetLocalSize(tao->solution, &nlocal));
  for (PetscInt k = 0; k < n; k++) {
    PetscInt nk;
    PetscCall(ISGetLocalSize(is[k], &nk));
    total += nk;
  }
  PetscCheck(nlocal < 0 || total == nlocal, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "TaoSMALXESetBlocks: the blocks have %" PetscInt_FMT " local entries in all, the solution %" PetscInt_FMT, total,
             nlocal);
  PetscCall(DestroyBlocks(s));
  for (PetscInt k = 0; k < n; k++) {
    SMALXEBlock blk;
    char        suffix[64];
    PetscCall(PetscObjectReference((PetscObject)is[k]));
    blk.is = is[k];
    PetscCall(PetscSNPrintf(suffix, sizeof(suffix), "tao_smalxe_block%" PetscInt_FMT "_", k));
    PetscCall(CreateSubsolver(tao, suffix, &blk.sub));
    PetscCallCXX(blk.suffix = suffix);
    PetscCall(RememberPrefix(blk));
    PetscCallCXX(s->blocks.push_back(blk));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetBlockSubsolver_SMALXE(Tao tao, PetscInt k, Tao *sub)
{
  TaoSMALXE *s = Get(tao);

  PetscFunctionBegin;
  PetscCheck(k >= 0 && k < (PetscInt)s->blocks.size(), PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE, "TAO smalxe: block %" PetscInt_FMT " does not exist (%zu blocks)", k,
             s->blocks.size());
  *sub = s->blocks[k].sub;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetPreSolve_SMALXE(Tao tao, PetscErrorCode (*fn)(Tao, PetscInt, Vec, void *), void *ctx)
{
  PetscFunctionBegin;
  Get(tao)->presolve     = fn;
  Get(tao)->presolve_ctx = ctx;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetEqualityMultiplier_SMALXE(Tao tao, Vec w)
{
  TaoSMALXE *s = Get(tao);

  PetscFunctionBegin;
  PetscCheck(s->setup, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_WRONGSTATE, "TAO smalxe: no multiplier before the first solve");
  if (s->projector) { /* C'mu = nu - Q(Ax - b) (the projected problem's multiplier misses the range(Q) part of the gradient) */
    PetscCall(MatMult(tao->hessian, tao->solution, s->w));
    s->counters.hessian_mults++;
    PetscCall(VecAXPY(s->w, -1.0, s->b));
    PetscCall(MatMult(s->Q, s->w, w));
    PetscCall(VecAYPX(w, -1.0, s->nu));
  } else PetscCall(MatMultTranspose(s->C, s->mu, w));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetConsistencyCheck_SMALXE(Tao tao, PetscErrorCode (*fn)(Tao, Vec, PetscBool *, void *), void *ctx)
{
  PetscFunctionBegin;
  Get(tao)->consistent     = fn;
  Get(tao)->consistent_ctx = ctx;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetAnderson_SMALXE(Tao tao, PetscInt depth, PetscInt start)
{
  TaoSMALXE *s = Get(tao);

  PetscFunctionBegin;
  PetscCheck(depth >= -1 && depth <= 20, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE, "TaoSMALXESetAnderson: the depth must be in [0, 20] (or -1: automatic), got %" PetscInt_FMT,
             depth);
  PetscCheck(start >= 1, PetscObjectComm((PetscObject)tao), PETSC_ERR_ARG_OUTOFRANGE, "TaoSMALXESetAnderson: the first accelerated outer iteration must be >= 1, got %" PetscInt_FMT, start);
  s->anderson       = depth;
  s->anderson_start = start;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetPenaltyPreconditioner_SMALXE(Tao tao, PetscBool flag)
{
  PetscFunctionBegin;
  Get(tao)->penalty_pc = flag;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetExactStop_SMALXE(Tao tao, PetscBool flag)
{
  PetscFunctionBegin;
  Get(tao)->exact_stop = flag;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SetProjectedPreconditioner_SMALXE(Tao tao, PC pc)
{
  TaoSMALXE *s = Get(tao);

  PetscFunctionBegin;
  if (pc) PetscCall(PetscObjectReference((PetscObject)pc));
  PetscCall(PCDestroy(&s->projected_pc));
  s->projected_pc = pc;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetProjectedPreconditioner_SMALXE(Tao tao, PC *pc)
{
  PetscFunctionBegin;
  *pc = Get(tao)->projected_pc;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetStagnated_SMALXE(Tao tao, PetscBool *flag)
{
  PetscFunctionBegin;
  *flag = Get(tao)->stagnated;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetInnerLimited_SMALXE(Tao tao, PetscInt *block)
{
  PetscFunctionBegin;
  *block = Get(tao)->inner_limited;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetStalled_SMALXE(Tao tao, PetscBool *flag)
{
  PetscFunctionBegin;
  *flag = Get(tao)->stalled;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetFeasibility_SMALXE(Tao tao, PetscReal *e)
{
  PetscFunctionBegin;
  *e = Get(tao)->feas;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* C'(mu_k - mu_j) over the last j <= k - GrowthSpacing() with a snapshot (h to 2h outer iterations): how the multiplier
   grew lately */
PetscErrorCode GetMultiplierGrowth_SMALXE(Tao tao, Vec w, PetscInt *its)
{
  TaoSMALXE     *s = Get(tao);
  const PetscInt k = (PetscInt)s->mult_history.size() - 1, gap = GrowthSpacing(s);
  PetscInt       j = -1;

  PetscFunctionBegin;
  *its = 0;
  for (int i = 1; i >= 0 && j < 0; i--)
    if (s->growth_k[i] >= 0 && k - s->growth_k[i] >= gap) j = i;
  if (j < 0) {
    PetscCall(VecSet(w, 0.0));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  *its = k - s->growth_k[j];
  if (s->projector) PetscCall(VecWAXPY(w, -1.0, s->growth_snap[j], s->nu));
  else {
    Vec dm;
    PetscCall(VecDuplicate(s->mu, &dm));
    PetscCall(VecWAXPY(dm, -1.0, s->growth_snap[j], s->mu));
    PetscCall(MatMultTranspose(s->C, dm, w));
    PetscCall(VecDestroy(&dm));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode GetOuterTolerances_SMALXE(Tao tao, PetscReal *tol_g, PetscReal *tol_e)
{
  PetscReal g, e;

  PetscFunctionBegin;
  PetscCall(Tolerances(tao, Get(tao), &g, &e));
  if (tol_g) *tol_g = g;
  if (tol_e) *tol_e = e;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/* The projector form's multiplier C'mu = nu that the next solve starts from instead of 0 (or the recycled one), once:
   a start that comes with its equality's multiplier (the contact layer's separated start, contactstart.cxx). nu must lie
   in range(Q); it is copied. */
PetscErrorCode TaoSMALXESetStartMultiplier_Private(Tao tao, Vec nu)
{
  PetscBool  is;
  TaoSMALXE *s;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)tao, TAOSMALXE, &is));
  if (!is) PetscFunctionReturn(PETSC_SUCCESS);
  s = Get(tao);
  PetscCall(VecDestroy(&s->nu_start));
  if (nu) {
    PetscCall(VecDuplicate(nu, &s->nu_start));
    PetscCall(VecCopy(nu, s->nu_start));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the slow-loop rule (-tao_smalxe_slow_its) of the last solve: the outer iterations after which it raised rho (0: it did
   not), and its settings; any may be NULL */
PetscErrorCode TaoSMALXEGetSlowLoop_Private(Tao tao, PetscInt *fired, PetscInt *its, PetscReal *factor)
{
  PetscBool  is;
  TaoSMALXE *s;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)tao, TAOSMALXE, &is));
  s = is ? Get(tao) : nullptr; /* another type: no such rule */
  if (fired) *fired = s ? s->slow_done : 0;
  if (its) *its = s ? s->slow_its : 0;
  if (factor) *factor = s ? s->slow_factor : 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the names of the Hessian and the projector in the errors of failed solves: a ContactProblem's F and Q */
PetscErrorCode TaoSMALXESetOperatorNames_Private(Tao tao, const char hessian[], const char projector[])
{
  PetscBool is;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)tao, TAOSMALXE, &is));
  if (!is) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCallCXX(Get(tao)->hessian_name = hessian);
  PetscCallCXX(Get(tao)->projector_name = projector);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*MC
  TAOSMALXE - "smalxe": min 1/2 x'Ax - b'x over a separable set subject to C x = d, by the
  semi-monotonic augmented Lagrangian with adaptive precision (Dostal's SMALBE) around a nested
  `TAOMPRGP`/`TAOMPGP` solver.

  Options Database Keys:
+ -tao_smalxe_rho <1>          - penalty rho relative to ||A|| (||PAP|| in projector form)
. -tao_smalxe_rho_first <1>    - penalty of the first outer iteration relative to rho (below 1: the first inner solve, which finds the active set, runs at a smaller penalty)
. -tao_smalxe_repeat_first <0> - with a pre-solve hook (`TaoSMALXESetPreSolve()`), the inner solves of this many first outer iterations run twice, the hook before each
. -tao_smalxe_M <0.1>          - initial M relative to ||H|| (inner precision |gP| <= min(M |Cx - d|, eta))
. -tao_smalxe_M_min <1e-4>     - floor of M relative to ||H|| (0: none)
. -tao_smalxe_eta <0.1>        - eta relative to |b|
. -tao_smalxe_beta <10>        - update factor of M or rho
. -tao_smalxe_update <M>       - M (SMALBE-M, rho fixed) or rho (SMALBE)
. -tao_smalxe_projector        - C has orthonormal rows: use the projector form, inner Hessian PAP + rho Q
. -tao_smalxe_sweeps <1>       - block Gauss-Seidel sweeps per outer iteration (with `TaoSMALXESetBlocks()`)
. -tao_smalxe_block_rtol <0>    - with blocks, a block solve also stops when its projected gradient fell by this factor (0: off)
. -tao_smalxe_norm <value>     - ||A|| (||PAP||) given, not estimated
. -tao_smalxe_norm_method      - slepc or power
. -tao_smalxe_norm_margin      - safety margin on the estimate (negative: the method's default, 0.01 slepc, 0.05 power)
. -tao_smalxe_stagnation_its <30> - stop when |Cx - d| falls by less than 1% in this many outer iterations (equality infeasible over the set)
. -tao_smalxe_stall_rho_growths <1> - a stall with |Cx - d| above 10 times its tolerance first multiplies rho by beta this many times, each followed by a full window (update M only)
. -tao_smalxe_slow_its <100> - projector form, update M: after this many outer iterations, the first time |Cx - d| lags |gP| (relative), rho times the next factor (0: never)
. -tao_smalxe_slow_rho_factor <10> - that factor (>= 1; 1: off)
. -tao_smalxe_inner_limit_its <5> - stop when inner solves reach their iteration limit this many outer iterations in a row without 1% progress
. -tao_smalxe_inner_floor <0.5> - inner solves also stop at this fraction of the final |gP| tolerance, times rho/rho_default below 1 (0: only the adaptive precision)
. -tao_smalxe_anderson <-1>    - Anderson acceleration of the multiplier update with this depth (0: plain update; -1: 3, or 0 with blocks; see `TaoSMALXESetAnderson()`)
. -tao_smalxe_anderson_start <3> - first outer iteration (counted from 0, at least 1) whose update is accelerated
. -tao_smalxe_rho_balance <-1> - with blocks: residual balancing of rho by this factor (0: off; -1: 2 with blocks, 0 without)
. -tao_smalxe_exact_stop <true> - confirm a stop on the inner solver's exact gradient (see `TaoSMALXESetExactStop()`)
. -tao_smalxe_penalty_pc <true> - projector form: precondition the inner CG steps by I - rho/(||PAP|| + rho) Q (see `TaoSMALXESetPenaltyPreconditioner()`)
. -tao_smalxe_pc_q_scale <1>   - with a preconditioner of A (`TaoSMALXESetProjectedPreconditioner()`): the inner CG steps use P M P + (this/rho) Q
. -tao_smalxe_counters_view    - print the counters as one JSON line after each solve
. -tao_smalxe_subsolver_tao_*  - options of the nested solver (monolithic inner solves)
- -tao_smalxe_block<k>_tao_*   - options of block k's nested solver

  Notes:
  A, b and the set as for `TAOMPGP`. The equality comes from `TaoSMALXESetEqualityConstraints()`, from
  `TaoSMALXESetProjector()` (projector form with a given projector and particular solution), or
  from TAO's equality routines (`TaoSetEqualityConstraintsRoutine()` with c(x) = C x - d, and
  `TaoSetJacobianEqualityRoutine()` giving C). The solver stops when |gP| <= max(gatol, gttol |b|)
  and |Cx - d| <= max(catol, t ||C|| / ||H_0||) with t = crtol |b| if crtol is given, else the gradient's
  tolerance (|b| is |P(b - A x~)| in projector form; H_0 is the inner Hessian at the default penalty,
  ||H_0|| = ||PAP|| in projector form and 2 ||A|| otherwise, so that the tolerance does not change with rho;
  ||C|| = 1 in projector form, so that it does not change when C and d are scaled together). `-tao_monitor` prints the augmented Lagrangian L(x, mu, rho) and |gP|
  (`-tao_cmonitor` also |Cx - d|). Counters: outer iterations and own products, nested solvers' products separately.
  A solve starts from the solution vector (a warm start) and from the multiplier 0 of the equality;
  with `TaoSetRecycleHistory()` (`-tao_recycle_history`) it starts from the multiplier the previous
  solve ended with, which a sequence of nearby problems needs for the warm start to pay: from
  multiplier 0 the first inner solve undoes it. The algorithm: docs/algorithms.md, 'SMALXE: the semi-monotonic
  augmented Lagrangian'.
  A must be symmetric and a given projector Q an orthogonal projector. When an inner solve fails, smalxe tests A's
  symmetry and Q's |Q(Qx) - Qx| and symmetry with products (counted; never after a successful solve) and its error
  names the one that is not, else asks whether the Hessian is positive semidefinite. -tao_max_it must be >= 1.

  References:
+ * - Z. Dostal, Inexact semi-monotonic augmented Lagrangians with optimal feasibility convergence for quadratic programming with simple bounds and equality constraints, SIAM J. Numer. Anal.
. * - Z. Dostal, Optimal Quadratic Programming Algorithms, with Applications to Variational Inequalities, Springer (2009)
. * - C. Farhat, J. Mandel, F.-X. Roux, Optimal convergence properties of the FETI domain decomposition method, Comput. Methods Appl. Mech. Eng. 115, 367-388 (1994) (projector form)
- * - D. G. Anderson, Iterative procedures for nonlinear integral equations, J. ACM 12(4), 547-560 (1965) (Anderson mixing of the multiplier update)

  Level: beginner

.seealso: `TAOMPGP`, `TAOMPRGP`, `TaoSMALXESetEqualityConstraints()`, `TaoSMALXESetBlocks()`
M*/
PETSC_INTERN PetscErrorCode TaoCreate_SMALXE(Tao tao)
{
  TaoSMALXE  *s;
  SMALXEBlock blk;

  PetscFunctionBegin;
  PetscCallCXX(s = new TaoSMALXE);
  s->tao    = tao;
  tao->data = s;

  tao->ops->setup          = TaoSetUp_SMALXE;
  tao->ops->solve          = TaoSolve_SMALXE;
  tao->ops->setfromoptions = TaoSetFromOptions_SMALXE;
  tao->ops->view           = TaoView_SMALXE;
  tao->ops->destroy        = TaoDestroy_SMALXE;
  if (tao->ops->convergencetest == TaoDefaultConvergenceTest) tao->ops->convergencetest = OuterConvergenceTest;
  if (!tao->gatol_changed) tao->gatol = 0.0;
  if (!tao->grtol_changed) tao->grtol = 0.0;
  if (!tao->gttol_changed) tao->gttol = 1e-8;
  if (!tao->catol_changed) tao->catol = 0.0;
  if (!tao->max_it_changed) tao->max_it = 1000;

  PetscCall(CreateSubsolver(tao, "tao_smalxe_subsolver_", &blk.sub));
  PetscCallCXX(blk.suffix = "tao_smalxe_subsolver_");
  PetscCall(RememberPrefix(blk));
  PetscCallCXX(s->blocks.push_back(blk));

  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPSetConstraints_C", SetConstraints_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPGetConstraints_C", GetConstraints_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPSetLinearTerm_C", SetLinearTerm_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPSetNormEstimate_C", SetNormEstimate_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPGetNormEstimate_C", GetNormEstimate_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPGetCounters_C", GetCounters_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoQPResetCounters_C", ResetCounters_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXESetEqualityConstraints_C", SetEqualityConstraints_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXESetProjector_C", SetProjector_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXEGetSubsolver_C", GetSubsolver_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXESetBlocks_C", SetBlocks_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXEGetBlockSubsolver_C", GetBlockSubsolver_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXESetPreSolve_C", SetPreSolve_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXEGetEqualityMultiplier_C", GetEqualityMultiplier_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXEGetFeasibility_C", GetFeasibility_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXEGetMultiplierGrowth_C", GetMultiplierGrowth_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXEGetOuterTolerances_C", GetOuterTolerances_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXESetConsistencyCheck_C", SetConsistencyCheck_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXEGetStagnated_C", GetStagnated_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXEGetStalled_C", GetStalled_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXEGetInnerLimited_C", GetInnerLimited_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXESetAnderson_C", SetAnderson_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXESetPenaltyPreconditioner_C", SetPenaltyPreconditioner_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXESetExactStop_C", SetExactStop_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXESetProjectedPreconditioner_C", SetProjectedPreconditioner_SMALXE));
  PetscCall(PetscObjectComposeFunction((PetscObject)tao, "TaoSMALXEGetProjectedPreconditioner_C", GetProjectedPreconditioner_SMALXE));
  PetscCall(TaoQPAdoptComposed_Private(tao));
  PetscFunctionReturn(PETSC_SUCCESS);
}
