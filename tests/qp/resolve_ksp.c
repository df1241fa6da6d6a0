/* Bounds changed between two KSPSolve() calls, in place (the vectors' values, not the objects), reach
   the solver: through KSPMPRGPSetBounds() and through a user SeparableSet (KSPQPSetConstraints()).
   -case 1: KSPMPRGPSetBounds(lb, NULL); solve; change lb in place; solve again
   -case 2: KSPQPSetConstraints(SeparableSet with lb); solve; change lb in place; solve again
   -case 3: KSPMPRGPSetBounds; then KSPSetOperators with a bigger matrix (new size) and solve
   -case 4: KSPMPRGPSetBounds before KSPSetType (type from options, default cg) */
#include <conefeti.h>
#include "quadratic.h"

static PetscErrorCode Rep(KSP ksp, Vec x, Vec lb, const char *tag)
{
  KSPConvergedReason r;
  PetscInt           its;
  PetscReal          mn, viol;
  Vec                d;
  PetscFunctionBeginUser;
  PetscCall(KSPGetConvergedReason(ksp, &r));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  PetscCall(VecMin(x, NULL, &mn));
  PetscCall(VecDuplicate(x, &d));
  PetscCall(VecWAXPY(d, -1.0, lb, x));
  PetscCall(VecMin(d, NULL, &viol));
  PetscCall(VecDestroy(&d));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: %s its %d min x %.6f min(x-lb) %.3e\n", tag, KSPConvergedReasons[r], (int)its, (double)mn, (double)viol));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  Mat      A;
  Vec      x, b, lb;
  KSP      ksp;
  PetscInt n = 100, c = 1;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-case", &c, NULL));
  PetscCall(CreateTridiagonal(PETSC_COMM_WORLD, n, 2.0, &A));
  PetscCall(MatCreateVecs(A, &x, &b));
  PetscCall(VecDuplicate(x, &lb));
  PetscCall(VecSet(b, -0.01));
  PetscCall(VecSet(lb, -0.3));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, A, A));
  if (c != 4) PetscCall(KSPSetType(ksp, KSPMPRGP));
  if (c == 1 || c == 3 || c == 4) PetscCall(KSPMPRGPSetBounds(ksp, lb, NULL));
  if (c == 2) {
    SeparableSet set;
    PetscInt     nl;
    PetscCall(VecGetLocalSize(x, &nl));
    PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, nl, n, &set));
    PetscCall(SeparableSetSetBounds(set, lb, NULL));
    PetscCall(KSPQPSetConstraints(ksp, set));
    PetscCall(SeparableSetDestroy(&set));
  }
  PetscCall(KSPSetTolerances(ksp, 1e-10, PETSC_DEFAULT, PETSC_DEFAULT, 2000));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCall(KSPSolve(ksp, b, x));
  PetscCall(Rep(ksp, x, lb, "solve1 (lb=-0.3)"));
  if (c == 1 || c == 2 || c == 4) {
    PetscCall(VecSet(lb, -0.1));
    PetscCall(KSPSolve(ksp, b, x));
    PetscCall(Rep(ksp, x, lb, "solve2 (lb=-0.1 in place)"));
  }
  if (c == 3) {
    Mat A2;
    Vec x2, b2, lb2;
    PetscCall(CreateTridiagonal(PETSC_COMM_WORLD, 2 * n, 2.0, &A2));
    PetscCall(MatCreateVecs(A2, &x2, &b2));
    PetscCall(VecDuplicate(x2, &lb2));
    PetscCall(VecSet(b2, -0.01));
    PetscCall(VecSet(lb2, -0.3));
    PetscCall(KSPSetOperators(ksp, A2, A2));
    PetscCall(KSPMPRGPSetBounds(ksp, lb2, NULL));
    PetscCall(KSPSolve(ksp, b2, x2));
    PetscCall(Rep(ksp, x2, lb2, "solve2 (n doubled)"));
    PetscCall(MatDestroy(&A2));
    PetscCall(VecDestroy(&x2));
    PetscCall(VecDestroy(&b2));
    PetscCall(VecDestroy(&lb2));
  }
  PetscCall(KSPDestroy(&ksp));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&lb));
  PetscCall(MatDestroy(&A));
  PetscCall(PetscFinalize());
  return 0;
}
