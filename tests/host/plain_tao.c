/* An unmodified PETSc program (it does not link conefeti): minimizes 1/2 x'Ax - b'x with A the 1D
   Laplacian plus a shift (-shift), b = -rhs*1 (-rhs), subject to -bound <= x <= bound, with
   whatever TAO the options select. With conefeti loaded by -dll_append, `-tao_type mpgp
   -tao_mpgp_block_type disk` reads each consecutive pair's bound box as the inscribed disk
   |(x_2i, x_2i+1)| <= bound. Prints the largest pair norm and entry, so a test can check which set
   was enforced. */
#include "quadratic.h"

int main(int argc, char **argv)
{
  Quadratic          app;
  Tao                tao;
  Vec                x, lb, ub;
  PetscInt           n     = 200, rstart, rend, its;
  PetscReal          shift = 0.01, rhs = 1.0, bound = 0.5, maxpair = 0, maxentry;
  TaoConvergedReason reason;
  TaoType            type;
  const PetscScalar *xa;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Unmodified PETSc program: bound-constrained QP with any TAO\n"));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-n", &n, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-shift", &shift, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-rhs", &rhs, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-bound", &bound, NULL));
  PetscCall(CreateTridiagonal(PETSC_COMM_WORLD, n, 2.0 + shift, &app.A));
  PetscCall(MatGetOwnershipRange(app.A, &rstart, &rend));
  PetscCall(MatCreateVecs(app.A, &x, &app.b));
  PetscCall(VecDuplicate(x, &lb));
  PetscCall(VecDuplicate(x, &ub));
  PetscCall(VecSet(app.b, rhs));
  PetscCall(VecSet(lb, -bound));
  PetscCall(VecSet(ub, bound));
  PetscCall(VecSet(x, 0.0));

  PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
  PetscCall(TaoSetSolution(tao, x));
  PetscCall(TaoSetObjectiveAndGradient(tao, NULL, QuadraticObjectiveGradient, &app));
  PetscCall(TaoSetHessian(tao, app.A, app.A, QuadraticHessian, &app));
  PetscCall(TaoSetVariableBounds(tao, lb, ub));
  PetscCall(TaoSetFromOptions(tao));
  PetscCall(TaoSolve(tao));
  PetscCall(TaoGetType(tao, &type));
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCall(TaoGetIterationNumber(tao, &its));

  PetscCall(VecGetArrayRead(x, &xa));
  for (PetscInt i = 0; i + 1 < rend - rstart; i += 2) maxpair = PetscMax(maxpair, PetscSqrtReal(PetscRealPart(xa[i] * xa[i] + xa[i + 1] * xa[i + 1])));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &maxpair, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(VecNorm(x, NORM_INFINITY, &maxentry));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "plain_tao: type %s, %s after %" PetscInt_FMT " iterations; max |x_i| = %.6f, max pair norm = %.6f, bound %.6f\n", type, TaoConvergedReasons[reason], its,
                        (double)maxentry, (double)maxpair, (double)bound));
  PetscCall(TaoDestroy(&tao));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&lb));
  PetscCall(VecDestroy(&ub));
  PetscCall(VecDestroy(&app.b));
  PetscCall(MatDestroy(&app.A));
  PetscCall(PetscFinalize());
  return 0;
}
