/* Bad input must stop with a clear PETSc error that names the problem, never a crash or NaN.
   -case <name> selects one mistake; the program ends with PETSc's error report, whose message a test
   checks (conefeti_error_test); a case that does not fail ends with status 0 and fails the test. */
#include "scene.h"

/* One subdomain per rank: the body's subdomain 0 local K, f, and the FETI as FEMCreateFETI() makes it */
static PetscErrorCode Scene(FEM *fem, FETI *feti)
{
  PetscFunctionBeginUser;
  PetscCall(CreateTestScene(PETSC_COMM_WORLD, fem));
  PetscCall(FEMCreateFETI(*fem, feti));
  PetscCall(FETISetFromOptions(*feti));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Coordinates (3 per node) of local subdomain 0, optionally in a wrong node order */
static PetscErrorCode SubdomainCoordinates(FEM fem, PetscBool reversed, Vec *coords)
{
  PetscInt         body, nn;
  const PetscInt  *nodes;
  const PetscReal *x;
  PetscScalar     *a;

  PetscFunctionBeginUser;
  PetscCall(FEMGetSubdomainMesh(fem, 0, &body, &nn, &nodes, NULL, NULL));
  PetscCall(FEMGetBodyNodes(fem, body, NULL, &x));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * nn, coords));
  PetscCall(VecGetArray(*coords, &a));
  for (PetscInt l = 0; l < nn; l++)
    for (PetscInt d = 0; d < 3; d++) a[3 * l + d] = x[3 * nodes[reversed ? (l + 1) % nn : l] + d]; /* shifted by one node */
  PetscCall(VecRestoreArray(*coords, &a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RunCase(const char *name)
{
  FEM  fem  = NULL;
  FETI feti = NULL;

  PetscFunctionBeginUser;
  if (!strcmp(name, "wrong_block_size") || !strcmp(name, "not_square")) {
    Mat      K;
    PetscInt m = 6, n = !strcmp(name, "not_square") ? 9 : 6;
    PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, m, n, 1, NULL, &K));
    if (m == n) PetscCall(MatSetBlockSize(K, 1));
    else PetscCall(MatSetBlockSizes(K, 3, 3));
    PetscCall(MatAssemblyBegin(K, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(K, MAT_FINAL_ASSEMBLY));
    PetscCall(FETICreate(PETSC_COMM_WORLD, &feti));
    PetscCall(FETISetSubdomains(feti, 1, &K, NULL));
  } else if (!strcmp(name, "B_wrong_columns")) {
    Mat         B;
    FETIRowKind kind = FETI_ROW_GLUING;
    PetscInt    nprimal;
    PetscCall(Scene(&fem, &feti));
    PetscCall(FETIGetConstraints(feti, &B, NULL, NULL));
    PetscCall(MatGetSize(B, NULL, &nprimal));
    PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, 1, nprimal + 3, 1, NULL, 1, NULL, &B));
    PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
    {
      PetscInt m;
      PetscCall(MatGetLocalSize(B, &m, NULL));
      PetscCall(FETISetConstraints(feti, B, NULL, m ? &kind : NULL));
    }
    PetscCall(FETISetUp(feti));
  } else if (!strcmp(name, "kernel_missing_a_mode") || !strcmp(name, "coordinates_do_not_match")) {
    Vec coords;
    PetscCall(Scene(&fem, &feti));
    PetscCall(SubdomainCoordinates(fem, strcmp(name, "coordinates_do_not_match") ? PETSC_FALSE : PETSC_TRUE, &coords));
    if (!strcmp(name, "kernel_missing_a_mode")) {
      /* translations x, y, z and two of the three rotations: K_s still has the third rotation */
      Mat                R;
      PetscInt           n;
      const PetscScalar *x;
      PetscCall(VecGetSize(coords, &n));
      PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, 5, NULL, &R));
      PetscCall(VecGetArrayRead(coords, &x));
      for (PetscInt i = 0; i < n / 3; i++) {
        for (PetscInt d = 0; d < 3; d++) PetscCall(MatSetValue(R, 3 * i + d, d, 1.0, INSERT_VALUES));
        PetscCall(MatSetValue(R, 3 * i + 0, 3, -x[3 * i + 1], INSERT_VALUES));
        PetscCall(MatSetValue(R, 3 * i + 1, 3, x[3 * i + 0], INSERT_VALUES));
        PetscCall(MatSetValue(R, 3 * i + 1, 4, -x[3 * i + 2], INSERT_VALUES));
        PetscCall(MatSetValue(R, 3 * i + 2, 4, x[3 * i + 1], INSERT_VALUES));
      }
      PetscCall(VecRestoreArrayRead(coords, &x));
      PetscCall(MatAssemblyBegin(R, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(R, MAT_FINAL_ASSEMBLY));
      PetscCall(FETISetSubdomainKernel(feti, 0, R));
    } else PetscCall(FETISetSubdomainCoordinates(feti, 0, coords));
    PetscCall(FETISetUp(feti));
  } else if (!strcmp(name, "prefixed_fem")) { /* the same for the FEM's options */
    PetscReal lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    PetscInt  c[3] = {2, 2, 2};
    PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
    PetscCall(FEMSetOptionsPrefix(fem, "my_"));
    PetscCall(FEMAddBox(fem, lo, hi, c, NULL));
    PetscCall(FEMSetFromOptions(fem));
  } else if (!strcmp(name, "prefixed")) { /* a bad value of a prefixed option: the error names the option as given */
    PetscCall(CreateTestScene(PETSC_COMM_WORLD, &fem));
    PetscCall(FEMCreateFETI(fem, &feti));
    PetscCall(FETISetOptionsPrefix(feti, "my_"));
    PetscCall(FETISetFromOptions(feti));
  } else if (!strcmp(name, "setup")) { /* a valid scene: the options on the command line are the mistake */
    PetscCall(Scene(&fem, &feti));
    PetscCall(FETISetUp(feti));
  } else if (!strcmp(name, "fewer_subdomains_than_ranks") || !strcmp(name, "bad_option")) {
    PetscCall(CreateTestScene(PETSC_COMM_WORLD, &fem));
  } else if (!strcmp(name, "body_without_dirichlet")) {
    PetscReal lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    PetscInt  c[3] = {2, 2, 2}, b, parts[3] = {2, 1, 1};
    PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
    PetscCall(FEMAddBox(fem, lo, hi, c, &b));
    PetscCall(FEMSetDecomposition(fem, b, FEM_DECOMPOSITION_STRUCTURED, parts));
    PetscCall(FEMSetUp(fem));
    PetscCall(FEMCreateFETI(fem, &feti));
    PetscCall(FETISetFromOptions(feti));
    PetscCall(FETISetUp(feti));
  } else if (!strcmp(name, "huge_box") || !strcmp(name, "bodies_too_large")) {
    /* meshes too large for PetscInt indices: one huge box (its counts overflow even 64-bit integers), or three
       boxes that fit alone (2.1e9 tetrahedra, 1.06e9 unknowns each) but not together */
    const PetscReal lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    const PetscInt  huge[3] = {2000000000, 2000000000, 2000000000}, big[3] = {1000, 1000, 350};
    PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
    if (!strcmp(name, "huge_box")) PetscCall(FEMAddBox(fem, lo, hi, huge, NULL));
    else
      for (int b = 0; b < 3; b++) PetscCall(FEMAddBox(fem, lo, hi, big, NULL));
  } else if (!strcmp(name, "recover_primal_dual_u") || !strcmp(name, "apply_k_dual_x") || !strcmp(name, "alpha_primal")) {
    /* vectors of the wrong space: FETIRecoverPrimal() wrote K+(f - B'l) past the end of a short u before it said so,
       FETIApplyK() read past a short x and returned success */
    Vec u, lambda, alpha;
    PetscCall(Scene(&fem, &feti));
    PetscCall(FETISetUp(feti));
    PetscCall(FETICreateVecs(feti, &u, &lambda, &alpha));
    if (!strcmp(name, "recover_primal_dual_u")) PetscCall(FETIRecoverPrimal(feti, lambda, NULL, lambda));
    else if (!strcmp(name, "apply_k_dual_x")) PetscCall(FETIApplyK(feti, lambda, u));
    else PetscCall(FETIComputeAlpha(feti, lambda, NULL, u));
  } else if (!strcmp(name, "operator_after_destroy")) {
    /* a caller's reference to F outlives the FETI object: the product is an error, not a read of freed memory */
    Mat F;
    Vec u, lambda, alpha, y;
    PetscCall(Scene(&fem, &feti));
    PetscCall(FETISetUp(feti));
    PetscCall(FETICreateVecs(feti, &u, &lambda, &alpha));
    PetscCall(FETIGetOperators(feti, &F, NULL, NULL, NULL));
    PetscCall(PetscObjectReference((PetscObject)F));
    PetscCall(FETIDestroy(&feti));
    PetscCall(VecDuplicate(lambda, &y));
    PetscCall(MatMult(F, lambda, y));
  } else SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "unknown -case %s", name);
  PetscCall(FETIDestroy(&feti));
  PetscCall(FEMDestroy(&fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char name[64] = "";

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Bad input gives clear errors"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", name, sizeof(name), NULL));
  PetscCall(RunCase(name)); /* the error ends the program here */
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "case %s: the bad input was accepted\n", name));
  PetscCall(PetscFinalize());
  return 0;
}
