/* A QP type set in code and then changed by -tao_type keeps no stopping test of the first type.

   TaoSetType() keeps tao->ops->convergencetest, and each of smalxe and mprgp/mpgp installs its own test only
   over TAO's default: after a change the new type ran the old one's test on its own data (smalxe's test on
   mpgp's data crashed; mpgp's test under smalxe ran 1000 outer iterations on a solved problem).

   Problem: min 1/2 x'Ax - b'x, A = tridiag(-1, 3, -1) (n = 10), b = 1, x >= 0; the bound is inactive at the
   solution A^-1 b, so the check is |A x - b| / |b| <= 1e-6 with a converged reason.
   -first_type: the type the program sets before TaoSetFromOptions(); -tao_type the one the user picks; -n the
   size (0: an empty problem, which converges at once; the norm estimate failed in SLEPc on it).
   Prints "reason R iterations k residual r" and "CORRECT". */
#include <conefeti.h>

int main(int argc, char **argv)
{
  PetscInt           n         = 10;
  char               first[64] = TAOSMALXE;
  Mat                A;
  Vec                x, b, lb, ub, r;
  Tao                tao;
  TaoConvergedReason reason;
  PetscInt           its;
  PetscReal          rnorm, bnorm;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-first_type", first, sizeof(first), NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-n", &n, NULL));
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 3, NULL, &A));
  for (PetscInt i = 0; i < n; i++) {
    PetscCall(MatSetValue(A, i, i, 3.0, INSERT_VALUES));
    if (i > 0) PetscCall(MatSetValue(A, i, i - 1, -1.0, INSERT_VALUES));
    if (i < n - 1) PetscCall(MatSetValue(A, i, i + 1, -1.0, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(A, &x, &b));
  PetscCall(VecDuplicate(x, &lb));
  PetscCall(VecDuplicate(x, &ub));
  PetscCall(VecDuplicate(x, &r));
  PetscCall(VecSet(b, 1.0));
  PetscCall(VecSet(x, 0.0));
  PetscCall(VecSet(lb, 0.0));
  PetscCall(VecSet(ub, PETSC_INFINITY));

  PetscCall(TaoCreate(PETSC_COMM_SELF, &tao));
  PetscCall(TaoSetType(tao, first));
  PetscCall(TaoSetSolution(tao, x));
  PetscCall(TaoSetVariableBounds(tao, lb, ub));
  PetscCall(TaoSetHessian(tao, A, A, NULL, NULL));
  PetscCall(TaoSetFromOptions(tao));
  PetscCall(TaoQPSetLinearTerm(tao, b));
  PetscCall(TaoSolve(tao));
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCall(TaoGetIterationNumber(tao, &its));
  PetscCall(MatMult(A, x, r)); /* the residual recomputed, not the solver's */
  PetscCall(VecAXPY(r, -1.0, b));
  PetscCall(VecNorm(r, NORM_2, &rnorm));
  PetscCall(VecNorm(b, NORM_2, &bnorm));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "reason %s iterations %" PetscInt_FMT " residual %.1e\n", TaoConvergedReasons[reason], its, (double)(rnorm / bnorm)));
  if (reason > 0 && rnorm <= 1e-6 * bnorm) PetscCall(PetscPrintf(PETSC_COMM_SELF, "CORRECT\n"));
  PetscCall(TaoDestroy(&tao));
  PetscCall(MatDestroy(&A));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&lb));
  PetscCall(VecDestroy(&ub));
  PetscCall(VecDestroy(&r));
  PetscCall(PetscFinalize());
  return 0;
}
