/* A Hessian that is not symmetric is named so, not blamed on semidefiniteness or the norm estimate.

   min 1/2 x'Ax - b'x with A = tridiag(-1 - s, 2, -1 + s), n = 30 (-skew s, default 1: A's symmetric part is the
   Dirichlet Laplacian, its skew part s tridiag(-1, 0, 1)), b_i = 1 + sin(i), x >= 0 with -lower. -shell gives A as a
   MATSHELL (MatIsSymmetric() cannot test it); -ksp solves with KSPSetOperators() and the KSP type of -ksp_type
   (default mprgp), else a TAO solve of -tao_type (default mprgp). Prints the reason. */
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
  const PetscInt n = 30;
  PetscReal      s = 1;
  Mat            A, S, H;
  Vec            x, b, lb = NULL;
  PetscBool      shell = PETSC_FALSE, lower = PETSC_FALSE, useksp = PETSC_FALSE;
  SeparableSet   set = NULL;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-skew", &s, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-shell", &shell, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-lower", &lower, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-ksp", &useksp, NULL));
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 3, NULL, &A));
  for (PetscInt i = 0; i < n; i++) {
    PetscCall(MatSetValue(A, i, i, 2.0, INSERT_VALUES));
    if (i > 0) PetscCall(MatSetValue(A, i, i - 1, -1.0 - s, INSERT_VALUES));
    if (i < n - 1) PetscCall(MatSetValue(A, i, i + 1, -1.0 + s, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateShell(PETSC_COMM_SELF, n, n, n, n, A, &S));
  PetscCall(MatShellSetOperation(S, MATOP_MULT, (void (*)(void))ShellMult));
  H = shell ? S : A;
  PetscCall(MatCreateVecs(A, &x, &b));
  for (PetscInt i = 0; i < n; i++) PetscCall(VecSetValue(b, i, 1 + PetscSinReal((PetscReal)i), INSERT_VALUES));
  PetscCall(VecAssemblyBegin(b));
  PetscCall(VecAssemblyEnd(b));
  PetscCall(VecSet(x, 0.0));
  if (lower) {
    PetscCall(VecDuplicate(x, &lb));
    PetscCall(VecSet(lb, 0.0));
  }
  if (useksp) {
    KSP                ksp;
    KSPConvergedReason reason;
    PetscCall(KSPCreate(PETSC_COMM_SELF, &ksp));
    PetscCall(KSPSetType(ksp, KSPMPRGP));
    PetscCall(KSPSetOperators(ksp, H, H));
    if (lower) {
      PetscCall(SeparableSetCreate(PETSC_COMM_SELF, n, n, &set));
      PetscCall(SeparableSetSetBounds(set, lb, NULL));
      PetscCall(KSPQPSetConstraints(ksp, set));
    }
    PetscCall(KSPSetFromOptions(ksp));
    PetscCall(KSPSolve(ksp, b, x));
    PetscCall(KSPGetConvergedReason(ksp, &reason));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "reason %s\n", KSPConvergedReasons[reason]));
    PetscCall(KSPDestroy(&ksp));
  } else {
    Tao                tao;
    TaoConvergedReason reason;
    PetscCall(TaoCreate(PETSC_COMM_SELF, &tao));
    PetscCall(TaoSetType(tao, TAOMPRGP));
    PetscCall(TaoSetSolution(tao, x));
    if (lower) PetscCall(TaoSetVariableBounds(tao, lb, NULL));
    PetscCall(TaoSetHessian(tao, H, H, NULL, NULL));
    PetscCall(TaoQPSetLinearTerm(tao, b));
    PetscCall(TaoSetFromOptions(tao));
    PetscCall(TaoSolve(tao));
    PetscCall(TaoGetConvergedReason(tao, &reason));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "reason %s\n", TaoConvergedReasons[reason]));
    PetscCall(TaoDestroy(&tao));
  }
  PetscCall(SeparableSetDestroy(&set));
  PetscCall(MatDestroy(&A));
  PetscCall(MatDestroy(&S));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&lb));
  PetscCall(PetscFinalize());
  return 0;
}
