/* An unmodified TAO program (conefeti comes with -dll_append): min 1/2 x'Ax - b'x, x >= lb, sum(x)/n = vol
   (one equality, through TAO's equality routines). The test: a second TaoSolve after the equality's
   right-hand side changed must meet the new equality, as with TAO's own almm.
   A = tridiag(-1,2,-1), b = load/n^2. -resolve: second TaoSolve after changing vol (-vol2).
   Checks KKT: x >= lb, |Cx - d|, and the Lagrangian's projected gradient with mu fitted on the free set. */
#include "quadratic.h"

typedef struct {
  Quadratic q; /* first: the callbacks of quadratic.h take this context */
  PetscReal vol;
  PetscInt  n;
} AppCtx;

static PetscErrorCode CE(Tao tao, Vec x, Vec c, void *ptr)
{
  AppCtx     *app = (AppCtx *)ptr;
  PetscScalar s;
  PetscFunctionBeginUser;
  PetscCall(VecSum(x, &s));
  PetscCall(VecSet(c, s / app->n - app->vol));
  PetscFunctionReturn(0);
}
static PetscErrorCode JE(Tao tao, Vec x, Mat J, Mat Jp, void *ptr) { return 0; }

static PetscErrorCode Check(Tao tao, AppCtx *app, Vec x, Vec lb, const char *tag)
{
  TaoConvergedReason r;
  PetscInt           its, rs, re, nfree = 0;
  PetscReal          f, gn, cn, xd, viol, sumg = 0, kkt = 0, s;
  Vec                g, d;
  const PetscScalar *xa, *la, *ga;
  PetscFunctionBeginUser;
  PetscCall(TaoGetConvergedReason(tao, &r));
  PetscCall(TaoGetSolutionStatus(tao, &its, &f, &gn, &cn, &xd, NULL));
  PetscCall(VecDuplicate(x, &g));
  PetscCall(VecDuplicate(x, &d));
  PetscCall(MatMult(app->q.A, x, g));
  PetscCall(VecAXPY(g, -1.0, app->q.b));
  PetscCall(VecWAXPY(d, -1.0, lb, x));
  PetscCall(VecMin(d, NULL, &viol));
  PetscCall(VecSum(x, &s));
  PetscCall(VecGetOwnershipRange(x, &rs, &re));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArrayRead(lb, &la));
  PetscCall(VecGetArrayRead(g, &ga));
  for (PetscInt i = 0; i < re - rs; i++)
    if (xa[i] > la[i] + 1e-10) {
      sumg += ga[i];
      nfree++;
    }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sumg, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nfree, 1, MPIU_INT, MPIU_SUM, PETSC_COMM_WORLD));
  {
    PetscReal m = nfree ? sumg / nfree : 0; /* g = C' mu on the free set, C' mu = mu/n * 1 */
    for (PetscInt i = 0; i < re - rs; i++) {
      PetscReal gi = ga[i] - m;
      if (xa[i] <= la[i] + 1e-10) gi = PetscMin(gi, 0.0);
      kkt += gi * gi;
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &kkt, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecRestoreArrayRead(lb, &la));
  PetscCall(VecRestoreArrayRead(g, &ga));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: %s its %d f %.10e gnorm %.2e cnorm %.2e | min(x-lb) %.2e |mean(x)-vol| %.2e KKT %.2e nfree %d\n", tag, TaoConvergedReasons[r], (int)its, (double)f,
                        (double)gn, (double)cn, (double)viol, (double)PetscAbsReal(s / app->n - app->vol), (double)PetscSqrtReal(kkt), (int)nfree));
  PetscCall(VecDestroy(&g));
  PetscCall(VecDestroy(&d));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  AppCtx    app;
  Tao       tao;
  Mat       J;
  Vec       x, lb, ub, ce;
  PetscInt  n    = 100, rs, re;
  PetscReal load = 20, vol2 = -0.02;
  PetscBool resolve = PETSC_FALSE;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-n", &n, NULL));
  app.n   = n;
  app.vol = -0.05;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-vol", &app.vol, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-vol2", &vol2, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-load", &load, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-resolve", &resolve, NULL));
  PetscCall(CreateTridiagonal(PETSC_COMM_WORLD, n, 2.0, &app.q.A));
  PetscCall(MatGetOwnershipRange(app.q.A, &rs, &re));
  PetscCall(MatCreateVecs(app.q.A, &x, &app.q.b));
  PetscCall(VecDuplicate(x, &lb));
  PetscCall(VecDuplicate(x, &ub));
  PetscCall(VecSet(app.q.b, -load / (n * n)));
  PetscCall(VecSet(lb, -0.08));
  PetscCall(VecSet(ub, PETSC_INFINITY));
  PetscCall(VecSet(x, 0));
  /* C = ones/n : 1 x n, row owned by rank 0 */
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, rs == 0 ? 1 : 0, re - rs, 1, n, re - rs, NULL, n, NULL, &J));
  for (PetscInt i = rs; i < re; i++) PetscCall(MatSetValue(J, 0, i, 1.0 / n, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(J, NULL, &ce));

  PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
  PetscCall(TaoSetSolution(tao, x));
  PetscCall(TaoSetObjectiveAndGradient(tao, NULL, QuadraticObjectiveGradient, &app));
  PetscCall(TaoSetHessian(tao, app.q.A, app.q.A, QuadraticHessian, &app));
  PetscCall(TaoSetVariableBounds(tao, lb, ub));
  PetscCall(TaoSetEqualityConstraintsRoutine(tao, ce, CE, &app));
  PetscCall(TaoSetJacobianEqualityRoutine(tao, J, J, JE, &app));
  PetscCall(TaoSetFromOptions(tao));
  PetscCall(TaoSolve(tao));
  PetscCall(Check(tao, &app, x, lb, "solve1"));
  if (resolve) {
    app.vol = vol2;
    PetscCall(VecSet(x, 0));
    PetscCall(TaoSolve(tao));
    PetscCall(Check(tao, &app, x, lb, "solve2 (vol changed)"));
  }
  PetscCall(TaoDestroy(&tao));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&lb));
  PetscCall(VecDestroy(&ub));
  PetscCall(VecDestroy(&ce));
  PetscCall(VecDestroy(&app.q.b));
  PetscCall(MatDestroy(&app.q.A));
  PetscCall(MatDestroy(&J));
  PetscCall(PetscFinalize());
  return 0;
}
