/* Explicit K+ on the dofs touched by B (-feti_kplus explicit, or auto where it pays: fetimemory.cxx).

   F = B K+ B' only needs the rows and columns of K+ at the dofs that B touches (the subdomain's
   "interface": gluing and contact dofs). When that set is small, the dense block (K+)_bb applied
   by one matrix-vector product reads far less memory than the two sparse triangular solves of
   K+ (the brick of the seed paper: 1.6M factor entries per subdomain against at most 1500^2/2
   useful dense entries), so every F product is cheaper; building it costs |b| solves with many
   right-hand sides at once (BLAS 3) at setup, or (with MUMPS) one extra factorization that keeps the
   Schur complement on b and a dense inversion. K+ x itself (primal recovery, h) keeps the factor. */
#include <conefeti/private/fetiimpl.h>

#include <algorithm>
#include <type_traits>

/* BLAS dsymv reads one triangle: half the memory traffic of a general product (the product is memory bound) */
extern "C" void dsymv_(const char *, const PetscBLASInt *, const double *, const double *, const PetscBLASInt *, const double *, const PetscBLASInt *, const double *, double *, const PetscBLASInt *);
static_assert(std::is_same<PetscScalar, double>::value, "the explicit K+ blocks call BLAS dsymv: real double precision PETSc only");

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

/* Is there a dof that is neither in kb nor removed? Without one (a subdomain so thin that B touches every node:
   fewer than two cells across) the "interior" MUMPS would eliminate before its Schur complement on kb is only
   removed dofs, decoupled in Kreg (rows and columns d*I): the Schur complement is Kreg_bb itself, and MUMPS,
   asked for a Schur complement of almost the whole matrix, underestimates its workspace (INFOG(1) = -8) by far.
   Such a block is best built by solves with the subdomain's own factor. */
static PetscErrorCode HasInterior(const FETISubdomain &sd, const std::vector<PetscInt> &kb, PetscBool *has)
{
  std::vector<char> covered;

  PetscFunctionBegin;
  PetscCallCXX(covered.assign(sd.n, 0));
  for (PetscInt k : kb) covered[k] = 1;
  for (PetscInt r : sd.removed) covered[r] = 1;
  *has = PETSC_FALSE;
  for (PetscInt k = 0; k < sd.n && !*has; k++)
    if (!covered[k]) *has = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Before the subdomain's factorization: when it is MUMPS, ask it to keep the Schur complement on the
   dofs B touches (Dirichlet dofs excluded; fixing dofs included, their rows are zeroed afterwards) */
PetscErrorCode FETISubdomainSetSchurDofs(FETI feti, FETISubdomain &sd)
{
  FETI_Impl         &impl = *feti->impl;
  PC                 pc;
  Mat                factor;
  MatSolverType      type;
  PetscBool          mumps;
  IS                 is;
  const PetscScalar *mask;
  std::vector<char>  isD(sd.n, 0);
  PetscBool          interior;

  PetscFunctionBegin;
  sd.schurfactor = PETSC_FALSE;
  if (!impl.kplusexplicit || !impl.kplusschur || sd.kplusimplicit) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(KSPGetPC(sd.ksp, &pc));
  PetscCall(PCFactorGetMatSolverType(pc, &type));
  PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &mumps));
  if (!mumps) PetscFunctionReturn(PETSC_SUCCESS); /* FETISetUpExplicitKplus() builds the blocks later */
  for (PetscInt d : sd.dirichletdofs) isD[d] = 1;
  sd.kb.clear();
  PetscCall(VecGetArrayRead(impl.boundarymask, &mask));
  for (PetscInt k = 0; k < sd.n; k++)
    if (mask[sd.localoffset + k] != 0.0 && !isD[k]) PetscCallCXX(sd.kb.push_back(k));
  PetscCall(VecRestoreArrayRead(impl.boundarymask, &mask));
  PetscCall(HasInterior(sd, sd.kb, &interior));
  if (sd.kb.empty() || !interior) PetscFunctionReturn(PETSC_SUCCESS); /* FETISetUpExplicitKplus() builds the blocks by solves */
  PetscCall(PCFactorSetUpMatSolverType(pc));
  PetscCall(PCFactorGetMatrix(pc, &factor));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)sd.kb.size(), sd.kb.data(), PETSC_COPY_VALUES, &is));
  PetscCall(MatFactorSetSchurIS(factor, is));
  PetscCall(ISDestroy(&is));
  sd.schurfactor = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Symmetrize (K+)_bb exactly (so that F is) and zero the rows and columns of removed dofs (K+ is zero there) */
/* S^-1 in place. A zero pivot there means the regularized K_s is not positive definite on its interface: an
   indefinite K_s (an element of negative stiffness), which the sparse factorizations let through, or one singular
   beyond its kernel. PETSc's own message names a dense Cholesky deep in the call stack: name the subdomain */
static PetscErrorCode InvertSchur(Mat factor, PetscInt s)
{
  PetscErrorCode ierr;

  PetscFunctionBegin;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = MatFactorInvertSchurComplement(factor);
  PetscCall(PetscPopErrorHandler());
  PetscCheck(!ierr, PETSC_COMM_SELF, PETSC_ERR_MAT_CH_ZRPVT,
             "Subdomain %" PetscInt_FMT ": its explicit (K+)_bb failed: the Schur complement of the regularized K_s on the subdomain's interface is not positive definite (PETSc error %d): K_s is "
             "indefinite (a negative stiffness?) or singular beyond its kernel; -feti_kplus implicit skips the block but FETI needs a positive semidefinite K_s",
             s, (int)ierr);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode FinishBlock(FETISubdomain &sd)
{
  const PetscInt    nb = (PetscInt)sd.kb.size();
  std::vector<char> removed(sd.n, 0);
  PetscScalar      *s;
  PetscInt          lda;

  PetscFunctionBegin;
  for (PetscInt r : sd.removed) removed[r] = 1;
  PetscCall(MatDenseGetLDA(sd.Kplusbb, &lda));
  PetscCall(MatDenseGetArray(sd.Kplusbb, &s));
  for (PetscInt j = 0; j < nb; j++)
    for (PetscInt i = j + 1; i < nb; i++) {
      const PetscScalar a    = 0.5 * (s[(size_t)j * lda + i] + s[(size_t)i * lda + j]);
      s[(size_t)j * lda + i] = s[(size_t)i * lda + j] = a;
    }
  for (PetscInt j = 0; j < nb; j++)
    if (removed[sd.kb[j]])
      for (PetscInt i = 0; i < nb; i++) s[(size_t)j * lda + i] = s[(size_t)i * lda + j] = 0;
  PetscCall(MatDenseRestoreArray(sd.Kplusbb, &s));
  PetscCall(MatCreateVecs(sd.Kplusbb, &sd.kx, &sd.ky));
  PetscCall(PetscInfo(NULL, "Explicit (K+)_bb on %" PetscInt_FMT " of the subdomain's %" PetscInt_FMT " dofs: %.1f MB\n", nb, sd.n, (double)nb * (double)lda * sizeof(PetscScalar) / 1048576.0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* After the factorization kept the Schur complement S on kb: (K+)_bb = S^-1, inverted in place and shared
   with the factor rather than copied (a copy of a block this size costs setup time in page faults alone).
   The factor's own solves use it too; FinishBlock() changes nothing they see: symmetrizing moves entries
   by rounding, and K+ zeroes the removed dofs of its input and output anyway. */
PetscErrorCode FETISubdomainExplicitKplusFromSchur(FETISubdomain &sd, PetscInt s)
{
  PC                   pc;
  Mat                  factor, S;
  MatFactorSchurStatus status;
  PetscBool            dense;

  PetscFunctionBegin;
  if (!sd.schurfactor) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(KSPGetPC(sd.ksp, &pc));
  PetscCall(PCFactorGetMatrix(pc, &factor));
  PetscCall(InvertSchur(factor, s));
  PetscCall(MatDestroy(&sd.Kplusbb));
  PetscCall(MatFactorGetSchurComplement(factor, &S, &status));
  PetscCall(PetscObjectTypeCompare((PetscObject)S, MATSEQDENSE, &dense));
  if (dense) {
    PetscCall(PetscObjectReference((PetscObject)S));
    sd.Kplusbb = S;
  } else PetscCall(MatConvert(S, MATSEQDENSE, MAT_INITIAL_MATRIX, &sd.Kplusbb));
  PetscCall(MatFactorRestoreSchurComplement(factor, &S, status));
  PetscCall(FinishBlock(sd));
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
  if (sd.ffactor.nb) { /* the factor is a float copy (-feti_kplus_precision single): column by column, refined to double accuracy */
    Vec e, x;
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, nb, nb, NULL, &sd.Kplusbb));
    PetscCall(MatDenseGetArrayWrite(sd.Kplusbb, &s));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, sd.n, &e));
    PetscCall(VecDuplicate(e, &x));
    for (PetscInt j = 0; j < nb; j++) {
      const PetscScalar *xa;
      PetscCall(VecSet(e, 0.0));
      PetscCall(VecSetValue(e, sd.kb[j], 1.0, INSERT_VALUES));
      PetscCall(VecAssemblyBegin(e));
      PetscCall(VecAssemblyEnd(e));
      PetscCall(FETISubdomainApplyKplus(sd, e, x, PETSC_TRUE));
      PetscCall(VecGetArrayRead(x, &xa));
      for (PetscInt i = 0; i < nb; i++) s[(size_t)j * nb + i] = xa[sd.kb[i]];
      PetscCall(VecRestoreArrayRead(x, &xa));
    }
    PetscCall(VecDestroy(&e));
    PetscCall(VecDestroy(&x));
    PetscCall(MatDenseRestoreArrayWrite(sd.Kplusbb, &s));
    PetscCall(FinishBlock(sd));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
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
    for (PetscInt j = 0; j < nc; j++) e[(size_t)j * sd.n + FETISubdomainFactorRow(sd, sd.kb[j0 + j])] = 1.0; /* the factor may be of Kreg permuted */
    PetscCall(MatDenseRestoreArrayWrite(E, &e));
    PetscCall(MatMatSolve(factor, E, X));
    PetscCall(MatDenseGetArrayRead(X, &x));
    for (PetscInt j = 0; j < nc; j++)
      for (PetscInt i = 0; i < nb; i++) s[(size_t)(j0 + j) * nb + i] = x[(size_t)j * sd.n + FETISubdomainFactorRow(sd, sd.kb[i])];
    PetscCall(MatDenseRestoreArrayRead(X, &x));
  }
  PetscCall(MatDenseRestoreArrayWrite(sd.Kplusbb, &s));
  PetscCall(MatDestroy(&E));
  PetscCall(MatDestroy(&X));
  PetscCall(FinishBlock(sd));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the Schur dofs on a fresh MUMPS factor: before the first attempt and before every retry with more workspace */
struct SchurISContext {
  KSP ksp;
  IS  is;
};

static PetscErrorCode SetSchurIS(void *ctx)
{
  SchurISContext *c = static_cast<SchurISContext *>(ctx);
  PC              pc;
  Mat             factor;
  MatSolverType   type;
  PetscBool       mumps;
  const char     *prefix;

  PetscFunctionBegin;
  PetscCall(KSPGetPC(c->ksp, &pc));
  PetscCall(PCFactorGetMatSolverType(pc, &type));
  PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &mumps));
  PetscCall(KSPGetOptionsPrefix(c->ksp, &prefix));
  PetscCheck(mumps, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "-%spc_factor_mat_solver_type %s: the Schur complement for the explicit (K+)_bb needs mumps", prefix ? prefix : "", type ? type : "");
  PetscCall(PCFactorSetUpMatSolverType(pc));
  PetscCall(PCFactorGetMatrix(pc, &factor));
  PetscCall(MatFactorSetSchurIS(factor, c->is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* When the subdomain factor is not MUMPS: (K+)_bb = S^-1 from a second, MUMPS, factorization (options prefix
   feti_schur_) that keeps the Schur complement S on b, and a dense inversion; cheaper than |b| solves with the
   factor. It goes through FETIKSPSetUpFactorization(), so a MUMPS workspace estimate that is too small is
   raised and the factorization repeated, as for every other factorization. */
static PetscErrorCode SubdomainExplicitKplusBySchur(FETI feti, FETISubdomain &sd, PetscInt s)
{
  const PetscInt nb = (PetscInt)sd.kb.size();
  const char    *fetiprefix;
  char           prefix[256];
  PC             pc;
  Mat            factor, S;
  SchurISContext ctx;
  PetscBool      failed;

  PetscFunctionBegin;
  PetscCall(MatDestroy(&sd.Kplusbb));
  PetscCall(VecDestroy(&sd.kx));
  PetscCall(VecDestroy(&sd.ky));
  if (!nb) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)feti, &fetiprefix));
  PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "%sfeti_schur_", fetiprefix ? fetiprefix : ""));
  PetscCall(KSPCreate(PETSC_COMM_SELF, &ctx.ksp));
  PetscCall(KSPSetOptionsPrefix(ctx.ksp, prefix));
  PetscCall(KSPSetType(ctx.ksp, KSPPREONLY));
  PetscCall(KSPSetOperators(ctx.ksp, sd.Kreg, sd.Kreg));
  PetscCall(KSPGetPC(ctx.ksp, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSetFromOptions(ctx.ksp));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nb, sd.kb.data(), PETSC_USE_POINTER, &ctx.is));
  PetscCall(SetSchurIS(&ctx));
  PetscCall(FETIKSPSetUpFactorization(feti, ctx.ksp, SetSchurIS, &ctx, &failed));
  PetscCheck(!failed, PETSC_COMM_SELF, PETSC_ERR_CONV_FAILED,
             "Subdomain %" PetscInt_FMT
             ": the MUMPS factorization that gives the Schur complement for the explicit (K+)_bb met a zero pivot: the regularized K_s is singular (a disconnected subdomain, a "
             "mechanism?)",
             s);
  PetscCall(PCFactorGetMatrix(pc, &factor));
  PetscCall(InvertSchur(factor, s));
  PetscCall(MatFactorCreateSchurComplement(factor, &S, NULL));
  PetscCall(MatConvert(S, MATSEQDENSE, MAT_INITIAL_MATRIX, &sd.Kplusbb));
  PetscCall(MatDestroy(&S));
  PetscCall(KSPDestroy(&ctx.ksp));
  PetscCall(ISDestroy(&ctx.is));
  PetscCall(FinishBlock(sd));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Build (K+)_bb for every local subdomain; after the factorizations and B are set up. With -feti_kplus auto,
   first choose (FETIChooseKplusBlocks(): every subdomain's block against the factor just built, by the reads an
   F product saves and the memory, the same choice on any number of ranks); the chosen blocks come from a second,
   transient, MUMPS factorization (or solves with the factor), so that the subdomain keeps only its own factor
   and the block, not MUMPS's factor and workspace as well. */
PetscErrorCode FETISetUpExplicitKplus(FETI feti)
{
  FETI_Impl         &impl = *feti->impl;
  const PetscScalar *mask;
  const PetscBool    autochoice = impl.kplustype == FETI_KPLUS_AUTO ? PETSC_TRUE : PETSC_FALSE;
  PetscInt           counts[2]  = {0, 0}; /* auto: subdomains with a block, subdomains that keep the factor for F */
  double             entries[2] = {0, 0}; /* auto: factor entries, block entries */
  std::vector<char>  chosen;              /* auto: the local subdomains that get a block */

  PetscFunctionBegin;
  PetscCall(FETISetUpBoundaryMask(feti));
  PetscCall(VecGetArrayRead(impl.boundarymask, &mask));
  if (autochoice) {
    std::vector<PetscInt>  gidx;
    std::vector<PetscReal> nb, fentries, freads;
    for (size_t s = 0; s < impl.sub.size(); s++) {
      FETISubdomain &sd = impl.sub[s];
      PetscReal      e, r;
      PetscBool      measured;
      PetscCall(BoundaryDofs(sd, mask, sd.kb));
      PetscCall(FETISubdomainKplusCosts(feti, sd, &e, &r, &measured));
      PetscCallCXX(gidx.push_back(impl.firstsub + (PetscInt)s));
      PetscCallCXX(nb.push_back((PetscReal)sd.kb.size()));
      PetscCallCXX(fentries.push_back(e));
      PetscCallCXX(freads.push_back(r));
      entries[0] += e;
    }
    PetscCall(FETIChooseKplusBlocks(feti, gidx, nb, fentries, freads, chosen));
  }
  for (size_t s = 0; s < impl.sub.size(); s++) {
    FETISubdomain &sd    = impl.sub[s];
    PetscBool      mumps = PETSC_FALSE, interior;
    if (s) PetscCall(ConeFETIProgressStep_Private(impl.progress, (PetscInt)s)); /* the ones before are done */
    if (autochoice) {
      if (sd.kb.empty()) { /* B does not touch it: nothing to apply for F */
        sd.kplusimplicit = PETSC_FALSE;
        continue;
      }
      sd.kplusimplicit = chosen[s] ? PETSC_FALSE : PETSC_TRUE;
      counts[chosen[s] ? 0 : 1]++;
      if (!chosen[s]) {
        PetscCallCXX(std::vector<PetscInt>().swap(sd.kb));
        continue;
      }
      entries[1] += (double)sd.kb.size() * (double)sd.kb.size();
    } else {
      if (sd.schurfactor || sd.kplusimplicit) continue; /* built with the subdomain's factorization, or not at all (F uses the factor) */
      PetscCall(BoundaryDofs(sd, mask, sd.kb));
    }
    PetscCall(HasInterior(sd, sd.kb, &interior));
    if (impl.kplusschur && interior) PetscCall(MatGetFactorAvailable(sd.Kreg, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, &mumps));
    if (mumps) PetscCall(SubdomainExplicitKplusBySchur(feti, sd, impl.firstsub + (PetscInt)s));
    else PetscCall(SubdomainExplicitKplusBySolves(sd));
  }
  PetscCall(ConeFETIProgressStep_Private(impl.progress, (PetscInt)impl.sub.size()));
  PetscCall(VecRestoreArrayRead(impl.boundarymask, &mask));
  if (autochoice) {
    MPI_Comm comm = PetscObjectComm((PetscObject)feti);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, entries, 2, MPI_DOUBLE, MPI_SUM, comm));
    impl.nkplusblocks       = counts[0];
    impl.nkplusimplicit     = counts[1];
    impl.kplusfactorentries = entries[0];
    impl.kplusblockentries  = entries[1];
    PetscCall(PetscInfo(feti,
                        "-feti_kplus auto: dense blocks (K+)_bb in %" PetscInt_FMT " of %" PetscInt_FMT " subdomains (%.1f MB), the factor for F in %" PetscInt_FMT " (factors: %.1f MB of entries)\n",
                        counts[0], impl.nglobalsub, 8.0 * entries[1] / 1048576.0, counts[1], 8.0 * entries[0] / 1048576.0));
    if (!counts[0]) impl.kplusexplicit = PETSC_FALSE; /* no block anywhere: the plain products with the factors, as -feti_kplus implicit */
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = K+ x for x supported on the dofs touched by B; y is exact on those dofs (zero elsewhere, except in the
   subdomains that keep their factor for F, where it is K+ x everywhere) */
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
    const PetscInt     nb  = (PetscInt)sd.kb.size();
    const PetscScalar  one = 1.0, zero = 0.0;
    const PetscScalar *k;
    PetscScalar       *a, *b;
    PetscBLASInt       bn, blda, inc = 1;
    PetscInt           lda;
    if (sd.kplusimplicit) { /* two triangular solves with the factor, as FETIApplyKplus() */
      PetscCall(VecPlaceArray(sd.xa, xa + sd.localoffset));
      PetscCall(VecPlaceArray(sd.ya, ya + sd.localoffset));
      PetscCall(FETISubdomainApplyKplus(sd, sd.xa, sd.ya, impl.kplusrefine));
      PetscCall(VecResetArray(sd.xa));
      PetscCall(VecResetArray(sd.ya));
      continue;
    }
    if (!nb) continue;
    PetscCall(PetscBLASIntCast(nb, &bn));
    PetscCall(MatDenseGetLDA(sd.Kplusbb, &lda));
    PetscCall(PetscBLASIntCast(lda, &blda));
    PetscCall(VecGetArrayWrite(sd.kx, &a));
    PetscCall(VecGetArrayWrite(sd.ky, &b));
    for (PetscInt i = 0; i < nb; i++) a[i] = xa[sd.localoffset + sd.kb[i]];
    PetscCall(MatDenseGetArrayRead(sd.Kplusbb, &k));
    dsymv_("L", &bn, &one, k, &blda, a, &inc, &zero, b, &inc);
    PetscCall(MatDenseRestoreArrayRead(sd.Kplusbb, &k));
    PetscCall(PetscLogFlops(2.0 * nb * nb));
    for (PetscInt i = 0; i < nb; i++) ya[sd.localoffset + sd.kb[i]] = b[i];
    PetscCall(VecRestoreArrayWrite(sd.kx, &a));
    PetscCall(VecRestoreArrayWrite(sd.ky, &b));
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(PetscLogEventEnd(FETI_ApplyKplus, feti, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
