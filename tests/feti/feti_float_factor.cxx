/* The float copy of PETSc's block Cholesky factor (src/feti/fetifloatfactor.cxx, compiled into this program: its
   functions are internal to the library) solves as MatSolve() with the double factor does, up to the rounding of
   the factor to float: on random sparse SPD matrices with 3x3 blocks and moderate condition numbers the relative
   difference must stay below -tol (default 1e-6; cond * 6e-8 is below it here), must not be zero (the copy really is
   float), and the copy must take less than 0.6 times the double factor's memory. Prints "float solve agrees". */
#include <conefeti/private/fetiimpl.h>

#include <algorithm>
#include <ctime>
#include <vector>

/* A random symmetric block matrix on nb nodes: each node coupled to its successor and to a few random nodes by
   random 3x3 blocks; the diagonal blocks make it strictly diagonally dominant by a margin, so it is SPD with a
   condition number of some tens to hundreds */
static PetscErrorCode RandomSPD(PetscRandom rnd, PetscInt nb, Mat *A)
{
  std::vector<std::vector<PetscInt>> nbrs(nb);
  std::vector<PetscReal>             rowsum(3 * nb, 0.0);

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i + 1 < nb; i++) nbrs[i].push_back(i + 1);
  for (PetscInt i = 0; i < nb; i++)
    for (int t = 0; t < 3; t++) {
      PetscReal r;
      PetscCall(PetscRandomGetValueReal(rnd, &r));
      const PetscInt j = (PetscInt)(r * nb) % nb;
      if (j > i && std::find(nbrs[i].begin(), nbrs[i].end(), j) == nbrs[i].end()) nbrs[i].push_back(j);
    }
  PetscCall(MatCreateSeqSBAIJ(PETSC_COMM_SELF, 3, 3 * nb, 3 * nb, 8, NULL, A));
  PetscCall(MatSetOption(*A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  for (PetscInt i = 0; i < nb; i++)
    for (PetscInt j : nbrs[i]) {
      PetscScalar v[9];
      for (int k = 0; k < 9; k++) {
        PetscReal r;
        PetscCall(PetscRandomGetValueReal(rnd, &r));
        v[k] = 2 * r - 1;
      }
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
          rowsum[3 * i + a] += PetscAbsScalar(v[3 * a + b]);
          rowsum[3 * j + b] += PetscAbsScalar(v[3 * a + b]);
        }
      PetscCall(MatSetValuesBlocked(*A, 1, &i, 1, &j, v, INSERT_VALUES)); /* row-major block (i, j), i < j */
    }
  for (PetscInt i = 0; i < nb; i++) {
    PetscScalar d[9];
    for (int k = 0; k < 9; k++) {
      PetscReal r;
      PetscCall(PetscRandomGetValueReal(rnd, &r));
      d[k] = 0.1 * (2 * r - 1);
    }
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < a; b++) d[3 * a + b] = d[3 * b + a];
    for (int a = 0; a < 3; a++) {
      PetscReal off = 0;
      for (int b = 0; b < 3; b++)
        if (b != a) off += PetscAbsScalar(d[3 * a + b]);
      d[3 * a + a] = rowsum[3 * i + a] + off + 0.5;
    }
    PetscCall(MatSetValuesBlocked(*A, 1, &i, 1, &i, d, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -bench k: the SPD block matrix of a cube of k^3 cells ((k+1)^3 nodes, every pair of nodes of a cell coupled,
   as trilinear elasticity couples them), nodes in AMD order as the subdomains' factors have them; prints the CPU
   seconds per solve of MatSolve() and of the float copy, cycling through -bench_copies factors as F cycles through
   the subdomains (a benchmark, not a test: k = 6 is the brick's subdomain at H/h = 6) */
static PetscErrorCode Bench(PetscRandom rnd, PetscInt k, PetscInt nsolves, PetscInt ncopies)
{
  const PetscInt m = k + 1, nb = m * m * m;
  Mat            A, Ab, Ap;
  IS             rows, cols, perm, nat;
  MatFactorInfo  info;
  Vec            b, x;
  PetscScalar   *a;

  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqBAIJ(PETSC_COMM_SELF, 3, 3 * nb, 3 * nb, 27, NULL, &A));
  for (PetscInt c0 = 0; c0 < k; c0++)
    for (PetscInt c1 = 0; c1 < k; c1++)
      for (PetscInt c2 = 0; c2 < k; c2++) {
        PetscInt nodes[8], t = 0;
        for (PetscInt d0 = 0; d0 < 2; d0++)
          for (PetscInt d1 = 0; d1 < 2; d1++)
            for (PetscInt d2 = 0; d2 < 2; d2++) nodes[t++] = ((c0 + d0) * m + c1 + d1) * m + c2 + d2;
        for (PetscInt i = 0; i < 8; i++)
          for (PetscInt j = 0; j < 8; j++) {
            PetscScalar v[9];
            for (int q = 0; q < 9; q++) v[q] = (i == j) ? (q % 4 == 0 ? 8.0 : 0.0) : (q % 4 == 0 ? -1.0 : 0.05);
            PetscCall(MatSetValuesBlocked(A, 1, &nodes[i], 1, &nodes[j], v, ADD_VALUES));
          }
      }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatShift(A, 0.1));
  PetscCall(MatGetOrdering(A, MATORDERINGAMD, &rows, &cols));
  {
    const PetscInt       *idx;
    std::vector<PetscInt> p(3 * nb);
    PetscCall(ISGetIndices(rows, &idx));
    for (PetscInt i = 0; i < nb; i++)
      for (PetscInt c = 0; c < 3; c++) p[3 * i + c] = 3 * idx[i] + c;
    PetscCall(ISRestoreIndices(rows, &idx));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, 3 * nb, p.data(), PETSC_COPY_VALUES, &perm));
    PetscCall(ISSetPermutation(perm));
  }
  PetscCall(MatConvert(A, MATSEQAIJ, MAT_INITIAL_MATRIX, &Ab));
  PetscCall(MatPermute(Ab, perm, perm, &Ap));
  PetscCall(MatSetBlockSize(Ap, 3));
  PetscCall(MatSetOption(Ap, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatConvert(Ap, MATSEQSBAIJ, MAT_INPLACE_MATRIX, &Ap));
  /* as many copies as the F product cycles through subdomains, so that the factors do not stay in the cache */
  PetscCall(ISCreateStride(PETSC_COMM_SELF, nb, 0, 1, &nat));
  PetscCall(MatFactorInfoInitialize(&info));
  std::vector<Mat>             Fs(ncopies);
  std::vector<FETIFloatFactor> ffs(ncopies);
  for (PetscInt c = 0; c < ncopies; c++) {
    PetscCall(MatGetFactor(Ap, MATSOLVERPETSC, MAT_FACTOR_CHOLESKY, &Fs[c]));
    PetscCall(MatCholeskyFactorSymbolic(Fs[c], Ap, nat, &info));
    PetscCall(MatCholeskyFactorNumeric(Fs[c], Ap, &info));
    PetscCall(FETIFloatFactorCreate(Fs[c], "-feti_kplus_precision", ffs[c]));
  }
  PetscCall(MatCreateVecs(Ap, &b, &x));
  PetscCall(VecSetRandom(b, rnd));
  std::clock_t t0 = std::clock();
  for (PetscInt i = 0; i < nsolves; i++) PetscCall(MatSolve(Fs[i % ncopies], b, x));
  std::clock_t t1 = std::clock();
  for (PetscInt i = 0; i < nsolves; i++) {
    PetscCall(VecCopy(b, x));
    PetscCall(VecGetArray(x, &a));
    PetscCall(FETIFloatFactorSolve(ffs[i % ncopies], a));
    PetscCall(VecRestoreArray(x, &a));
  }
  std::clock_t t2 = std::clock();
  const double sd = (double)(t1 - t0) / CLOCKS_PER_SEC / nsolves, sf = (double)(t2 - t1) / CLOCKS_PER_SEC / nsolves;
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "bench: %" PetscInt_FMT " dofs, factor %.2f MB double, %.2f MB float, %" PetscInt_FMT " copies; CPU per solve: MatSolve %.1f us, float %.1f us (ratio %.2f)\n",
                        3 * nb, ffs[0].doublebytes / 1048576.0, FETIFloatFactorBytes(ffs[0]) / 1048576.0, ncopies, 1e6 * sd, 1e6 * sf, sf / sd));
  for (Mat &Fc : Fs) PetscCall(MatDestroy(&Fc));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&x));
  PetscCall(MatDestroy(&Ap));
  PetscCall(MatDestroy(&Ab));
  PetscCall(MatDestroy(&A));
  PetscCall(ISDestroy(&rows));
  PetscCall(ISDestroy(&cols));
  PetscCall(ISDestroy(&perm));
  PetscCall(ISDestroy(&nat));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscInt    sizes[] = {1, 2, 17, 400}, ntrials = 3;
  PetscReal   tol = 1e-6, worst = 0;
  PetscRandom rnd;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-tol", &tol, NULL));
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetSeed(rnd, 2718));
  PetscCall(PetscRandomSeed(rnd));
  {
    PetscInt  k = 0, nsolves = 2000, ncopies = 64;
    PetscBool bench;
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench", &k, &bench));
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_solves", &nsolves, NULL));
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_copies", &ncopies, NULL));
    if (bench) {
      PetscCall(Bench(rnd, k, nsolves, ncopies));
      PetscCall(PetscRandomDestroy(&rnd));
      PetscCall(PetscFinalize());
      return 0;
    }
  }
  for (PetscInt nb : sizes)
    for (PetscInt trial = 0; trial < ntrials; trial++) {
      Mat             A, F;
      IS              perm;
      MatFactorInfo   info;
      Vec             b, xd, xf;
      FETIFloatFactor ff;
      PetscReal       diff, norm;
      PetscScalar    *a;
      PetscCall(RandomSPD(rnd, nb, &A));
      PetscCall(MatGetFactor(A, MATSOLVERPETSC, MAT_FACTOR_CHOLESKY, &F));
      PetscCall(ISCreateStride(PETSC_COMM_SELF, nb, 0, 1, &perm)); /* natural ordering of the blocks */
      PetscCall(MatFactorInfoInitialize(&info));
      PetscCall(MatCholeskyFactorSymbolic(F, A, perm, &info));
      PetscCall(MatCholeskyFactorNumeric(F, A, &info));
      PetscCall(MatCreateVecs(A, &b, &xd));
      PetscCall(VecDuplicate(b, &xf));
      PetscCall(VecSetRandom(b, rnd));
      PetscCall(MatSolve(F, b, xd));
      PetscCall(FETIFloatFactorCreate(F, "-feti_kplus_precision", ff));
      PetscCall(VecCopy(b, xf));
      PetscCall(VecGetArray(xf, &a));
      PetscCall(FETIFloatFactorSolve(ff, a));
      PetscCall(VecRestoreArray(xf, &a));
      PetscCall(VecAXPY(xf, -1.0, xd));
      PetscCall(VecNorm(xf, NORM_2, &diff));
      PetscCall(VecNorm(xd, NORM_2, &norm));
      diff /= norm;
      worst = PetscMax(worst, diff);
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "%4" PetscInt_FMT " nodes: |x_float - x_double| / |x_double| = %.2e, float copy %.0f bytes, double factor %.0f bytes\n", nb, (double)diff,
                            FETIFloatFactorBytes(ff), ff.doublebytes));
      PetscCheck(diff <= tol, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%" PetscInt_FMT " nodes: the float solve is %g from MatSolve(), above -tol %g", nb, (double)diff, (double)tol);
      PetscCheck(nb < 17 || diff > 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%" PetscInt_FMT " nodes: the float solve equals MatSolve() to the bit: is the copy float at all?", nb);
      PetscCheck(FETIFloatFactorBytes(ff) < 0.6 * ff.doublebytes, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%" PetscInt_FMT " nodes: the float copy takes %.0f bytes, not less than 0.6 times %.0f", nb,
                 FETIFloatFactorBytes(ff), ff.doublebytes);
      PetscCall(VecDestroy(&b));
      PetscCall(VecDestroy(&xd));
      PetscCall(VecDestroy(&xf));
      PetscCall(ISDestroy(&perm));
      PetscCall(MatDestroy(&F));
      PetscCall(MatDestroy(&A));
    }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "float solve agrees with MatSolve (worst relative difference %.2e, bound %.0e)\n", (double)worst, (double)tol));
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(PetscFinalize());
  return 0;
}
