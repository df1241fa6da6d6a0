/* smalxe: C x = d and s C x = s d are one constraint, and give one solution.

   The tolerance of |C x - d| did not scale with ||C||: with ||C|| = 4.5 (the sum of 20 entries) it was held
   4.5 times tighter than the gradient's floor in the inner solves can reach, and the outer loop stalled
   (DIVERGED_USER after 72 outer iterations, the inner solves taking no step). Problem: min 1/2 x'Ax - b'x,
   A = tridiag(-1, 3, -1), b_i = 1 + sin(i), 0 <= x <= 0.3, s sum(x) = 5 s, n = 20; solved for s = 1/sqrt(20)
   (||C|| = 1), 1 and 10. Prints a line per solve and "CORRECT" when every solve converged, is feasible and
   agrees with the first to 1e-6. */
#include <conefeti.h>
#include <cmath>

static PetscErrorCode Solve(PetscReal scale, Vec x)
{
  const PetscInt     n = 20;
  Mat                A, C;
  Vec                b, lb, ub, d;
  Tao                tao;
  TaoConvergedReason reason;
  PetscInt           its;

  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 3, NULL, &A));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, 1, n, NULL, &C));
  for (PetscInt i = 0; i < n; i++) {
    PetscCall(MatSetValue(A, i, i, 3.0, INSERT_VALUES));
    if (i > 0) PetscCall(MatSetValue(A, i, i - 1, -1.0, INSERT_VALUES));
    if (i < n - 1) PetscCall(MatSetValue(A, i, i + 1, -1.0, INSERT_VALUES));
    PetscCall(MatSetValue(C, 0, i, scale, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyBegin(C, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(C, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(A, NULL, &b));
  PetscCall(VecDuplicate(b, &lb));
  PetscCall(VecDuplicate(b, &ub));
  PetscCall(MatCreateVecs(C, NULL, &d));
  for (PetscInt i = 0; i < n; i++) PetscCall(VecSetValue(b, i, 1 + std::sin((PetscReal)i), INSERT_VALUES));
  PetscCall(VecAssemblyBegin(b));
  PetscCall(VecAssemblyEnd(b));
  PetscCall(VecSet(lb, 0.0));
  PetscCall(VecSet(ub, 0.3));
  PetscCall(VecSet(d, 5 * scale));
  PetscCall(VecSet(x, 0.0));

  PetscCall(TaoCreate(PETSC_COMM_SELF, &tao));
  PetscCall(TaoSetType(tao, TAOSMALXE));
  PetscCall(TaoSetSolution(tao, x));
  PetscCall(TaoSetVariableBounds(tao, lb, ub));
  PetscCall(TaoSetHessian(tao, A, A, NULL, NULL));
  PetscCall(TaoQPSetLinearTerm(tao, b));
  PetscCall(TaoSMALXESetEqualityConstraints(tao, C, d));
  PetscCall(TaoSetFromOptions(tao));
  PetscCall(TaoSolve(tao));
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCall(TaoGetIterationNumber(tao, &its));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "scale %g: reason %s outer iterations %" PetscInt_FMT "\n", (double)scale, TaoConvergedReasons[reason], its + 1));
  PetscCheck(reason > 0, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED, "scale %g: not converged", (double)scale);
  PetscCall(TaoDestroy(&tao));
  PetscCall(MatDestroy(&A));
  PetscCall(MatDestroy(&C));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&lb));
  PetscCall(VecDestroy(&ub));
  PetscCall(VecDestroy(&d));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Vec       x[3];
  PetscReal scales[3] = {1 / std::sqrt(20.0), 1, 10}, worst = 0, sum, xnorm;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(ConeFETIInitializePackage());
  for (int k = 0; k < 3; k++) {
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, 20, &x[k]));
    PetscCall(Solve(scales[k], x[k]));
    PetscCall(VecSum(x[k], &sum));
    PetscCheck(std::abs(sum - 5) <= 1e-6 * 5, PETSC_COMM_SELF, PETSC_ERR_PLIB, "scale %g: sum(x) = %.10g, not 5", (double)scales[k], (double)sum);
  }
  PetscCall(VecNorm(x[0], NORM_2, &xnorm));
  for (int k = 1; k < 3; k++) {
    PetscReal diff;
    PetscCall(VecAXPY(x[k], -1.0, x[0]));
    PetscCall(VecNorm(x[k], NORM_2, &diff));
    worst = std::max(worst, diff / xnorm);
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "largest relative difference to scale 1/sqrt(20): %.1e\n", (double)worst));
  if (worst <= 1e-6) PetscCall(PetscPrintf(PETSC_COMM_SELF, "CORRECT\n"));
  for (int k = 0; k < 3; k++) PetscCall(VecDestroy(&x[k]));
  PetscCall(PetscFinalize());
  return 0;
}
