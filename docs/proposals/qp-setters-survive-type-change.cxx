/* Reproducer for docs/proposals/qp-setters-survive-type-change.patch: a disk-constrained QP
   (A = I, b = (1, 1), |x| <= 0.1) whose set and linear term are given while the Tao is mprgp; run
   with -tao_type mpgp, TaoSetFromOptions() changes the type and mpgp silently solves the
   unconstrained problem (prints |x| = 1.41421; correct is 0.1).
   Build: mpicxx -std=c++17 -Iinclude $(pkg-config --cflags PETSc SLEPc) this.cxx -Lbuild -lconefeti $(pkg-config --libs PETSc SLEPc) */
#include <conefeti.h>
static PetscErrorCode FG(Tao, Vec x, PetscReal *f, Vec g, void *ctx)
{
  Vec         b = (Vec)ctx;
  PetscScalar xb;
  PetscFunctionBeginUser;
  PetscCall(VecCopy(x, g));
  PetscCall(VecAXPY(g, -1.0, b));
  PetscCall(VecDot(x, b, &xb));
  PetscCall(VecDot(x, x, f));
  *f = 0.5 * *f - xb;
  PetscFunctionReturn(0);
}
int main(int argc, char **argv)
{
  Tao          tao;
  Mat          A;
  Vec          x, b;
  SeparableSet set;
  PetscInt     idx[2] = {0, 1};
  PetscReal    r      = 0.1, nrm;
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(MatCreateConstantDiagonal(PETSC_COMM_SELF, 2, 2, 2, 2, 1.0, &A));
  PetscCall(MatCreateVecs(A, &x, &b));
  PetscCall(VecSet(b, 1.0));
  PetscCall(SeparableSetCreate(PETSC_COMM_SELF, 2, 2, &set));
  PetscCall(SeparableSetAddDisks(set, 1, idx, NULL, &r));
  PetscCall(TaoCreate(PETSC_COMM_SELF, &tao));
  PetscCall(TaoSetType(tao, TAOMPRGP));
  PetscCall(TaoSetSolution(tao, x));
  PetscCall(TaoSetHessian(tao, A, A, NULL, NULL));
  PetscCall(TaoSetObjectiveAndGradient(tao, NULL, FG, b));
  PetscCall(TaoQPSetConstraints(tao, set));
  PetscCall(TaoQPSetLinearTerm(tao, b));
  PetscCall(TaoSetFromOptions(tao)); /* -tao_type mpgp */
  PetscCall(TaoSolve(tao));
  PetscCall(VecNorm(x, NORM_2, &nrm));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "|x| = %g (disk radius %g)\n", (double)nrm, (double)r));
  PetscCall(TaoDestroy(&tao));
  PetscCall(SeparableSetDestroy(&set));
  PetscCall(MatDestroy(&A));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&b));
  PetscCall(PetscFinalize());
  return 0;
}
