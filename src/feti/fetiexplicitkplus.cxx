/* Explicit K+ on the dofs touched by B (-feti_kplus_explicit).

   F = B K+ B' only needs the rows and columns of K+ at the dofs that B touches (the subdomain's
   "interface": gluing and contact dofs). When that set is small, the dense block (K+)_bb applied
   by one matrix-vector product reads far less memory than the two sparse triangular solves of
   K+ (the brick of the seed paper: 1.6M factor entries per subdomain against at most 1500^2/2
   useful dense entries), so every F product is cheaper; building it costs |b| solves with many
   right-hand sides at once (BLAS 3) at setup, or (with MUMPS) one extra factorization that keeps the
   Schur complement on b and a dense inversion. K+ x itself (primal recovery, h) keeps the factor. */
#include <conefeti/private/fetiimpl.h>

#include <algorithm>

/* The dofs of sd that B touches and that K+ does not zero (removed dofs are fixed to zero) */
static PetscErrorCode BoundaryDofs(FETISubdomain &sd, const PetscScalar *mask, std::vector<PetscInt> &kb)
{
  std::vector<char> removed(sd.n, 0);

  PetscFunctionBegin;
  for (PetscInt r : sd.removed) removed[r] = 1;
  kb.clear();
  for (PetscInt k = 0; k < sd.n; k++)
    if (mask[sd.localoffset + k] != 0.0 && !removed[k]) PetscCallCXX(kb.push_back(k));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Without MUMPS: (K+)_bb = columns of Kreg^-1 at the unit vectors e_b, rows b; built in chunks of columns to bound the work memory */
static PetscErrorCode SubdomainExplicitKplusBySolves(FETISubdomain &sd)
{
  const PetscInt nb = (PetscInt)sd.kb.size(), chunk = std::min<PetscInt>(nb, 128);
  PC             pc;
  Mat            factor, E = nullptr, X = nullptr;
  PetscScalar   *s;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&sd.Kplusbb));
  PetscCall(VecDestroy(&sd.kx));
  PetscCall(VecDestroy(&sd.ky));
  if (!nb) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(KSPGetPC(sd.ksp, &pc));
  PetscCall(PCFactorGetMatrix(pc, &factor));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, nb, nb, NULL, &sd.Kplusbb));
  PetscCall(MatDenseGetArrayWrite(sd.Kplusbb, &s));
  for (PetscInt j0 = 0; j0 < nb; j0 += chunk) {
    const PetscInt     nc = std::min(chunk, nb - j0);
    PetscScalar       *e;
    const PetscScalar *x;
    if (nc != chunk || !E) {
      PetscCall(MatDestroy(&E));
      PetscCall(MatDestroy(&X));
      PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, sd.n, nc, NULL, &E));
      PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, sd.n, nc, NULL, &X));
    }
    PetscCall(MatDenseGetArrayWrite(E, &e));
    std::fill(e, e + (size_t)sd.n * nc, 0.0);
    for (PetscInt j = 0; j < nc; j++) e[(size_t)j * sd.n + sd.kb[j0 + j]] = 1.0;
    PetscCall(MatDenseRestoreArrayWrite(E, &e));
    PetscCall(MatMatSolve(factor, E, X));
    PetscCall(MatDenseGetArrayRead(X, &x));
    for (PetscInt j = 0; j < nc; j++)
      for (PetscInt i = 0; i < nb; i++) s[(size_t)(j0 + j) * nb + i] = x[(size_t)j * sd.n + sd.kb[i]];
    PetscCall(MatDenseRestoreArrayRead(X, &x));
  }
  /* exactly symmetric, so that F is */
  for (PetscInt j = 0; j < nb; j++)
    for (PetscInt i = j + 1; i < nb; i++) {
      const PetscScalar a   = 0.5 * (s[(size_t)j * nb + i] + s[(size_t)i * nb + j]);
      s[(size_t)j * nb + i] = s[(size_t)i * nb + j] = a;
    }
  PetscCall(MatDenseRestoreArrayWrite(sd.Kplusbb, &s));
  PetscCall(MatDestroy(&E));
  PetscCall(MatDestroy(&X));
  PetscCall(MatCreateVecs(sd.Kplusbb, &sd.kx, &sd.ky));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* (K+)_bb = S^-1, S = the Schur complement of Kreg on the dofs b: one MUMPS factorization that eliminates
   everything else and keeps S dense, then a dense inversion; cheaper than |b| solves with the factor */
static PetscErrorCode SubdomainExplicitKplusBySchur(FETISubdomain &sd)
{
  const PetscInt nb = (PetscInt)sd.kb.size();
  Mat            factor, S;
  IS             isb, rperm, cperm;
  MatFactorInfo  info;
  PetscScalar   *s;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&sd.Kplusbb));
  PetscCall(VecDestroy(&sd.kx));
  PetscCall(VecDestroy(&sd.ky));
  if (!nb) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(MatGetFactor(sd.Kreg, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &factor));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nb, sd.kb.data(), PETSC_USE_POINTER, &isb));
  PetscCall(MatFactorSetSchurIS(factor, isb));
  PetscCall(MatGetOrdering(sd.Kreg, MATORDERINGNATURAL, &rperm, &cperm));
  PetscCall(MatFactorInfoInitialize(&info));
  PetscCall(MatCholeskyFactorSymbolic(factor, sd.Kreg, rperm, &info));
  PetscCall(MatCholeskyFactorNumeric(factor, sd.Kreg, &info));
  PetscCall(MatFactorInvertSchurComplement(factor));
  PetscCall(MatFactorCreateSchurComplement(factor, &S, NULL));
  PetscCall(MatConvert(S, MATSEQDENSE, MAT_INITIAL_MATRIX, &sd.Kplusbb));
  PetscCall(MatDestroy(&S));
  PetscCall(MatDestroy(&factor));
  PetscCall(ISDestroy(&isb));
  PetscCall(ISDestroy(&rperm));
  PetscCall(ISDestroy(&cperm));
  PetscCall(MatDenseGetArray(sd.Kplusbb, &s));
  for (PetscInt j = 0; j < nb; j++)
    for (PetscInt i = j + 1; i < nb; i++) {
      const PetscScalar a   = 0.5 * (s[(size_t)j * nb + i] + s[(size_t)i * nb + j]);
      s[(size_t)j * nb + i] = s[(size_t)i * nb + j] = a;
    }
  PetscCall(MatDenseRestoreArray(sd.Kplusbb, &s));
  PetscCall(MatCreateVecs(sd.Kplusbb, &sd.kx, &sd.ky));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Build (K+)_bb for every local subdomain; after the factorizations and B are set up */
PetscErrorCode FETISetUpExplicitKplus(FETI feti)
{
  FETI_Impl         &impl = *feti->impl;
  const PetscScalar *mask;

  PetscFunctionBegin;
  PetscCall(FETISetUpBoundaryMask(feti));
  PetscCall(VecGetArrayRead(impl.boundarymask, &mask));
  for (FETISubdomain &sd : impl.sub) {
    PetscBool mumps = PETSC_FALSE;
    PetscCall(BoundaryDofs(sd, mask, sd.kb));
    if (impl.kplusschur) PetscCall(MatGetFactorAvailable(sd.Kreg, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &mumps));
    if (mumps) PetscCall(SubdomainExplicitKplusBySchur(sd));
    else PetscCall(SubdomainExplicitKplusBySolves(sd));
  }
  PetscCall(VecRestoreArrayRead(impl.boundarymask, &mask));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = K+ x for x supported on the dofs touched by B; y is exact on those dofs and zero elsewhere */
PetscErrorCode FETIApplyKplusOnBoundary(FETI feti, Vec x, Vec y)
{
  FETI_Impl         &impl = *feti->impl;
  const PetscScalar *xa;
  PetscScalar       *ya;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(FETI_ApplyKplus, feti, 0, 0, 0));
  PetscCall(VecSet(y, 0.0));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  for (FETISubdomain &sd : impl.sub) {
    const PetscInt nb = (PetscInt)sd.kb.size();
    PetscScalar   *a;
    if (!nb) continue;
    PetscCall(VecGetArrayWrite(sd.kx, &a));
    for (PetscInt i = 0; i < nb; i++) a[i] = xa[sd.localoffset + sd.kb[i]];
    PetscCall(VecRestoreArrayWrite(sd.kx, &a));
    PetscCall(MatMult(sd.Kplusbb, sd.kx, sd.ky));
    PetscCall(VecGetArrayRead(sd.ky, (const PetscScalar **)&a));
    for (PetscInt i = 0; i < nb; i++) ya[sd.localoffset + sd.kb[i]] = a[i];
    PetscCall(VecRestoreArrayRead(sd.ky, (const PetscScalar **)&a));
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(PetscLogEventEnd(FETI_ApplyKplus, feti, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
