/* The QP setters survive a change of solver type: the feasible set (and the bounds for KSP) given
   before -tao_type / -ksp_type picks the QP type are still used.

   Problem: min 1/2 |x|^2 - b'x with b = (1, 1) and |x| <= r = 0.1 (one disk), solution
   x = r b / |b|; without the disk it would be b (|x| = 1.41). -bounds instead gives 0 <= x <= r on
   both components, solution (r, r) (KSP only: KSPMPRGPSetBounds).
   -api tao|ksp; -initial_type: the type the program sets before the setters ("none": no type);
   the options then choose the final type (-tao_type mpgp, -ksp_type mpgp).
   Prints "RESULT x = (x0, x1) expected (e0, e1) error e" and "CORRECT" when the error is below 1e-8. */
#include <conefeti.h>
#include <conefeti/compat.h>
#include <string>
#include "quadratic.h"

int main(int argc, char **argv)
{
  Mat          A;
  Vec          x, b, lb = NULL, ub = NULL;
  SeparableSet set     = NULL;
  PetscInt     idx[2]  = {0, 1};
  PetscReal    r       = 0.1, e[2];
  char         api[16] = "tao", initial[32] = "none";
  PetscBool    bounds = PETSC_FALSE;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-api", api, sizeof(api), NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-initial_type", initial, sizeof(initial), NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-bounds", &bounds, NULL));
  const std::string which(api), first(initial);
  PetscCheck(which == "tao" || which == "ksp", PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "-api must be tao or ksp, not %s", api);
  PetscCheck(!bounds || which == "ksp", PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "-bounds is for -api ksp");

  PetscCall(MatCreateConstantDiagonal(PETSC_COMM_SELF, 2, 2, 2, 2, 1.0, &A));
  PetscCall(MatCreateVecs(A, &x, &b));
  PetscCall(VecSet(b, 1.0));
  if (bounds) {
    PetscCall(VecDuplicate(x, &lb));
    PetscCall(VecDuplicate(x, &ub));
    PetscCall(VecSet(lb, 0.0));
    PetscCall(VecSet(ub, r));
    e[0] = e[1] = r;
  } else {
    PetscCall(SeparableSetCreate(PETSC_COMM_SELF, 2, 2, &set));
    PetscCall(SeparableSetAddDisks(set, 1, idx, NULL, &r));
    e[0] = e[1] = r / PetscSqrtReal(2.0);
  }

  if (which == "tao") {
    Tao       tao;
    Quadratic q = {A, b};
    PetscCall(TaoCreate(PETSC_COMM_SELF, &tao));
    if (first != "none") PetscCall(TaoSetType(tao, first.c_str()));
    PetscCall(TaoSetSolution(tao, x));
    PetscCall(TaoSetHessian(tao, A, A, NULL, NULL));
    PetscCall(TaoSetObjectiveAndGradient(tao, NULL, QuadraticObjectiveGradient, &q));
    PetscCall(TaoQPSetConstraints(tao, set));
    PetscCall(TaoQPSetLinearTerm(tao, b));
    PetscCall(TaoSetFromOptions(tao));
    PetscCall(TaoSolve(tao));
    PetscCall(TaoDestroy(&tao));
  } else {
    KSP ksp;
    PetscCall(KSPCreate(PETSC_COMM_SELF, &ksp));
    if (first != "none") PetscCall(KSPSetType(ksp, first.c_str()));
    PetscCall(KSPSetOperators(ksp, A, A));
    if (set) PetscCall(KSPQPSetConstraints(ksp, set));
    if (bounds) PetscCall(KSPMPRGPSetBounds(ksp, lb, ub));
    PetscCall(KSPSetFromOptions(ksp));
    PetscCall(KSPSolve(ksp, b, x));
    PetscCall(KSPDestroy(&ksp));
  }

  const PetscScalar *xa;
  PetscCall(VecGetArrayRead(x, &xa));
  const PetscReal err = PetscMax(PetscAbsReal(PetscRealPart(xa[0]) - e[0]), PetscAbsReal(PetscRealPart(xa[1]) - e[1]));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "RESULT x = (%g, %g) expected (%g, %g) error %.1e\n", (double)PetscRealPart(xa[0]), (double)PetscRealPart(xa[1]), (double)e[0], (double)e[1], (double)err));
  if (err < 1e-8) PetscCall(PetscPrintf(PETSC_COMM_SELF, "CORRECT\n"));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(SeparableSetDestroy(&set));
  PetscCall(VecDestroy(&lb));
  PetscCall(VecDestroy(&ub));
  PetscCall(MatDestroy(&A));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&b));
  PetscCall(PetscFinalize());
  return 0;
}
