/* FEMComputeFreeRigidMotions(): the rigid motions of a box that its Dirichlet conditions and the given rows leave
   free. Clamped on one face: none; rollers (z fixed) under it: the slides along x and y and the turn about z, as
   unit coordinates of the echelon basis; no support: all 6; rollers and two rows at one node: the turn about z
   through that node; two boxes that nothing supports, three z rows between them: 12 - 3 (their relative lift and
   tilts are held). The same on any number of ranks. */
#include <conefeti.h>
#include <cmath>

static PetscErrorCode Box(PetscInt fix, const PetscBool components[3], FEM *fem)
{
  PetscReal lo[3] = {0, 0, 0}, hi[3] = {2.0, 1.0, 1.0};
  PetscInt  cells[3] = {4, 2, 2}, parts[3] = {2, 1, 1}, body;

  PetscFunctionBegin;
  PetscCall(FEMCreate(PETSC_COMM_WORLD, fem));
  PetscCall(FEMAddBox(*fem, lo, hi, cells, &body));
  PetscCall(FEMSetMaterial(*fem, body, 1.0, 0.3));
  PetscCall(FEMSetDecomposition(*fem, body, FEM_DECOMPOSITION_STRUCTURED, parts));
  if (fix >= 0) PetscCall(FEMSetDirichlet(*fem, body, fix == 0 ? "x0" : "z0", components));
  PetscCall(FEMSetFromOptions(*fem));
  PetscCall(FEMSetUp(*fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the motions are exactly these unit coordinates, in this order */
static PetscErrorCode CheckUnit(const char *name, PetscInt nfree, const PetscReal *motions, PetscInt nexpect, const PetscInt unit[])
{
  PetscFunctionBegin;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: %" PetscInt_FMT " free rigid motions\n", name, nfree));
  PetscCheck(nfree == nexpect, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%s: %" PetscInt_FMT " free rigid motions, expected %" PetscInt_FMT, name, nfree, nexpect);
  for (PetscInt j = 0; j < nfree; j++)
    for (PetscInt q = 0; q < 6; q++)
      PetscCheck(motions[6 * j + q] == (q == unit[j] ? 1 : 0), PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%s: motion %" PetscInt_FMT " coordinate %" PetscInt_FMT " is %g, expected %d", name, j, q,
                 (double)motions[6 * j + q], q == unit[j] ? 1 : 0);
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  FEM             fem;
  PetscInt        nfree;
  PetscReal      *motions;
  const PetscBool all[3] = {PETSC_TRUE, PETSC_TRUE, PETSC_TRUE}, rollers[3] = {PETSC_FALSE, PETSC_FALSE, PETSC_TRUE};

  PetscCall(PetscInitialize(&argc, &argv, NULL, "free rigid motions of a box"));
  PetscCall(ConeFETIInitializePackage());

  /* clamped on x = 0 */
  PetscCall(Box(0, all, &fem));
  PetscCall(FEMComputeFreeRigidMotions(fem, 0, NULL, &nfree, &motions));
  PetscCall(CheckUnit("clamped", nfree, motions, 0, NULL));
  PetscCheck(!motions, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "clamped: motions given for no free motion");
  PetscCall(FEMDestroy(&fem));

  /* rollers under it: slide along x, slide along y, turn about z */
  {
    const PetscInt unit[3] = {0, 1, 5};
    PetscCall(Box(1, rollers, &fem));
    PetscCall(FEMComputeFreeRigidMotions(fem, 0, NULL, &nfree, NULL));
    PetscCheck(nfree == 3, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "rollers: %" PetscInt_FMT " free rigid motions counted without the motions, expected 3", nfree);
    PetscCall(FEMComputeFreeRigidMotions(fem, 0, NULL, &nfree, &motions));
    PetscCall(CheckUnit("rollers", nfree, motions, 3, unit));
    PetscCall(PetscFree(motions));
  }

  /* the rollers and two rows at node p = (2, 0, 1) (a corner of the top face) along x and y: only the turn about
     the vertical axis through p is left, which does not move p */
  {
    const PetscInt      p = 4 + 5 * (0 + 3 * 2);
    const PetscReal    *X;
    PetscReal           c[3], L, u[3];
    const FEMHoldingRow rows[2] = {{0, p, -1, 0, {0, 0, 0}, {0, 0, 0}, {1, 0, 0}}, {0, p, -1, 0, {0, 0, 0}, {0, 0, 0}, {0, 1, 0}}};
    PetscCall(FEMComputeFreeRigidMotions(fem, 2, rows, &nfree, &motions));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "rollers and two rows: %" PetscInt_FMT " free rigid motions\n", nfree));
    PetscCheck(nfree == 1, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "rollers and two rows: %" PetscInt_FMT " free rigid motions, expected 1", nfree);
    PetscCheck(motions[5] != 0 && motions[2] == 0 && motions[3] == 0 && motions[4] == 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "rollers and two rows: not a turn about z");
    PetscCall(FEMGetBodyNodes(fem, 0, NULL, &X));
    PetscCall(FEMComputeRigidMotionFrame(fem, 0, c, &L));
    PetscCheck(std::fabs(c[0] - 1) < 1e-14 && std::fabs(c[1] - 0.5) < 1e-14 && std::fabs(c[2] - 0.5) < 1e-14 && std::fabs(L - std::sqrt(1.5)) < 1e-14, PETSC_COMM_WORLD, PETSC_ERR_PLIB,
               "frame: centroid (%g, %g, %g), radius %g", (double)c[0], (double)c[1], (double)c[2], (double)L);
    PetscCheck(X[3 * p] == 2 && X[3 * p + 1] == 0 && X[3 * p + 2] == 1, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "node %" PetscInt_FMT " is not (2, 0, 1)", p);
    /* u(p) = t + w x (p - c), w = (0, 0, motions[5] / L) */
    u[0] = motions[0] - motions[5] / L * (X[3 * p + 1] - c[1]);
    u[1] = motions[1] + motions[5] / L * (X[3 * p] - c[0]);
    u[2] = motions[2];
    PetscCheck(std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) < 1e-12, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "rollers and two rows: the motion moves the held node by (%g, %g, %g)", (double)u[0],
               (double)u[1], (double)u[2]);
    PetscCall(PetscFree(motions));
    PetscCall(FEMDestroy(&fem));
  }

  /* no support */
  {
    const PetscInt unit[6] = {0, 1, 2, 3, 4, 5};
    PetscCall(Box(-1, all, &fem));
    PetscCall(FEMComputeFreeRigidMotions(fem, 0, NULL, &nfree, &motions));
    PetscCall(CheckUnit("no support", nfree, motions, 6, unit));
    PetscCall(PetscFree(motions));
    PetscCall(FEMDestroy(&fem));
  }

  /* two unsupported boxes, the second on top of the first, three z rows between their touching faces: the
     rows hold the relative lift and the relative tilts about x and y */
  {
    PetscReal lo0[3] = {0, 0, 0}, hi0[3] = {1, 1, 1}, lo1[3] = {0, 0, 1}, hi1[3] = {1, 1, 2};
    PetscInt  cells[3] = {2, 2, 2}, b0, b1;
    /* box node (i, j, k) = i + 3 (j + 3 k): top of body 0 (k = 2) under the bottom of body 1 (k = 0) */
    const FEMHoldingRow rows[3] = {{1, 0, 0, 1, {18, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {1, 2, 0, 1, {20, 0, 0}, {1, 0, 0}, {0, 0, 1}}, {1, 6, 0, 1, {24, 0, 0}, {1, 0, 0}, {0, 0, 1}}};
    PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
    PetscCall(FEMAddBox(fem, lo0, hi0, cells, &b0));
    PetscCall(FEMAddBox(fem, lo1, hi1, cells, &b1));
    PetscCall(FEMSetFromOptions(fem));
    PetscCall(FEMSetUp(fem));
    PetscCall(FEMComputeFreeRigidMotions(fem, 0, NULL, &nfree, NULL));
    PetscCheck(nfree == 12, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "two boxes: %" PetscInt_FMT " free rigid motions without rows, expected 12", nfree);
    PetscCall(FEMComputeFreeRigidMotions(fem, 3, rows, &nfree, &motions));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "two boxes and three rows between them: %" PetscInt_FMT " free rigid motions\n", nfree));
    PetscCheck(nfree == 9, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "two boxes and three rows: %" PetscInt_FMT " free rigid motions, expected 9", nfree);
    /* the lift of both together is free: some motion moves both boxes along z */
    {
      PetscBool lift = PETSC_FALSE;
      for (PetscInt j = 0; j < nfree; j++)
        if (motions[12 * j + 2] != 0 && std::fabs(motions[12 * j + 6 + 2] - motions[12 * j + 2]) < 1e-12) lift = PETSC_TRUE;
      PetscCheck(lift, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "two boxes and three rows: no motion lifts both together");
    }
    PetscCall(PetscFree(motions));
    PetscCall(FEMDestroy(&fem));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "free rigid motions check passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
