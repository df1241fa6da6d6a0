/* FEMSetTractionField(): a traction that varies linearly over a face (as a user's code would give, e.g. a
   hydrostatic-like pressure) must give, through the assembled load vector, the analytic resultant
   R = int t dA and moment M = int x x t dA about the origin. P1 shape functions reproduce x exactly, so
   sum_i f_i = R and sum_i x_i x f_i = M hold to roundoff when the rule integrates t phi_i (quadratic)
   exactly, as the edge-midpoint rule does. A one-point (centroid) rule still gets R right but not M, and a
   field that is ignored gets neither: the test fails on both. Checked on the face x = 1 of a box with
   unequal spacings, undecomposed and decomposed, on 1 and 2 ranks. */
#include <conefeti.h>
#include <conefeti/compat.h>

/* t(x) = t0 + ty y + tz z on the face x = 1 */
static const PetscReal T0[3] = {2.0, -1.0, 0.5}, TY[3] = {3.0, 0.25, -4.0}, TZ[3] = {-1.5, 2.0, 1.0};
static const PetscReal LY = 0.5, LZ = 2.0;

static PetscErrorCode LinearTraction(const PetscReal x[3], PetscReal t[3], void *)
{
  PetscFunctionBeginUser;
  for (int a = 0; a < 3; a++) t[a] = T0[a] + TY[a] * x[1] + TZ[a] * x[2];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* int_0^LY int_0^LZ y^p z^q dz dy */
static PetscReal Monomial(int p, int q) { return PetscPowReal(LY, p + 1) / (p + 1) * PetscPowReal(LZ, q + 1) / (q + 1); }

static void Cross(const PetscReal a[3], const PetscReal b[3], PetscReal c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

int main(int argc, char **argv)
{
  FEM                fem;
  Mat                K;
  Vec                f, coords;
  PetscReal          lo[3] = {0, 0, 0}, hi[3] = {1.0, LY, LZ}, R[3] = {0, 0, 0}, M[3] = {0, 0, 0}, sums[6] = {0, 0, 0, 0, 0, 0};
  PetscInt           cells[3] = {3, 4, 5}, body, parts[3] = {1, 2, 2}, n;
  const PetscScalar *fa, *xa;
  PetscReal          err = 0, scale = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "FEMSetTractionField: resultant and moment of a linear traction"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
  PetscCall(FEMAddBox(fem, lo, hi, cells, &body));
  PetscCall(FEMSetMaterial(fem, body, 2.0e11, 0.3));
  PetscCall(FEMSetDecomposition(fem, body, FEM_DECOMPOSITION_STRUCTURED, parts));
  PetscCall(FEMSetTractionField(fem, body, "x1", LinearTraction, NULL));
  PetscCall(FEMSetFromOptions(fem));
  PetscCall(FEMSetUp(fem));
  PetscCall(FEMAssembleGlobal(fem, &K, &f));
  PetscCall(FEMCreateGlobalCoordinates(fem, &coords));

  /* analytic: p = (1, y, z) = e_x + e_y y + e_z z on the face, t = T0 + TY y + TZ z */
  {
    const PetscReal *tv[3]    = {T0, TY, TZ};
    const PetscReal  pv[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int        py[3] = {0, 1, 0}, pz[3] = {0, 0, 1};
    for (int j = 0; j < 3; j++)
      for (int a = 0; a < 3; a++) R[a] += tv[j][a] * Monomial(py[j], pz[j]);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        PetscReal c[3];
        Cross(pv[i], tv[j], c);
        for (int a = 0; a < 3; a++) M[a] += c[a] * Monomial(py[i] + py[j], pz[i] + pz[j]);
      }
  }

  /* discrete: sum_i f_i and sum_i x_i x f_i over the owned nodes, then over the ranks */
  PetscCall(VecGetLocalSize(f, &n));
  PetscCall(VecGetArrayRead(f, &fa));
  PetscCall(VecGetArrayRead(coords, &xa));
  for (PetscInt i = 0; i < n; i += 3) {
    PetscReal x[3] = {PetscRealPart(xa[i]), PetscRealPart(xa[i + 1]), PetscRealPart(xa[i + 2])}, fi[3] = {PetscRealPart(fa[i]), PetscRealPart(fa[i + 1]), PetscRealPart(fa[i + 2])}, c[3];
    Cross(x, fi, c);
    for (int a = 0; a < 3; a++) {
      sums[a] += fi[a];
      sums[3 + a] += c[a];
    }
  }
  PetscCall(VecRestoreArrayRead(coords, &xa));
  PetscCall(VecRestoreArrayRead(f, &fa));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sums, 6, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));

  for (int a = 0; a < 3; a++) {
    err   = PetscMax(err, PetscMax(PetscAbsReal(sums[a] - R[a]), PetscAbsReal(sums[3 + a] - M[a])));
    scale = PetscMax(scale, PetscMax(PetscAbsReal(R[a]), PetscAbsReal(M[a])));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "resultant  FE (%.12g, %.12g, %.12g) analytic (%.12g, %.12g, %.12g)\n", (double)sums[0], (double)sums[1], (double)sums[2], (double)R[0], (double)R[1],
                        (double)R[2]));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "moment     FE (%.12g, %.12g, %.12g) analytic (%.12g, %.12g, %.12g)\n", (double)sums[3], (double)sums[4], (double)sums[5], (double)M[0], (double)M[1],
                        (double)M[2]));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "max error / max |component| = %.3e\n", (double)(err / scale)));
  PetscCheck(err <= 1e-12 * scale, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Linear traction field: resultant or moment off by %g (relative)", (double)(err / scale));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "traction field check passed\n"));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&coords));
  PetscCall(MatDestroy(&K));
  PetscCall(FEMDestroy(&fem));
  PetscCall(PetscFinalize());
  return 0;
}
