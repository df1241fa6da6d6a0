/* FEMSetBodyForce(): a volume force density that varies linearly over a box must give, through the
   assembled load vector, the analytic resultant R = int g dV and moment M = int x x g dV about the origin.
   P1 shape functions reproduce x exactly and the 4-point rule integrates g phi_i (quadratic) exactly, so
   sum_i f_i = R and sum_i x_i x f_i = M hold to roundoff (the sum of the global load vector's components;
   FEMComputeLoadResultant() for the moment). A field that is ignored, integrated at the centroid only, or
   applied to the wrong body fails; a second body without a body force must carry no load. A box with
   unequal spacings, decomposed in subdomains (run on 2 ranks). */
#include <conefeti.h>
#include <conefeti/compat.h>

/* g(x) = g0 + gx x + gy y + gz z on the box (0,LX)x(0,LY)x(0,LZ) */
static const PetscReal G0[3] = {1.0, -2.0, -9.81}, GX[3] = {0.5, 3.0, -1.0}, GY[3] = {-2.0, 0.25, 4.0}, GZ[3] = {1.5, -1.0, 2.0};
static const PetscReal L[3] = {1.5, 0.5, 2.0};

static PetscErrorCode LinearForce(const PetscReal x[3], PetscReal g[3], void *)
{
  PetscFunctionBeginUser;
  for (int a = 0; a < 3; a++) g[a] = G0[a] + GX[a] * x[0] + GY[a] * x[1] + GZ[a] * x[2];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* int over the box of g_c(x) x_d (d = -1: of g_c alone) */
static PetscReal Integral(int c, int d)
{
  const PetscReal *gv[4] = {G0, GX, GY, GZ};
  PetscReal        sum   = 0;
  for (int j = 0; j < 4; j++) { /* the term gv[j][c] x_(j-1) (j = 0: the constant), times x_d */
    int e[3] = {0, 0, 0};
    if (j > 0) e[j - 1]++;
    if (d >= 0) e[d]++;
    PetscReal v = gv[j][c];
    for (int a = 0; a < 3; a++) v *= PetscPowReal(L[a], e[a] + 1) / (e[a] + 1);
    sum += v;
  }
  return sum;
}

int main(int argc, char **argv)
{
  FEM       fem;
  Mat       K;
  Vec       f;
  PetscReal lo[3] = {0, 0, 0}, lo2[3] = {5, 0, 0}, hi2[3] = {6, 1, 1}, R[3], M[3], sums[3], origin[3] = {0, 0, 0}, fr[3], mr[3], magnitude;
  PetscInt  cells[3] = {3, 2, 5}, cells2[3] = {1, 1, 1}, body, other, parts[3] = {2, 1, 2}, one[3] = {1, 1, 1};
  PetscReal err = 0, scale = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "FEMSetBodyForce: resultant and moment of a linear body force"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
  PetscCall(FEMAddBox(fem, lo, L, cells, &body));
  PetscCall(FEMAddBox(fem, lo2, hi2, cells2, &other));
  PetscCall(FEMSetMaterial(fem, body, 2.0e11, 0.3));
  PetscCall(FEMSetMaterial(fem, other, 2.0e11, 0.3));
  PetscCall(FEMSetDecomposition(fem, body, FEM_DECOMPOSITION_STRUCTURED, parts));
  PetscCall(FEMSetDecomposition(fem, other, FEM_DECOMPOSITION_STRUCTURED, one));
  PetscCall(FEMSetBodyForce(fem, body, LinearForce, NULL));
  PetscCall(FEMSetFromOptions(fem));
  PetscCall(FEMSetUp(fem));
  PetscCall(FEMAssembleGlobal(fem, &K, &f));

  /* analytic: R = int g, M = int x x g */
  for (int c = 0; c < 3; c++) R[c] = Integral(c, -1);
  M[0] = Integral(2, 1) - Integral(1, 2);
  M[1] = Integral(0, 2) - Integral(2, 0);
  M[2] = Integral(1, 0) - Integral(0, 1);

  /* discrete: the components of the assembled load summed directly, and the resultant and moment the FEM
     reports for each body (the second one's load magnitude must be 0) */
  {
    const PetscScalar *fa;
    PetscInt           rstart, rend;
    PetscCall(VecGetOwnershipRange(f, &rstart, &rend));
    PetscCall(VecGetArrayRead(f, &fa));
    for (PetscInt c = 0; c < 3; c++) sums[c] = 0;
    for (PetscInt i = rstart; i < rend; i++) sums[i % 3] += PetscRealPart(fa[i - rstart]); /* dofs x, y, z per node */
    PetscCall(VecRestoreArrayRead(f, &fa));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, sums, 3, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  }
  PetscCall(FEMComputeLoadResultant(fem, body, origin, fr, mr, NULL));
  PetscCall(FEMComputeLoadResultant(fem, other, origin, NULL, NULL, &magnitude));

  for (int a = 0; a < 3; a++) {
    err   = PetscMax(err, PetscMax(PetscAbsReal(sums[a] - R[a]), PetscMax(PetscAbsReal(fr[a] - R[a]), PetscAbsReal(mr[a] - M[a]))));
    scale = PetscMax(scale, PetscMax(PetscAbsReal(R[a]), PetscAbsReal(M[a])));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "force  sum f (%.12g, %.12g, %.12g), FEM (%.12g, %.12g, %.12g), analytic (%.12g, %.12g, %.12g)\n", (double)sums[0], (double)sums[1], (double)sums[2],
                        (double)fr[0], (double)fr[1], (double)fr[2], (double)R[0], (double)R[1], (double)R[2]));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "moment FEM (%.12g, %.12g, %.12g), analytic (%.12g, %.12g, %.12g)\n", (double)mr[0], (double)mr[1], (double)mr[2], (double)M[0], (double)M[1], (double)M[2]));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "max error / max |component| = %.3e; load on the body without a body force %g\n", (double)(err / scale), (double)magnitude));
  PetscCheck(err <= 1e-12 * scale, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Linear body force: resultant or moment off by %g (relative)", (double)(err / scale));
  PetscCheck(magnitude == 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The body without a body force carries a load (magnitude %g)", (double)magnitude);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "body force check passed\n"));
  PetscCall(VecDestroy(&f));
  PetscCall(MatDestroy(&K));
  PetscCall(FEMDestroy(&fem));
  PetscCall(PetscFinalize());
  return 0;
}
