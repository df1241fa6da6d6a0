/* TaoSMALXEGetMultiplierGrowth() on a QP whose equality cannot be met over its set: min 1/2 x'Ax - x'b over x >= 0
   with sum x = -1 (A the 1D Laplacian, b = -1). The loop stagnates and the multiplier of the one row grows, so the
   growth C'(mu_k - mu_j) is a nonzero multiple of the row, a constant vector, and spans h to 2h - 1 outer iterations
   (h = half the stagnation window). A second solve stopped after 5 outer iterations has no such span: its 0, w = 0.
   -projector uses the projector form (Q = C'C, C with one unit row). Prints one RESULT line per solve. */
#include <conefeti.h>
#include "quadratic.h"

static PetscErrorCode Report(Tao tao, Vec w, PetscInt solve)
{
  TaoConvergedReason reason;
  PetscBool          stagnated;
  PetscInt           its;
  PetscReal          wmax, wmin, wnorm;

  PetscFunctionBeginUser;
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCall(TaoSMALXEGetStagnated(tao, &stagnated));
  PetscCall(TaoSMALXEGetMultiplierGrowth(tao, w, &its));
  PetscCall(VecMax(w, NULL, &wmax));
  PetscCall(VecMin(w, NULL, &wmin));
  PetscCall(VecNorm(w, NORM_2, &wnorm));
  /* constant: the spread of the entries against their size */
  const PetscReal spread = wnorm > 0 ? (wmax - wmin) / PetscMax(PetscAbsReal(wmax), PetscAbsReal(wmin)) : 0;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "RESULT solve %" PetscInt_FMT ": %s stagnated %d its %" PetscInt_FMT " |w| %s constant %s\n", solve, TaoConvergedReasons[reason], (int)stagnated, its,
                        wnorm > 0 ? "> 0" : "0", spread < 1e-8 ? "yes" : "no"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Mat          A, C, Q = NULL;
  Vec          x, b, lb, d, w, xt = NULL;
  Tao          tao;
  SeparableSet set;
  PetscInt     n         = 40, rs, re;
  PetscBool    projector = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-projector", &projector, NULL));
  PetscCall(CreateTridiagonal(PETSC_COMM_WORLD, n, 2.0, &A));
  PetscCall(MatGetOwnershipRange(A, &rs, &re));
  PetscCall(MatCreateVecs(A, &x, &b));
  PetscCall(VecDuplicate(x, &lb));
  PetscCall(VecDuplicate(x, &w));
  PetscCall(VecSet(b, -1.0));
  PetscCall(VecSet(lb, 0.0));
  /* C: one unit row, (1/sqrt(n)) sum x = d with d < 0: no x >= 0 meets it */
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, rs == 0 ? 1 : 0, re - rs, 1, n, n, NULL, n, NULL, &C));
  if (rs == 0)
    for (PetscInt j = 0; j < n; j++) PetscCall(MatSetValue(C, 0, j, 1.0 / PetscSqrtReal((PetscReal)n), INSERT_VALUES));
  PetscCall(MatAssemblyBegin(C, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(C, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(C, NULL, &d));
  PetscCall(VecSet(d, -1.0));
  PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, re - rs, n, &set));
  PetscCall(SeparableSetSetBounds(set, lb, NULL));
  PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
  PetscCall(TaoSetType(tao, TAOSMALXE));
  PetscCall(TaoSetSolution(tao, x));
  PetscCall(TaoSetHessian(tao, A, A, NULL, NULL));
  PetscCall(TaoQPSetLinearTerm(tao, b));
  PetscCall(TaoQPSetConstraints(tao, set));
  if (projector) {
    PetscCall(MatTransposeMatMult(C, C, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &Q));
    PetscCall(VecDuplicate(x, &xt));
    PetscCall(MatMultTranspose(C, d, xt));
    PetscCall(TaoSMALXESetProjector(tao, Q, xt));
  } else PetscCall(TaoSMALXESetEqualityConstraints(tao, C, d));
  PetscCall(TaoSetFromOptions(tao));
  for (PetscInt k = 0; k < 2; k++) {
    PetscCall(VecSet(x, 0.0));
    if (k == 1) PetscCall(TaoSetMaximumIterations(tao, 5));
    PetscCall(TaoSolve(tao));
    PetscCall(Report(tao, w, k + 1));
  }
  PetscCall(TaoDestroy(&tao));
  PetscCall(SeparableSetDestroy(&set));
  PetscCall(MatDestroy(&Q));
  PetscCall(VecDestroy(&xt));
  PetscCall(MatDestroy(&A));
  PetscCall(MatDestroy(&C));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&w));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&lb));
  PetscCall(VecDestroy(&d));
  PetscCall(PetscFinalize());
  return 0;
}
