/* Prescribed displacements (FEMSetDisplacement()): a bar [0,1]x[0,1]x[0,L] with nu = 0, clamped at z = 0 and its top
   moved by (0, 0, -delta). The exact solution u = (0, 0, -delta z / L) is linear, so P1 reproduces it: FETI's u must
   equal the prescribed value on the top, the direct solve of the lifted global system (FEMAssembleGlobal()) everywhere,
   and the reactions (FEMComputeReactions()) must be -E A delta / L on the top and +E A delta / L on the bottom, in
   whichever mode -fem_dirichlet (and -fem_dirichlet_min_hold) chooses. The RESULT line lets runs in the two modes
   and on several ranks be compared. */
#include <conefeti.h>
#include <conefeti/compat.h>
#include "femsolve.h"

int main(int argc, char **argv)
{
  FEM                fem;
  FETI               feti;
  Vec                lambda, u, uglobal, ref[3], ug;
  PetscReal          lo[3] = {0, 0, 0}, hi[3] = {1, 1, 2}, E = 1e9, delta = 0.01, value[3] = {0, 0, -delta}, reaction[6];
  PetscInt           cells[3] = {2, 2, 4}, body, n;
  PetscMPIInt        rank;
  const PetscScalar *a, *r;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "prescribed displacement of a bar"));
  PetscCall(ConeFETIInitializePackage());
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
  PetscCall(FEMAddBox(fem, lo, hi, cells, &body));
  PetscCall(FEMSetMaterial(fem, body, E, 0.0));
  PetscCall(FEMSetDirichlet(fem, body, "z0", NULL));
  PetscCall(FEMSetDisplacement(fem, body, "z1", NULL, value));
  PetscCall(FEMSetFromOptions(fem));
  PetscCall(FEMSetUp(fem));
  PetscCall(FEMCreateFETI(fem, &feti));
  PetscCall(FETISetFromOptions(feti));
  PetscCall(FETISetUp(feti));
  PetscCall(FETICreateVecs(feti, &u, &lambda, NULL));
  PetscCall(FETISolveLinear(feti, lambda, u));

  /* FETI's u against the exact linear field, node by node, and against the lifted direct solve */
  PetscCall(FEMTestSolveGathered(fem, ref));
  PetscCall(VecDuplicate(ref[2], &ug));
  {
    Mat K;
    Vec f;
    PetscCall(FEMAssembleGlobal(fem, &K, &f));
    PetscCall(VecDuplicate(f, &uglobal));
    PetscCall(FEMPrimalToGlobal(fem, u, uglobal));
    PetscCall(VecDestroy(&f));
    PetscCall(MatDestroy(&K));
  }
  {
    VecScatter sc;
    Vec        g;
    PetscCall(VecScatterCreateToZero(uglobal, &sc, &g));
    PetscCall(VecScatterBegin(sc, uglobal, g, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sc, uglobal, g, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterDestroy(&sc));
    PetscCall(VecCopy(g, ug));
    PetscCall(VecDestroy(&g));
  }
  if (rank == 0) {
    PetscInt         nn;
    const PetscReal *X;
    PetscReal        top = 0, exact = 0, direct = 0;
    PetscCall(FEMGetBodyNodes(fem, body, &nn, &X));
    PetscCall(VecGetSize(ug, &n));
    PetscCall(VecGetArrayRead(ug, &a));
    PetscCall(VecGetArrayRead(ref[2], &r));
    for (PetscInt i = 0; i < nn; i++) {
      const PetscReal z = X[3 * i + 2];
      for (PetscInt c = 0; c < 3; c++) {
        const PetscReal ue = c == 2 ? -delta * z / hi[2] : 0.0;
        exact              = PetscMax(exact, PetscAbsReal(PetscRealPart(a[3 * i + c]) - ue));
        direct             = PetscMax(direct, PetscAbsReal(PetscRealPart(a[3 * i + c] - r[3 * i + c])));
        if (z == hi[2]) top = PetscMax(top, PetscAbsReal(PetscRealPart(a[3 * i + c]) - value[c]));
      }
    }
    PetscCall(VecRestoreArrayRead(ug, &a));
    PetscCall(VecRestoreArrayRead(ref[2], &r));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "max |u - u_D| on the top %.1e, |u - exact| %.1e, |u - direct solve| %.1e (delta %g)\n", (double)top, (double)exact, (double)direct, (double)delta));
    PetscCheck(top <= 1e-9 * delta && exact <= 1e-7 * delta && direct <= 1e-7 * delta, PETSC_COMM_SELF, PETSC_ERR_PLIB, "prescribed displacement check failed");
  }

  /* reactions: E A delta / L, up on the clamped bottom, down on the displaced top */
  {
    const PetscReal P = E * 1.0 * delta / hi[2];
    PetscInt        nd;
    PetscCall(FEMGetNumDirichlet(fem, body, &nd));
    PetscCheck(nd == 2, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%" PetscInt_FMT " Dirichlet conditions, expected 2", nd);
    PetscCall(FEMComputeReactions(fem, feti, u, lambda, reaction));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "reaction bottom (%g, %g, %g), top (%g, %g, %g), E A delta / L = %g\n", (double)reaction[0], (double)reaction[1], (double)reaction[2], (double)reaction[3],
                          (double)reaction[4], (double)reaction[5], (double)P));
    PetscCheck(PetscAbsReal(reaction[2] - P) <= 1e-8 * P && PetscAbsReal(reaction[5] + P) <= 1e-8 * P, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the reactions are not E A delta / L");
    for (PetscInt c = 0; c < 2; c++) PetscCheck(PetscAbsReal(reaction[c]) <= 1e-8 * P && PetscAbsReal(reaction[3 + c]) <= 1e-8 * P, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "a lateral reaction");
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "RESULT bottom=%.6e top=%.6e\n", (double)reaction[2], (double)reaction[5]));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "prescribed displacement check passed\n"));
  for (int i = 0; i < 3; i++) PetscCall(VecDestroy(&ref[i]));
  PetscCall(VecDestroy(&ug));
  PetscCall(VecDestroy(&uglobal));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&lambda));
  PetscCall(FETIDestroy(&feti));
  PetscCall(FEMDestroy(&fem));
  PetscCall(PetscFinalize());
  return 0;
}
