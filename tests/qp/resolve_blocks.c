/* smalxe with TaoSMALXESetBlocks and a user SeparableSet: a lower bound changed in place between two
   solves reaches the blocks (their sets are copies of parts of the set, made again when it changed) */
#include <conefeti.h>
#include "quadratic.h"
int main(int argc, char **argv)
{
  Mat          A, C;
  Vec          x, b, lb, d;
  Tao          tao;
  SeparableSet set;
  IS           is[2];
  PetscInt     n = 40, rs, re;
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(CreateTridiagonal(PETSC_COMM_WORLD, n, 2.0, &A));
  PetscCall(MatGetOwnershipRange(A, &rs, &re));
  PetscCall(MatCreateVecs(A, &x, &b));
  PetscCall(VecDuplicate(x, &lb));
  PetscCall(VecSet(b, -1.0));
  PetscCall(VecSet(lb, -1.0));
  PetscCall(VecSet(x, 0.0));
  /* C: one row, x_0 - x_{n-1} = 0 */
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, re - rs, 1, n, 2, NULL, 2, NULL, &C));
  if (rs == 0) {
    PetscCall(MatSetValue(C, 0, 0, 1.0, INSERT_VALUES));
    PetscCall(MatSetValue(C, 0, n - 1, -1.0, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(C, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(C, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(C, NULL, &d));
  PetscCall(VecSet(d, 0.0));
  PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, re - rs, n, &set));
  PetscCall(SeparableSetSetBounds(set, lb, NULL));
  /* two blocks: first and second half of each rank's range */
  {
    PetscInt m = re - rs, h = m / 2;
    PetscCall(ISCreateStride(PETSC_COMM_WORLD, h, rs, 1, &is[0]));
    PetscCall(ISCreateStride(PETSC_COMM_WORLD, m - h, rs + h, 1, &is[1]));
  }
  PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
  PetscCall(TaoSetType(tao, TAOSMALXE));
  PetscCall(TaoSetSolution(tao, x));
  PetscCall(TaoSetHessian(tao, A, A, NULL, NULL));
  PetscCall(TaoQPSetLinearTerm(tao, b));
  PetscCall(TaoQPSetConstraints(tao, set));
  PetscCall(TaoSMALXESetEqualityConstraints(tao, C, d));
  PetscCall(TaoSMALXESetBlocks(tao, 2, is));
  PetscCall(TaoSetFromOptions(tao));
  for (int k = 0; k < 2; k++) {
    PetscReal          mn;
    TaoConvergedReason r;
    PetscCall(VecSet(x, 0.0));
    PetscCall(TaoSolve(tao));
    PetscCall(TaoGetConvergedReason(tao, &r));
    PetscCall(VecMin(x, NULL, &mn));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "solve%d: %s min x %.6f (lb %g)\n", k + 1, TaoConvergedReasons[r], (double)mn, k ? -0.1 : -1.0));
    PetscCall(VecSet(lb, -0.1)); /* in place */
  }
  PetscCall(TaoDestroy(&tao));
  PetscCall(SeparableSetDestroy(&set));
  PetscCall(ISDestroy(&is[0]));
  PetscCall(ISDestroy(&is[1]));
  PetscCall(MatDestroy(&A));
  PetscCall(MatDestroy(&C));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&lb));
  PetscCall(VecDestroy(&d));
  PetscCall(PetscFinalize());
  return 0;
}
