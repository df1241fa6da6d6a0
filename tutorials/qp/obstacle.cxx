/* obstacle: bound-constrained QP benchmark on a 2D grid (the classic obstacle problem, or a
   journal-bearing problem), solved by whichever TAO type the options select.

   What it does
   ------------
   Builds min 1/2 u'Au - b'u subject to u >= psi on an N x N grid of interior nodes (a DMDA), with
   A a 5-point finite-difference operator and Dirichlet boundary values eliminated into b:

   -problem obstacle (default): the radially symmetric obstacle problem of the literature (Bueler,
     "PETSc for Partial Differential Equations", chapter 12; also in many MPRGP and multigrid papers):
     on (-2,2)^2, -Lap u >= 0, u >= psi, complementarity, with psi = sqrt(1 - r^2) for r <= 1 and
     -1 outside, and boundary values from the exact solution u = psi for r <= r*, u = -r*^2 log(r/2) /
     sqrt(1 - r*^2) for r > r* (r* = 0.69797). A is the stencil [-1 -1 4 -1 -1] (h^2 times the
     Laplacian), so ||A|| < 8 and cond(A) grows like N^2. The run reports the max-norm error against
     the exact solution, a check that the QP solved is the right one.
   -problem bearing: a journal-bearing problem in the style of MINPACK-2 and TAO's jbearing tutorial
     (re-implemented here with a finite-difference discretization): on (0, 2 pi) x (0, 2 b), minimize
     int 1/2 w_q |grad v|^2 - w_l v with w_q = (1 + e cos x)^3, w_l = e sin x, v >= 0, v = 0 on the
     boundary (options -bearing_ecc e = 0.1, -bearing_b b = 10).

   There is no upper bound unless -upper U is given (a finite U above the solution changes nothing
   but lets bqpip converge: it replaces infinite bounds by 1e20 and then stalls on the bearing).
   The initial guess is the projection of 0 onto the set, for every solver. For mprgp/mpgp the
   linear term is given by TaoQPSetLinearTerm(); TAO's own solvers get the objective and gradient
   (one product with A each) and the Hessian (a copy of A, since bqpip shifts its diagonal in place).
   The program then measures the projected gradient at the returned point itself (bench.h):
     gP_i = g_i for l < u_i < u, min(g_i, 0) on the lower bound, max(g_i, 0) on the upper one,
   with g = A u - b, after clamping u to the bounds and snapping entries within -bench_snap (relative
   to max |u|) of a bound onto it. The result is one JSON line: solver, n, iterations, Hessian
   products, time, |gP| and |gP|/|b|, objective, and whether |gP| <= -bench_rtol |b|.

   Sample runs
   -----------
     obstacle -n 99 -tao_type mprgp
     obstacle -n 319 -tao_type mprgp -bench_rtol 1e-8                 # 101761 unknowns
     obstacle -n 319 -tao_type blmvm                                  # TAO's L-BFGS-B-like solver
     obstacle -n 319 -tao_type bqpip -upper 100 -bench_own_factor 1e-2   # tighter own tolerance
     obstacle -problem bearing -n 199 -tao_type gpcg
     mpiexec -n 2 obstacle -n 319 -tao_type mpgp -tao_view

   What to expect
   --------------
   Every solver listed by scripts/bench-qp.sh converges to the same objective (to about the
   tolerance) and its line ends with "met":true; with -n 319 the obstacle error against the exact
   solution is about 5e-5 (discretization error). The Hessian is assembled (AIJ), so mprgp and mpgp
   precondition their CG steps in face with ICC(0) by default, with the projected CG expansion and
   Gamma = 2 (-tao_view says so): mprgp needs about 380 products at -n 316 with the default -bench_rtol
   1e-6 (about 890 with the old defaults -tao_mprgp_pc_type none -tao_mprgp_expansion_projcg 0
   -tao_mprgp_gamma 1), blmvm about 630, gpcg about 1460; the numbers for all solvers and what they mean
   are in docs/qp-benchmark.md. -bench_repeat k solves k times and reports the shortest time. */
#include "bench.h"
#include <petscdmda.h>
#include <cmath>

namespace {

enum ProblemType {
  PROBLEM_OBSTACLE,
  PROBLEM_BEARING
};
const char *const ProblemTypes[] = {"obstacle", "bearing", "ProblemType", "PROBLEM_", NULL};

struct AppCtx {
  ProblemType  problem = PROBLEM_OBSTACLE;
  PetscInt     N       = 99;
  PetscReal    ecc = 0.1, bearing_b = 10.0;
  PetscReal    upper = PETSC_INFINITY; /* upper bound of every entry (an inactive finite one helps bqpip) */
  DM           da    = nullptr;
  Mat          A     = nullptr; /* used by the objective and the measurement */
  Vec          b = nullptr, lb = nullptr, ub = nullptr;
  BenchCounts *counts = nullptr;
};

/* Obstacle problem: the obstacle and the exact solution. */
constexpr PetscReal kRStar = 0.697965148223374; /* free-boundary radius */

PetscReal ObstaclePsi(PetscReal x, PetscReal y)
{
  const PetscReal r = std::hypot(x, y);
  return r <= 1 ? std::sqrt(1 - r * r) : -1.0;
}

PetscReal ObstacleExact(PetscReal x, PetscReal y)
{
  const PetscReal r = std::hypot(x, y);
  if (r <= kRStar) return ObstaclePsi(x, y);
  return -kRStar * kRStar * std::log(r / 2) / std::sqrt(1 - kRStar * kRStar);
}

/* Assembles A, b and the bounds. Node (i, j), 0 <= i, j < N, is interior; boundary values enter b. */
PetscErrorCode BuildProblem(AppCtx *app)
{
  DMDALocalInfo  info;
  PetscScalar  **bb, **ll, **uu;
  const PetscInt N = app->N;

  PetscFunctionBeginUser;
  PetscCall(DMDACreate2d(PETSC_COMM_WORLD, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DMDA_STENCIL_STAR, N, N, PETSC_DECIDE, PETSC_DECIDE, 1, 1, NULL, NULL, &app->da));
  PetscCall(DMSetUp(app->da));
  PetscCall(DMCreateMatrix(app->da, &app->A));
  PetscCall(DMCreateGlobalVector(app->da, &app->b));
  PetscCall(VecDuplicate(app->b, &app->lb));
  PetscCall(VecDuplicate(app->b, &app->ub));
  PetscCall(VecSet(app->ub, app->upper));
  PetscCall(DMDAGetLocalInfo(app->da, &info));
  PetscCall(DMDAVecGetArray(app->da, app->b, &bb));
  PetscCall(DMDAVecGetArray(app->da, app->lb, &ll));
  PetscCall(DMDAVecGetArray(app->da, app->ub, &uu));
  for (PetscInt j = info.ys; j < info.ys + info.ym; j++) {
    for (PetscInt i = info.xs; i < info.xs + info.xm; i++) {
      MatStencil  row = {0, j, i, 0}, col[5];
      PetscScalar v[5];
      PetscInt    nc = 0;
      if (app->problem == PROBLEM_OBSTACLE) {
        const PetscReal h     = 4.0 / (N + 1);
        auto            X     = [&](PetscInt k) { return -2.0 + (k + 1) * h; };
        const PetscInt  di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
        PetscReal       rhs = 0; /* f = 0: only boundary values */
        col[nc]             = row;
        v[nc++]             = 4.0;
        for (int q = 0; q < 4; q++) {
          const PetscInt ii = i + di[q], jj = j + dj[q];
          if (ii < 0 || ii >= N || jj < 0 || jj >= N) rhs += ObstacleExact(X(ii), X(jj));
          else {
            col[nc] = {0, jj, ii, 0};
            v[nc++] = -1.0;
          }
        }
        bb[j][i] = rhs;
        ll[j][i] = ObstaclePsi(X(i), X(j));
      } else {
        const PetscReal hx = 2 * PETSC_PI / (N + 1), hy = 2 * app->bearing_b / (N + 1);
        auto            wq = [&](PetscReal x) { return std::pow(1 + app->ecc * std::cos(x), 3); };
        const PetscReal x = (i + 1) * hx, ax = hy / hx, ay = hx / hy;
        const PetscReal we = wq(x + hx / 2) * ax, ww = wq(x - hx / 2) * ax, wns = wq(x) * ay; /* east, west, north/south weights */
        col[nc] = row;
        v[nc++] = we + ww + 2 * wns;
        if (i > 0) {
          col[nc] = {0, j, i - 1, 0};
          v[nc++] = -ww;
        }
        if (i < N - 1) {
          col[nc] = {0, j, i + 1, 0};
          v[nc++] = -we;
        }
        if (j > 0) {
          col[nc] = {0, j - 1, i, 0};
          v[nc++] = -wns;
        }
        if (j < N - 1) {
          col[nc] = {0, j + 1, i, 0};
          v[nc++] = -wns;
        }
        bb[j][i] = app->ecc * std::sin(x) * hx * hy; /* zero boundary values */
        ll[j][i] = 0.0;
      }
      PetscCall(MatSetValuesStencil(app->A, 1, &row, nc, col, v, INSERT_VALUES));
    }
  }
  PetscCall(DMDAVecRestoreArray(app->da, app->b, &bb));
  PetscCall(DMDAVecRestoreArray(app->da, app->lb, &ll));
  PetscCall(DMDAVecRestoreArray(app->da, app->ub, &uu));
  PetscCall(MatAssemblyBegin(app->A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(app->A, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* q(u) = 1/2 u'Au - b'u and its gradient Au - b: one product with A. */
PetscErrorCode FormObjectiveGradient(Tao, Vec u, PetscReal *f, Vec g, void *ptr)
{
  AppCtx     *app = static_cast<AppCtx *>(ptr);
  PetscScalar ug, ub;

  PetscFunctionBeginUser;
  PetscCall(MatMult(app->A, u, g));
  PetscCall(VecAXPY(g, -1.0, app->b));
  PetscCall(VecDotBegin(u, g, &ug));
  PetscCall(VecDotBegin(u, app->b, &ub));
  PetscCall(VecDotEnd(u, g, &ug));
  PetscCall(VecDotEnd(u, app->b, &ub));
  *f = 0.5 * (PetscRealPart(ug) - PetscRealPart(ub));
  app->counts->callbacks++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FormObjective(Tao tao, Vec u, PetscReal *f, void *ptr)
{
  AppCtx *app = static_cast<AppCtx *>(ptr);
  Vec     g;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(u, &g));
  PetscCall(FormObjectiveGradient(tao, u, f, g, app));
  PetscCall(VecDestroy(&g));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The Hessian is constant: nothing to do. */
PetscErrorCode FormHessian(Tao, Vec, Mat, Mat, void *)
{
  PetscFunctionBeginUser;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The measurement of bench.h for bounds: clamp, snap, then gP, q, and the active count. */
PetscErrorCode MeasureBounds(AppCtx *app, Vec u, PetscReal snap, BenchAccuracy *acc)
{
  Vec                ub, g, gp;
  PetscReal          umax, delta;
  const PetscScalar *l, *h, *ga;
  PetscScalar       *xa, *pa, ug, ubv;
  PetscInt           n, active = 0;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(u, &ub));
  PetscCall(VecDuplicate(u, &g));
  PetscCall(VecDuplicate(u, &gp));
  PetscCall(VecMedian(app->lb, u, app->ub, ub));
  PetscCall(VecNorm(ub, NORM_INFINITY, &umax));
  delta = snap * PetscMax(umax, PETSC_SMALL);
  PetscCall(VecGetLocalSize(u, &n));
  PetscCall(VecGetArrayRead(app->lb, &l));
  PetscCall(VecGetArrayRead(app->ub, &h));
  PetscCall(VecGetArray(ub, &xa));
  for (PetscInt i = 0; i < n; i++) {
    if (PetscRealPart(xa[i] - l[i]) <= delta) xa[i] = l[i];
    else if (PetscRealPart(h[i] - xa[i]) <= delta) xa[i] = h[i];
  }
  PetscCall(VecRestoreArray(ub, &xa));
  PetscCall(MatMult(app->A, ub, g));
  PetscCall(VecAXPY(g, -1.0, app->b));
  PetscCall(VecGetArrayRead(ub, (const PetscScalar **)&xa));
  PetscCall(VecGetArrayRead(g, &ga));
  PetscCall(VecGetArray(gp, &pa));
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal x = PetscRealPart(xa[i]), gi = PetscRealPart(ga[i]), lo = PetscRealPart(l[i]), hi = PetscRealPart(h[i]);
    if (lo == hi) pa[i] = 0;
    else if (x <= lo) pa[i] = PetscMin(gi, 0);
    else if (x >= hi) pa[i] = PetscMax(gi, 0);
    else pa[i] = gi;
    if (x <= lo || x >= hi) active++;
  }
  PetscCall(VecRestoreArray(gp, &pa));
  PetscCall(VecRestoreArrayRead(g, &ga));
  PetscCall(VecRestoreArrayRead(ub, (const PetscScalar **)&xa));
  PetscCall(VecRestoreArrayRead(app->lb, &l));
  PetscCall(VecRestoreArrayRead(app->ub, &h));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &active, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(VecNorm(gp, NORM_2, &acc->gp));
  PetscCall(VecDot(ub, g, &ug));
  PetscCall(VecDot(ub, app->b, &ubv));
  acc->objective = 0.5 * (PetscRealPart(ug) - PetscRealPart(ubv));
  acc->active    = active;
  PetscCall(VecAXPY(ub, -1.0, u));
  PetscCall(VecNorm(ub, NORM_2, &acc->moved));
  PetscCall(VecDestroy(&ub));
  PetscCall(VecDestroy(&g));
  PetscCall(VecDestroy(&gp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Max-norm error against the exact solution of the obstacle problem. */
PetscErrorCode ObstacleError(AppCtx *app, Vec u, PetscReal *err)
{
  DMDALocalInfo   info;
  PetscScalar   **ua;
  PetscReal       e = 0;
  const PetscReal h = 4.0 / (app->N + 1);

  PetscFunctionBeginUser;
  PetscCall(DMDAGetLocalInfo(app->da, &info));
  PetscCall(DMDAVecGetArrayRead(app->da, u, &ua));
  for (PetscInt j = info.ys; j < info.ys + info.ym; j++)
    for (PetscInt i = info.xs; i < info.xs + info.xm; i++) e = PetscMax(e, PetscAbsReal(PetscRealPart(ua[j][i]) - ObstacleExact(-2 + (i + 1) * h, -2 + (j + 1) * h)));
  PetscCall(DMDAVecRestoreArrayRead(app->da, u, &ua));
  PetscCall(MPIU_Allreduce(&e, err, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

int main(int argc, char **argv)
{
  AppCtx        app;
  BenchCounts   counts;
  BenchAccuracy acc;
  Tao           tao;
  Mat           H;
  Vec           u, u0;
  PetscReal     rtol = 1e-6, factor = 1.0, snap = 1e-9, bnorm;
  PetscInt      n, repeat = 1;
  char          extra[256] = "";

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Bound-constrained QP benchmark: obstacle or journal-bearing problem, any TAO type\n"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(BenchCountsInitialize(&counts));
  app.counts = &counts;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Obstacle / journal-bearing QP benchmark", "obstacle");
  PetscCall(PetscOptionsEnum("-problem", "Which problem", "obstacle", ProblemTypes, (PetscEnum)app.problem, (PetscEnum *)&app.problem, NULL));
  /* n^2 unknowns must fit PetscInt */
  PetscCall(PetscOptionsRangeInt("-n", "Interior grid nodes per direction (n^2 unknowns)", "obstacle", app.N, &app.N, NULL, 3, (PetscInt)PetscSqrtReal((PetscReal)PETSC_MAX_INT)));
  PetscCall(PetscOptionsReal("-bearing_ecc", "Journal bearing: eccentricity e, 0 < e < 1", "obstacle", app.ecc, &app.ecc, NULL));
  PetscCall(PetscOptionsReal("-bearing_b", "Journal bearing: half width b > 0 of the domain (0,2pi) x (0,2b)", "obstacle", app.bearing_b, &app.bearing_b, NULL));
  PetscCall(PetscOptionsReal("-upper", "Upper bound of every entry (default: none); a large inactive one changes nothing but helps bqpip", "obstacle", app.upper, &app.upper, NULL));
  PetscCall(PetscOptionsReal("-bench_rtol", "Target: |projected gradient| <= rtol |b|, measured by this program", "obstacle", rtol, &rtol, NULL));
  PetscCall(PetscOptionsReal("-bench_own_factor", "The solver's own tolerance is factor * rtol (|b|-relative, or absolute times |b| for TAO's solvers)", "obstacle", factor, &factor, NULL));
  PetscCall(PetscOptionsReal("-bench_snap", "Entries within snap * max|u| of a bound count as on it when measuring", "obstacle", snap, &snap, NULL));
  PetscCall(PetscOptionsBoundedInt("-bench_repeat", "Solve this many times and report the shortest time", "obstacle", repeat, &repeat, NULL, 1));
  PetscOptionsEnd();
  /* the bearing's weight (1 + e cos x)^3 must stay positive and its load e sin x nonzero: 0 < e < 1 (MINPACK-2's
     range); b is the domain's half width */
  PetscCall(BenchCheckReal("-bearing_ecc", app.ecc, 0, PETSC_TRUE, 1, PETSC_TRUE, "the journal bearing's eccentricity"));
  PetscCall(BenchCheckReal("-bearing_b", app.bearing_b, 0, PETSC_TRUE, PETSC_MAX_REAL, PETSC_FALSE, "the half width of the domain (0,2pi) x (0,2b)"));
  PetscCheck(!PetscIsNanReal(app.upper), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-upper %g: must be a number (infinity: no upper bound)", (double)app.upper);
  PetscCall(BenchCheckOptions(rtol, factor, snap));

  PetscCall(BuildProblem(&app));
  {
    PetscReal lmax; /* an upper bound below the obstacle leaves no feasible point */
    PetscCall(VecMax(app.lb, NULL, &lmax));
    PetscCheck(app.upper >= lmax, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-upper %g: lies below the lower bound (its maximum is %g): no feasible point", (double)app.upper, (double)lmax);
  }
  PetscCall(VecNorm(app.b, NORM_2, &bnorm));
  PetscCall(VecGetSize(app.b, &n));
  PetscCall(MatDuplicate(app.A, MAT_COPY_VALUES, &H));
  PetscCall(VecDuplicate(app.b, &u));
  PetscCall(VecSet(u, 0.0));
  PetscCall(VecMedian(app.lb, u, app.ub, u)); /* every solver starts from the projection of 0 */
  PetscCall(VecDuplicate(u, &u0));
  PetscCall(VecCopy(u, u0));

  PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
  PetscCall(TaoSetType(tao, TAOMPRGP));
  PetscCall(TaoSetSolution(tao, u));
  PetscCall(TaoSetVariableBounds(tao, app.lb, app.ub));
  PetscCall(TaoSetObjective(tao, FormObjective, &app));
  PetscCall(TaoSetObjectiveAndGradient(tao, NULL, FormObjectiveGradient, &app));
  PetscCall(TaoSetHessian(tao, H, H, FormHessian, &app));
  PetscCall(TaoSetFromOptions(tao));         /* the type first: type-specific settings below are lost when the type changes */
  PetscCall(TaoQPSetLinearTerm(tao, app.b)); /* ignored by TAO's own types */
  PetscCall(BenchSetStoppingRule(tao, rtol, factor, bnorm));
  PetscCall(TaoSetFromOptions(tao)); /* command-line tolerances still win */

  PetscCall(BenchRepeatedSolve(tao, u, u0, H, repeat, &counts));
  PetscCall(MeasureBounds(&app, u, snap, &acc));
  if (app.problem == PROBLEM_OBSTACLE) {
    PetscReal err;
    PetscCall(ObstacleError(&app, u, &err));
    PetscCall(PetscSNPrintf(extra, sizeof(extra), ",\"error_vs_exact\":%.3e", (double)err));
  }
  PetscCall(BenchReport(tao, ProblemTypes[app.problem], n, bnorm, rtol, factor, &counts, &acc, PETSC_FALSE, extra));

  PetscCall(TaoDestroy(&tao));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&u0));
  PetscCall(MatDestroy(&H));
  PetscCall(MatDestroy(&app.A));
  PetscCall(VecDestroy(&app.b));
  PetscCall(VecDestroy(&app.lb));
  PetscCall(VecDestroy(&app.ub));
  PetscCall(DMDestroy(&app.da));
  PetscCall(PetscFinalize());
  return 0;
}
