/* A user's mprgp/mpgp solve stops only on an exact gradient, also after CG steps.

   CG updates the gradient by the recurrence g - a A p, which drifts from A x - b where A is ill conditioned.
   On this QP the recurred projected gradient met the tolerance (CONVERGED_GTTOL) while that of A x - b was
   5.6 times it. Problem: min 1/2 x'Ax - b'x without constraints, n = 50, A = Q D Q' dense with D's diagonal
   spaced logarithmically from 1 to -cond (1e10) and Q the Householder reflector I - 2 v v'/(v'v), v_i = 1 + i;
   b_i = 1 + sin(i). The gradient is recomputed here; prints "reason R iterations k exact |g|/|b| r" and
   "CORRECT" when the solve converged with the recomputed |A x - b| within the tolerance (gttol 1e-8 |b|), or
   stopped without claiming convergence. */
#include <conefeti.h>
#include <cmath>

int main(int argc, char **argv)
{
  const PetscInt     n    = 50;
  PetscReal          cond = 1e10, vv = 0, rnorm, bnorm;
  Mat                A;
  Vec                x, b, r;
  Tao                tao;
  TaoConvergedReason reason;
  PetscInt           its;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-cond", &cond, NULL));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, &A));
  for (PetscInt i = 0; i < n; i++) vv += (1.0 + i) * (1.0 + i);
  for (PetscInt i = 0; i < n; i++)
    for (PetscInt j = 0; j < n; j++) {
      PetscReal a = 0;
      for (PetscInt k = 0; k < n; k++) {
        const PetscReal qik = (i == k) - 2 * (1.0 + i) * (1.0 + k) / vv, qjk = (j == k) - 2 * (1.0 + j) * (1.0 + k) / vv;
        a += qik * std::pow(cond, (PetscReal)k / (n - 1)) * qjk;
      }
      PetscCall(MatSetValue(A, i, j, a, INSERT_VALUES));
    }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(A, &x, &b));
  PetscCall(VecDuplicate(x, &r));
  for (PetscInt i = 0; i < n; i++) PetscCall(VecSetValue(b, i, 1 + std::sin((PetscReal)i), INSERT_VALUES));
  PetscCall(VecAssemblyBegin(b));
  PetscCall(VecAssemblyEnd(b));
  PetscCall(VecSet(x, 0.0));

  PetscCall(TaoCreate(PETSC_COMM_SELF, &tao));
  PetscCall(TaoSetType(tao, TAOMPRGP));
  PetscCall(TaoSetSolution(tao, x));
  PetscCall(TaoSetHessian(tao, A, A, NULL, NULL));
  PetscCall(TaoQPSetLinearTerm(tao, b));
  PetscCall(TaoSetFromOptions(tao));
  PetscCall(TaoSolve(tao));
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCall(TaoGetIterationNumber(tao, &its));
  PetscCall(MatMult(A, x, r));
  PetscCall(VecAXPY(r, -1.0, b));
  PetscCall(VecNorm(r, NORM_2, &rnorm));
  PetscCall(VecNorm(b, NORM_2, &bnorm));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "reason %s iterations %" PetscInt_FMT " exact |g|/|b| %.2e\n", TaoConvergedReasons[reason], its, (double)(rnorm / bnorm)));
  if (reason <= 0 || rnorm <= 1e-8 * bnorm) PetscCall(PetscPrintf(PETSC_COMM_SELF, "CORRECT\n"));
  PetscCall(TaoDestroy(&tao));
  PetscCall(MatDestroy(&A));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&r));
  PetscCall(PetscFinalize());
  return 0;
}
