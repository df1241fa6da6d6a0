/* The FETI operators as MATSHELLs (created by FETISetUp(), feti.cxx):
     K+  primal -> primal  block diagonal generalized inverse
     F   dual -> dual      B K+ B' (one B' product, one solve per subdomain, one B product; never formed)
     G   dual -> coarse    R'B' (a B' product, then R' on the rows of R at the dofs B touches; never formed)
     P   dual -> dual      I - Gt (G Gt)^-1 G, the orthogonal projector onto Ker G
     Q   dual -> dual      I - P
   The coarse matrix G G' is assembled from Gt = B R and factorized once; Gt is not kept. The products
   with B and B' sum in a fixed order (fetirowsum.cxx), so that every operator gives the same bits on
   any number of ranks. */
#include <conefeti/private/fetiimpl.h>

#include <algorithm>
#include <cstring>

static PetscErrorCode ShellGetFETI(Mat A, FETI *feti)
{
  PetscFunctionBegin;
  PetscCall(MatShellGetContext(A, feti));
  if (!*feti) { /* FETIReset() took it away */
    const char *name;
    PetscCall(PetscObjectGetName((PetscObject)A, &name));
    SETERRQ(PetscObjectComm((PetscObject)A), PETSC_ERR_ARG_WRONGSTATE,
            "FETI operator %s: its FETI object was destroyed (or given new subdomains); keep the FETI object as long as its operators are used (a ContactProblem's solves)", name);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIFromMat - internal: the FETI object behind one of its shell operators (used by the FETI preconditioners)
@*/
PetscErrorCode FETIFromMat(Mat A, FETI *feti)
{
  PetscErrorCode (*f)(Mat, FETI *) = NULL;

  PetscFunctionBegin;
  *feti = NULL;
  PetscCall(PetscObjectQueryFunction((PetscObject)A, "FETIShellGetFETI_C", &f));
  if (f) PetscCall(f(A, feti));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = K+ x on the global primal vectors, subdomain by subdomain. exact: K+ of K_s to double accuracy even where the
   factor is stored in float (-feti_kplus_precision single: refined against Kreg); else the F products' K+ */
PetscErrorCode FETIApplyKplus(FETI feti, Vec x, Vec y, PetscBool exact)
{
  FETI_Impl         &impl = *feti->impl;
  const PetscScalar *xa;
  PetscScalar       *ya;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(FETI_ApplyKplus, feti, 0, 0, 0));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  for (FETISubdomain &sd : impl.sub) {
    PetscCall(VecPlaceArray(sd.xa, xa + sd.localoffset));
    PetscCall(VecPlaceArray(sd.ya, ya + sd.localoffset));
    PetscCall(FETISubdomainApplyKplus(sd, sd.xa, sd.ya, exact));
    PetscCall(VecResetArray(sd.xa));
    PetscCall(VecResetArray(sd.ya));
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(PetscLogEventEnd(FETI_ApplyKplus, feti, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIApplyK - Multiply a primal vector by the block-diagonal stiffness matrix K (on the primal space: Dirichlet dofs kept in the primal are zero in and out).

  Collective

  Input Parameters:
+ feti - the FETI problem, set up
- x    - primal vector

  Output Parameter:
. y - K x

  Notes:
  For equilibrium residuals K u - f + B' lambda after primal recovery.

  Level: intermediate

.seealso: `FETIRecoverPrimal()`, `FETIGetLoad()`
@*/
PetscErrorCode FETIApplyK(FETI feti, Vec x, Vec y)
{
  const PetscScalar *xa;
  PetscScalar       *ya;

  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  FETI_Impl &impl = *feti->impl;
  PetscValidHeaderSpecific(x, VEC_CLASSID, 2);
  PetscValidHeaderSpecific(y, VEC_CLASSID, 3);
  PetscCheck(impl.setupcalled, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER, "Call FETISetUp() first");
  PetscCall(FETICheckVec_Private(feti, x, FETI_VEC_PRIMAL, "FETIApplyK", "x"));
  PetscCall(FETICheckVec_Private(feti, y, FETI_VEC_PRIMAL, "FETIApplyK", "y"));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  for (FETISubdomain &sd : impl.sub) {
    PetscCall(VecPlaceArray(sd.xa, xa + sd.localoffset));
    PetscCall(VecPlaceArray(sd.ya, ya + sd.localoffset));
    PetscCall(FETISubdomainApplyK(sd, sd.xa, sd.ya));
    PetscCall(VecResetArray(sd.xa));
    PetscCall(VecResetArray(sd.ya));
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIApplyCoarseInverse - Solve the coarse problem (G G') y = x.

  Collective

  Input Parameters:
+ feti - the FETI problem, set up
- x    - coarse vector

  Output Parameter:
. y - (G G')^-1 x

  Notes:
  With -feti_coarse_refine steps (chosen at setup unless given: none on a well-conditioned G G'), each solve is
  followed by that many steps of iterative refinement, y += (G G')^-1 (x - G (G' y)), each one more coarse solve in
  `FETIGetCoarseSolveCount()`; x and y must then be different vectors.

  Level: developer

.seealso: `FETIGetOperators()`, `FETIGetCoarseSolveCount()`
@*/
PetscErrorCode FETIApplyCoarseInverse(FETI feti, Vec x, Vec y)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  FETI_Impl &impl = *feti->impl;
  PetscCheck(impl.setupcalled, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER, "Call FETISetUp() first");
  if (!impl.ncoarse) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(x != y || !impl.coarsesteps, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_IDN, "FETIApplyCoarseInverse(): x and y must differ when the solves are refined (-feti_coarse_refine)");
  PetscCall(PetscLogEventBegin(FETI_CoarseSolve, feti, 0, 0, 0));
  impl.ncoarsesolves++;
  PetscCall(FETICoarseSolverApply(impl.coarse, x, y));
  /* iterative refinement with the residual through G' and G (SetUpCoarseRefinement(), feti.cxx): on a long chain of
     subdomains the factors' residual, rounding of |G G'| |y|, is far above the rounding of |G' y| that P needs */
  for (PetscInt k = 0; k < impl.coarsesteps; k++) {
    PetscCall(FETIApplyGt(feti, y, impl.wdr));
    PetscCall(FETIApplyG(feti, impl.wdr, impl.wcr));
    PetscCall(VecAYPX(impl.wcr, -1.0, x));
    impl.ncoarsesolves++;
    PetscCall(FETICoarseSolverApply(impl.coarse, impl.wcr, impl.wcdy));
    PetscCall(VecAXPY(y, 1.0, impl.wcdy));
  }
  PetscCall(PetscLogEventEnd(FETI_CoarseSolve, feti, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The rows of R that G = R'B' and G' = B R need. B' x vanishes outside the dofs B touches (the rows of B'
   with entries), and B reads R x only there: at H/h = 6 almost half of the primal dofs (the interior ones and
   those on a free surface; 45% on the brick) are not touched, and the
   products with all of R (MatMultTranspose() above all, ~11 ms at 10^6 unknowns, three or four times per
   Hessian product) read them for nothing. The rows kept are a copy of those rows of R's diagonal block (R
   is block diagonal: no entry outside it), and the products below add in PETSc's order, so G and G' give
   the same bits as MatMultTranspose() and MatMult() of R: R' adds row after row into each column (a row
   skipped holds a zero of B' x, and adding zeros changes no sum), and R's product sums each row from
   the first column, in pairs when PETSc's inode kernel does (consecutive rows with the same columns, which
   R's rows within a subdomain have). Anything else (R's off-diagonal block not empty) keeps PETSc's products. */
static PetscErrorCode FETISetUpCoarseRows(FETI feti)
{
  FETI_Impl      &impl = *feti->impl;
  Mat             Rd = impl.R, Ro = nullptr, Btd = impl.Btsum.Ad, Bto = impl.Btsum.Ao;
  const PetscInt *ria, *rja, *bia, *oia                               = nullptr, *garray;
  PetscScalar    *rv, *bv;
  PetscBool       mpi;
  PetscInt        m, ocols = 0, nodes = 0, *sizes = nullptr, limit;

  PetscFunctionBegin;
  if (impl.growsset) PetscFunctionReturn(PETSC_SUCCESS);
  impl.growsset = PETSC_TRUE;
  PetscCall(PetscObjectBaseTypeCompare((PetscObject)impl.R, MATMPIAIJ, &mpi));
  if (mpi) PetscCall(MatMPIAIJGetSeqAIJ(impl.R, &Rd, &Ro, &garray));
  if (Ro) PetscCall(MatGetLocalSize(Ro, NULL, &ocols));
  if (ocols) { /* not block diagonal: PETSc's products (every rank takes part in the rigid rows' decision) */
    PetscCall(FETISetUpRigidRows(feti, NULL, 0));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(MatGetLocalSize(Rd, &m, NULL));
  PetscCall(MatSeqAIJGetCSRAndMemType(Rd, &ria, &rja, &rv, NULL));
  PetscCall(MatSeqAIJGetCSRAndMemType(Btd, &bia, NULL, &bv, NULL));
  if (Bto) PetscCall(MatSeqAIJGetCSRAndMemType(Bto, &oia, NULL, &bv, NULL));
  PetscCall(MatInodeGetInodeSizes(Rd, &nodes, &sizes, &limit)); /* no inodes in use: 0 nodes */
  impl.gpairs = nodes > 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscCallCXX(impl.gptr.assign(1, 0));
  for (PetscInt i = 0; i < m; i++) {
    if (bia[i + 1] == bia[i] && (!oia || oia[i + 1] == oia[i])) continue; /* B touches no entry of this dof */
    PetscCallCXX(impl.grows.push_back(i));
    for (PetscInt k = ria[i]; k < ria[i + 1]; k++) {
      PetscCallCXX(impl.gcols.push_back(rja[k]));
      PetscCallCXX(impl.gvals.push_back(rv[k]));
    }
    PetscCallCXX(impl.gptr.push_back((PetscInt)impl.gcols.size()));
  }
  /* R's rows within a subdomain hold its k <= 6 consecutive coarse columns: then only the first is kept, and the
     products read 8 bytes per entry instead of 12 (they are memory-bound: ~13 ms per G at 10^6 unknowns) */
  {
    const PetscInt nrows  = (PetscInt)impl.grows.size();
    PetscBool      contig = PETSC_TRUE;
    for (PetscInt t = 0; t < nrows && contig; t++)
      for (PetscInt k = impl.gptr[t]; k < impl.gptr[t + 1]; k++)
        if (impl.gcols[k] != impl.gcols[impl.gptr[t]] + (k - impl.gptr[t])) {
          contig = PETSC_FALSE;
          break;
        }
    if (contig && nrows) {
      PetscCallCXX(impl.gfirst.resize(nrows));
      for (PetscInt t = 0; t < nrows; t++) impl.gfirst[t] = impl.gptr[t + 1] > impl.gptr[t] ? impl.gcols[impl.gptr[t]] : 0;
      PetscCallCXX(std::vector<PetscInt>().swap(impl.gcols));
    }
  }
  {
    PetscInt cstart;
    PetscCall(MatGetOwnershipRangeColumn(impl.R, &cstart, NULL));
    PetscCall(FETISetUpRigidRows(feti, Rd, cstart));
  }
  if (impl.rigid.use) {
    PetscCall(PetscInfo(feti, "G and G' through the rigid-body modes of %zu nodes (%zu of %" PetscInt_FMT " local rows of R touched by B): coordinates and a 6 x k transform per subdomain\n",
                        impl.rigid.nodebase.size(), impl.grows.size(), m));
    for (auto *v : {&impl.gptr, &impl.gcols, &impl.gfirst}) PetscCallCXX(std::vector<PetscInt>().swap(*v));
    PetscCallCXX(std::vector<PetscScalar>().swap(impl.gvals));
  } else
    PetscCall(PetscInfo(feti, "G and G' through %zu of %" PetscInt_FMT " local rows of R (the dofs B touches), %s%s\n", impl.grows.size(), m,
                        impl.gpairs ? "rows summed in pairs (inode)" : "rows summed in order", impl.gfirst.empty() ? "" : ", consecutive columns"));
  if (impl.grows.empty()) PetscCallCXX(impl.gptr.clear());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = G x = R'(B' x): R is block diagonal, so R' sums within each subdomain, in its dof order */
PetscErrorCode FETIApplyG(FETI feti, Vec x, Vec y)
{
  FETI_Impl &impl = *feti->impl;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(FETI_ApplyG, feti, 0, 0, 0));
  PetscCall(FETISetUpCoarseRows(feti));
  if (impl.rigid.use) {
    const PetscScalar *w;
    PetscScalar       *ya;
    /* B' x at every dof of the touched nodes (its other rows are empty: 0 there) */
    PetscCall(FETIRowSumApplyRows(impl.Btsum, x, (PetscInt)impl.rigid.rows.size(), impl.rigid.rows.data(), impl.wp3));
    PetscCall(VecSet(y, 0.0));
    PetscCall(VecGetArrayRead(impl.wp3, &w));
    PetscCall(VecGetArray(y, &ya));
    PetscCall(FETIRigidRowsApplyRt(feti, w, ya));
    PetscCall(VecRestoreArray(y, &ya));
    PetscCall(VecRestoreArrayRead(impl.wp3, &w));
  } else if (impl.gptr.empty()) {
    PetscCall(FETIRowSumApply(impl.Btsum, x, impl.wp3));
    PetscCall(MatMultTranspose(impl.R, impl.wp3, y));
  } else {
    const PetscScalar *w;
    PetscScalar       *ya;
    /* B' x only at the dofs B touches (its other rows are empty): the only ones read below */
    PetscCall(FETIRowSumApplyRows(impl.Btsum, x, (PetscInt)impl.grows.size(), impl.grows.data(), impl.wp3));
    PetscCall(VecSet(y, 0.0));
    PetscCall(VecGetArrayRead(impl.wp3, &w));
    PetscCall(VecGetArray(y, &ya));
    const PetscInt nrows = (PetscInt)impl.grows.size();
    if (impl.gfirst.empty())
      for (PetscInt t = 0; t < nrows; t++) {
        const PetscScalar a = w[impl.grows[t]];
        for (PetscInt k = impl.gptr[t]; k < impl.gptr[t + 1]; k++) ya[impl.gcols[k]] += a * impl.gvals[k];
      }
    else /* the same terms in the same order, the columns counted from the row's first */
      for (PetscInt t = 0; t < nrows; t++) {
        const PetscScalar  a  = w[impl.grows[t]];
        const PetscScalar *v  = impl.gvals.data() + impl.gptr[t];
        PetscScalar       *yc = ya + impl.gfirst[t];
        const PetscInt     n  = impl.gptr[t + 1] - impl.gptr[t];
        for (PetscInt k = 0; k < n; k++) yc[k] += a * v[k];
      }
    PetscCall(VecRestoreArray(y, &ya));
    PetscCall(VecRestoreArrayRead(impl.wp3, &w));
    PetscCall(PetscLogFlops(2.0 * impl.gptr[nrows]));
  }
  PetscCall(PetscLogEventEnd(FETI_ApplyG, feti, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One row of R times x, summed as PETSc's product of R sums it (two terms added to each other, then to the sum,
   when its inode kernel does): the same bits for a rank's own rows and for the ghost rows below */
static inline PetscScalar RowOfRTimes(PetscInt n, const PetscInt *c, const PetscScalar *v, const PetscScalar *xa, PetscBool pairs)
{
  PetscScalar sum = 0;
  PetscInt    k   = 0;
  if (pairs)
    for (; k < n - 1; k += 2) sum += v[k] * xa[c[k]] + v[k + 1] * xa[c[k + 1]];
  for (; k < n; k++) sum += v[k] * xa[c[k]];
  return sum;
}

/* The same for a row whose columns are c0, c0 + 1, ...: the same terms, added in the same order */
static inline PetscScalar ConsecutiveRowOfRTimes(PetscInt n, PetscInt c0, const PetscScalar *v, const PetscScalar *xa, PetscBool pairs)
{
  const PetscScalar *xc  = xa + c0;
  PetscScalar        sum = 0;
  PetscInt           k   = 0;
  if (pairs)
    for (; k < n - 1; k += 2) sum += v[k] * xc[k] + v[k + 1] * xc[k + 1];
  for (; k < n; k++) sum += v[k] * xc[k];
  return sum;
}

/* The rows of R at B's ghost primal columns (Bsum.garray), with global coarse columns. Why: G' x = B (R x), and
   a dual row of this rank reads R x at dofs of other ranks' subdomains, which the product with B receives from
   them (one message of some 40 KB per product at 2 ranks on the brick, 4 per Hessian product). In redundant and
   split mode every rank holds the whole coarse solution x (FETICoarseSolverGetFull()), so it can form R x at those
   dofs itself, with the same rows of R summed in the same order: the same bits, no message. Only when every rank
   takes PETSc-independent products of R (FETISetUpCoarseRows() kept rows) and the coarse solver is redundant or split;
   collective (the first G' product). */
static PetscErrorCode FETISetUpGhostCoarseRows(FETI feti)
{
  FETI_Impl  &impl = *feti->impl;
  MPI_Comm    comm = PetscObjectComm((PetscObject)feti);
  PetscMPIInt size, ok, all;
  PetscInt    nghost = 0;

  PetscFunctionBegin;
  impl.ghostrows = -1;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size == 1 || (impl.coarse.mode != FETI_COARSE_REDUNDANT && impl.coarse.mode != FETI_COARSE_SPLIT) || !impl.Bsum.scatter) PetscFunctionReturn(PETSC_SUCCESS);
  if (impl.rigid.use) { /* the same for every rank: the rigid rows are used on all or on none */
    PetscBool rigidok;
    PetscCall(FETISetUpRigidGhostRows(feti, &rigidok));
    if (!rigidok) PetscFunctionReturn(PETSC_SUCCESS);
    PetscCall(VecGetLocalSize(impl.Bsum.ghosts, &nghost));
    PetscCallCXX(impl.ghbuf.assign(nghost, 0.0));
    impl.ghostrows = 1;
    PetscCall(PetscInfo(feti, "G' in %s coarse mode: R x at the %" PetscInt_FMT " ghost dofs of B from the full coarse solution, without their exchange\n", FETICoarseModes[impl.coarse.mode], nghost));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  ok = impl.gptr.empty() ? 0 : 1;
  PetscCallMPI(MPIU_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, comm));
  if (!all) PetscFunctionReturn(PETSC_SUCCESS);
  {
    IS                 rows, cols;
    Mat               *sub;
    const PetscInt    *ia, *ja;
    const PetscScalar *va;
    PetscScalar       *v;
    PetscCall(VecGetLocalSize(impl.Bsum.ghosts, &nghost));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nghost, impl.Bsum.garray, PETSC_USE_POINTER, &rows));
    PetscCall(ISCreateStride(PETSC_COMM_SELF, impl.ncoarse, 0, 1, &cols));
    PetscCall(MatCreateSubMatrices(impl.R, 1, &rows, &cols, MAT_INITIAL_MATRIX, &sub));
    PetscCall(ISDestroy(&rows));
    PetscCall(ISDestroy(&cols));
    PetscCall(MatSeqAIJGetCSRAndMemType(sub[0], &ia, &ja, &v, NULL));
    va = v;
    PetscCallCXX(impl.ghptr.assign(ia, ia + nghost + 1));
    PetscCallCXX(impl.ghcols.assign(ja, ja + ia[nghost]));
    PetscCallCXX(impl.ghvals.assign(va, va + ia[nghost]));
    PetscCallCXX(impl.ghbuf.assign(nghost, 0.0));
    PetscCall(MatDestroySubMatrices(1, &sub));
  }
  impl.ghostrows = 1;
  PetscCall(PetscInfo(feti, "G' in %s coarse mode: R x at the %" PetscInt_FMT " ghost dofs of B from the full coarse solution, without their exchange\n", FETICoarseModes[impl.coarse.mode], nghost));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = G' x = B (R x); R x only where B reads it */
PetscErrorCode FETIApplyGt(FETI feti, Vec x, Vec y)
{
  FETI_Impl &impl = *feti->impl;
  Vec        full = NULL;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(FETI_ApplyGt, feti, 0, 0, 0));
  PetscCall(FETISetUpCoarseRows(feti));
  if (!impl.ghostrows) PetscCall(FETISetUpGhostCoarseRows(feti));
  /* the same decision on every rank: x is the same collective vector, just solved for (or not) on all of them */
  if (impl.ghostrows > 0) PetscCall(FETICoarseSolverGetFull(impl.coarse, x, &full));
  if (impl.rigid.use && !impl.rigid.compact) PetscCall(FETISetUpRigidCompactColumns(feti));
  /* R x only at the touched nodes, in a compact array, when no ghost value has to be exchanged: one rank, or the
     ghost values formed here from the full coarse solution (after the first product has checked them) */
  const PetscBool compact = impl.rigid.use && impl.rigid.compact > 0 && (!impl.Bsum.scatter || (full && impl.ghostrows == 2)) ? PETSC_TRUE : PETSC_FALSE;
  if (compact) {
    const PetscScalar *xa;
    PetscCall(VecGetArrayRead(x, &xa));
    PetscCall(FETIRigidRowsApplyR(feti, xa, PETSC_TRUE, impl.rigid.wc.data()));
    PetscCall(VecRestoreArrayRead(x, &xa));
  } else if (impl.rigid.use) {
    const PetscScalar *xa;
    PetscScalar       *w;
    PetscCall(VecGetArrayRead(x, &xa));
    PetscCall(VecGetArray(impl.wp3, &w)); /* the dofs outside the touched nodes keep what they held: B never reads them */
    PetscCall(FETIRigidRowsApplyR(feti, xa, PETSC_FALSE, w));
    PetscCall(VecRestoreArray(impl.wp3, &w));
    PetscCall(VecRestoreArrayRead(x, &xa));
  } else if (impl.gptr.empty()) PetscCall(MatMult(impl.R, x, impl.wp3));
  else {
    const PetscScalar *xa;
    PetscScalar       *w;
    const PetscInt     nrows = (PetscInt)impl.grows.size();
    PetscCall(VecGetArrayRead(x, &xa));
    PetscCall(VecGetArray(impl.wp3, &w)); /* the dofs B does not touch keep what they held: B never reads them */
    if (impl.gfirst.empty())
      for (PetscInt t = 0; t < nrows; t++) {
        const PetscInt k0 = impl.gptr[t];
        w[impl.grows[t]]  = RowOfRTimes(impl.gptr[t + 1] - k0, impl.gcols.data() + k0, impl.gvals.data() + k0, xa, impl.gpairs);
      }
    else
      for (PetscInt t = 0; t < nrows; t++) {
        const PetscInt k0 = impl.gptr[t];
        w[impl.grows[t]]  = ConsecutiveRowOfRTimes(impl.gptr[t + 1] - k0, impl.gfirst[t], impl.gvals.data() + k0, xa, impl.gpairs);
      }
    PetscCall(VecRestoreArray(impl.wp3, &w));
    PetscCall(VecRestoreArrayRead(x, &xa));
    PetscCall(PetscLogFlops(2.0 * impl.gptr[nrows]));
  }
  if (full) {
    const PetscScalar *xa;
    const PetscInt     nghost = (PetscInt)impl.ghbuf.size();
    PetscCall(VecGetArrayRead(full, &xa));
    if (impl.rigid.use) PetscCall(FETIRigidRowsApplyGhosts(feti, xa, impl.ghbuf.data()));
    else {
      for (PetscInt t = 0; t < nghost; t++) {
        const PetscInt k0 = impl.ghptr[t];
        impl.ghbuf[t]     = RowOfRTimes(impl.ghptr[t + 1] - k0, impl.ghcols.data() + k0, impl.ghvals.data() + k0, xa, impl.gpairs);
      }
      PetscCall(PetscLogFlops(2.0 * impl.ghptr[nghost]));
    }
    PetscCall(VecRestoreArrayRead(full, &xa));
    if (impl.ghostrows == 1) { /* the first time: the exchange as well, and the local values must be its bits on every rank */
      const PetscScalar *ga;
      PetscMPIInt        same, all;
      PetscCall(FETIRowSumApply(impl.Bsum, impl.wp3, y));
      PetscCall(VecGetArrayRead(impl.Bsum.ghosts, &ga));
      same = nghost == 0 || !std::memcmp(ga, impl.ghbuf.data(), nghost * sizeof(PetscScalar)) ? 1 : 0;
      PetscCall(VecRestoreArrayRead(impl.Bsum.ghosts, &ga));
      PetscCallMPI(MPIU_Allreduce(&same, &all, 1, MPI_INT, MPI_MIN, PetscObjectComm((PetscObject)feti)));
      impl.ghostrows = all ? 2 : -1;
      if (!all) PetscCall(PetscInfo(feti, "G': R x at the ghost dofs differs from the exchanged values in some bit; the exchange stays\n"));
    } else if (compact) PetscCall(FETIRowSumApplyCompact(impl.Bsum, impl.rigid.bcols.data(), impl.rigid.wc.data(), impl.ghbuf.data(), y));
    else PetscCall(FETIRowSumApplyWithGhosts(impl.Bsum, impl.wp3, impl.ghbuf.data(), y));
  } else if (compact) PetscCall(FETIRowSumApplyCompact(impl.Bsum, impl.rigid.bcols.data(), impl.rigid.wc.data(), nullptr, y));
  else PetscCall(FETIRowSumApply(impl.Bsum, impl.wp3, y));
  PetscCall(PetscLogEventEnd(FETI_ApplyGt, feti, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Gt = B R (dual x coarse, AIJ). Each entry sums the few dofs of one subdomain that a row of B
   touches, in their order, so it is the same on any number of ranks. */
PetscErrorCode FETICreateGt(FETI feti, Mat *Gt)
{
  FETI_Impl &impl = *feti->impl;

  PetscFunctionBegin;
  PetscCall(MatMatMult(impl.B, impl.R, MAT_INITIAL_MATRIX, PETSC_DEFAULT, Gt));
  PetscCall(MatProductClear(*Gt)); /* computed once: PETSc would keep the gathered rows of R for a reuse */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* M = G W G' (W = diag(w.^2), w = NULL: the identity), reproducible (FETIAssembleCoarseMatrix()), from
   the Gt that FETIGetGt() keeps, else from a transient one */
PetscErrorCode FETICreateCoarseMatrix(FETI feti, Vec w, Mat *M)
{
  FETI_Impl &impl = *feti->impl;
  Mat        Gt   = impl.Gt;

  PetscFunctionBegin;
  if (!Gt) PetscCall(FETICreateGt(feti, &Gt));
  PetscCall(FETIAssembleCoarseMatrix(Gt, w, M));
  if (Gt != impl.Gt) PetscCall(MatDestroy(&Gt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* v_i in [-1, 1) from splitmix64 of the global index i: a fixed right-hand side that is no combination of anything in
   particular, the same on any number of ranks (the checks that factors of a coarse matrix solve) */
PetscErrorCode FETISetPseudoRandom_Private(Vec v)
{
  PetscInt     lo, hi;
  PetscScalar *a;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(v, &lo, &hi));
  PetscCall(VecGetArrayWrite(v, &a));
  for (PetscInt i = lo; i < hi; i++) {
    unsigned long long z = 0x9E3779B97F4A7C15ULL * (unsigned long long)(i + 1);
    z                    = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z                    = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    a[i - lo] = (PetscScalar)((double)(z >> 11) / 4503599627370496.0 - 1.0);
  }
  PetscCall(VecRestoreArrayWrite(v, &a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = Q x = Gt (G Gt)^-1 G x */
static PetscErrorCode ApplyQ(FETI feti, Vec x, Vec y)
{
  FETI_Impl &impl = *feti->impl;

  PetscFunctionBegin;
  if (!impl.ncoarse) {
    PetscCall(VecSet(y, 0.0));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(FETIApplyG(feti, x, impl.wc1));
  PetscCall(FETIApplyCoarseInverse(feti, impl.wc1, impl.wc2));
  PetscCall(FETIApplyGt(feti, impl.wc2, y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode MatMult_G(Mat A, Vec x, Vec y)
{
  FETI feti;

  PetscFunctionBegin;
  PetscCall(ShellGetFETI(A, &feti));
  PetscCall(FETIApplyG(feti, x, y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode MatMultTranspose_G(Mat A, Vec x, Vec y)
{
  FETI feti;

  PetscFunctionBegin;
  PetscCall(ShellGetFETI(A, &feti));
  PetscCall(FETIApplyGt(feti, x, y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = P x = x - Q x (y may be x) */
PetscErrorCode FETIApplyP(FETI feti, Vec x, Vec y)
{
  FETI_Impl &impl = *feti->impl;

  PetscFunctionBegin;
  PetscCall(ApplyQ(feti, x, impl.wd2));
  if (x == y) PetscCall(VecAXPY(y, -1.0, impl.wd2));
  else PetscCall(VecWAXPY(y, -1.0, impl.wd2, x));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode MatMult_F(Mat A, Vec x, Vec y)
{
  FETI feti;

  PetscFunctionBegin;
  PetscCall(ShellGetFETI(A, &feti));
  FETI_Impl &impl = *feti->impl;
  PetscCall(PetscLogEventBegin(FETI_MultF, feti, 0, 0, 0));
  PetscCall(FETIRowSumApply(impl.Btsum, x, impl.wp1));
  if (impl.kplusexplicit) PetscCall(FETIApplyKplusOnBoundary(feti, impl.wp1, impl.wp2)); /* B' x lives on the dofs B touches */
  else PetscCall(FETIApplyKplus(feti, impl.wp1, impl.wp2, impl.kplusrefine));
  PetscCall(FETIRowSumApply(impl.Bsum, impl.wp2, y));
  PetscCall(PetscLogEventEnd(FETI_MultF, feti, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode MatMult_P(Mat A, Vec x, Vec y)
{
  FETI feti;

  PetscFunctionBegin;
  PetscCall(ShellGetFETI(A, &feti));
  PetscCall(FETIApplyP(feti, x, y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode MatMult_Q(Mat A, Vec x, Vec y)
{
  FETI feti;

  PetscFunctionBegin;
  PetscCall(ShellGetFETI(A, &feti));
  PetscCall(ApplyQ(feti, x, y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode MatMult_Kplus(Mat A, Vec x, Vec y)
{
  FETI feti;

  PetscFunctionBegin;
  PetscCall(ShellGetFETI(A, &feti));
  PetscCall(FETIApplyKplus(feti, x, y, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = P F P x; x and y are distinct */
static PetscErrorCode MatMult_PFP(Mat A, Vec x, Vec y)
{
  FETI feti;

  PetscFunctionBegin;
  PetscCall(ShellGetFETI(A, &feti));
  FETI_Impl &impl = *feti->impl;
  PetscCall(FETIApplyP(feti, x, impl.wd1));
  PetscCall(MatMult(impl.F, impl.wd1, y));
  PetscCall(FETIApplyP(feti, y, y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CreateShell(FETI feti, PetscInt m, PetscInt n, PetscErrorCode (*mult)(Mat, Vec, Vec), const char *name, Mat *A)
{
  PetscFunctionBegin;
  PetscCall(MatCreateShell(PetscObjectComm((PetscObject)feti), m, n, PETSC_DETERMINE, PETSC_DETERMINE, feti, A));
  PetscCall(MatShellSetOperation(*A, MATOP_MULT, (void (*)(void))mult));
  PetscCall(MatShellSetOperation(*A, MATOP_MULT_TRANSPOSE, (void (*)(void))mult)); /* all are symmetric */
  PetscCall(MatSetOption(*A, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(PetscObjectComposeFunction((PetscObject)*A, "FETIShellGetFETI_C", ShellGetFETI));
  PetscCall(PetscObjectSetName((PetscObject)*A, name));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* KSPSetUp() of a direct solver, reporting a failed factorization (zero or negative pivot: a singular
   matrix) through *failed instead of the factorization package's own error, so that the caller can
   say what the singularity means. MUMPS running out of its workspace estimate (it underestimates it for
   small matrices with a large Schur complement: tiny subdomains) is retried with a larger ICNTL(14),
   up to three times (INFOG(1) = -8, -9, ...; not -13, an allocation that failed, nor -19, the ICNTL(23) cap:
   more workspace would not help those); prepare(ctx), when given, redoes what the caller set on the factor before the
   first attempt (the Schur dofs). Any other failure inside the package (an ordering that fails, out of
   memory, a bad package option) is an error that names the options prefix: it says nothing about the
   matrix. */
PetscErrorCode FETIKSPSetUpFactorization(FETI feti, KSP ksp, PetscErrorCode (*prepare)(void *), void *ctx, PetscBool *failed)
{
  PetscErrorCode ierr;
  PC             pc;
  PCFailedReason reason = PC_NOERROR;
  PetscBool      errorif, factorpc, mumps = PETSC_FALSE;
  const char    *prefix;
  const PetscInt max_retries = 3;
  PetscInt       workspace = 0, used = 0; /* ICNTL(14): asked for by the last retry, in effect in the last attempt */
  PetscInt       infog[2] = {0, 0};       /* MUMPS's INFOG(1), INFOG(2) of the last failed attempt */
  PetscBool      given;

  PetscFunctionBegin;
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)pc, &factorpc, PCCHOLESKY, PCLU, ""));
  for (PetscInt attempt = 0;; attempt++) {
    PetscCall(PetscLogEventBegin(FETI_Factorization, feti, 0, 0, 0));
    /* without error-if-failure a zero pivot is a PC failed reason in every package (MUMPS would raise the
       same library error code as for any other failure) */
    PetscCall(KSPGetErrorIfNotConverged(ksp, &errorif));
    PetscCall(KSPSetErrorIfNotConverged(ksp, PETSC_FALSE));
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = KSPSetUp(ksp);
    PetscCall(PetscPopErrorHandler());
    PetscCall(KSPSetErrorIfNotConverged(ksp, errorif));
    PetscCall(PetscLogEventEnd(FETI_Factorization, feti, 0, 0, 0));
    reason = PC_NOERROR;
    if (!ierr) PetscCall(PCGetFailedReason(pc, &reason));
    if (factorpc) {
      MatSolverType type = NULL;
      PetscCall(PCFactorGetMatSolverType(pc, &type));
      PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &mumps));
    }
    if (!ierr && mumps && reason != PC_NOERROR) {
      Mat factor;
      PetscCall(PCFactorGetMatrix(pc, &factor));
      PetscCall(MatMumpsGetIcntl(factor, 14, &used));
      PetscCall(MatMumpsGetInfog(factor, 1, &infog[0]));
      PetscCall(MatMumpsGetInfog(factor, 2, &infog[1]));
    }
    /* -13: an allocation failed (the machine is out of memory), -19: the ICNTL(23) cap: more workspace cannot help */
    PetscCheck(infog[0] != -19, PETSC_COMM_SELF, PETSC_ERR_LIB,
               "The sparse factorization (options prefix -%s) needs more memory than the cap -%smat_mumps_icntl_23 gives MUMPS (INFOG(1) = -19): raise or remove it", prefix ? prefix : "",
               prefix ? prefix : "");
    PetscCheck(infog[0] != -13, PETSC_COMM_SELF, PETSC_ERR_MEM,
               "The sparse factorization (options prefix -%s) ran out of memory inside MUMPS (INFOG(1) = %" PetscInt_FMT ", INFOG(2) = %" PetscInt_FMT
               "): this machine cannot hold the factors; use a coarser mesh or more subdomains, more nodes, or -feti_kplus_explicit 0 (FETISetUp() estimates the memory before factoring: "
               "-info :feti, -feti_memory_budget)",
               prefix ? prefix : "", infog[0], infog[1]);
    if (ierr || reason != PC_FACTOR_OUTMEMORY || !mumps) break;
    if (attempt == max_retries || (attempt > 0 && used < workspace)) break; /* used < workspace: an explicit -mat_mumps_icntl_14 wins */
    {                                                                       /* same matrix, a fresh factor with a larger workspace */
      Mat      A, factor;
      PetscInt pct = used;
      workspace    = PetscMax(2 * pct, 100);
      PetscCall(PetscInfo(ksp, "MUMPS workspace estimate too small (ICNTL(14) = %" PetscInt_FMT "%%): factoring again with %" PetscInt_FMT "%%\n", pct, workspace));
      PetscCall(KSPGetOperators(ksp, &A, NULL));
      PetscCall(PetscObjectReference((PetscObject)A));
      PetscCall(PCReset(pc));
      PetscCall(KSPSetOperators(ksp, A, A));
      PetscCall(MatDestroy(&A));
      if (prepare) PetscCall((*prepare)(ctx));
      PetscCall(PCFactorSetUpMatSolverType(pc));
      PetscCall(PCFactorGetMatrix(pc, &factor));
      PetscCall(MatMumpsSetIcntl(factor, 14, workspace));
    }
  }
  if (!ierr && reason != PC_NOERROR && reason != PC_FACTOR_STRUCT_ZEROPIVOT && reason != PC_FACTOR_NUMERIC_ZEROPIVOT) {
    /* out of memory or another failure the package reports without raising an error */
    PetscCall(PetscOptionsHasName(((PetscObject)ksp)->options, prefix, "-mat_mumps_icntl_14", &given));
    PetscCheck(!mumps || reason != PC_FACTOR_OUTMEMORY || !given, PETSC_COMM_SELF, PETSC_ERR_LIB,
               "The sparse factorization (options prefix -%s) failed inside MUMPS (FACTOR_OUTMEMORY): its workspace estimate was too small with -%smat_mumps_icntl_14 %" PetscInt_FMT
               " (percent); raise it or leave it out (without it the workspace is raised until the factorization fits)",
               prefix ? prefix : "", prefix ? prefix : "", used);
    PetscCheck(!mumps || reason != PC_FACTOR_OUTMEMORY, PETSC_COMM_SELF, PETSC_ERR_LIB,
               "The sparse factorization (options prefix -%s) failed inside MUMPS (FACTOR_OUTMEMORY): its workspace estimate was too small, also after %" PetscInt_FMT
               " retries with a larger one (last ICNTL(14) = %" PetscInt_FMT "%%); raise it, e.g. -%smat_mumps_icntl_14 %" PetscInt_FMT " (percent), or check the memory",
               prefix ? prefix : "", max_retries, used, prefix ? prefix : "", 4 * used);
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB,
            "The sparse factorization (options prefix -%s) failed inside the solver package (%s), not at a zero pivot: check the -%spc_factor_mat_solver_type and -%smat_* options, or the memory",
            prefix ? prefix : "", PCFailedReasons[reason], prefix ? prefix : "", prefix ? prefix : "");
  }
  PetscCheck(!ierr || ierr == PETSC_ERR_MAT_CH_ZRPVT || ierr == PETSC_ERR_MAT_LU_ZRPVT, PETSC_COMM_SELF, ierr,
             "The sparse factorization (options prefix -%s) failed inside the solver package with PETSc error %d, not at a zero pivot: the package's message above says why (out of "
             "memory, or a bad option: check the memory, the -%spc_factor_mat_solver_type and the -%smat_* options)",
             prefix ? prefix : "", (int)ierr, prefix ? prefix : "", prefix ? prefix : "");
  *failed = (ierr || reason != PC_NOERROR) ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The MATSHELLs F, P, Q, PFP, K+ and G of a FETI whose layout, factors and coarse problem are set up
   (FETISetUp()); each carries the FETI as its context. */
/* -info: what this rank holds, the quantities that set its share of an F product and of the dual vector
   operations (the load balance of a run on several ranks: docs/scale.md, "Two ranks: where the time goes") */
static PetscErrorCode InfoBalance(FETI feti)
{
  FETI_Impl         &impl      = *feti->impl;
  PetscInt           nfloating = 0, nb = 0, rows[4] = {0, 0, 0, 0}, ghostsB = 0, ghostsBt = 0;
  PetscReal          nb2  = 0;
  const PetscScalar *mask = nullptr;
  PetscBool          info, own = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCall(PetscInfoEnabled(FETI_CLASSID, &info));
  if (!info) PetscFunctionReturn(PETSC_SUCCESS);
  if (!impl.boundarymask) { /* a transient mask: the run without -info keeps no more memory */
    PetscCall(FETISetUpBoundaryMask(feti));
    own = PETSC_TRUE;
  }
  PetscCall(VecGetArrayRead(impl.boundarymask, &mask));
  for (const FETISubdomain &sd : impl.sub) {
    PetscInt b = 0;
    if (sd.nkernel) nfloating++;
    for (PetscInt i = 0; i < sd.n; i++) b += mask[sd.localoffset + i] != 0.0;
    nb += b;
    nb2 += (PetscReal)b * (PetscReal)b;
  }
  PetscCall(VecRestoreArrayRead(impl.boundarymask, &mask));
  if (own) PetscCall(VecDestroy(&impl.boundarymask));
  for (FETIRowKind k : impl.kinds) rows[k]++;
  if (impl.Bsum.ghosts) PetscCall(VecGetLocalSize(impl.Bsum.ghosts, &ghostsB));
  if (impl.Btsum.ghosts) PetscCall(VecGetLocalSize(impl.Btsum.ghosts, &ghostsBt));
  { /* PetscInfo() prints on the first rank of the communicator only: it prints every rank's line */
    MPI_Comm            comm = PetscObjectComm((PetscObject)feti);
    PetscMPIInt         size, rank;
    const int           nv       = 12;
    const double        mine[nv] = {(double)impl.sub.size(),
                                    (double)nfloating,
                                    (double)impl.nlocalprimal,
                                    (double)nb,
                                    nb2,
                                    (double)impl.nlocalcoarse,
                                    (double)impl.kinds.size(),
                                    (double)rows[FETI_ROW_GLUING],
                                    (double)rows[FETI_ROW_DIRICHLET],
                                    (double)rows[FETI_ROW_CONTACT_NORMAL],
                                    (double)rows[FETI_ROW_CONTACT_TANGENTIAL],
                                    (double)(ghostsB + ghostsBt)};
    std::vector<double> all;
    PetscCallMPI(MPI_Comm_size(comm, &size));
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    PetscCallCXX(all.resize((size_t)nv * size));
    PetscCallMPI(MPI_Gather(mine, nv, MPI_DOUBLE, all.data(), nv, MPI_DOUBLE, 0, comm));
    for (PetscMPIInt r = 0; r < size; r++) {
      const double *v = &all[(size_t)nv * r];
      PetscCall(PetscInfo(feti,
                          "Load of rank %d: %.0f subdomains (%.0f floating), %.0f primal dofs, %.0f touched by B (sum of squares %.4g), %.0f coarse; %.0f dual rows (gluing %.0f, Dirichlet %.0f, "
                          "normal %.0f, tangential %.0f); ghost entries of B and B' %.0f\n",
                          r, v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11]));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FETICreateOperators_Private(FETI feti)
{
  FETI_Impl &impl = *feti->impl;
  MPI_Comm   comm = PetscObjectComm((PetscObject)feti);
  PetscInt   nd, mlocal;

  PetscFunctionBegin;
  PetscCall(MatGetSize(impl.B, &nd, NULL));
  PetscCall(MatGetLocalSize(impl.B, &mlocal, NULL));
  PetscCall(CreateShell(feti, mlocal, mlocal, MatMult_F, "F", &impl.F));
  PetscCall(CreateShell(feti, mlocal, mlocal, MatMult_P, "P", &impl.P));
  PetscCall(CreateShell(feti, mlocal, mlocal, MatMult_Q, "Q", &impl.Q));
  PetscCall(CreateShell(feti, mlocal, mlocal, MatMult_PFP, "PFP", &impl.PFP));
  PetscCall(CreateShell(feti, impl.nlocalprimal, impl.nlocalprimal, MatMult_Kplus, "Kplus", &impl.Kplus));
  PetscCall(MatCreateShell(comm, impl.nlocalcoarse, mlocal, impl.ncoarse, nd, feti, &impl.G));
  PetscCall(MatShellSetOperation(impl.G, MATOP_MULT, (void (*)(void))MatMult_G));
  PetscCall(MatShellSetOperation(impl.G, MATOP_MULT_TRANSPOSE, (void (*)(void))MatMultTranspose_G));
  PetscCall(PetscObjectComposeFunction((PetscObject)impl.G, "FETIShellGetFETI_C", ShellGetFETI));
  PetscCall(PetscObjectSetName((PetscObject)impl.G, "G"));
  PetscCall(InfoBalance(feti));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CheckSetUp(FETI feti)
{
  PetscFunctionBegin;
  PetscCheck(feti->impl->setupcalled, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER, "Call FETISetUp() first");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetOperators - The dual operators as matrices (shells; never formed).

  Not Collective

  Input Parameter:
. feti - the FETI problem, set up

  Output Parameters:
+ F - B K+ B' (dual x dual)
. G - R'B' (coarse x dual; a shell whose transpose product is B R x)
. P - I - G'(G G')^-1 G, orthogonal projector onto Ker G
- Q - I - P

  Notes:
  Any output may be NULL. The matrices belong to the FETI object: do not destroy them. A reference taken to
  one (a `ContactProblem` takes F and Q) does not keep the FETI object alive: a product with it after
  `FETIDestroy()` is an error that says so, so destroy the FETI object after those who use its operators.
  F, P, Q are symmetric and support `MatMult()` and `MatMultTranspose()`.

  Level: beginner

.seealso: `FETIGetRHS()`, `FETIGetParticularSolution()`, `FETIGetGeneralizedInverse()`
@*/
PetscErrorCode FETIGetOperators(FETI feti, Mat *F, Mat *G, Mat *P, Mat *Q)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(CheckSetUp(feti));
  if (F) *F = feti->impl->F;
  if (G) *G = feti->impl->G;
  if (P) *P = feti->impl->P;
  if (Q) *Q = feti->impl->Q;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetCoarseSolveCount - How many solves with the coarse matrix G G' the FETI object did since `FETISetUp()`.

  Not Collective

  Input Parameter:
. feti - the FETI problem, set up

  Output Parameter:
. count - the solves (the same on every rank)

  Notes:
  Every product with P, Q and the particular solution's setup takes one; a Hessian product P F P + rho Q of the
  contact solver takes two. The count shows what the projector costs beside the F products (docs/scale.md).

  Level: intermediate

.seealso: `FETIGetOperators()`, `FETIApplyCoarseInverse()`
@*/
PetscErrorCode FETIGetCoarseSolveCount(FETI feti, PetscInt *count)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscAssertPointer(count, 2);
  *count = feti->impl->ncoarsesolves;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetGeneralizedInverse - The block-diagonal generalized inverse K+ as a shell matrix (K K+ K = K).

  Not Collective

  Input Parameter:
. feti - the FETI problem, set up

  Output Parameter:
. Kplus - primal x primal shell (do not destroy)

  Level: intermediate

.seealso: `FETIApplyK()`, `FETIGetOperators()`
@*/
PetscErrorCode FETIGetGeneralizedInverse(FETI feti, Mat *Kplus)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(CheckSetUp(feti));
  *Kplus = feti->impl->Kplus;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetKernel - The block-diagonal kernel basis R (primal x coarse, orthonormal columns per subdomain).

  Not Collective

  Input Parameter:
. feti - the FETI problem, set up

  Output Parameter:
. R - the matrix (do not destroy)

  Level: intermediate

.seealso: `FETIGetGt()`, `FETIGetSubdomainKernel()`
@*/
PetscErrorCode FETIGetKernel(FETI feti, Mat *R)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(CheckSetUp(feti));
  *R = feti->impl->R;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetGt - The sparse matrix G' = B R (dual x coarse).

  Collective on the first call

  Input Parameter:
. feti - the FETI problem, set up

  Output Parameter:
. Gt - the matrix (do not destroy)

  Notes:
  The operators do not need it (G is applied as R'B'), so `FETISetUp()` drops it after assembling the
  coarse matrix; the first call builds it again and keeps it.

  Level: intermediate

.seealso: `FETIGetOperators()`, `FETIGetKernel()`
@*/
PetscErrorCode FETIGetGt(FETI feti, Mat *Gt)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(CheckSetUp(feti));
  if (!feti->impl->Gt) PetscCall(FETICreateGt(feti, &feti->impl->Gt));
  *Gt = feti->impl->Gt;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetRHS - The right-hand sides of the dual problem: h = B K+ f - c and e = R' f.

  Not Collective

  Input Parameter:
. feti - the FETI problem, set up

  Output Parameters:
+ h - dual vector (do not destroy or change)
- e - coarse vector (do not destroy or change)

  Notes:
  The dual problem is min 1/2 l'F l - l'h subject to G l = e (and the contact constraints).

  Level: beginner

.seealso: `FETIGetOperators()`, `FETIGetParticularSolution()`
@*/
PetscErrorCode FETIGetRHS(FETI feti, Vec *h, Vec *e)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(CheckSetUp(feti));
  if (h) *h = feti->impl->h;
  if (e) *e = feti->impl->e;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetParticularSolution - lambda~ = G'(G G')^-1 e, the least-norm solution of G lambda = e.

  Not Collective

  Input Parameter:
. feti - the FETI problem, set up

  Output Parameter:
. lambdatilde - dual vector (do not destroy or change)

  Notes:
  lambda = lambda~ + mu with G mu = 0 homogenizes the equality constraint.

  Level: intermediate

.seealso: `FETIGetRHS()`
@*/
PetscErrorCode FETIGetParticularSolution(FETI feti, Vec *lambdatilde)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(CheckSetUp(feti));
  *lambdatilde = feti->impl->lambdatilde;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetConstraints - The constraint matrix, right-hand side and row kinds.

  Not Collective

  Input Parameter:
. feti - the FETI problem

  Output Parameters:
+ B     - the constraint matrix (do not destroy)
. c     - the right-hand side (NULL when zero; do not destroy)
- kinds - kind of each local row (do not free)

  Level: intermediate

.seealso: `FETISetConstraints()`
@*/
PetscErrorCode FETIGetConstraints(FETI feti, Mat *B, Vec *c, const FETIRowKind **kinds)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  if (B) *B = feti->impl->B;
  if (c) *c = feti->impl->c;
  if (kinds) *kinds = feti->impl->kinds.data();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetLoad - The global primal load vector f (zero at Dirichlet dofs kept in the primal; with their prescribed values lifted, f - K u_D: `FETISetSubdomainDirichletValues()`).

  Not Collective

  Input Parameter:
. feti - the FETI problem, set up

  Output Parameter:
. f - primal vector (do not destroy or change)

  Level: intermediate

.seealso: `FETIApplyK()`
@*/
PetscErrorCode FETIGetLoad(FETI feti, Vec *f)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(CheckSetUp(feti));
  *f = feti->impl->f;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETICreateVecs - Create vectors in the primal, dual and coarse layouts.

  Collective

  Input Parameter:
. feti - the FETI problem, set up

  Output Parameters:
+ primal - primal vector (may be NULL)
. dual   - dual vector, the layout of B's rows (may be NULL)
- coarse - coarse vector (may be NULL)

  Level: beginner

.seealso: `FETIGetSizes()`
@*/
PetscErrorCode FETICreateVecs(FETI feti, Vec *primal, Vec *dual, Vec *coarse)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(CheckSetUp(feti));
  if (primal) PetscCall(VecDuplicate(feti->impl->wp1, primal));
  if (dual) PetscCall(VecDuplicate(feti->impl->wd1, dual));
  if (coarse) PetscCall(VecDuplicate(feti->impl->wc1, coarse));
  PetscFunctionReturn(PETSC_SUCCESS);
}
