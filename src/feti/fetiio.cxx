/* Interchange: a FETI problem as a sequence of standard PETSc binary objects (docs/feti-interchange.md).

     IS   header       [1211216 ("FETI"), version 1, number of subdomains, has coordinates 0/1]
     IS   sizes        dofs of each subdomain (primal vector = subdomains concatenated in this order)
     IS   kernels      kernel dimension of each subdomain (coarse vector = kernels concatenated)
     IS   dirichlet    global primal indices of dofs kept at zero in the primal (may be empty)
     Mat  K            block-diagonal stiffness, primal x primal (AIJ), zero rows/columns at those dofs
     Vec  f            primal load
     Mat  B            constraints, multipliers x primal (AIJ)
     Vec  c            right-hand side of B u = c
     IS   kinds        FETIRowKind of each row of B (0 gluing, 1 Dirichlet, 2 contact normal, 3 contact tangential)
     Mat  R            block-diagonal kernel basis, primal x coarse (AIJ)
     Vec  coordinates  3 per node in the primal layout (only when the header says so)

   Any code that writes these objects with PETSc (MatView/VecView/ISView, or PetscBinaryIO.py) can be
   solved here; the subdomains are redistributed over the reading ranks. */
#include <conefeti/private/fetiimpl.h>

#include <algorithm>

#define FETI_FILE_MAGIC   1211216
#define FETI_FILE_VERSION 1

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
    PetscCall(MatConvert(sd.Kreg, MATSEQAIJ, MAT_INITIAL_MATRIX, &KV[s]));
    if (sd.correction) PetscCall(MatAXPY(KV[s], 1.0, sd.correction, DIFFERENT_NONZERO_PATTERN));
    for (PetscInt r : sd.removed) PetscCall(MatSetValue(KV[s], r, r, -sd.regdiag, ADD_VALUES));
    PetscCall(MatAssemblyBegin(KV[s], MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(KV[s], MAT_FINAL_ASSEMBLY));
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

/*@C
  FETIWrite - Write the FETI problem (block-diagonal K, f, B with row kinds, c, R, coordinates) to a PETSc binary viewer.

  Collective

  Input Parameters:
+ feti   - the FETI problem, set up
- viewer - a binary viewer (`PetscViewerBinaryOpen()`)

  Notes:
  The file is a sequence of standard PETSc objects, readable by any PETSc program or by
  PetscBinaryIO.py; the format is documented in docs/feti-interchange.md. K is written as the
  operator on the primal space (what `FETIApplyK()` applies), R as the kernel basis actually used.
  Reading it back with `FETILoad()`, on any number of ranks, gives the same problem.

  Level: intermediate

.seealso: `FETILoad()`, `FETISetUp()`
@*/
PetscErrorCode FETIWrite(FETI feti, PetscViewer viewer)
{
  FETI_Impl            &impl = *feti->impl;
  MPI_Comm              comm = PetscObjectComm((PetscObject)feti);
  PetscMPIInt           rank;
  PetscInt              hascoords = 1, hasall;
  std::vector<PetscInt> header, sizes, kernels, dirichlet, kinds(impl.kinds.begin(), impl.kinds.end());
  Mat                   K;
  Vec                   c, coords;
  PetscBool             isbinary;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(feti, FETI_CLASSID, 1);
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 2);
  PetscCheck(impl.setupcalled, comm, PETSC_ERR_ORDER, "Call FETISetUp() before FETIWrite()");
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERBINARY, &isbinary));
  PetscCheck(isbinary, comm, PETSC_ERR_ARG_WRONG, "FETIWrite() needs a binary viewer (PetscViewerBinaryOpen())");
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  for (FETISubdomain &sd : impl.sub) {
    PetscCallCXX(sizes.push_back(sd.n));
    PetscCallCXX(kernels.push_back(sd.nkernel));
    for (PetscInt d : sd.dirichletdofs) PetscCallCXX(dirichlet.push_back(sd.offset + d));
    if (!sd.coords) hascoords = 0;
  }
  PetscCall(MPIU_Allreduce(&hascoords, &hasall, 1, MPIU_INT, MPI_MIN, comm));
  if (rank == 0) header = {FETI_FILE_MAGIC, FETI_FILE_VERSION, impl.nglobalsub, hasall};
  PetscCall(ViewInts(comm, header, viewer));
  PetscCall(ViewInts(comm, sizes, viewer));
  PetscCall(ViewInts(comm, kernels, viewer));
  PetscCall(ViewInts(comm, dirichlet, viewer));
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

/*@C
  FETILoad - Read a FETI problem written by `FETIWrite()` (or by another code in the same format) into an empty FETI object.

  Collective

  Input Parameters:
+ feti   - a FETI object from `FETICreate()`
- viewer - a binary viewer (`PetscViewerBinaryOpen()` with `FILE_MODE_READ`)

  Notes:
  The subdomains are spread over the ranks of feti's communicator in contiguous ranges (there
  must be at least as many subdomains as ranks). The kernels stored in the file are used (as
  `FETISetSubdomainKernel()`), the coordinates, if present, place the fixing nodes. Call
  `FETISetFromOptions()` and `FETISetUp()` afterwards.

  Level: intermediate

.seealso: `FETIWrite()`, `FETICreate()`
@*/
PetscErrorCode FETILoad(FETI feti, PetscViewer viewer)
{
  MPI_Comm              comm = PetscObjectComm((PetscObject)feti);
  PetscMPIInt           size, rank;
  std::vector<PetscInt> header, sizes, kernels, dirichlet, kinds, offsets, localsizes;
  PetscInt              nsub, first, nlocal, nlocalprimal = 0, nlocalcoarse = 0, nprimal = 0, ncoarse = 0, primalstart = 0;
  Mat                   K, B, R;
  Vec                   f, c, coords = NULL;
  std::vector<Mat>      Ks;
  std::vector<Vec>      fs, xs;
  PetscBool             isbinary;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(feti, FETI_CLASSID, 1);
  PetscValidHeaderSpecific(viewer, PETSC_VIEWER_CLASSID, 2);
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERBINARY, &isbinary));
  PetscCheck(isbinary, comm, PETSC_ERR_ARG_WRONG, "FETILoad() needs a binary viewer (PetscViewerBinaryOpen())");
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(LoadInts(comm, viewer, header));
  PetscCheck(header.size() == 4 && header[0] == FETI_FILE_MAGIC, comm, PETSC_ERR_FILE_UNEXPECTED, "FETILoad(): the file does not start with a FETI header (docs/feti-interchange.md)");
  PetscCheck(header[1] == FETI_FILE_VERSION, comm, PETSC_ERR_FILE_UNEXPECTED, "FETILoad(): file format version %" PetscInt_FMT ", this library reads version %d", header[1], FETI_FILE_VERSION);
  nsub = header[2];
  PetscCall(LoadInts(comm, viewer, sizes));
  PetscCall(LoadInts(comm, viewer, kernels));
  PetscCall(LoadInts(comm, viewer, dirichlet));
  PetscCheck((PetscInt)sizes.size() == nsub && (PetscInt)kernels.size() == nsub, comm, PETSC_ERR_FILE_UNEXPECTED,
             "FETILoad(): %" PetscInt_FMT " subdomains announced, %d sizes and %d kernel dimensions found", nsub, (int)sizes.size(), (int)kernels.size());
  PetscCheck(nsub >= size, comm, PETSC_ERR_ARG_SIZ, "FETILoad(): %" PetscInt_FMT " subdomains for %d MPI ranks: every rank needs at least one subdomain", nsub, size);
  first  = (nsub * rank) / size;
  nlocal = (nsub * (rank + 1)) / size - first;
  for (PetscInt s = 0; s < nsub; s++) {
    if (s < first) primalstart += sizes[s];
    nprimal += sizes[s];
    ncoarse += kernels[s];
  }
  for (PetscInt s = first; s < first + nlocal; s++) {
    PetscCallCXX(offsets.push_back(nlocalprimal));
    PetscCallCXX(localsizes.push_back(sizes[s]));
    nlocalprimal += sizes[s];
    nlocalcoarse += kernels[s];
  }

  PetscCall(MatCreate(comm, &K));
  PetscCall(MatSetSizes(K, nlocalprimal, nlocalprimal, nprimal, nprimal));
  PetscCall(MatSetType(K, MATAIJ));
  PetscCall(MatLoad(K, viewer));
  PetscCall(VecCreate(comm, &f));
  PetscCall(VecSetSizes(f, nlocalprimal, nprimal));
  PetscCall(VecSetType(f, VECSTANDARD));
  PetscCall(VecLoad(f, viewer));
  PetscCall(MatCreate(comm, &B));
  PetscCall(MatSetSizes(B, PETSC_DECIDE, nlocalprimal, PETSC_DETERMINE, nprimal));
  PetscCall(MatSetType(B, MATAIJ));
  PetscCall(MatLoad(B, viewer));
  PetscCall(MatCreateVecs(B, NULL, &c));
  PetscCall(VecLoad(c, viewer));
  PetscCall(LoadInts(comm, viewer, kinds));
  PetscCall(MatCreate(comm, &R));
  PetscCall(MatSetSizes(R, nlocalprimal, nlocalcoarse, nprimal, ncoarse));
  PetscCall(MatSetType(R, MATAIJ));
  PetscCall(MatLoad(R, viewer));
  if (header[3]) {
    PetscCall(VecDuplicate(f, &coords));
    PetscCall(VecLoad(coords, viewer));
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
    PetscInt                 rstart, rend, nrows;
    std::vector<FETIRowKind> k;
    PetscCall(MatGetOwnershipRange(B, &rstart, &rend));
    PetscCall(MatGetSize(B, &nrows, NULL));
    PetscCheck((PetscInt)kinds.size() == nrows, comm, PETSC_ERR_FILE_UNEXPECTED, "FETILoad(): %d row kinds for %" PetscInt_FMT " rows of B", (int)kinds.size(), nrows);
    for (PetscInt r = rstart; r < rend; r++) PetscCallCXX(k.push_back((FETIRowKind)kinds[r]));
    PetscCall(FETISetConstraints(feti, B, c, k.data()));
  }
  PetscCall(MatDestroy(&B));
  PetscCall(VecDestroy(&c));
  PetscFunctionReturn(PETSC_SUCCESS);
}
