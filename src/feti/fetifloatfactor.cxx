/* A single-precision copy of a block Cholesky factor: a subdomain's K_s for F (-feti_kplus_precision single) or
   the interior block K_ii of the Dirichlet preconditioner (-feti_dirichlet_pc_precision single).

   The F products spend most of their time in the two triangular solves with the subdomains' factors, and
   each solve is bound by memory traffic: the factor is read twice per solve and is far larger than the
   vectors. Storing its values in float halves that traffic. Only the storage is single: the vectors and
   every sum stay double, so the solve is that of the factor rounded to float, L_f D_f L_f', exactly
   symmetric, and F = B K+ B' stays a symmetric operator. What changes is the operator itself, by about
   cond(K_s) times the float rounding (6e-8): where K+ x must be that of K_s (the h of the dual problem, the
   primal recovery, the explicit blocks), FETISubdomainApplyKplus() corrects it by iterative refinement with
   Kreg in double.

   The source is PETSc's own factor of an SBAIJ matrix with block size 3 in its natural ordering (the nodes are
   permuted into the matrix beforehand, FETIPermuteByNodes()): U' D U with U unit upper block triangular. PETSc keeps,
   in column-major 3x3 blocks, the inverted diagonal blocks D_k^-1 first (block k at offset 9 k) and then, for
   block row k, the off-diagonal blocks of -U at offsets ai[k] .. ai[k+1]-1 with their block columns in aj. The
   layout is read through public calls (MatGetRowIJ() for ai, aj; MatSeqSBAIJGetArray() for the values) and
   checked against MatSolve() at setup (FETISubdomainSetUpFactorization(), -feti_check). */
#include <conefeti/private/fetiimpl.h>

/* Copy the double factor into ff (block size 3, natural ordering; see above); option: the caller's option that asked
   for the copy, named by the errors */
PetscErrorCode FETIFloatFactorCreate(Mat factor, const char option[], FETIFloatFactor &ff)
{
  const PetscInt *ai, *aj;
  PetscInt        mbs, bs;
  PetscBool       done, sbaij;
  PetscScalar    *aa;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)factor, MATSEQSBAIJ, &sbaij));
  PetscCall(MatGetBlockSize(factor, &bs));
  PetscCheck(sbaij && bs == 3, PETSC_COMM_SELF, PETSC_ERR_SUP, "%s single: a float copy is made of PETSc's own block Cholesky factor (SBAIJ, block size 3) only", option);
  PetscCall(MatGetRowIJ(factor, 0, PETSC_FALSE, PETSC_TRUE, &mbs, &ai, &aj, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "%s single: the factor does not give its block structure (MatGetRowIJ())", option);
  PetscCall(MatSeqSBAIJGetArray(factor, &aa));
  ff.nb                = mbs;
  const PetscInt first = ai[0], nz = ai[mbs] - ai[0];
  PetscCallCXX(ff.rowstart.resize(mbs + 1));
  PetscCallCXX(ff.col.resize(nz));
  PetscCallCXX(ff.diag.resize((size_t)9 * mbs));
  PetscCallCXX(ff.off.resize((size_t)9 * nz));
  for (PetscInt k = 0; k <= mbs; k++) ff.rowstart[k] = (std::int32_t)(ai[k] - first);
  for (PetscInt t = 0; t < nz; t++) ff.col[t] = (std::int32_t)aj[first + t];
  for (size_t t = 0; t < (size_t)9 * mbs; t++) ff.diag[t] = (float)PetscRealPart(aa[t]);
  for (size_t t = 0; t < (size_t)9 * nz; t++) ff.off[t] = (float)PetscRealPart(aa[(size_t)9 * first + t]);
  /* the double factor's memory, for the comparison FETIView() and the summary print: values, block columns, row starts */
  ff.doublebytes = (double)9 * ai[mbs] * sizeof(PetscScalar) + (double)ai[mbs] * sizeof(PetscInt) + (double)(mbs + 1) * sizeof(PetscInt);
  PetscCall(MatSeqSBAIJRestoreArray(factor, &aa));
  PetscCall(MatRestoreRowIJ(factor, 0, PETSC_FALSE, PETSC_TRUE, &mbs, &ai, &aj, &done));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Bytes of the float copy */
double FETIFloatFactorBytes(const FETIFloatFactor &ff)
{
  return (double)ff.rowstart.size() * sizeof(std::int32_t) + (double)ff.col.size() * sizeof(std::int32_t) + (double)(ff.diag.size() + ff.off.size()) * sizeof(float);
}

/* x <- (U' D U)^-1 x in place, x of length 3 nb in the factor's (permuted) order; float factor, double sums */
PetscErrorCode FETIFloatFactorSolve(const FETIFloatFactor &ff, PetscScalar *x)
{
  const std::int32_t *rs = ff.rowstart.data(), *col = ff.col.data();
  const float        *off = ff.off.data(), *diag = ff.diag.data();

  PetscFunctionBegin;
  /* U' z = x, column by column: once block k of z is final, push its contribution -U_kj' z_k to the blocks j > k
     of the rows below; then y_k = D_k^-1 z_k */
  for (PetscInt k = 0; k < ff.nb; k++) {
    const double z0 = x[3 * k], z1 = x[3 * k + 1], z2 = x[3 * k + 2];
    for (std::int32_t t = rs[k]; t < rs[k + 1]; t++) {
      const float *v  = off + (size_t)9 * t; /* column-major: v[r + 3 c] is entry (r, c) of -U_kj */
      PetscScalar *xj = x + 3 * (PetscInt)col[t];
      xj[0] += (double)v[0] * z0 + (double)v[1] * z1 + (double)v[2] * z2;
      xj[1] += (double)v[3] * z0 + (double)v[4] * z1 + (double)v[5] * z2;
      xj[2] += (double)v[6] * z0 + (double)v[7] * z1 + (double)v[8] * z2;
    }
    const float *d = diag + (size_t)9 * k;
    x[3 * k]       = (double)d[0] * z0 + (double)d[3] * z1 + (double)d[6] * z2;
    x[3 * k + 1]   = (double)d[1] * z0 + (double)d[4] * z1 + (double)d[7] * z2;
    x[3 * k + 2]   = (double)d[2] * z0 + (double)d[5] * z1 + (double)d[8] * z2;
  }
  /* U x = y, row by row from the last: x_k = y_k + sum_j (-U_kj) x_j */
  for (PetscInt k = ff.nb - 1; k >= 0; k--) {
    double s0 = x[3 * k], s1 = x[3 * k + 1], s2 = x[3 * k + 2];
    for (std::int32_t t = rs[k]; t < rs[k + 1]; t++) {
      const float       *v  = off + (size_t)9 * t;
      const PetscScalar *xj = x + 3 * (PetscInt)col[t];
      s0 += (double)v[0] * xj[0] + (double)v[3] * xj[1] + (double)v[6] * xj[2];
      s1 += (double)v[1] * xj[0] + (double)v[4] * xj[1] + (double)v[7] * xj[2];
      s2 += (double)v[2] * xj[0] + (double)v[5] * xj[1] + (double)v[8] * xj[2];
    }
    x[3 * k]     = s0;
    x[3 * k + 1] = s1;
    x[3 * k + 2] = s2;
  }
  PetscCall(PetscLogFlops(36.0 * (double)ff.col.size() + 15.0 * (double)ff.nb));
  PetscFunctionReturn(PETSC_SUCCESS);
}
