/* An unmodified PETSc program (it does not link conefeti): solves the 1D Laplacian system
   A x = 1 with whatever KSP the options select. Used to prove that -dll_append libconefeti.so
   makes the conefeti KSP types available to any PETSc program. */
#include <petscksp.h>
#include "quadratic.h"

int main(int argc, char **argv)
{
  Mat                A;
  Vec                x, b;
  KSP                ksp;
  PetscInt           n = 100, its;
  KSPConvergedReason reason;
  KSPType            type;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Unmodified PETSc program: 1D Laplacian with any KSP\n"));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-n", &n, NULL));
  PetscCall(CreateTridiagonal(PETSC_COMM_WORLD, n, 2.0, &A));
  PetscCall(MatCreateVecs(A, &x, &b));
  PetscCall(VecSet(b, 1.0));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCall(KSPSolve(ksp, b, x));
  PetscCall(KSPGetType(ksp, &type));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "plain_ksp: type %s, %s after %" PetscInt_FMT " iterations\n", type, KSPConvergedReasons[reason], its));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&b));
  PetscCall(MatDestroy(&A));
  PetscCall(PetscFinalize());
  return 0;
}
