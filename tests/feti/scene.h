/* The test scene shared by the FETI tests: two bodies of different materials, each fixed on part of
   its boundary (one with a symmetry-plane condition on a single component), loaded by tractions and
   gravity. Decomposition and Dirichlet mode come from the options (-fem_decomposition,
   -fem_subdomains, -fem_dirichlet); -scene_cells <n> scales the meshes. */
#pragma once
#include <conefeti.h>
#include <conefeti/private/compat.h>

static PetscErrorCode Gravity(const PetscReal x[3], PetscReal f[3], void *ctx)
{
  (void)x;
  (void)ctx;
  f[0] = 0;
  f[1] = 0;
  f[2] = -7850 * 9.81;
  return PETSC_SUCCESS;
}

static PetscErrorCode CreateTestScene(MPI_Comm comm, FEM *fem)
{
  PetscReal lo0[3] = {0, 0, 0}, hi0[3] = {2, 1, 1}, lo1[3] = {0, 0, 1.5}, hi1[3] = {1, 1, 2.5};
  PetscReal t0[3] = {0, 2e5, -1e6}, t1[3] = {3e5, 0, -2e5};
  PetscInt  n        = 4, c0[3], c1[3], b0, b1;
  PetscBool xonly[3] = {PETSC_TRUE, PETSC_FALSE, PETSC_FALSE};

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-scene_cells", &n, NULL));
  c0[0] = 2 * n;
  c0[1] = n;
  c0[2] = n;
  c1[0] = c1[1] = c1[2] = n;
  PetscCall(FEMCreate(comm, fem));
  PetscCall(FEMAddBox(*fem, lo0, hi0, c0, &b0));
  PetscCall(FEMSetMaterial(*fem, b0, 2.1e11, 0.3));
  PetscCall(FEMSetDirichlet(*fem, b0, "x0", NULL));
  PetscCall(FEMSetTraction(*fem, b0, "x1", t0));
  PetscCall(FEMSetBodyForce(*fem, b0, Gravity, NULL));
  PetscCall(FEMAddBox(*fem, lo1, hi1, c1, &b1));
  PetscCall(FEMSetMaterial(*fem, b1, 7.0e10, 0.35));
  PetscCall(FEMSetDirichlet(*fem, b1, "z0", NULL));
  PetscCall(FEMSetDirichlet(*fem, b1, "x1", xonly)); /* symmetry plane: only u_x = 0 */
  PetscCall(FEMSetTraction(*fem, b1, "z1", t1));
  PetscCall(FEMSetFromOptions(*fem));
  PetscCall(FEMSetUp(*fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}
