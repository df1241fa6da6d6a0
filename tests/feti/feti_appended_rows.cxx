/* Rows appended in body-node terms (FEMCreateFETIWithRows(), as the contact layer hands them over) reach B
   with their kind and right-hand side, and act on the right dofs: a clamped bar whose bottom face z0
   gets one row u_z = 0 per node (kinds Dirichlet and gluing in turn: FETISolveLinear() takes equalities only and
   refuses contact rows; FEMCreateFETIWithRows() passes every kind through unchanged) must give the
   same displacements as the undecomposed direct solve with u_z = 0 imposed on z0 as a Dirichlet
   condition. Also checks FETIComputeAlpha(): with a mask of all rows, and with a mask that leaves the
   appended rows out (gluing and Dirichlet rows still fix every subdomain), alpha is the same. */
#include <conefeti.h>
#include <conefeti/compat.h>

static PetscErrorCode Bar(PetscBool bottomdirichlet, FEM *fem)
{
  PetscReal lo[3] = {0, 0, 0}, hi[3] = {2, 1, 1}, t[3] = {1e6, 2e5, -3e6};
  PetscInt  cells[3] = {8, 4, 4}, b, parts[3] = {2, 2, 1};
  PetscBool zonly[3] = {PETSC_FALSE, PETSC_FALSE, PETSC_TRUE};

  PetscFunctionBeginUser;
  PetscCall(FEMCreate(PETSC_COMM_WORLD, fem));
  PetscCall(FEMAddBox(*fem, lo, hi, cells, &b));
  PetscCall(FEMSetDirichlet(*fem, b, "x0", NULL));
  if (bottomdirichlet) PetscCall(FEMSetDirichlet(*fem, b, "z0", zonly));
  PetscCall(FEMSetTraction(*fem, b, "z1", t));
  PetscCall(FEMSetDecomposition(*fem, b, FEM_DECOMPOSITION_STRUCTURED, parts));
  PetscCall(FEMSetFromOptions(*fem));
  PetscCall(FEMSetUp(*fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  FEM                fem, ref;
  FETI               feti;
  Mat                K;
  Vec                f, uref, u, ug, lambda, alpha1, alpha2, alpha3, mask, c;
  KSP                ksp;
  PC                 pc;
  PetscInt           n, nappended, rstart, rend;
  const PetscInt    *nodes;
  PetscInt          *rows;
  const FETIRowKind *kinds;
  PetscReal          err, norm, da, na;
  PetscBool          x0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Appended constraint rows"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(Bar(PETSC_FALSE, &fem));
  PetscCall(FEMGetTaggedNodes(fem, 0, "z0", &n, &nodes, NULL, NULL));
  {
    /* one row per bottom node not on the clamped face x0 (there u = 0 already): -u_z = 0 */
    const PetscReal *x;
    PetscInt         m = 0;
    PetscCall(FEMGetBodyNodes(fem, 0, NULL, &x));
    FETIRowKind *k;
    PetscInt    *ptr, *body, *node, *comp;
    PetscScalar *coef, *rhs;
    PetscCall(PetscMalloc7(n, &k, n + 1, &ptr, n, &body, n, &node, n, &comp, n, &coef, n, &rhs));
    ptr[0] = 0;
    for (PetscInt i = 0; i < n; i++) {
      x0 = x[3 * nodes[i]] == 0.0 ? PETSC_TRUE : PETSC_FALSE;
      if (x0) continue;
      k[m]       = m % 2 ? FETI_ROW_GLUING : FETI_ROW_DIRICHLET; /* two kinds: each row must keep its own */
      body[m]    = 0;
      node[m]    = nodes[i];
      comp[m]    = 2;
      coef[m]    = -1.0;
      rhs[m]     = 0.0;
      ptr[m + 1] = m + 1;
      m++;
    }
    PetscCall(PetscMalloc1(m, &rows));
    PetscCall(FEMCreateFETIWithRows(fem, m, k, ptr, body, node, comp, coef, rhs, rows, &feti));
    nappended = m;
    PetscCall(PetscFree7(k, ptr, body, node, comp, coef, rhs));
  }
  PetscCall(FETISetFromOptions(feti));
  PetscCall(FETISetUp(feti));
  /* the appended rows are in B with their kind */
  PetscCall(FETIGetConstraints(feti, NULL, &c, &kinds));
  PetscCall(VecGetOwnershipRange(c, &rstart, &rend));
  for (PetscInt i = 0; i < nappended; i++)
    if (rows[i] >= rstart && rows[i] < rend)
      PetscCheck(kinds[rows[i] - rstart] == (i % 2 ? FETI_ROW_GLUING : FETI_ROW_DIRICHLET), PETSC_COMM_SELF, PETSC_ERR_PLIB, "appended row %d has kind %s", (int)i,
                 FETIRowKinds[kinds[rows[i] - rstart]]);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%d appended rows in B\n", (int)nappended));

  PetscCall(FETICreateVecs(feti, &u, &lambda, &alpha1));
  PetscCall(VecDuplicate(alpha1, &alpha2));
  PetscCall(VecDuplicate(alpha1, &alpha3));
  PetscCall(FETISolveLinear(feti, lambda, u));

  PetscCall(Bar(PETSC_TRUE, &ref));
  PetscCall(FEMAssembleGlobal(ref, &K, &f));
  PetscCall(VecDuplicate(f, &uref));
  PetscCall(VecDuplicate(f, &ug));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, K, K));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSolve(ksp, f, uref));
  PetscCall(FEMPrimalToGlobal(fem, u, ug));
  PetscCall(VecAXPY(ug, -1.0, uref));
  PetscCall(VecNorm(ug, NORM_2, &err));
  PetscCall(VecNorm(uref, NORM_2, &norm));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "relative difference to the direct solution with u_z = 0 on z0: %.2e\n", (double)(err / norm)));
  PetscCheck(err <= 1e-8 * norm, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "appended rows do not act as the Dirichlet condition: %g", (double)(err / norm));

  /* alpha: all rows, mask of all rows, mask without the appended rows */
  PetscCall(FETIComputeAlpha(feti, lambda, NULL, alpha1));
  PetscCall(VecDuplicate(lambda, &mask));
  PetscCall(VecSet(mask, 1.0));
  PetscCall(FETIComputeAlpha(feti, lambda, mask, alpha2));
  for (PetscInt i = 0; i < nappended; i++)
    if (rows[i] >= rstart && rows[i] < rend) PetscCall(VecSetValue(mask, rows[i], 0.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(mask));
  PetscCall(VecAssemblyEnd(mask));
  PetscCall(FETIComputeAlpha(feti, lambda, mask, alpha3));
  PetscCall(VecNorm(alpha1, NORM_2, &na));
  PetscCall(VecAXPY(alpha2, -1.0, alpha1));
  PetscCall(VecNorm(alpha2, NORM_2, &da));
  PetscCheck(da <= 1e-8 * na, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "alpha with a full mask differs: %g", (double)(da / na));
  PetscCall(VecAXPY(alpha3, -1.0, alpha1));
  PetscCall(VecNorm(alpha3, NORM_2, &da));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "alpha without the appended rows differs by %.2e relative\n", (double)(da / na)));
  PetscCheck(da <= 1e-6 * na, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "alpha from a partial mask differs: %g", (double)(da / na));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "appended rows behave\n"));
  PetscCall(PetscFree(rows));

  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&K));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&uref));
  PetscCall(VecDestroy(&ug));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&lambda));
  PetscCall(VecDestroy(&alpha1));
  PetscCall(VecDestroy(&alpha2));
  PetscCall(VecDestroy(&alpha3));
  PetscCall(VecDestroy(&mask));
  PetscCall(FETIDestroy(&feti));
  PetscCall(FEMDestroy(&fem));
  PetscCall(FEMDestroy(&ref));
  PetscCall(PetscFinalize());
  return 0;
}
