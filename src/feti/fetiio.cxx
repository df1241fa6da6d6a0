/* Interchange: a FETI problem as a sequence of standard PETSc binary objects (docs/feti-interchange.md).

     IS   header       [1211216 ("FETI"), version 2, number of subdomains, has coordinates 0/1, rows of B,
                        contact nodes in the pairing (-1: no pairing stored)]
     IS   sizes        dofs of each subdomain (primal vector = subdomains concatenated in this order)
     IS   kernels      kernel dimension of each subdomain (coarse vector = kernels concatenated)
     IS   dirichlet    global primal indices of dofs kept at zero in the primal (may be empty)
     IS   pairing      per contact node: normal row, first and second tangential row (-1: none), law
                        (0 frictionless, 1 Tresca, 2 Coulomb)
     Vec  coefficients per contact node: slip bound (Tresca) or friction coefficient (Coulomb), 0 frictionless
     Mat  K            block-diagonal stiffness, primal x primal (AIJ), zero rows/columns at those dofs
     Vec  f            primal load
     Mat  B            constraints, multipliers x primal (AIJ)
     Vec  c            right-hand side of B u = c
     IS   kinds        FETIRowKind of each row of B (0 gluing, 1 Dirichlet, 2 contact normal, 3 contact tangential)
     Mat  R            block-diagonal kernel basis, primal x coarse (AIJ)
     Vec  coordinates  3 per node in the primal layout (only when the header says so)

   Version 1 (still read) has the header's first four entries and neither pairing nor coefficients: its
   contact rows carry their kind only. The pairing comes before B so that the reader can spread the rows
   of B over the ranks without cutting a contact node (its rows must live on one rank: a cone is one block
   of the solver's set). Any code that writes these objects with PETSc (MatView/VecView/ISView, or
   PetscBinaryIO.py) can be solved here; the subdomains are redistributed over the reading ranks. */
#include <conefeti/private/fetiimpl.h>
#include <conefeti/private/fetiinterchange.h>

#include <algorithm>

#define FETI_FILE_MAGIC   1211216
#define FETI_FILE_VERSION 2 /* written; 1 and 2 are read */

/* An IS holding the given local integers */
static PetscErrorCode ViewInts(MPI_Comm comm, const std::vector<PetscInt> &v, PetscViewer viewer)
{
  IS is;

  PetscFunctionBegin;
  PetscCall(ISCreateGeneral(comm, (PetscInt)v.size(), v.data(), PETSC_COPY_VALUES, &is));
  PetscCall(ISView(is, viewer));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* All entries of the next IS in the file, on every rank */
static PetscErrorCode LoadInts(MPI_Comm comm, PetscViewer viewer, std::vector<PetscInt> &v)
{
  IS              is, all;
  const PetscInt *idx;
  PetscInt        n;

  PetscFunctionBegin;
  PetscCall(ISCreate(comm, &is));
  PetscCall(ISLoad(is, viewer));
  PetscCall(ISAllGather(is, &all));
  PetscCall(ISGetLocalSize(all, &n));
  PetscCall(ISGetIndices(all, &idx));
  PetscCallCXX(v.assign(idx, idx + n));
  PetscCall(ISRestoreIndices(all, &idx));
  PetscCall(ISDestroy(&all));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The block-diagonal K_V (K on the primal space) as one parallel AIJ matrix */
static PetscErrorCode AssembleBlockDiagonalK(FETI feti, Mat *K)
{
  FETI_Impl            &impl = *feti->impl;
  std::vector<Mat>      KV(impl.sub.size());
  std::vector<PetscInt> nnz(impl.nlocalprimal);

  PetscFunctionBegin;
  for (size_t s = 0; s < impl.sub.size(); s++) {
    FETISubdomain &sd = impl.sub[s];
    /* K_V = Kreg without its regularizing diagonal, plus the correction (K_V's entries in the fixing rows and columns):
       the diagonal is zeroed before the correction is added, not subtracted after, so that every entry is K_V's to the
       bit and a reader regularizes exactly as the writer did */
    PetscCall(MatConvert(sd.Kreg, MATSEQAIJ, MAT_INITIAL_MATRIX, &KV[s]));
    for (PetscInt r : sd.removed) PetscCall(MatSetValue(KV[s], r, r, 0.0, INSERT_VALUES));
    PetscCall(MatAssemblyBegin(KV[s], MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(KV[s], MAT_FINAL_ASSEMBLY));
    if (sd.correction) PetscCall(MatAXPY(KV[s], 1.0, sd.correction, DIFFERENT_NONZERO_PATTERN));
    for (PetscInt i = 0; i < sd.n; i++) {
      PetscInt ncols;
      PetscCall(MatGetRow(KV[s], i, &ncols, NULL, NULL));
      nnz[sd.localoffset + i] = ncols;
      PetscCall(MatRestoreRow(KV[s], i, &ncols, NULL, NULL));
    }
  }
  PetscCall(MatCreate(PetscObjectComm((PetscObject)feti), K));
  PetscCall(MatSetSizes(*K, impl.nlocalprimal, impl.nlocalprimal, impl.nprimal, impl.nprimal));
  PetscCall(MatSetType(*K, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(*K, 0, nnz.data()));
  PetscCall(MatMPIAIJSetPreallocation(*K, 0, nnz.data(), 0, NULL));
  for (size_t s = 0; s < impl.sub.size(); s++) {
    FETISubdomain &sd = impl.sub[s];
    for (PetscInt i = 0; i < sd.n; i++) {
      const PetscInt    *cols;
      const PetscScalar *vals;
      PetscInt           ncols, row = sd.offset + i;
      PetscCall(MatGetRow(KV[s], i, &ncols, &cols, &vals));
      std::vector<PetscInt> gcols(cols, cols + ncols);
      for (PetscInt &c : gcols) c += sd.offset;
      PetscCall(MatSetValues(*K, 1, &row, ncols, gcols.data(), vals, INSERT_VALUES));
      PetscCall(MatRestoreRow(KV[s], i, &ncols, &cols, &vals));
    }
    PetscCall(MatDestroy(&KV[s]));
  }
  PetscCall(MatAssemblyBegin(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*K, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The name of the viewer's file, for the error messages */
static PetscErrorCode FileName(PetscViewer viewer, const char **name)
{
  PetscFunctionBegin;
  PetscCall(PetscViewerFileGetName(viewer, name));
  if (!*name) *name = "(unnamed)";
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FETIWriteWithPairing_Private(FETI feti, PetscViewer viewer, const FETIContactPairing *pairing)
{
  MPI_Comm              comm = PetscObjectComm((PetscObject)feti);
  PetscMPIInt           rank;
  PetscInt              hascoords = 1, hasall, nrows, npairing = 0, hascontact = 0;
  std::vector<PetscInt> header, sizes, kernels, dirichlet, pairs, kinds;
  Mat                   K;
  Vec                   c, coords, coef;
  PetscBool             isbinary;
  const char           *file;

  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  FETI_Impl &impl = *feti->impl;
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 2);
  PetscCheck(impl.setupcalled, comm, PETSC_ERR_ORDER, "Call FETISetUp() before writing the FETI problem");
  PetscCallCXX(kinds.assign(impl.kinds.begin(), impl.kinds.end()));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERBINARY, &isbinary));
  PetscCheck(isbinary, comm, PETSC_ERR_ARG_WRONG, "Writing a FETI problem needs a binary viewer (PetscViewerBinaryOpen())");
  PetscCall(FileName(viewer, &file));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(MatGetSize(impl.B, &nrows, NULL));
  for (FETISubdomain &sd : impl.sub) {
    PetscCallCXX(sizes.push_back(sd.n));
    PetscCallCXX(kernels.push_back(sd.nkernel));
    for (PetscInt d : sd.dirichletdofs) PetscCallCXX(dirichlet.push_back(sd.offset + d));
    if (!sd.coords) hascoords = 0;
  }
  for (FETIRowKind k : impl.kinds)
    if (k == FETI_ROW_CONTACT_NORMAL || k == FETI_ROW_CONTACT_TANGENTIAL) hascontact = 1;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &hascontact, 1, MPIU_INT, MPI_MAX, comm));
  PetscCall(MPIU_Allreduce(&hascoords, &hasall, 1, MPIU_INT, MPI_MIN, comm));
  if (pairing) {
    const PetscInt n = (PetscInt)pairing->normal.size();
    PetscCheck((PetscInt)pairing->t1.size() == n && (PetscInt)pairing->t2.size() == n && (PetscInt)pairing->law.size() == n && (PetscInt)pairing->coef.size() == n, PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "contact pairing with arrays of different lengths");
    /* the writer checks what it can see alone (indices, laws); the reader checks the rest against the row kinds */
    for (PetscInt k = 0; k < n; k++) {
      const PetscInt row[3] = {pairing->normal[k], pairing->t1[k], pairing->t2[k]};
      PetscCheck(row[0] >= 0 && row[0] < nrows, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                 "%s: contact node %" PetscInt_FMT " of this rank has normal row %" PetscInt_FMT ", B has rows 0 .. %" PetscInt_FMT, file, k, row[0], nrows - 1);
      for (PetscInt q = 1; q < 3; q++)
        PetscCheck(row[q] >= -1 && row[q] < nrows, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                   "%s: contact node %" PetscInt_FMT " of this rank has tangential row %" PetscInt_FMT ", B has rows 0 .. %" PetscInt_FMT, file, k, row[q], nrows - 1);
      PetscCheck(pairing->law[k] >= 0 && pairing->law[k] <= 2, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "%s: contact node %" PetscInt_FMT " of this rank has law %" PetscInt_FMT " (0, 1 or 2)", file,
                 k, pairing->law[k]);
      PetscCallCXX(pairs.insert(pairs.end(), {row[0], row[1], row[2], pairing->law[k]}));
    }
    PetscCall(MPIU_Allreduce(&n, &npairing, 1, MPIU_INT, MPI_SUM, comm));
  } else npairing = hascontact ? -1 : 0; /* contact rows without a pairing: the file says so */
  if (rank == 0) header = {FETI_FILE_MAGIC, FETI_FILE_VERSION, impl.nglobalsub, hasall, nrows, npairing};
  PetscCall(ViewInts(comm, header, viewer));
  PetscCall(ViewInts(comm, sizes, viewer));
  PetscCall(ViewInts(comm, kernels, viewer));
  PetscCall(ViewInts(comm, dirichlet, viewer));
  PetscCall(ViewInts(comm, pairs, viewer));
  PetscCall(VecCreateMPI(comm, pairing ? (PetscInt)pairing->coef.size() : 0, PETSC_DETERMINE, &coef));
  if (pairing) {
    PetscScalar *a;
    PetscCall(VecGetArray(coef, &a));
    for (size_t k = 0; k < pairing->coef.size(); k++) a[k] = pairing->coef[k];
    PetscCall(VecRestoreArray(coef, &a));
  }
  PetscCall(VecView(coef, viewer));
  PetscCall(VecDestroy(&coef));
  PetscCall(AssembleBlockDiagonalK(feti, &K));
  PetscCall(MatView(K, viewer));
  PetscCall(MatDestroy(&K));
  PetscCall(VecView(impl.f, viewer));
  PetscCall(MatView(impl.B, viewer));
  PetscCall(VecDuplicate(impl.h, &c));
  if (impl.c) PetscCall(VecCopy(impl.c, c));
  else PetscCall(VecSet(c, 0.0));
  PetscCall(VecView(c, viewer));
  PetscCall(VecDestroy(&c));
  PetscCall(ViewInts(comm, kinds, viewer));
  PetscCall(MatView(impl.R, viewer));
  if (hasall) {
    PetscScalar *a;
    PetscCall(VecDuplicate(impl.f, &coords));
    PetscCall(VecGetArray(coords, &a));
    for (FETISubdomain &sd : impl.sub) {
      const PetscScalar *x;
      PetscCall(VecGetArrayRead(sd.coords, &x));
      for (PetscInt i = 0; i < sd.n; i++) a[sd.localoffset + i] = x[i];
      PetscCall(VecRestoreArrayRead(sd.coords, &x));
    }
    PetscCall(VecRestoreArray(coords, &a));
    PetscCall(VecView(coords, viewer));
    PetscCall(VecDestroy(&coords));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIWrite - Write the FETI problem (block-diagonal K, f, B with row kinds, c, R, coordinates) to a PETSc binary viewer.

  Collective

  Input Parameters:
+ feti   - the FETI problem, set up
- viewer - a binary viewer (`PetscViewerBinaryOpen()`)

  Notes:
  The file is a sequence of standard PETSc objects, readable by any PETSc program or by
  PetscBinaryIO.py; the format (version 2) is documented in docs/feti-interchange.md. K is written as the
  operator on the primal space (what `FETIApplyK()` applies), R as the kernel basis actually used.
  Reading it back with `FETILoad()`, on any number of ranks, gives the same problem.

  The FETI object does not know which contact rows form one contact node, nor their law: a problem with
  contact rows written here is marked as carrying no contact pairing. `FETIWriteContact()` writes the
  same file with the pairing of a `ContactProblem`, which `FETILoadContact()` reads back.

  Level: intermediate

.seealso: `FETILoad()`, `FETISetUp()`, `FETIWriteContact()`
@*/
PetscErrorCode FETIWrite(FETI feti, PetscViewer viewer)
{
  PetscFunctionBegin;
  PetscCall(FETIWriteWithPairing_Private(feti, viewer, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Local block [r0, r0+m) x [c0, c0+n) of the local diagonal part of a parallel AIJ matrix, as a sequential matrix */
static PetscErrorCode ExtractBlock(Mat A, PetscInt r0, PetscInt m, PetscInt c0, PetscInt n, PetscInt bs, PetscBool dense, Mat *S)
{
  Mat                   Ad;
  std::vector<PetscInt> nnz(m, 0);

  PetscFunctionBegin;
  PetscCall(MatGetDiagonalBlock(A, &Ad));
  for (PetscInt i = 0; i < m; i++) {
    const PetscInt *cols;
    PetscInt        ncols;
    PetscCall(MatGetRow(Ad, r0 + i, &ncols, &cols, NULL));
    for (PetscInt k = 0; k < ncols; k++)
      if (cols[k] >= c0 && cols[k] < c0 + n) nnz[i]++;
    PetscCall(MatRestoreRow(Ad, r0 + i, &ncols, &cols, NULL));
  }
  if (dense) PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, m, n, NULL, S));
  else {
    PetscCall(MatCreate(PETSC_COMM_SELF, S));
    PetscCall(MatSetSizes(*S, m, n, m, n));
    PetscCall(MatSetBlockSize(*S, bs));
    PetscCall(MatSetType(*S, MATSEQAIJ));
    PetscCall(MatSeqAIJSetPreallocation(*S, 0, nnz.data()));
  }
  for (PetscInt i = 0; i < m; i++) {
    const PetscInt    *cols;
    const PetscScalar *vals;
    PetscInt           ncols;
    PetscCall(MatGetRow(Ad, r0 + i, &ncols, &cols, &vals));
    for (PetscInt k = 0; k < ncols; k++)
      if (cols[k] >= c0 && cols[k] < c0 + n) PetscCall(MatSetValue(*S, i, cols[k] - c0, vals[k], INSERT_VALUES));
    PetscCall(MatRestoreRow(Ad, r0 + i, &ncols, &cols, &vals));
  }
  PetscCall(MatAssemblyBegin(*S, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*S, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Split a parallel primal vector into sequential per-subdomain vectors */
static PetscErrorCode SplitVec(Vec v, const std::vector<PetscInt> &offsets, const std::vector<PetscInt> &sizes, std::vector<Vec> &parts)
{
  const PetscScalar *a;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(v, &a));
  PetscCallCXX(parts.resize(sizes.size()));
  for (size_t s = 0; s < sizes.size(); s++) {
    PetscScalar *p;
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, sizes[s], &parts[s]));
    PetscCall(VecGetArray(parts[s], &p));
    for (PetscInt i = 0; i < sizes[s]; i++) p[i] = a[offsets[s] + i];
    PetscCall(VecRestoreArray(parts[s], &p));
  }
  PetscCall(VecRestoreArrayRead(v, &a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A read that fails (the file ends early, or holds another object than the format says) becomes an error
   naming the file and the item, on every rank: PETSc's binary viewer reads on rank 0 and shares the outcome
   (the tests cut files inside an object's header and inside its data, on 1 and 2 ranks). */
#define FETIReadItem(call, item)                                                                                                                                                   \
  do {                                                                                                                                                                             \
    PetscErrorCode ierr_;                                                                                                                                                          \
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));                                                                                                               \
    ierr_ = (call);                                                                                                                                                                \
    PetscCall(PetscPopErrorHandler());                                                                                                                                             \
    PetscCheck(!ierr_, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: cannot read the %s: the file is truncated or is not a FETI interchange file (docs/feti-interchange.md)", file, item); \
  } while (0)

/* The rows of B this rank owns: an even split, each cut moved forward past any contact node whose rows it would separate */
static PetscErrorCode PairingRowLayout(MPI_Comm comm, PetscInt nrows, const FETIContactPairing &pairing, PetscInt *nlocalrows)
{
  PetscMPIInt           size, rank;
  std::vector<PetscInt> inside(nrows + 2, 0), cut;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  for (size_t k = 0; k < pairing.normal.size(); k++) {
    PetscInt lo = pairing.normal[k], hi = lo;
    for (PetscInt t : {pairing.t1[k], pairing.t2[k]})
      if (t >= 0) lo = PetscMin(lo, t), hi = PetscMax(hi, t);
    inside[lo + 1]++; /* a cut before row r separates the node when lo < r <= hi */
    inside[hi + 1]--;
  }
  for (PetscInt r = 1; r <= nrows; r++) inside[r] += inside[r - 1];
  PetscCallCXX(cut.assign(size + 1, nrows));
  cut[0] = 0;
  for (PetscMPIInt p = 1; p < size; p++) {
    PetscInt r = PetscMax((PetscInt)(((PetscInt64)nrows * p) / size), cut[p - 1]);
    while (r < nrows && inside[r] > 0) r++;
    cut[p] = r;
  }
  *nlocalrows = cut[rank + 1] - cut[rank];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The pairing against the rows of B and their kinds: indices in range, the right kinds, tangential rows for the
   friction laws only, each contact row in exactly one node */
static PetscErrorCode CheckPairing(MPI_Comm comm, const char *file, PetscInt nrows, const FETIContactPairing &pairing, const std::vector<PetscInt> *kinds)
{
  std::vector<PetscInt> owner(nrows, -1);
  const char           *laws[] = {"frictionless", "Tresca", "Coulomb"};

  PetscFunctionBegin;
  for (size_t k = 0; k < pairing.normal.size(); k++) {
    const PetscInt  l = pairing.law[k], row[3] = {pairing.normal[k], pairing.t1[k], pairing.t2[k]};
    const PetscReal c = pairing.coef[k];
    PetscCheck(l >= 0 && l <= 2, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: contact node %d has law %" PetscInt_FMT ": the laws are 0 (frictionless), 1 (Tresca), 2 (Coulomb)", file, (int)k, l);
    PetscCheck(row[0] >= 0 && row[0] < nrows, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: contact node %d has normal row %" PetscInt_FMT ", out of the rows 0 .. %" PetscInt_FMT " of B", file, (int)k,
               row[0], nrows - 1);
    for (PetscInt q = 1; q < 3; q++) {
      if (l == 0) PetscCheck(row[q] == -1, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: contact node %d is frictionless but has tangential row %" PetscInt_FMT " (must be -1)", file, (int)k, row[q]);
      else
        PetscCheck(row[q] >= 0 && row[q] < nrows, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: contact node %d (%s) has tangential row %" PetscInt_FMT ", out of the rows 0 .. %" PetscInt_FMT " of B", file,
                   (int)k, laws[l], row[q], nrows - 1);
    }
    PetscCheck(c >= 0 && !PetscIsInfOrNanReal(c), comm, PETSC_ERR_FILE_UNEXPECTED, "%s: contact node %d has coefficient %g (must be finite and >= 0)", file, (int)k, (double)c);
    for (PetscInt q = 0; q < 3; q++) {
      if (row[q] < 0) continue;
      PetscCheck(owner[row[q]] < 0, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: row %" PetscInt_FMT " of B belongs to contact nodes %d and %d", file, row[q], (int)owner[row[q]], (int)k);
      owner[row[q]] = (PetscInt)k;
      if (kinds)
        PetscCheck((*kinds)[row[q]] == (q ? FETI_ROW_CONTACT_TANGENTIAL : FETI_ROW_CONTACT_NORMAL), comm, PETSC_ERR_FILE_UNEXPECTED,
                   "%s: row %" PetscInt_FMT " of B is the %s row of contact node %d but its kind is %" PetscInt_FMT, file, row[q], q ? "tangential" : "normal", (int)k, (*kinds)[row[q]]);
    }
  }
  if (kinds)
    for (PetscInt r = 0; r < nrows; r++) {
      const PetscInt kind = (*kinds)[r];
      PetscCheck(kind >= FETI_ROW_GLUING && kind <= FETI_ROW_CONTACT_TANGENTIAL, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: row %" PetscInt_FMT " of B has kind %" PetscInt_FMT " (0 .. 3)", file, r, kind);
      PetscCheck(owner[r] >= 0 || (kind != FETI_ROW_CONTACT_NORMAL && kind != FETI_ROW_CONTACT_TANGENTIAL), comm, PETSC_ERR_FILE_UNEXPECTED,
                 "%s: row %" PetscInt_FMT " of B is a contact %s row of no contact node in the pairing", file, r, kind == FETI_ROW_CONTACT_NORMAL ? "normal" : "tangential");
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FETILoadWithPairing_Private(FETI feti, PetscViewer viewer, FETIContactPairing *pairing, PetscBool *given)
{
  MPI_Comm              comm = PetscObjectComm((PetscObject)feti);
  PetscMPIInt           size, rank;
  std::vector<PetscInt> header, sizes, kernels, dirichlet, kinds, offsets, localsizes, pairs;
  PetscInt              nsub, first, nlocal, nlocalprimal = 0, nlocalcoarse = 0, nprimal = 0, ncoarse = 0, primalstart = 0;
  PetscInt              version = 0, nrows = PETSC_DETERMINE, nlocalrows = PETSC_DECIDE, npairing = -1;
  Mat                   K, B, R;
  Vec                   f, c, coords = NULL;
  std::vector<Mat>      Ks;
  std::vector<Vec>      fs, xs;
  PetscBool             isbinary;
  FETIContactPairing    p;
  const char           *file;

  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 2);
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERBINARY, &isbinary));
  PetscCheck(isbinary, comm, PETSC_ERR_ARG_WRONG, "Reading a FETI problem needs a binary viewer (PetscViewerBinaryOpen())");
  PetscCall(FileName(viewer, &file));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  FETIReadItem(LoadInts(comm, viewer, header), "header");
  PetscCheck(header.size() >= 2 && header[0] == FETI_FILE_MAGIC, comm, PETSC_ERR_FILE_UNEXPECTED, "%s does not start with a FETI header (docs/feti-interchange.md)", file);
  version = header[1];
  PetscCheck(version == 1 || version == 2, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: FETI interchange format version %" PetscInt_FMT "; this library reads versions 1 and 2", file, version);
  PetscCheck((PetscInt)header.size() == (version == 1 ? 4 : 6), comm, PETSC_ERR_FILE_UNEXPECTED, "%s: the header of a version %" PetscInt_FMT " file has %d entries, not %d", file, version,
             version == 1 ? 4 : 6, (int)header.size());
  nsub = header[2];
  if (version >= 2) {
    nrows    = header[4];
    npairing = header[5];
    PetscCheck(nrows >= 0 && npairing >= -1, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: the header announces %" PetscInt_FMT " rows of B and %" PetscInt_FMT " contact nodes", file, nrows, npairing);
  }
  FETIReadItem(LoadInts(comm, viewer, sizes), "subdomain sizes");
  FETIReadItem(LoadInts(comm, viewer, kernels), "kernel dimensions");
  FETIReadItem(LoadInts(comm, viewer, dirichlet), "Dirichlet dofs");
  PetscCheck((PetscInt)sizes.size() == nsub && (PetscInt)kernels.size() == nsub, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %" PetscInt_FMT " subdomains announced, %d sizes and %d kernel dimensions found",
             file, nsub, (int)sizes.size(), (int)kernels.size());
  PetscCheck(nsub >= size, comm, PETSC_ERR_ARG_SIZ, "FETILoad(): %" PetscInt_FMT " subdomains for %d MPI ranks: every rank needs at least one subdomain", nsub, size);
  for (PetscInt s = 0; s < nsub; s++) {
    PetscCheck(sizes[s] > 0 && sizes[s] % 3 == 0 && kernels[s] >= 0 && kernels[s] <= sizes[s], comm, PETSC_ERR_FILE_UNEXPECTED,
               "%s: subdomain %" PetscInt_FMT " has %" PetscInt_FMT " dofs and kernel dimension %" PetscInt_FMT, file, s, sizes[s], kernels[s]);
    if (s < (nsub * rank) / size) primalstart += sizes[s];
    nprimal += sizes[s];
    ncoarse += kernels[s];
  }
  for (PetscInt g : dirichlet)
    PetscCheck(g >= 0 && g < nprimal, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: Dirichlet dof %" PetscInt_FMT " out of the primal dofs 0 .. %" PetscInt_FMT, file, g, nprimal - 1);
  if (version >= 2) {
    Vec                coef, all;
    VecScatter         sc;
    const PetscScalar *a;
    const PetscInt     np = PetscMax(npairing, 0);
    FETIReadItem(LoadInts(comm, viewer, pairs), "contact pairing");
    PetscCheck((PetscInt)pairs.size() == 4 * np, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: the contact pairing has %d entries; %" PetscInt_FMT " contact nodes need %" PetscInt_FMT, file,
               (int)pairs.size(), np, 4 * np);
    PetscCall(VecCreate(comm, &coef));
    PetscCall(VecSetSizes(coef, PETSC_DECIDE, np));
    PetscCall(VecSetType(coef, VECSTANDARD));
    FETIReadItem(VecLoad(coef, viewer), "contact coefficients");
    PetscCall(VecScatterCreateToAll(coef, &sc, &all));
    PetscCall(VecScatterBegin(sc, coef, all, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sc, coef, all, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(all, &a));
    for (PetscInt k = 0; k < np; k++) {
      PetscCallCXX(p.normal.push_back(pairs[4 * k]));
      PetscCallCXX(p.t1.push_back(pairs[4 * k + 1]));
      PetscCallCXX(p.t2.push_back(pairs[4 * k + 2]));
      PetscCallCXX(p.law.push_back(pairs[4 * k + 3]));
      PetscCallCXX(p.coef.push_back(PetscRealPart(a[k])));
    }
    PetscCall(VecRestoreArrayRead(all, &a));
    PetscCall(VecScatterDestroy(&sc));
    PetscCall(VecDestroy(&all));
    PetscCall(VecDestroy(&coef));
    PetscCall(CheckPairing(comm, file, nrows, p, NULL)); /* before its indices place the rows of B */
    PetscCall(PairingRowLayout(comm, nrows, p, &nlocalrows));
  }
  first  = (nsub * rank) / size;
  nlocal = (nsub * (rank + 1)) / size - first;
  for (PetscInt s = first; s < first + nlocal; s++) {
    PetscCallCXX(offsets.push_back(nlocalprimal));
    PetscCallCXX(localsizes.push_back(sizes[s]));
    nlocalprimal += sizes[s];
    nlocalcoarse += kernels[s];
  }

  PetscCall(MatCreate(comm, &K));
  PetscCall(MatSetSizes(K, nlocalprimal, nlocalprimal, nprimal, nprimal));
  PetscCall(MatSetType(K, MATAIJ));
  FETIReadItem(MatLoad(K, viewer), "stiffness K");
  PetscCall(VecCreate(comm, &f));
  PetscCall(VecSetSizes(f, nlocalprimal, nprimal));
  PetscCall(VecSetType(f, VECSTANDARD));
  FETIReadItem(VecLoad(f, viewer), "load f");
  PetscCall(MatCreate(comm, &B));
  PetscCall(MatSetSizes(B, nlocalrows, nlocalprimal, nrows, nprimal));
  PetscCall(MatSetType(B, MATAIJ));
  FETIReadItem(MatLoad(B, viewer), "constraint matrix B");
  PetscCall(MatGetSize(B, &nrows, NULL));
  PetscCall(MatCreateVecs(B, NULL, &c));
  FETIReadItem(VecLoad(c, viewer), "right-hand side c");
  FETIReadItem(LoadInts(comm, viewer, kinds), "row kinds");
  PetscCheck((PetscInt)kinds.size() == nrows, comm, PETSC_ERR_FILE_UNEXPECTED, "%s: %d row kinds for %" PetscInt_FMT " rows of B", file, (int)kinds.size(), nrows);
  if (npairing >= 0) PetscCall(CheckPairing(comm, file, nrows, p, &kinds));
  PetscCall(MatCreate(comm, &R));
  PetscCall(MatSetSizes(R, nlocalprimal, nlocalcoarse, nprimal, ncoarse));
  PetscCall(MatSetType(R, MATAIJ));
  FETIReadItem(MatLoad(R, viewer), "kernel basis R");
  if (header[3]) {
    PetscCall(VecDuplicate(f, &coords));
    FETIReadItem(VecLoad(coords, viewer), "coordinates");
  }

  /* per-subdomain pieces */
  PetscCallCXX(Ks.resize(nlocal));
  for (PetscInt s = 0; s < nlocal; s++) PetscCall(ExtractBlock(K, offsets[s], localsizes[s], offsets[s], localsizes[s], 3, PETSC_FALSE, &Ks[s]));
  PetscCall(MatDestroy(&K));
  PetscCall(SplitVec(f, offsets, localsizes, fs));
  PetscCall(VecDestroy(&f));
  PetscCall(FETISetSubdomains(feti, nlocal, Ks.data(), fs.data()));
  for (PetscInt s = 0, coarse0 = 0; s < nlocal; s++) {
    Mat                   Rs;
    IS                    is;
    std::vector<PetscInt> d;
    const PetscInt        k = kernels[first + s];
    PetscCall(MatDestroy(&Ks[s]));
    PetscCall(VecDestroy(&fs[s]));
    PetscCall(ExtractBlock(R, offsets[s], localsizes[s], coarse0, k, 1, PETSC_TRUE, &Rs));
    coarse0 += k;
    PetscCall(FETISetSubdomainKernel(feti, s, Rs));
    PetscCall(MatDestroy(&Rs));
    for (PetscInt g : dirichlet)
      if (g >= primalstart + offsets[s] && g < primalstart + offsets[s] + localsizes[s]) PetscCallCXX(d.push_back(g - primalstart - offsets[s]));
    if (!d.empty()) {
      PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)d.size(), d.data(), PETSC_COPY_VALUES, &is));
      PetscCall(FETISetSubdomainDirichletDofs(feti, s, is));
      PetscCall(ISDestroy(&is));
    }
  }
  PetscCall(MatDestroy(&R));
  if (coords) {
    PetscCall(SplitVec(coords, offsets, localsizes, xs));
    for (PetscInt s = 0; s < nlocal; s++) {
      PetscCall(FETISetSubdomainCoordinates(feti, s, xs[s]));
      PetscCall(VecDestroy(&xs[s]));
    }
    PetscCall(VecDestroy(&coords));
  }
  {
    PetscInt                 rstart, rend;
    std::vector<FETIRowKind> k;
    PetscCall(MatGetOwnershipRange(B, &rstart, &rend));
    for (PetscInt r = rstart; r < rend; r++) PetscCallCXX(k.push_back((FETIRowKind)kinds[r]));
    PetscCall(FETISetConstraints(feti, B, c, k.data()));
  }
  PetscCall(MatDestroy(&B));
  PetscCall(VecDestroy(&c));
  if (given) *given = npairing >= 0 ? PETSC_TRUE : PETSC_FALSE;
  if (pairing) PetscCallCXX(*pairing = std::move(p));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETILoad - Read a FETI problem written by `FETIWrite()` (or by another code in the same format) into an empty FETI object.

  Collective

  Input Parameters:
+ feti   - a FETI object from `FETICreate()`
- viewer - a binary viewer (`PetscViewerBinaryOpen()` with `FILE_MODE_READ`)

  Notes:
  Reads the format's versions 1 and 2 (docs/feti-interchange.md). The subdomains are spread over the ranks
  of feti's communicator in contiguous ranges (there must be at least as many subdomains as ranks), the rows
  of B evenly, without cutting a contact node of the file's pairing (version 2). The kernels stored in the
  file are used (as `FETISetSubdomainKernel()`), the coordinates, if present, place the fixing nodes. Call
  `FETISetFromOptions()` and `FETISetUp()` afterwards. A file that is truncated, of another version, or whose
  indices are out of range gives an error naming it. The contact pairing itself is read by `FETILoadContact()`.

  Level: intermediate

.seealso: `FETIWrite()`, `FETICreate()`, `FETILoadContact()`
@*/
PetscErrorCode FETILoad(FETI feti, PetscViewer viewer)
{
  PetscFunctionBegin;
  PetscCall(FETILoadWithPairing_Private(feti, viewer, NULL, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}
