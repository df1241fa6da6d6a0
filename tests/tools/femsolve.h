/* A model's assembled system, for tests that compare two models of the same body node for node:
   K x for a smooth x (sin of a combination of the coordinates, nowhere symmetric), f, and u = K^-1 f by a
   tight CG, each gathered on rank 0 in the model's global node order (FEMAssembleGlobal()). */
#pragma once

#include <conefeti.h>

static inline PetscErrorCode FEMTestSolveGathered(FEM fem, Vec out[3])
{
  Mat                K;
  Vec                x, f, u, Kx, coords;
  KSP                ksp;
  const PetscScalar *c;
  PetscScalar       *a;
  PetscInt           n;

  PetscFunctionBeginUser;
  PetscCall(FEMAssembleGlobal(fem, &K, &f));
  PetscCall(MatCreateVecs(K, &x, &u));
  PetscCall(VecDuplicate(u, &Kx));
  PetscCall(FEMCreateGlobalCoordinates(fem, &coords));
  PetscCall(VecGetLocalSize(x, &n));
  PetscCall(VecGetArrayRead(coords, &c));
  PetscCall(VecGetArray(x, &a));
  for (PetscInt i = 0; i < n / 3; i++)
    for (PetscInt d = 0; d < 3; d++) a[3 * i + d] = PetscSinReal(1.3 * c[3 * i] + 0.7 * (d + 1) * c[3 * i + 1] - 0.4 * c[3 * i + 2] + d);
  PetscCall(VecRestoreArray(x, &a));
  PetscCall(VecRestoreArrayRead(coords, &c));
  PetscCall(MatMult(K, x, Kx));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, K, K));
  PetscCall(KSPSetType(ksp, KSPCG));
  PetscCall(KSPSetTolerances(ksp, 1e-13, 1e-50, PETSC_DEFAULT, 10000));
  PetscCall(KSPSolve(ksp, f, u));
  Vec in[3] = {Kx, f, u};
  for (int i = 0; i < 3; i++) {
    VecScatter sc;
    PetscCall(VecScatterCreateToZero(in[i], &sc, &out[i]));
    PetscCall(VecScatterBegin(sc, in[i], out[i], INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sc, in[i], out[i], INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterDestroy(&sc));
    PetscCall(VecDestroy(&in[i]));
  }
  PetscCall(KSPDestroy(&ksp));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&coords));
  PetscCall(MatDestroy(&K));
  PetscFunctionReturn(PETSC_SUCCESS);
}
