/* Convergence check against a smooth manufactured solution on the unit cube, clamped on all faces:
     u*(x) = a phi(x),  phi = sin(pi x) sin(pi y) sin(pi z),  a = (1, -0.5, 0.25) * 1e-3,
   with the body force f = -div sigma(u*) = -[(lambda + mu) H(phi) a + mu a Laplace(phi)].
   P1 elements converge at order 2 in L2; the discrete L2 error of the nodal values is measured on
   meshes with 6, 12, 24 cells per side and the observed order must exceed 1.8. */
#include <conefeti.h>
#include <conefeti/compat.h>
#include <math.h>

static const PetscReal E = 1.0e9, nu = 0.3, amp[3] = {1e-3, -0.5e-3, 0.25e-3};

static PetscErrorCode BodyForce(const PetscReal x[3], PetscReal f[3], void *ctx)
{
  const PetscReal lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu)), pi = PETSC_PI;
  PetscReal       s[3], c[3], H[3][3], phi;

  (void)ctx;
  for (int d = 0; d < 3; d++) {
    s[d] = sin(pi * x[d]);
    c[d] = cos(pi * x[d]);
  }
  phi = s[0] * s[1] * s[2];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      if (i == j) H[i][j] = -pi * pi * phi;
      else {
        const int k = 3 - i - j;
        H[i][j]     = pi * pi * c[i] * c[j] * s[k];
      }
    }
  for (int i = 0; i < 3; i++) {
    PetscReal Ha = 0;
    for (int j = 0; j < 3; j++) Ha += H[i][j] * amp[j];
    f[i] = -((lambda + mu) * Ha + mu * amp[i] * (-3 * pi * pi * phi));
  }
  return PETSC_SUCCESS;
}

static PetscErrorCode SolveError(PetscInt n, PetscReal *err)
{
  FEM                fem;
  Mat                K;
  Vec                f, u, coords;
  KSP                ksp;
  PC                 pc;
  PetscReal          lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, sum = 0;
  PetscInt           cells[3] = {n, n, n}, body, nloc;
  const char        *faces[6] = {"x0", "x1", "y0", "y1", "z0", "z1"};
  const PetscScalar *ua, *xa;

  PetscFunctionBeginUser;
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
  PetscCall(FEMAddBox(fem, lo, hi, cells, &body));
  PetscCall(FEMSetMaterial(fem, body, E, nu));
  for (int i = 0; i < 6; i++) PetscCall(FEMSetDirichlet(fem, body, faces[i], NULL));
  PetscCall(FEMSetBodyForce(fem, body, BodyForce, NULL));
  {
    PetscMPIInt size;
    PetscInt    parts[3] = {1, 1, 1};
    PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
    parts[0] = size;
    PetscCall(FEMSetDecomposition(fem, body, FEM_DECOMPOSITION_STRUCTURED, parts));
  }
  PetscCall(FEMSetUp(fem));
  PetscCall(FEMAssembleGlobal(fem, &K, &f));
  PetscCall(FEMCreateGlobalCoordinates(fem, &coords));
  PetscCall(VecDuplicate(f, &u));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, K, K));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSolve(ksp, f, u));
  PetscCall(VecGetLocalSize(u, &nloc));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(coords, &xa));
  for (PetscInt i = 0; i < nloc; i += 3) {
    const PetscReal phi = sin(PETSC_PI * xa[i]) * sin(PETSC_PI * xa[i + 1]) * sin(PETSC_PI * xa[i + 2]);
    for (int d = 0; d < 3; d++) sum += PetscSqr(ua[i + d] - amp[d] * phi);
  }
  PetscCall(VecRestoreArrayRead(coords, &xa));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sum, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  *err = sqrt(sum / ((n + 1.0) * (n + 1.0) * (n + 1.0))); /* RMS over the nodes ~ L2 norm on the unit cube */
  PetscCall(KSPDestroy(&ksp));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&coords));
  PetscCall(MatDestroy(&K));
  PetscCall(FEMDestroy(&fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscReal err[3];
  PetscInt  n[3] = {6, 12, 24};

  PetscCall(PetscInitialize(&argc, &argv, NULL, "P1 elasticity convergence check"));
  PetscCall(ConeFETIInitializePackage());
  for (int k = 0; k < 3; k++) {
    PetscCall(SolveError(n[k], &err[k]));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "cells per side %2d: nodal L2 error %.4e%s", (int)n[k], (double)err[k], k ? "" : "\n"));
    if (k) PetscCall(PetscPrintf(PETSC_COMM_WORLD, ", observed order %.3f\n", (double)(log(err[k - 1] / err[k]) / log(2.0))));
  }
  const PetscReal order = log(err[1] / err[2]) / log(2.0);
  PetscCheck(order > 1.8, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Convergence order %g is below 1.8", (double)order);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "convergence check passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
