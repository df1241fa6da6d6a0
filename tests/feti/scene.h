/* The test scenes shared by the FETI tests (-scene <name>); decomposition and Dirichlet mode come from
   the options (-fem_decomposition, -fem_subdomains, -fem_dirichlet); -scene_cells <n> scales the meshes.
     twobodies  two bodies of different materials, each fixed on part of its boundary (one with a
                symmetry-plane condition on a single component), loaded by tractions and gravity
     brick      the paper's steel brick (0,3)x(0,1)x(0,1), cut into three cubes along x (use
                -fem_subdomains 3,1,1), clamped on x = 0, pressed on top: with Dirichlet kept in the
                primal only the two free cubes float (12 rigid modes), Total FETI has 18
     edge       a bar (0,2)x(0,1)x(0,1) clamped on the bottom only where x < 1 (cut at x = 1 with
                -fem_subdomains 2,1,1): the second subdomain touches the clamped part along one
                edge and keeps exactly one rigid mode, the rotation about that edge */
#pragma once
#include <conefeti.h>
#include <conefeti/compat.h>
#include <string.h>

static PetscErrorCode Gravity(const PetscReal x[3], PetscReal f[3], void *ctx)
{
  (void)x;
  (void)ctx;
  f[0] = 0;
  f[1] = 0;
  f[2] = -7850 * 9.81;
  return PETSC_SUCCESS;
}

static PetscErrorCode LeftHalf(const PetscReal c[3], const PetscReal n[3], PetscBool *tagged, void *ctx)
{
  (void)ctx;
  *tagged = (c[0] < 1.0 && n[2] < -0.5) ? PETSC_TRUE : PETSC_FALSE;
  return PETSC_SUCCESS;
}

static PetscErrorCode CreateBrickOrEdge(MPI_Comm comm, PetscBool brick, FEM *fem)
{
  PetscReal lo[3] = {0, 0, 0}, hi[3] = {brick ? 3.0 : 2.0, 1, 1}, top[3] = {0, 0, -1e7}, side[3] = {1e6, 0, 0};
  PetscInt  n = 4, c[3], b;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-scene_cells", &n, NULL));
  c[0] = (brick ? 3 : 2) * n;
  c[1] = c[2] = n;
  PetscCall(FEMCreate(comm, fem));
  PetscCall(FEMAddBox(*fem, lo, hi, c, &b));
  PetscCall(FEMSetMaterial(*fem, b, 21.2e10, 0.277));
  if (brick) PetscCall(FEMSetDirichlet(*fem, b, "x0", NULL));
  else {
    PetscCall(FEMTagFaces(*fem, b, "clamp", LeftHalf, NULL));
    PetscCall(FEMSetDirichlet(*fem, b, "clamp", NULL));
  }
  PetscCall(FEMSetTraction(*fem, b, "z1", top));
  PetscCall(FEMSetTraction(*fem, b, "x1", side));
  PetscCall(FEMSetFromOptions(*fem));
  PetscCall(FEMSetUp(*fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CreateTestScene(MPI_Comm comm, FEM *fem)
{
  char      scene[32] = "twobodies";
  PetscReal lo0[3] = {0, 0, 0}, hi0[3] = {2, 1, 1}, lo1[3] = {0, 0, 1.5}, hi1[3] = {1, 1, 2.5};
  PetscReal t0[3] = {0, 2e5, -1e6}, t1[3] = {3e5, 0, -2e5};
  PetscInt  n        = 4, c0[3], c1[3], b0, b1;
  PetscBool xonly[3] = {PETSC_TRUE, PETSC_FALSE, PETSC_FALSE};

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetString(NULL, NULL, "-scene", scene, sizeof(scene), NULL));
  if (!strcmp(scene, "brick") || !strcmp(scene, "edge")) {
    PetscCall(CreateBrickOrEdge(comm, strcmp(scene, "brick") ? PETSC_FALSE : PETSC_TRUE, fem));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCheck(!strcmp(scene, "twobodies"), comm, PETSC_ERR_ARG_WRONG, "-scene %s: use twobodies, brick or edge", scene);
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
