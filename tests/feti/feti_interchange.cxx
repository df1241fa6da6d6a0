/* Interchange round trip: the FETI problem of the test scene is solved, written with FETIWrite(),
   read back with FETILoad() into a fresh FETI object (which knows nothing of the mesh) and solved
   again: the multipliers and the primal solution agree to 1e-10 and the iteration counts differ by
   at most one. FETILoad() distributes the rows of B differently, so the products with B' sum in
   another order; at -feti_ksp_rtol 1e-12 that rounding can move the last iteration across the
   tolerance (it does with OpenBLAS's auto-detected kernels on this project's machine: 27 and 28).
   With -as_version1 the file is rewritten in format version 1 (tests/feti/fetifile.h) before it is read:
   files written before version 2 still read and give the same solution. */
#include "scene.h"
#include "fetifile.h"

static PetscErrorCode Solve(FETI feti, Vec *lambda, Vec *u, PetscInt *its)
{
  KSP ksp;

  PetscFunctionBeginUser;
  PetscCall(FETISetFromOptions(feti));
  PetscCall(FETISetUp(feti));
  PetscCall(FETICreateVecs(feti, u, lambda, NULL));
  PetscCall(FETISolveLinear(feti, *lambda, *u));
  PetscCall(FETIGetKSP(feti, &ksp));
  PetscCall(KSPGetIterationNumber(ksp, its));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  FEM         fem;
  FETI        feti, loaded;
  Vec         l1, u1, l2, u2;
  PetscInt    its1, its2, n1, n2;
  PetscReal   dl, du, nl, nu;
  PetscViewer viewer;
  char        file[PETSC_MAX_PATH_LEN] = "feti_interchange.bin", v1[PETSC_MAX_PATH_LEN + 4];
  PetscBool   asv1                     = PETSC_FALSE;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "FETI interchange round trip"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-file", file, sizeof(file), NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-as_version1", &asv1, NULL));
  PetscCall(CreateTestScene(PETSC_COMM_WORLD, &fem));
  PetscCall(FEMCreateFETI(fem, &feti));
  PetscCall(Solve(feti, &l1, &u1, &its1));
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_WRITE, &viewer));
  PetscCall(FETIWrite(feti, viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  if (asv1) {
    PetscMPIInt rank;
    PetscCall(PetscSNPrintf(v1, sizeof(v1), "%s.v1", file));
    PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
    if (rank == 0) PetscCall(FETIFileRewrite(file, v1, "v1"));
    PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
    PetscCall(PetscStrncpy(file, v1, sizeof(file)));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "reading %s (format version 1)\n", file));
  }

  PetscCall(FETICreate(PETSC_COMM_WORLD, &loaded));
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_READ, &viewer));
  PetscCall(FETILoad(loaded, viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(Solve(loaded, &l2, &u2, &its2));

  PetscCall(VecGetSize(u1, &n1));
  PetscCall(VecGetSize(u2, &n2));
  PetscCheck(n1 == n2, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "primal sizes differ: %d and %d", (int)n1, (int)n2);
  PetscCall(VecNorm(l1, NORM_2, &nl));
  PetscCall(VecNorm(u1, NORM_2, &nu));
  {
    /* FETILoad() distributes the rows of B evenly, the model by subdomain: compare the multipliers gathered */
    VecScatter s1, s2;
    Vec        a1, a2;
    PetscCall(VecScatterCreateToAll(l1, &s1, &a1));
    PetscCall(VecScatterCreateToAll(l2, &s2, &a2));
    PetscCall(VecScatterBegin(s1, l1, a1, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(s1, l1, a1, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterBegin(s2, l2, a2, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(s2, l2, a2, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecAXPY(a2, -1.0, a1));
    PetscCall(VecNorm(a2, NORM_2, &dl));
    PetscCall(VecScatterDestroy(&s1));
    PetscCall(VecScatterDestroy(&s2));
    PetscCall(VecDestroy(&a1));
    PetscCall(VecDestroy(&a2));
  }
  PetscCall(VecAXPY(u2, -1.0, u1));
  PetscCall(VecNorm(u2, NORM_2, &du));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "iterations %d and %d; relative differences: multipliers %.2e, displacements %.2e\n", (int)its1, (int)its2, (double)(dl / nl), (double)(du / nu)));
  PetscCheck(PetscAbs(its1 - its2) <= 1 && dl <= 1e-10 * nl && du <= 1e-10 * nu, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The loaded problem gives a different solution");
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "round trip gives the same solution\n"));
  PetscCall(VecDestroy(&l1));
  PetscCall(VecDestroy(&u1));
  PetscCall(VecDestroy(&l2));
  PetscCall(VecDestroy(&u2));
  PetscCall(FETIDestroy(&loaded));
  PetscCall(FETIDestroy(&feti));
  PetscCall(FEMDestroy(&fem));
  PetscCall(PetscFinalize());
  return 0;
}
