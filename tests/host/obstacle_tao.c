/* Bound-constrained 1D obstacle QP with any TAO (an unmodified PETSc program; conefeti comes with -dll_append).
   Used by the tests of what a TAO user expects from our types besides a first solve: a second TaoSolve
   after the bounds changed (disk blocks built from the bounds follow them), a semicoercive Hessian
   (-neumann: the constant vector is in its kernel, the obstacle makes the problem well posed), and a
   zero linear term (-load 0: the bounds alone make the problem), each against TAO's gpcg (-ref).
   min 1/2 x'Ax - b'x, A = tridiag(-1, 2+shift, -1), b = -load*h^2, lower bound psi (parabola), upper optional.
   -bounds none|lower|both|inf|crossed|nocall
   -shell : Hessian is a MATSHELL wrapping A
   -resolve 0|1|2 : second TaoSolve with 1 = changed RHS, 2 = changed (lifted) bounds
   -sfo_first : TaoSetFromOptions before TaoSetVariableBounds
   -ref : also solve with a reference Tao (prefix ref_, default gpcg) and print |x - xref|_inf */
#include "quadratic.h"

static PetscErrorCode ShellMult(Mat S, Vec x, Vec y)
{
  Mat A;
  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(S, &A));
  PetscCall(MatMult(A, x, y));
  PetscFunctionReturn(0);
}

static PetscErrorCode Report(Tao tao, const char *tag, Vec x, Vec xref)
{
  TaoConvergedReason reason;
  PetscInt           its;
  PetscReal          f, gnorm, cnorm, xdiff, dx = -1;
  TaoType            type;
  PetscFunctionBeginUser;
  PetscCall(TaoGetType(tao, &type));
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCall(TaoGetSolutionStatus(tao, &its, &f, &gnorm, &cnorm, &xdiff, NULL));
  if (xref) {
    Vec d;
    PetscCall(VecDuplicate(x, &d));
    PetscCall(VecWAXPY(d, -1.0, xref, x));
    PetscCall(VecNorm(d, NORM_INFINITY, &dx));
    PetscCall(VecDestroy(&d));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: type %s reason %s(%d) its %d f %.12e gnorm %.3e cnorm %.3e xdiff %.3e |x-xref|inf %.3e\n", tag, type, TaoConvergedReasons[reason], (int)reason, (int)its,
                        (double)f, (double)gnorm, (double)cnorm, (double)xdiff, (double)dx));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  Quadratic app;
  Tao       tao;
  Mat       S = NULL, Hm;
  Vec       x, lb, ub, xref = NULL;
  PetscInt  n = 100, rstart, rend, resolve = 0;
  PetscReal scl = 10.0, shift = 0.0, load = 20.0, h;
  char      bounds[32] = "lower";
  PetscBool neumann = PETSC_FALSE, shell = PETSC_FALSE, sfo_first = PETSC_FALSE, ref = PETSC_FALSE, x0 = PETSC_FALSE;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-n", &n, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-shift", &shift, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-scl", &scl, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-load", &load, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-bounds", bounds, sizeof(bounds), NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-shell", &shell, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-neumann", &neumann, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-sfo_first", &sfo_first, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-ref", &ref, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-x0", &x0, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-resolve", &resolve, NULL));
  h = 1.0 / (n + 1);
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, n, n, 3, NULL, 1, NULL, &app.A));
  PetscCall(MatGetOwnershipRange(app.A, &rstart, &rend));
  for (PetscInt i = rstart; i < rend; i++) {
    if (i > 0) PetscCall(MatSetValue(app.A, i, i - 1, -1.0, INSERT_VALUES));
    if (i < n - 1) PetscCall(MatSetValue(app.A, i, i + 1, -1.0, INSERT_VALUES));
    PetscCall(MatSetValue(app.A, i, i, (neumann && (i == 0 || i == n - 1)) ? 1.0 : 2.0 + shift, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(app.A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(app.A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(app.A, &x, &app.b));
  PetscCall(VecDuplicate(x, &lb));
  PetscCall(VecDuplicate(x, &ub));
  PetscCall(VecSet(app.b, -load * h * h));
  for (PetscInt i = rstart; i < rend; i++) {
    PetscReal t = (i + 1) * h, psi = -0.1 - 2.0 * (t - 0.5) * (t - 0.5);
    PetscCall(VecSetValue(lb, i, psi, INSERT_VALUES));
    PetscCall(VecSetValue(ub, i, 0.05, INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(lb));
  PetscCall(VecAssemblyEnd(lb));
  PetscCall(VecAssemblyBegin(ub));
  PetscCall(VecAssemblyEnd(ub));
  if (!strcmp(bounds, "lower")) PetscCall(VecSet(ub, PETSC_INFINITY));
  if (!strcmp(bounds, "inf")) {
    PetscCall(VecSet(lb, PETSC_NINFINITY));
    PetscCall(VecSet(ub, PETSC_INFINITY));
  }
  if (!strcmp(bounds, "huge")) {
    PetscCall(VecSet(lb, -1e20));
    PetscCall(VecSet(ub, 1e20));
  }
  if (!strcmp(bounds, "lift")) {
    PetscCall(VecShift(lb, 0.3));
    PetscCall(VecSet(ub, PETSC_INFINITY));
  }
  if (!strcmp(bounds, "box")) {
    PetscCall(VecSet(lb, -0.1));
    PetscCall(VecSet(ub, 0.1));
  }
  if (!strcmp(bounds, "crossed")) PetscCall(VecSet(ub, -5.0)); /* ub < lb everywhere */
  if (!strcmp(bounds, "crossedlast")) {                        /* only the last entry has ub < lb */
    PetscCall(VecSet(ub, PETSC_INFINITY));
    if (rend == n) PetscCall(VecSetValue(ub, n - 1, -5.0, INSERT_VALUES));
    PetscCall(VecAssemblyBegin(ub));
    PetscCall(VecAssemblyEnd(ub));
  }
  if (!strcmp(bounds, "both")) PetscCall(VecSet(app.b, load * h * h * 0.5)); /* push up against ub=0.05 and have lb too */
  PetscCall(VecSet(x, x0 ? 1.0 : 0.0));

  Hm = app.A;
  if (shell) {
    PetscInt m;
    PetscCall(MatGetLocalSize(app.A, &m, NULL));
    PetscCall(MatCreateShell(PETSC_COMM_WORLD, m, m, n, n, app.A, &S));
    PetscCall(MatShellSetOperation(S, MATOP_MULT, (void (*)(void))ShellMult));
    Hm = S;
  }

  if (ref) {
    Tao rt;
    Mat Ac;
    Vec rx;
    PetscCall(MatDuplicate(app.A, MAT_COPY_VALUES, &Ac));
    PetscCall(VecDuplicate(x, &xref));
    PetscCall(VecDuplicate(x, &rx));
    PetscCall(VecSet(xref, 0.0));
    PetscCall(TaoCreate(PETSC_COMM_WORLD, &rt));
    PetscCall(TaoSetOptionsPrefix(rt, "ref_"));
    PetscCall(TaoSetType(rt, TAOGPCG));
    PetscCall(TaoSetSolution(rt, xref));
    PetscCall(TaoSetObjectiveAndGradient(rt, NULL, QuadraticObjectiveGradient, &app));
    PetscCall(TaoSetHessian(rt, Ac, Ac, QuadraticHessian, &app));
    if (strcmp(bounds, "none") && strcmp(bounds, "nocall")) PetscCall(TaoSetVariableBounds(rt, lb, ub));
    PetscCall(TaoSetTolerances(rt, 1e-12, 0, 0));
    PetscCall(TaoSetMaximumIterations(rt, 100000));
    PetscCall(TaoSetFromOptions(rt));
    PetscCall(TaoSolve(rt));
    PetscCall(Report(rt, "ref", xref, NULL));
    PetscCall(TaoDestroy(&rt));
    PetscCall(MatDestroy(&Ac));
    PetscCall(VecDestroy(&rx));
  }

  PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
  PetscCall(TaoSetSolution(tao, x));
  PetscCall(TaoSetObjectiveAndGradient(tao, NULL, QuadraticObjectiveGradient, &app));
  PetscCall(TaoSetHessian(tao, Hm, Hm, QuadraticHessian, &app));
  if (sfo_first) PetscCall(TaoSetFromOptions(tao));
  if (strcmp(bounds, "none") && strcmp(bounds, "nocall")) PetscCall(TaoSetVariableBounds(tao, lb, ub));
  if (!sfo_first) PetscCall(TaoSetFromOptions(tao));
  PetscCall(TaoSolve(tao));
  PetscCall(Report(tao, "solve1", x, xref));
  {
    PetscReal mn;
    PetscCall(VecMin(x, NULL, &mn));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "solve1: min x %.6f\n", (double)mn));
  }
  if (resolve == 1) { /* changed RHS: double the load */
    PetscCall(VecScale(app.b, 2.0));
    PetscCall(VecSet(x, 0.0));
    PetscCall(TaoSolve(tao));
    PetscCall(Report(tao, "solve2(rhs*2)", x, NULL));
  } else if (resolve == 2) { /* lift the lower bound by 0.05 */
    PetscCall(VecShift(lb, 0.05));
    PetscCall(VecSet(x, 0.0));
    PetscCall(TaoSolve(tao));
    PetscCall(Report(tao, "solve2(lb+0.05)", x, NULL));
  } else if (resolve == 4) { /* Hessian values change behind a MATSHELL (or in the AIJ): A *= 10, b *= 10 */
    PetscCall(MatScale(app.A, scl));
    PetscCall(VecScale(app.b, scl));
    PetscCall(VecSet(x, 0.0));
    PetscCall(TaoSolve(tao));
    PetscCall(Report(tao, "solve2(A*scl,b*scl)", x, NULL));
  } else if (resolve == 5) { /* shrink the box to +-0.02 */
    PetscCall(VecSet(lb, -0.02));
    PetscCall(VecSet(ub, 0.02));
    PetscCall(VecSet(x, 0.0));
    PetscCall(TaoSolve(tao));
    PetscCall(Report(tao, "solve2(box +-0.02)", x, NULL));
    PetscReal mx;
    PetscCall(VecNorm(x, NORM_INFINITY, &mx));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "solve2: max|x_i| %.6f\n", (double)mx));
  } else if (resolve == 3) { /* same problem again from the solution */
    PetscCall(TaoSolve(tao));
    PetscCall(Report(tao, "solve2(same, warm)", x, NULL));
  }
  if (resolve) {
    PetscReal mn;
    Vec       d;
    PetscCall(VecMin(x, NULL, &mn));
    PetscCall(VecDuplicate(x, &d));
    PetscCall(VecWAXPY(d, -1.0, lb, x));
    PetscReal viol;
    PetscCall(VecMin(d, NULL, &viol));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "solve2: min x %.6f  min(x-lb) %.3e\n", (double)mn, (double)viol));
    PetscCall(VecDestroy(&d));
  }
  PetscCall(TaoDestroy(&tao));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&xref));
  PetscCall(VecDestroy(&lb));
  PetscCall(VecDestroy(&ub));
  PetscCall(VecDestroy(&app.b));
  PetscCall(MatDestroy(&app.A));
  PetscCall(MatDestroy(&S));
  PetscCall(PetscFinalize());
  return 0;
}
