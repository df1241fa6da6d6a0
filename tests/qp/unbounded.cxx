/* A semidefinite QP that is unbounded below is named so.

   min 1/2 x'Ax - b'x with A the Neumann Laplacian tridiag(-1, 2, -1) (1 at both ends: singular, its kernel the
   constants) and b_i = 1 + sin(i), which is not in the range of A: q falls without bound along the constants, and no
   constraint stops it (-lower gives x >= 0, which does not either). A CG direction there has a curvature of
   rounding size, positive: the solver took a step of 1e30 and said "the norm estimate is too small".
   -shell gives A as a MATSHELL. Run with -tao_view: "stopped: q is unbounded below". */
#include <conefeti.h>

static PetscErrorCode ShellMult(Mat S, Vec x, Vec y)
{
  Mat A;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(S, &A));
  PetscCall(MatMult(A, x, y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const PetscInt     n = 20;
  Mat                A, S;
  Vec                x, b, lb = NULL;
  Tao                tao;
  PetscBool          shell = PETSC_FALSE, lower = PETSC_FALSE;
  TaoConvergedReason reason;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-shell", &shell, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-lower", &lower, NULL));
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 3, NULL, &A));
  for (PetscInt i = 0; i < n; i++) {
    PetscCall(MatSetValue(A, i, i, i == 0 || i == n - 1 ? 1.0 : 2.0, INSERT_VALUES));
    if (i > 0) PetscCall(MatSetValue(A, i, i - 1, -1.0, INSERT_VALUES));
    if (i < n - 1) PetscCall(MatSetValue(A, i, i + 1, -1.0, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateShell(PETSC_COMM_SELF, n, n, n, n, A, &S));
  PetscCall(MatShellSetOperation(S, MATOP_MULT, (void (*)(void))ShellMult));
  PetscCall(MatCreateVecs(A, &x, &b));
  for (PetscInt i = 0; i < n; i++) PetscCall(VecSetValue(b, i, 1 + PetscSinReal((PetscReal)i), INSERT_VALUES));
  PetscCall(VecAssemblyBegin(b));
  PetscCall(VecAssemblyEnd(b));
  PetscCall(VecSet(x, 0.0));
  PetscCall(TaoCreate(PETSC_COMM_SELF, &tao));
  PetscCall(TaoSetType(tao, TAOMPRGP));
  PetscCall(TaoSetSolution(tao, x));
  if (lower) {
    PetscCall(VecDuplicate(x, &lb));
    PetscCall(VecSet(lb, 0.0));
    PetscCall(TaoSetVariableBounds(tao, lb, NULL));
  }
  PetscCall(TaoSetHessian(tao, shell ? S : A, shell ? S : A, NULL, NULL));
  PetscCall(TaoQPSetLinearTerm(tao, b));
  PetscCall(TaoSetFromOptions(tao));
  PetscCall(TaoSolve(tao));
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "reason %s\n", TaoConvergedReasons[reason]));
  PetscCall(TaoDestroy(&tao));
  PetscCall(MatDestroy(&A));
  PetscCall(MatDestroy(&S));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&lb));
  PetscCall(PetscFinalize());
  return 0;
}
