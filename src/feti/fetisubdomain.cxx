/* One subdomain: kernel, regularized matrix, factorization, and the products with K and K+.

   Kreg is K with the rows and columns of the removed dofs (fixing dofs and Dirichlet dofs kept in the
   primal) replaced by d*I, d the mean diagonal entry (so the scale of the pivots is unchanged).
   Kreg is built in place when nobody but the FETI object holds K (FEMCreateFETI() hands its
   matrices over this way), otherwise from a copy; either way only Kreg is kept. The products with
   K on the primal space V (where Dirichlet dofs are zero) are recovered exactly as
       K_V x = Kreg x + C x - d x_removed,
   where C holds the entries of K_V in the rows and columns of the fixing dofs (a few columns). */
#include <conefeti/private/fetiimpl.h>

#include <algorithm>
#include <cmath>

/* y = K_V x for sequential vectors of length n */
PetscErrorCode FETISubdomainApplyK(FETISubdomain &sd, Vec x, Vec y)
{
  const PetscScalar *xa;
  PetscScalar       *ya;

  PetscFunctionBegin;
  PetscCall(MatMult(sd.Kreg, x, y));
  if (sd.correction) PetscCall(MatMultAdd(sd.correction, x, y, y));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  for (PetscInt r : sd.removed) ya[r] -= sd.regdiag * xa[r];
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* out = (factor)^-1 in with the float copy of the factor, both of length n in the dof order; in is read as zero at
   the removed dofs (out is zero there: Kreg decouples them) */
static PetscErrorCode FloatSolve(FETISubdomain &sd, const PetscScalar *in, PetscScalar *out)
{
  PetscScalar *ta;

  PetscFunctionBegin;
  PetscCall(VecGetArrayWrite(sd.x, &ta));
  for (PetscInt k = 0; k < sd.n; k++) ta[k] = in[sd.perm[k]];
  for (PetscInt r : sd.removed) ta[sd.iperm[r]] = 0;
  PetscCall(FETIFloatFactorSolve(sd.ffactor, ta));
  for (PetscInt k = 0; k < sd.n; k++) out[sd.perm[k]] = ta[k];
  PetscCall(VecRestoreArrayWrite(sd.x, &ta));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The largest number of refinement steps of an exact K+ x with the float factor. Each step gains about
   -log10(cond(K_s) * 6e-8) digits (3 to 4 on the brick's cubes), so 2 to 4 steps reach the double solve's accuracy */
#define FETI_FLOAT_REFINE_MAX 12

/* y = K+ x with the float factor; exact: refined against Kreg in double, y += solve(x - Kreg y), until the
   correction stops shrinking or is at the double rounding of y */
static PetscErrorCode ApplyKplusFloat(FETISubdomain &sd, Vec x, Vec y, PetscBool exact)
{
  const PetscScalar *xa;
  PetscScalar       *ya;
  PetscReal          prev = PETSC_MAX_REAL;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArrayWrite(y, &ya));
  PetscCall(FloatSolve(sd, xa, ya));
  PetscCall(VecRestoreArrayWrite(y, &ya));
  for (PetscInt it = 0; exact && it < FETI_FLOAT_REFINE_MAX; it++) {
    const PetscScalar *ra;
    PetscReal          dnorm = 0, ynorm = 0;
    PetscCall(MatMult(sd.Kreg, y, sd.y)); /* y vanishes at the removed dofs, whose residual FloatSolve() skips */
    PetscCallCXX(sd.work.resize(sd.n));
    PetscCall(VecGetArrayRead(sd.y, &ra));
    for (PetscInt i = 0; i < sd.n; i++) sd.work[i] = xa[i] - ra[i];
    PetscCall(VecRestoreArrayRead(sd.y, &ra));
    PetscCall(FloatSolve(sd, sd.work.data(), sd.work.data()));
    PetscCall(VecGetArray(y, &ya));
    for (PetscInt i = 0; i < sd.n; i++) {
      ya[i] += sd.work[i];
      dnorm = PetscMax(dnorm, PetscAbsScalar(sd.work[i]));
      ynorm = PetscMax(ynorm, PetscAbsScalar(ya[i]));
    }
    PetscCall(VecRestoreArray(y, &ya));
    PetscCheck(it > 0 || dnorm <= 0.5 * ynorm, PETSC_COMM_SELF, PETSC_ERR_NOT_CONVERGED,
               "-feti_kplus_precision single: the float factor of a subdomain is too inaccurate to be refined (first correction %g of the solution %g: cond(K_s) near 1e7 or above); use "
               "-feti_kplus_precision double",
               (double)dnorm, (double)ynorm);
    if (dnorm <= 4 * PETSC_MACHINE_EPSILON * ynorm || dnorm > 0.5 * prev) break;
    prev = dnorm;
  }
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = K+ x = [K_NN^-1 0; 0 0] x. exact matters with a float factor only (-feti_kplus_precision single): F products
   take its solve as it is (unless -feti_kplus_refine), everything else (exact) the refined one */
PetscErrorCode FETISubdomainApplyKplus(FETISubdomain &sd, Vec x, Vec y, PetscBool exact)
{
  PetscScalar *a;

  PetscFunctionBegin;
  if (sd.ffactor.nb) {
    PetscCall(ApplyKplusFloat(sd, x, y, exact));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (sd.factor) { /* a factor of Kreg permuted by nodes: permute in and out around one MatSolve (no KSPSolve bookkeeping per call) */
    const PetscScalar *xa, *ya;
    PetscScalar       *ta;
    PetscCall(VecGetArrayRead(x, &xa));
    PetscCall(VecGetArrayWrite(sd.x, &ta));
    for (PetscInt k = 0; k < sd.n; k++) ta[k] = xa[sd.perm[k]];
    for (PetscInt r : sd.removed) ta[sd.iperm[r]] = 0;
    PetscCall(VecRestoreArrayWrite(sd.x, &ta));
    PetscCall(VecRestoreArrayRead(x, &xa));
    PetscCall(MatSolve(sd.factor, sd.x, sd.y));
    PetscCall(VecGetArrayRead(sd.y, &ya));
    PetscCall(VecGetArrayWrite(y, &ta));
    for (PetscInt k = 0; k < sd.n; k++) ta[sd.perm[k]] = ya[k];
    PetscCall(VecRestoreArrayWrite(y, &ta));
    PetscCall(VecRestoreArrayRead(sd.y, &ya));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(VecCopy(x, sd.x));
  PetscCall(VecGetArray(sd.x, &a));
  for (PetscInt r : sd.removed) a[r] = 0;
  PetscCall(VecRestoreArray(sd.x, &a));
  PetscCall(KSPSolve(sd.ksp, sd.x, y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode KernelFromInput(FETI feti, FETISubdomain &sd, PetscInt s)
{
  PetscFunctionBegin;
  if (sd.coords) {
    PetscInt nc;
    PetscCall(VecGetSize(sd.coords, &nc));
    PetscCheck(nc == sd.n, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
               "FETISetSubdomainCoordinates(): subdomain %" PetscInt_FMT ": %" PetscInt_FMT " coordinates for %" PetscInt_FMT " dofs (need 3 per node, interleaved like the dofs)", s, nc, sd.n);
  }
  if (sd.Ruser) {
    Mat                dense;
    const PetscScalar *a;
    PetscInt           m, k, lda;
    PetscCall(MatGetSize(sd.Ruser, &m, &k));
    PetscCheck(m == sd.n, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "FETISetSubdomainKernel(): subdomain %" PetscInt_FMT ": the kernel has %" PetscInt_FMT " rows but K_s has %" PetscInt_FMT, s, m, sd.n);
    PetscCall(MatConvert(sd.Ruser, MATSEQDENSE, MAT_INITIAL_MATRIX, &dense));
    PetscCall(MatDenseGetLDA(dense, &lda));
    PetscCall(MatDenseGetArrayRead(dense, &a));
    PetscCallCXX(sd.R.resize((size_t)m * k));
    for (PetscInt j = 0; j < k; j++)
      for (PetscInt i = 0; i < m; i++) sd.R[(size_t)j * m + i] = a[(size_t)j * lda + i];
    PetscCall(MatDenseRestoreArrayRead(dense, &a));
    PetscCall(MatDestroy(&dense));
    sd.nkernel = k;
  } else {
    PetscInt nc;
    PetscCheck(sd.coords, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONGSTATE, "Subdomain %" PetscInt_FMT ": give node coordinates (FETISetSubdomainCoordinates()) or a kernel basis (FETISetSubdomainKernel())",
               s);
    PetscCall(VecGetSize(sd.coords, &nc));
    PetscCheck(nc == sd.n, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
               "FETISetSubdomainCoordinates(): subdomain %" PetscInt_FMT ": %" PetscInt_FMT " coordinates for %" PetscInt_FMT " dofs (need 3 per node, interleaved like the dofs)", s, nc, sd.n);
    PetscCall(FETIRigidBodyModes(sd.coords, sd.n, sd.R));
    sd.nkernel = 6;
  }
  /* a kernel given with orthonormal columns (as FETIWrite() writes the basis in use) is kept to the bit, so that a
     problem read back from a file is the same problem to the last bit; another one is orthonormalized */
  PetscBool orthonormal = sd.Ruser ? PETSC_TRUE : PETSC_FALSE;
  for (PetscInt p = 0; p < sd.nkernel && orthonormal; p++)
    for (PetscInt q = 0; q <= p && orthonormal; q++) {
      PetscScalar dot = 0;
      for (PetscInt i = 0; i < sd.n; i++) dot += sd.R[(size_t)p * sd.n + i] * PetscConj(sd.R[(size_t)q * sd.n + i]);
      if (PetscAbsScalar(dot - (p == q ? 1.0 : 0.0)) > 1e-12) orthonormal = PETSC_FALSE;
    }
  if (!orthonormal) PetscCall(FETIOrthonormalizeColumns(sd.n, &sd.nkernel, sd.R, 1e-8));
  PetscCall(FETIKernelVanishingOn(sd.n, &sd.nkernel, sd.R, sd.dirichletdofs, feti->impl->kerneltol));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* C: the entries of K_V in the rows and columns of the fixing dofs, from the columns K e_f */
static PetscErrorCode BuildCorrection(FETISubdomain &sd, const std::vector<char> &isD)
{
  std::vector<std::vector<PetscInt>>    cols(sd.fixing.size());
  std::vector<std::vector<PetscScalar>> vals(sd.fixing.size());
  std::vector<PetscInt>                 nnz(sd.n, 0);
  Vec                                   ef, kf;

  PetscFunctionBegin;
  if (sd.fixing.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, sd.n, &ef));
  PetscCall(VecDuplicate(ef, &kf));
  for (size_t q = 0; q < sd.fixing.size(); q++) {
    const PetscScalar *a;
    PetscCall(VecSet(ef, 0.0));
    PetscCall(VecSetValue(ef, sd.fixing[q], 1.0, INSERT_VALUES));
    PetscCall(VecAssemblyBegin(ef));
    PetscCall(VecAssemblyEnd(ef));
    PetscCall(MatMult(sd.K, ef, kf));
    PetscCall(VecGetArrayRead(kf, &a));
    for (PetscInt i = 0; i < sd.n; i++)
      if (a[i] != 0.0 && !isD[i]) {
        PetscCallCXX(cols[q].push_back(i));
        PetscCallCXX(vals[q].push_back(a[i]));
      }
    PetscCall(VecRestoreArrayRead(kf, &a));
  }
  PetscCall(VecDestroy(&ef));
  PetscCall(VecDestroy(&kf));
  for (size_t q = 0; q < sd.fixing.size(); q++) {
    nnz[sd.fixing[q]] += (PetscInt)cols[q].size();
    for (PetscInt i : cols[q]) nnz[i]++;
  }
  for (PetscInt i = 0; i < sd.n; i++) nnz[i] = std::min(nnz[i], sd.n);
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, sd.n, sd.n, 0, nnz.data(), &sd.correction));
  for (size_t q = 0; q < sd.fixing.size(); q++) {
    const PetscInt f = sd.fixing[q];
    for (size_t t = 0; t < cols[q].size(); t++) {
      PetscCall(MatSetValue(sd.correction, cols[q][t], f, vals[q][t], INSERT_VALUES));
      PetscCall(MatSetValue(sd.correction, f, cols[q][t], vals[q][t], INSERT_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(sd.correction, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(sd.correction, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* max over kernel columns of ||K_V r|| / ||K||_inf (the columns are orthonormal) */
static PetscErrorCode KernelResidual(FETISubdomain &sd, const std::vector<char> &isD, PetscReal *res)
{
  Vec       r, kr;
  PetscReal knorm;

  PetscFunctionBegin;
  *res = 0;
  if (!sd.nkernel) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(MatNorm(sd.K, NORM_INFINITY, &knorm));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, sd.n, &kr));
  for (PetscInt j = 0; j < sd.nkernel; j++) {
    PetscScalar *a;
    PetscReal    norm;
    PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, sd.n, &sd.R[(size_t)j * sd.n], &r));
    PetscCall(MatMult(sd.K, r, kr));
    PetscCall(VecGetArray(kr, &a));
    for (PetscInt i = 0; i < sd.n; i++)
      if (isD[i]) a[i] = 0;
    PetscCall(VecRestoreArray(kr, &a));
    PetscCall(VecNorm(kr, NORM_2, &norm));
    const PetscReal rel = knorm > 0 ? norm / knorm : norm;
    if (!(rel <= *res)) *res = rel; /* a NaN residual is kept (std::max would drop it) and fails the check */
    PetscCall(VecDestroy(&r));
  }
  PetscCall(VecDestroy(&kr));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ||K+ K x - x|| / ||x|| for a random x vanishing at the removed dofs. In exact arithmetic it is 0;
   in floating point it is about cond(K_NN) * eps, so it exposes a K_NN made (nearly) singular by a
   zero-energy mode missing from the kernel basis, which K K+ K = K alone would not: there the huge
   component K+ puts along the missing mode is annihilated again by K. */
/* a random vector of the subdomain's dofs (a fixed seed: the checks are the same on every run) that vanishes on
   the removed dofs, where K_s and its generalized inverse act as the identity */
static PetscErrorCode CheckVector(FETISubdomain &sd, unsigned long seed, Vec *x)
{
  PetscRandom  rnd;
  PetscScalar *a;

  PetscFunctionBegin;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, sd.n, x));
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetSeed(rnd, seed));
  PetscCall(PetscRandomSeed(rnd));
  PetscCall(VecSetRandom(*x, rnd));
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(VecGetArray(*x, &a));
  for (PetscInt r : sd.removed) a[r] = 0;
  PetscCall(VecRestoreArray(*x, &a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RegularizationResidual(FETISubdomain &sd, PetscBool exact, PetscReal *res)
{
  Vec       x, kx, w;
  PetscReal norm, normx;

  PetscFunctionBegin;
  PetscCall(CheckVector(sd, 12345, &x));
  PetscCall(VecDuplicate(x, &kx));
  PetscCall(VecDuplicate(x, &w));
  PetscCall(FETISubdomainApplyK(sd, x, kx));
  PetscCall(FETISubdomainApplyKplus(sd, kx, w, exact));
  PetscCall(VecAXPY(w, -1.0, x));
  PetscCall(VecNorm(w, NORM_2, &norm));
  PetscCall(VecNorm(x, NORM_2, &normx));
  *res = normx > 0 ? norm / normx : norm;
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&kx));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* a factorization retried with more workspace starts from a fresh factor: the Schur dofs again */
struct SchurDofsContext {
  FETI           feti;
  FETISubdomain *sd;
};

static PetscErrorCode SetSchurDofsAgain(void *ctx)
{
  SchurDofsContext *c = static_cast<SchurDofsContext *>(ctx);

  PetscFunctionBegin;
  PetscCall(FETISubdomainSetSchurDofs(c->feti, *c->sd));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The kernel basis R_s (checked against K_s), the fixing dofs, the correction C and the diagonal d of
   the regularization: everything but the factorization */
PetscErrorCode FETISubdomainSetUpKernel(FETI feti, FETISubdomain &sd, PetscInt s)
{
  FETI_Impl        &impl = *feti->impl;
  std::vector<char> isD(sd.n, 0);
  Vec               diag;
  PetscReal         sum   = 0;
  PetscInt          nfree = 0;

  PetscFunctionBegin;
  sd.dirichletdofs.clear();
  if (sd.dirichlet) {
    const PetscInt *idx;
    PetscInt        nd;
    PetscCall(ISGetLocalSize(sd.dirichlet, &nd));
    PetscCall(ISGetIndices(sd.dirichlet, &idx));
    for (PetscInt i = 0; i < nd; i++) {
      PetscCheck(idx[i] >= 0 && idx[i] < sd.n, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                 "FETISetSubdomainDirichletDofs(): subdomain %" PetscInt_FMT ": dof %" PetscInt_FMT " is outside 0..%" PetscInt_FMT, s, idx[i], sd.n - 1);
      PetscCallCXX(sd.dirichletdofs.push_back(idx[i]));
    }
    PetscCall(ISRestoreIndices(sd.dirichlet, &idx));
    std::sort(sd.dirichletdofs.begin(), sd.dirichletdofs.end());
    sd.dirichletdofs.erase(std::unique(sd.dirichletdofs.begin(), sd.dirichletdofs.end()), sd.dirichletdofs.end());
  }
  for (PetscInt d : sd.dirichletdofs) isD[d] = 1;

  { /* NaN or Inf in K_s would pass the kernel check (a NaN residual) or blame the coordinates; the Frobenius norm
       sums the squares of all entries, so it is finite when they are (unless an entry beyond ~1e154 overflows it) */
    PetscReal knorm;
    PetscCall(MatNorm(sd.K, NORM_FROBENIUS, &knorm));
    PetscCheck(!PetscIsInfOrNanReal(knorm), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "FETISetUp(): K_s of subdomain %" PetscInt_FMT " (K[%" PetscInt_FMT
               "] of FETISetSubdomains() on its rank) has a non-finite entry (NaN or Inf, or entries so large that ||K_s||_F overflows)",
               s, (PetscInt)(&sd - impl.sub.data()));
  }
  PetscCall(KernelFromInput(feti, sd, s));
  if (impl.check) {
    PetscReal res;
    PetscCall(KernelResidual(sd, isD, &res));
    PetscCheck(res <= impl.checktol, PETSC_COMM_SELF, PETSC_ERR_ARG_INCOMP,
               "Subdomain %" PetscInt_FMT ": ||K_s R_s|| / ||K_s|| = %g exceeds -feti_check_tol %g: the coordinates (or kernel) do not match K_s (dof order x,y,z per node? same node order?)", s,
               (double)res, (double)impl.checktol);
  }
  PetscCall(FETIChooseFixingDofs(sd.n, sd.nkernel, sd.R, sd.coords, sd.dirichletdofs, impl.nfixingcandidates, sd.fixing));
  PetscCall(BuildCorrection(sd, isD));

  /* d = mean diagonal entry over the free dofs */
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, sd.n, &diag));
  PetscCall(MatGetDiagonal(sd.K, diag));
  {
    const PetscScalar *a;
    PetscCall(VecGetArrayRead(diag, &a));
    for (PetscInt i = 0; i < sd.n; i++)
      if (!isD[i]) {
        sum += PetscAbsScalar(a[i]);
        nfree++;
      }
    PetscCall(VecRestoreArrayRead(diag, &a));
  }
  PetscCall(VecDestroy(&diag));
  sd.regdiag = nfree && sum > 0 ? sum / nfree : 1.0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* FETI_BLOCK_CHOLESKY_MAX_DOFS (private/fetiimpl.h), the largest subdomain (dofs) whose factor for F is PETSc's
   block Cholesky by default: it factors more slowly
   than CHOLMOD (no supernodes, no BLAS 3), which its cheaper solves repay only for small subdomains (the brick
   measured at 1029, 2187 and 3993 dofs: docs/scale.md, "Memory of the factor path") */

/* Kreg as SBAIJ with block size 3, its nodes reordered by a fill-reducing ordering of the node graph (PETSc's
   own Cholesky of SBAIJ takes the natural order only, so the order is put into the matrix): perm[k] is the dof
   at row k. The factor keeps the 3x3 blocks (one column index per block, no relaxed supernodes), so it is
   smaller and its triangular solves read less memory than CHOLMOD's supernodal factor of the same matrix. */
PetscErrorCode FETIPermuteByNodes(Mat Kreg, MatOrderingType type, std::vector<PetscInt> &perm, std::vector<PetscInt> &iperm, Mat *Kperm)
{
  IS                    rows, cols;
  const PetscInt       *idx, *ia = NULL, *ja = NULL;
  PetscInt              n, nb = 0;
  PetscBool             sbaij, done;
  std::vector<PetscInt> inode;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(FETI_Reorder, 0, 0, 0, 0));
  PetscCall(MatGetSize(Kreg, &n, NULL));
  PetscCall(PetscObjectTypeCompare((PetscObject)Kreg, MATSEQSBAIJ, &sbaij));
  if (sbaij) { /* the node graph with both triangles (columns sorted, as a block matrix of K_s would have them) */
    std::vector<PetscInt>    gi, gj, fill;
    std::vector<PetscScalar> ones;
    Mat                      graph;
    PetscCall(MatGetRowIJ(Kreg, 0, PETSC_FALSE, PETSC_TRUE, &nb, &ia, &ja, &done));
    PetscCheck(done && 3 * nb == n, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Cannot read the block structure of Kreg");
    PetscCallCXX(gi.assign(nb + 1, 0));
    for (PetscInt r = 0; r < nb; r++)
      for (PetscInt p = ia[r]; p < ia[r + 1]; p++) {
        gi[r + 1]++;
        if (ja[p] != r) gi[ja[p] + 1]++;
      }
    for (PetscInt r = 0; r < nb; r++) gi[r + 1] += gi[r];
    PetscCallCXX(gj.resize(gi[nb]));
    PetscCallCXX(fill.assign(gi.begin(), gi.end() - 1));
    for (PetscInt r = 0; r < nb; r++) /* first the lower triangle, row by row: each row's columns come out in order */
      for (PetscInt p = ia[r]; p < ia[r + 1]; p++)
        if (ja[p] != r) gj[fill[ja[p]]++] = r;
    for (PetscInt r = 0; r < nb; r++)
      for (PetscInt p = ia[r]; p < ia[r + 1]; p++) gj[fill[r]++] = ja[p];
    PetscCallCXX(ones.assign(gi[nb], 1.0));
    PetscCall(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, nb, nb, gi.data(), gj.data(), ones.data(), &graph));
    PetscCall(MatGetOrdering(graph, type, &rows, &cols));
    PetscCall(MatDestroy(&graph));
  } else { /* AIJ with block size 3: its ordering is one of the block (node) graph */
    Mat Kb;
    PetscCall(MatConvert(Kreg, MATSEQBAIJ, MAT_INITIAL_MATRIX, &Kb));
    PetscCall(MatGetOrdering(Kb, type, &rows, &cols));
    PetscCall(MatDestroy(&Kb));
  }
  PetscCallCXX(perm.resize(n));
  PetscCallCXX(iperm.resize(n));
  PetscCallCXX(inode.resize(n / 3));
  PetscCall(ISGetIndices(rows, &idx));
  for (PetscInt k = 0; k < n / 3; k++) {
    inode[idx[k]] = k;
    for (PetscInt c = 0; c < 3; c++) perm[3 * k + c] = 3 * idx[k] + c;
  }
  PetscCall(ISRestoreIndices(rows, &idx));
  PetscCall(ISDestroy(&rows));
  PetscCall(ISDestroy(&cols));
  for (PetscInt k = 0; k < n; k++) iperm[perm[k]] = k;
  if (sbaij) {
    /* the permuted upper triangle block by block from Kreg's arrays (a block that falls below the diagonal goes in
       transposed): the values are copied, not recomputed, and no AIJ copy of K_s is made on the way */
    std::vector<PetscInt> nnz(nb, 0);
    PetscScalar          *va;
    for (PetscInt r = 0; r < nb; r++)
      for (PetscInt p = ia[r]; p < ia[r + 1]; p++) nnz[std::min(inode[r], inode[ja[p]])]++;
    PetscCall(MatCreateSeqSBAIJ(PETSC_COMM_SELF, 3, n, n, 0, nnz.data(), Kperm));
    PetscCall(MatSetOption(*Kperm, MAT_ROW_ORIENTED, PETSC_FALSE)); /* a block's 9 values column by column, as SBAIJ stores them */
    PetscCall(MatSeqSBAIJGetArray(Kreg, &va));
    for (PetscInt r = 0; r < nb; r++)
      for (PetscInt p = ia[r]; p < ia[r + 1]; p++) {
        const PetscScalar *b  = va + 9 * (size_t)p;
        PetscInt           pr = inode[r], pc = inode[ja[p]];
        PetscScalar        t[9];
        if (pr > pc) {
          std::swap(pr, pc);
          for (PetscInt i = 0; i < 3; i++)
            for (PetscInt j = 0; j < 3; j++) t[3 * i + j] = b[3 * j + i];
          b = t;
        } else if (pr == pc) { /* a diagonal block: its upper triangle mirrored, the entries K_s holds (its stored lower one may differ in the last bit) */
          for (PetscInt i = 0; i < 3; i++)
            for (PetscInt j = 0; j < 3; j++) t[i + 3 * j] = i <= j ? b[i + 3 * j] : b[j + 3 * i];
          b = t;
        }
        PetscCall(MatSetValuesBlocked(*Kperm, 1, &pr, 1, &pc, b, INSERT_VALUES));
      }
    PetscCall(MatSeqSBAIJRestoreArray(Kreg, &va));
    PetscCall(MatRestoreRowIJ(Kreg, 0, PETSC_FALSE, PETSC_TRUE, &nb, &ia, &ja, &done));
    PetscCall(MatAssemblyBegin(*Kperm, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(*Kperm, MAT_FINAL_ASSEMBLY));
  } else {
    Mat Ka;
    IS  is;
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, n, perm.data(), PETSC_USE_POINTER, &is));
    PetscCall(ISSetPermutation(is));
    PetscCall(MatConvert(Kreg, MATSEQAIJ, MAT_INITIAL_MATRIX, &Ka));
    PetscCall(MatPermute(Ka, is, is, Kperm));
    PetscCall(MatDestroy(&Ka));
    PetscCall(ISDestroy(&is));
    PetscCall(MatSetBlockSize(*Kperm, 3));
    PetscCall(MatConvert(*Kperm, MATSEQSBAIJ, MAT_INPLACE_MATRIX, Kperm));
  }
  PetscCall(MatSetOption(*Kperm, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(*Kperm, MAT_SPD, PETSC_TRUE));
  PetscCall(PetscLogEventEnd(FETI_Reorder, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -feti_kplus_precision single: replace the subdomain's double block Cholesky factor by its float copy and free it.
   With -feti_check, the copy's solve is compared with MatSolve() (a wrong reading of PETSc's layout would differ
   by O(1); the rounding to float by about cond(K_s) 6e-8) and K+ K x = x is checked again with the refined solve. */
static PetscErrorCode FactorToFloat(FETI feti, FETISubdomain &sd, PetscInt s)
{
  FETI_Impl &impl = *feti->impl;
  MatInfo    info;
  PC         pc;
  Vec        x = nullptr, wd = nullptr, wf = nullptr;

  PetscFunctionBegin;
  PetscCall(MatGetInfo(sd.factor, MAT_LOCAL, &info));
  sd.factorentries = (PetscReal)info.nz_used; /* FETISubdomainKplusCosts() reads it once the factor is gone */
  if (impl.check) {
    PetscCall(CheckVector(sd, 54321, &x));
    PetscCall(VecDuplicate(x, &wd));
    PetscCall(VecDuplicate(x, &wf));
    PetscCall(FETISubdomainApplyKplus(sd, x, wd, PETSC_FALSE)); /* the double factor still */
  }
  PetscCall(FETIFloatFactorCreate(sd.factor, "-feti_kplus_precision", sd.ffactor));
  if (impl.check) {
    PetscReal diff, norm, res, resf;
    PetscCall(FETISubdomainApplyKplus(sd, x, wf, PETSC_FALSE));
    PetscCall(VecAXPY(wf, -1.0, wd));
    PetscCall(VecNorm(wf, NORM_2, &diff));
    PetscCall(VecNorm(wd, NORM_2, &norm));
    diff = norm > 0 ? diff / norm : diff;
    PetscCheck(diff <= 0.25, PETSC_COMM_SELF, PETSC_ERR_LIB,
               "-feti_kplus_precision single: subdomain %" PetscInt_FMT ": the float copy of the factor solves %g away from MatSolve() (relative): this PETSc's block Cholesky factor is not laid "
               "out as expected; use -feti_kplus_precision double",
               s, (double)diff);
    PetscCall(RegularizationResidual(sd, PETSC_FALSE, &resf));
    PetscCall(RegularizationResidual(sd, PETSC_TRUE, &res));
    PetscCheck(res <= impl.checktol, PETSC_COMM_SELF, PETSC_ERR_CONV_FAILED,
               "-feti_kplus_precision single: subdomain %" PetscInt_FMT ": ||K+ K x - x|| / ||x|| = %g with the refined float factor exceeds -feti_check_tol %g; use -feti_kplus_precision double", s,
               (double)res, (double)impl.checktol);
    PetscCall(PetscInfo(NULL, "Subdomain %" PetscInt_FMT ": float factor %.2f MB (double %.2f MB): solve %.2e from MatSolve(), ||K+ K x - x|| / ||x|| = %.2e unrefined, %.2e refined\n", s,
                        FETIFloatFactorBytes(sd.ffactor) / 1048576.0, sd.ffactor.doublebytes / 1048576.0, (double)diff, (double)resf, (double)res));
    PetscCall(VecDestroy(&x));
    PetscCall(VecDestroy(&wd));
    PetscCall(VecDestroy(&wf));
  }
  /* nothing reads the double factor any more: FETIView() asks the PC for the package's name only */
  sd.factor = nullptr;
  PetscCall(KSPGetPC(sd.ksp, &pc));
  PetscCall(PCReset(pc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Kreg (in place when nobody else holds K_s) and its sparse Cholesky factorization, prefix feti_sub_ */
PetscErrorCode FETISubdomainSetUpFactorization(FETI feti, FETISubdomain &sd, PetscInt s)
{
  FETI_Impl  &impl = *feti->impl;
  const char *prefix;
  char        subprefix[256];
  PC          pc;

  PetscFunctionBegin;
  PetscCallCXX(sd.removed = sd.fixing);
  PetscCallCXX(sd.removed.insert(sd.removed.end(), sd.dirichletdofs.begin(), sd.dirichletdofs.end()));
  std::sort(sd.removed.begin(), sd.removed.end());
  sd.removed.erase(std::unique(sd.removed.begin(), sd.removed.end()), sd.removed.end());
  if (((PetscObject)sd.K)->refct == 1) { /* nobody else sees K: regularize in place */
    sd.Kreg = sd.K;
    sd.K    = nullptr;
  } else {
    PetscCall(MatDuplicate(sd.K, MAT_COPY_VALUES, &sd.Kreg));
    PetscCall(MatDestroy(&sd.K));
  }
  PetscCall(MatZeroRowsColumns(sd.Kreg, (PetscInt)sd.removed.size(), sd.removed.data(), sd.regdiag, NULL, NULL));
  PetscCall(MatSetOption(sd.Kreg, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(sd.Kreg, MAT_SPD, PETSC_TRUE));

  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)feti, &prefix));
  PetscCall(PetscSNPrintf(subprefix, sizeof(subprefix), "%sfeti_sub_", prefix ? prefix : ""));
  /* The package: MUMPS for explicit K+ blocks from its Schur complement; CHOLMOD for blocks built by solves (its
     supernodal solves with many right-hand sides at once); PETSc's own block Cholesky when F uses the factor
     (its solves are the F product: docs/scale.md, "Memory of the factor path"); the option overrides all.
     CHOLMOD takes AIJ or block-size-1 SBAIJ only: it factors a transient AIJ copy of an SBAIJ K_s. PETSc's own
     Cholesky factors a transient copy of Kreg with its nodes reordered (-feti_sub_pc_factor_mat_ordering_type,
     default amd, applied to the node graph). Either way Kreg stays symmetric storage (half the memory of AIJ)
     for the products with K, and only the factor is kept beside it. */
  const PetscBool factorpath    = (PetscBool)(!impl.kplusexplicit || sd.kplusimplicit); /* F applies K+ by this factor's solves */
  const char     *defaultsolver = !factorpath ? (impl.kplusschur ? MATSOLVERMUMPS : impl.subsolver) : (sd.n <= FETI_BLOCK_CHOLESKY_MAX_DOFS ? MATSOLVERPETSC : impl.subsolver);
  Mat             Kfactor       = sd.Kreg;
  PetscBool       bynodes       = PETSC_FALSE;
  {
    char      solver[64], ordering[64] = MATORDERINGAMD;
    PetscBool set, sbaij, cholmod, petsc;
    PetscInt  bs;
    PetscCall(PetscStrncpy(solver, defaultsolver, sizeof(solver)));
    PetscCall(PetscOptionsGetString(((PetscObject)feti)->options, subprefix, "-pc_factor_mat_solver_type", solver, sizeof(solver), &set));
    PetscCall(PetscOptionsGetString(((PetscObject)feti)->options, subprefix, "-pc_factor_mat_ordering_type", ordering, sizeof(ordering), &set));
    PetscCall(PetscStrcmp(solver, MATSOLVERCHOLMOD, &cholmod));
    PetscCall(PetscStrcmp(solver, MATSOLVERPETSC, &petsc));
    PetscCall(PetscObjectTypeCompare((PetscObject)sd.Kreg, MATSEQSBAIJ, &sbaij));
    PetscCall(MatGetBlockSize(sd.Kreg, &bs));
    sd.perm.clear();
    sd.iperm.clear();
    if (cholmod && sbaij) {
      PetscCall(MatConvert(sd.Kreg, MATSEQAIJ, MAT_INITIAL_MATRIX, &Kfactor));
      PetscCall(MatSetOption(Kfactor, MAT_SYMMETRIC, PETSC_TRUE));
      PetscCall(MatSetOption(Kfactor, MAT_SPD, PETSC_TRUE));
    } else if (petsc && bs == 3) {
      PetscCall(FETIPermuteByNodes(sd.Kreg, ordering, sd.perm, sd.iperm, &Kfactor));
      bynodes = PETSC_TRUE;
    }
  }
  PetscCall(KSPCreate(PETSC_COMM_SELF, &sd.ksp));
  PetscCall(KSPSetErrorIfNotConverged(sd.ksp, PETSC_TRUE));
  PetscCall(KSPSetOperators(sd.ksp, Kfactor, Kfactor));
  PetscCall(KSPSetOptionsPrefix(sd.ksp, subprefix));
  PetscCall(KSPSetType(sd.ksp, KSPPREONLY));
  PetscCall(KSPGetPC(sd.ksp, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
  /* with explicit K+ blocks, MUMPS factors K_s once and keeps the Schur complement on the dofs B touches */
  PetscCall(PCFactorSetMatSolverType(pc, defaultsolver));
  PetscCall(KSPSetFromOptions(sd.ksp));
  if (bynodes) PetscCall(PCFactorSetMatOrderingType(pc, MATORDERINGNATURAL)); /* the ordering is in Kfactor already */
  PetscCall(FETISubdomainSetSchurDofs(feti, sd));
  {
    PetscBool        failed;
    SchurDofsContext ctx{feti, &sd};
    PetscCall(FETIKSPSetUpFactorization(feti, sd.ksp, SetSchurDofsAgain, &ctx, &failed));
    PetscCheck(!failed, PETSC_COMM_SELF, PETSC_ERR_CONV_FAILED,
               "Subdomain %" PetscInt_FMT ": the regularized K_s is not positive definite: K_s has zero-energy modes outside its kernel basis of dimension %" PetscInt_FMT
               " (a disconnected subdomain, a mechanism, wrong coordinates?)",
               s, sd.nkernel);
  }
  if (Kfactor != sd.Kreg) { /* keep the factor, drop the copy: the KSP sees Kreg from now on and must not factor again */
    PetscCall(PCSetReusePreconditioner(pc, PETSC_TRUE));
    PetscCall(KSPSetOperators(sd.ksp, sd.Kreg, sd.Kreg));
    PetscCall(MatDestroy(&Kfactor));
  }
  sd.factor = nullptr;
  if (bynodes) { /* FETISubdomainApplyKplus() permutes around it and calls MatSolve() itself: -feti_sub_ksp_view is honoured here, as KSPSolve() would */
    PetscCall(PCFactorGetMatrix(pc, &sd.factor));
    PetscCall(KSPViewFromOptions(sd.ksp, NULL, "-ksp_view"));
  }
  PetscCall(FETISubdomainExplicitKplusFromSchur(sd, s));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, sd.n, &sd.x));
  PetscCall(VecDuplicate(sd.x, &sd.y));
  PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, sd.n, NULL, &sd.xa));
  PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, sd.n, NULL, &sd.ya));
  if (impl.check) {
    PetscReal res;
    PetscCall(RegularizationResidual(sd, PETSC_TRUE, &res));
    PetscCheck(res <= impl.checktol, PETSC_COMM_SELF, PETSC_ERR_CONV_FAILED,
               "Subdomain %" PetscInt_FMT
               ": ||K+ K x - x|| / ||x|| = %g exceeds -feti_check_tol %g: the regularized K_s is (nearly) singular, so K_s has zero-energy modes outside its kernel basis of dimension %" PetscInt_FMT
               " (a disconnected subdomain, a mechanism, wrong coordinates?)",
               s, (double)res, (double)impl.checktol, sd.nkernel);
    PetscCall(PetscInfo(NULL, "Subdomain %" PetscInt_FMT ": kernel dimension %" PetscInt_FMT ", ||K+ K x - x|| / ||x|| = %g\n", s, sd.nkernel, (double)res));
  }
  if (sd.factor) { /* PETSc's block Cholesky: its memory, kept as it is or as a float copy */
    if (impl.kplusprecision == FETI_KPLUS_PRECISION_SINGLE) PetscCall(FactorToFloat(feti, sd, s));
    else {
      const PetscInt *ai, *aj; /* the double factor's size, from its structure alone */
      PetscInt        mbs;
      PetscBool       done;
      PetscCall(MatGetRowIJ(sd.factor, 0, PETSC_FALSE, PETSC_TRUE, &mbs, &ai, &aj, &done));
      if (done) sd.ffactor.doublebytes = (double)9 * ai[mbs] * sizeof(PetscScalar) + (double)ai[mbs] * sizeof(PetscInt) + (double)(mbs + 1) * sizeof(PetscInt);
      PetscCall(MatRestoreRowIJ(sd.factor, 0, PETSC_FALSE, PETSC_TRUE, &mbs, &ai, &aj, &done));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FETISubdomainDestroy(FETISubdomain &sd)
{
  PetscFunctionBegin;
  PetscCall(MatDestroy(&sd.K));
  PetscCall(VecDestroy(&sd.f));
  PetscCall(VecDestroy(&sd.coords));
  PetscCall(MatDestroy(&sd.Ruser));
  PetscCall(ISDestroy(&sd.dirichlet));
  PetscCall(VecDestroy(&sd.uD));
  PetscCall(MatDestroy(&sd.Kreg));
  PetscCall(MatDestroy(&sd.correction));
  sd.factor  = nullptr; /* the KSP's */
  sd.ffactor = FETIFloatFactor();
  PetscCallCXX(std::vector<PetscScalar>().swap(sd.work));
  PetscCall(KSPDestroy(&sd.ksp));
  PetscCall(VecDestroy(&sd.x));
  PetscCall(VecDestroy(&sd.y));
  PetscCall(VecDestroy(&sd.xa));
  PetscCall(VecDestroy(&sd.ya));
  PetscCall(ISDestroy(&sd.boundary));
  PetscCall(ISDestroy(&sd.interior));
  PetscCall(MatDestroy(&sd.Fii));
  sd.fii = FETIFloatFactor();
  PetscCallCXX(std::vector<PetscInt>().swap(sd.iimap));
  PetscCallCXX(std::vector<PetscScalar>().swap(sd.iiwork));
  PetscCall(VecDestroy(&sd.wi));
  PetscCall(VecDestroy(&sd.wi2));
  PetscCall(MatDestroy(&sd.Kbi));
  PetscCall(VecDestroy(&sd.xi));
  PetscCall(VecDestroy(&sd.yi));
  PetscCall(VecDestroy(&sd.yb));
  PetscCall(MatDestroy(&sd.Kplusbb));
  PetscCall(VecDestroy(&sd.kx));
  PetscCall(VecDestroy(&sd.ky));
  PetscFunctionReturn(PETSC_SUCCESS);
}
