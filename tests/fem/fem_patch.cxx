/* Patch test: for a linear displacement u = A x the stress is constant, so the assembled stiffness
   times the nodal values of u must equal the load of the surface tractions sigma n on the six faces,
   node by node (interior nodes: zero). Checked on a box with unequal spacings in the three directions,
   undecomposed and through the subdomain matrices of a decomposition. */
#include <conefeti.h>
#include <conefeti/compat.h>

static const PetscReal A[3][3] = {{1.0e-3, 2.0e-4, -3.0e-4}, {-1.0e-4, 5.0e-4, 2.5e-4}, {4.0e-4, -2.0e-4, -6.0e-4}};
static const PetscReal E = 2.0e11, nu = 0.3;

static void Stress(PetscReal s[3][3])
{
  const PetscReal lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const PetscReal tr = A[0][0] + A[1][1] + A[2][2];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) s[i][j] = (i == j ? lambda * tr : 0) + mu * (A[i][j] + A[j][i]);
}

int main(int argc, char **argv)
{
  FEM                fem;
  Mat                K;
  Vec                f, u, coords, r;
  PetscReal          lo[3] = {0, 0, 0}, hi[3] = {1.0, 0.5, 2.0}, s[3][3], normr, normf;
  PetscInt           cells[3] = {3, 4, 5}, body, parts[3] = {1, 2, 2};
  const char        *faces[6] = {"x0", "x1", "y0", "y1", "z0", "z1"};
  PetscScalar       *ua;
  const PetscScalar *xa;
  PetscInt           n;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "P1 elasticity patch test"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
  PetscCall(FEMAddBox(fem, lo, hi, cells, &body));
  PetscCall(FEMSetMaterial(fem, body, E, nu));
  PetscCall(FEMSetDecomposition(fem, body, FEM_DECOMPOSITION_STRUCTURED, parts));
  Stress(s);
  for (int face = 0; face < 6; face++) {
    PetscReal nrm[3] = {0, 0, 0}, t[3];
    nrm[face / 2]    = face % 2 ? 1.0 : -1.0;
    for (int i = 0; i < 3; i++) t[i] = s[i][0] * nrm[0] + s[i][1] * nrm[1] + s[i][2] * nrm[2];
    PetscCall(FEMSetTraction(fem, body, faces[face], t));
  }
  PetscCall(FEMSetFromOptions(fem));
  PetscCall(FEMSetUp(fem));
  PetscCall(FEMAssembleGlobal(fem, &K, &f));
  PetscCall(FEMCreateGlobalCoordinates(fem, &coords));
  PetscCall(VecDuplicate(f, &u));
  PetscCall(VecDuplicate(f, &r));
  PetscCall(VecGetLocalSize(u, &n));
  PetscCall(VecGetArray(u, &ua));
  PetscCall(VecGetArrayRead(coords, &xa));
  for (PetscInt i = 0; i < n; i += 3)
    for (int a = 0; a < 3; a++) ua[i + a] = A[a][0] * xa[i] + A[a][1] * xa[i + 1] + A[a][2] * xa[i + 2];
  PetscCall(VecRestoreArrayRead(coords, &xa));
  PetscCall(VecRestoreArray(u, &ua));
  PetscCall(MatMult(K, u, r));
  PetscCall(VecAXPY(r, -1.0, f));
  PetscCall(VecNorm(r, NORM_2, &normr));
  PetscCall(VecNorm(f, NORM_2, &normf));
  /* roundoff only: K has entries ~E h, u ~1e-3 */
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "patch test ||K u - f|| / ||f|| = %.3e\n", (double)(normr / normf)));
  PetscCheck(normr <= 1e-11 * normf, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Patch test failed: ||K u - f|| / ||f|| = %g", (double)(normr / normf));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "patch test passed\n"));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&coords));
  PetscCall(MatDestroy(&K));
  PetscCall(FEMDestroy(&fem));
  PetscCall(PetscFinalize());
  return 0;
}
