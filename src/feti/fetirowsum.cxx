/* Sparse products whose results are bitwise the same on any number of ranks.

   PETSc's MatMult() of an MPIAIJ matrix sums each row as its diagonal block, then its off-diagonal block,
   and MatMultTranspose() and the matrix products add partial sums of several ranks: the order of the
   additions, and so the rounding, depends on how rows and columns are spread over the ranks. FETI's
   numbering of primal, dual and coarse unknowns does not (subdomains are numbered globally), so summing
   every row in increasing global column order makes B, B' and the coarse matrix G G' independent of the
   rank count; with the reproducible dot products of the QP solvers, a whole solve then takes the same
   iterations to the last bit on 1 or 64 ranks. The cost is a copy of the ghost entries of x per product
   (the products with B are a small part of an F product). */
#include <conefeti/private/fetiimpl.h>

#include <algorithm>

/* CSR arrays of a sequential AIJ block (borrowed: valid while the matrix lives and is not changed) */
static PetscErrorCode CSR(Mat A, const PetscInt **ia, const PetscInt **ja, const PetscScalar **a)
{
  PetscScalar *v;

  PetscFunctionBegin;
  PetscCall(MatSeqAIJGetCSRAndMemType(A, ia, ja, &v, NULL));
  if (a) *a = v;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Prepare y = A x (or y = A' x with transpose, through an explicit transpose kept here). A of any type:
   anything but (MPI|Seq)AIJ is converted once. */
PetscErrorCode FETIRowSumCreate(Mat A, PetscBool transpose, FETIRowSum &rs)
{
  PetscBool mpi, seq;
  Vec       x;

  PetscFunctionBegin;
  PetscCall(FETIRowSumDestroy(rs));
  PetscCall(PetscObjectBaseTypeCompare((PetscObject)A, MATMPIAIJ, &mpi));
  PetscCall(PetscObjectBaseTypeCompare((PetscObject)A, MATSEQAIJ, &seq));
  if (transpose) {
    Mat At;
    if (!mpi && !seq) {
      Mat aij;
      PetscCall(MatConvert(A, MATAIJ, MAT_INITIAL_MATRIX, &aij));
      PetscCall(MatTranspose(aij, MAT_INITIAL_MATRIX, &At));
      PetscCall(MatDestroy(&aij));
    } else PetscCall(MatTranspose(A, MAT_INITIAL_MATRIX, &At));
    rs.A = At;
  } else if (!mpi && !seq) PetscCall(MatConvert(A, MATAIJ, MAT_INITIAL_MATRIX, &rs.A));
  else {
    PetscCall(PetscObjectReference((PetscObject)A));
    rs.A = A;
  }
  PetscCall(PetscObjectBaseTypeCompare((PetscObject)rs.A, MATMPIAIJ, &mpi));
  if (mpi) {
    PetscInt        nghost, m, cend;
    const PetscInt *ia, *ja;
    IS              is;
    PetscCall(MatMPIAIJGetSeqAIJ(rs.A, &rs.Ad, &rs.Ao, &rs.garray));
    PetscCall(MatGetOwnershipRangeColumn(rs.A, &rs.cstart, &cend));
    PetscCall(MatGetLocalSize(rs.Ao, &m, &nghost));
    /* the ghost columns in garray are sorted: per row, the off-diagonal entries below cstart come first */
    PetscCall(CSR(rs.Ao, &ia, &ja, NULL));
    PetscCallCXX(rs.split.resize(m));
    for (PetscInt i = 0; i < m; i++) {
      PetscInt k = ia[i];
      while (k < ia[i + 1] && rs.garray[ja[k]] < rs.cstart) k++;
      rs.split[i] = k;
      if (ia[i + 1] > ia[i]) PetscCallCXX(rs.ghosted.push_back(i));
    }
    PetscCall(MatCreateVecs(rs.A, &x, NULL));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, nghost, &rs.ghosts));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nghost, rs.garray, PETSC_USE_POINTER, &is));
    PetscCall(VecScatterCreate(x, is, rs.ghosts, NULL, &rs.scatter));
    PetscCall(ISDestroy(&is));
    PetscCall(VecDestroy(&x));
  } else rs.Ad = rs.A;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ya[i] for the rows i of list (all m rows when list is NULL), each summed in increasing global column order: the
   ghost columns below the local ones, the local ones, the rest. ga NULL: only the rows without ghost entries.
   dcols NULL: the local columns are the diagonal block's own; otherwise one index per entry of the diagonal block
   (in its order) into xa, a compact copy of x (FETIRowSumApplyCompact()). */
static PetscErrorCode SumRows(const FETIRowSum &rs, const PetscScalar *xa, const PetscScalar *ga, PetscScalar *ya, PetscInt m, const PetscInt *list, const PetscInt *dcols = nullptr)
{
  const PetscInt    *dia, *dja, *oia = nullptr, *oja = nullptr;
  const PetscScalar *da = nullptr, *oa = nullptr;

  PetscFunctionBegin;
  PetscCall(CSR(rs.Ad, &dia, &dja, &da));
  if (dcols) dja = dcols;
  if (rs.scatter) PetscCall(CSR(rs.Ao, &oia, &oja, &oa));
  for (PetscInt t = 0; t < m; t++) {
    const PetscInt i = list ? list[t] : t;
    if (!ga && oia && oia[i + 1] > oia[i]) continue; /* its ghosts have not arrived */
    PetscScalar sum = 0;
    if (oia)
      for (PetscInt k = oia[i]; k < rs.split[i]; k++) sum += oa[k] * ga[oja[k]];
    for (PetscInt k = dia[i]; k < dia[i + 1]; k++) sum += da[k] * xa[dja[k]];
    if (oia)
      for (PetscInt k = rs.split[i]; k < oia[i + 1]; k++) sum += oa[k] * ga[oja[k]];
    ya[i] = sum;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode LogRowSumFlops(const FETIRowSum &rs)
{
  const PetscInt *dia, *dja, *oia = nullptr, *oja;
  PetscInt        m;

  PetscFunctionBegin;
  PetscCall(CSR(rs.Ad, &dia, &dja, NULL));
  if (rs.scatter) PetscCall(CSR(rs.Ao, &oia, &oja, NULL));
  PetscCall(MatGetLocalSize(rs.Ad, &m, NULL));
  PetscCall(PetscLogFlops(2.0 * (dia[m] + (oia ? oia[m] : 0))));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = A x, every row summed in increasing global column order. The rows without ghost entries (all but those
   at the boundary between the ranks' parts) are summed while the ghost values travel: a rank that comes first
   does them instead of waiting for the other, and each row is summed as it would be otherwise (the same bits) */
PetscErrorCode FETIRowSumApply(FETIRowSum &rs, Vec x, Vec y)
{
  PetscInt m;

  PetscFunctionBegin;
  PetscCall(MatGetLocalSize(rs.Ad, &m, NULL));
  PetscCall(FETIRowSumApplyRows(rs, x, m, NULL, y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The rows of y = A x in rows (increasing; NULL: all nrows = m rows), which must hold every row with ghost entries;
   the other rows of y are left as they were. For a caller that reads y only there (G = R'B' reads B' x only at the
   dofs B touches, fetioperators.cxx): the empty rows are neither visited nor written. */
PetscErrorCode FETIRowSumApplyRows(FETIRowSum &rs, Vec x, PetscInt nrows, const PetscInt rows[], Vec y)
{
  const PetscScalar *ga = nullptr, *xa;
  PetscScalar       *ya;

  PetscFunctionBegin;
  if (rs.scatter) PetscCall(VecScatterBegin(rs.scatter, x, rs.ghosts, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(y, &ya));
  PetscCall(SumRows(rs, xa, NULL, ya, nrows, rows));
  if (rs.scatter) {
    PetscCall(VecScatterEnd(rs.scatter, x, rs.ghosts, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(rs.ghosts, &ga));
    PetscCall(SumRows(rs, xa, ga, ya, (PetscInt)rs.ghosted.size(), rs.ghosted.data()));
    PetscCall(VecRestoreArrayRead(rs.ghosts, &ga));
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(LogRowSumFlops(rs));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = A x over all rows from the local entries xa (through dcols when not NULL, see SumRows()) and the ghost entries ga */
static PetscErrorCode SumAllRows(FETIRowSum &rs, const PetscScalar *xa, const PetscInt *dcols, const PetscScalar *ga, Vec y)
{
  PetscScalar *ya;
  PetscInt     m;

  PetscFunctionBegin;
  PetscCall(MatGetLocalSize(rs.Ad, &m, NULL));
  PetscCall(VecGetArray(y, &ya));
  PetscCall(SumRows(rs, xa, ga, ya, m, NULL, dcols));
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(LogRowSumFlops(rs));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = A x with the ghost entries of x (at garray) given by the caller instead of received: no message */
PetscErrorCode FETIRowSumApplyWithGhosts(FETIRowSum &rs, Vec x, const PetscScalar *ga, Vec y)
{
  const PetscScalar *xa;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(SumAllRows(rs, xa, NULL, ga, y));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = A x with x's local entries read from a compact array xc through dcols, one index per entry of the diagonal
   block in its order (the caller's numbering of the columns it fills), and the ghost entries from ga (NULL when A
   has no ghost block). The same terms in the same order as FETIRowSumApplyWithGhosts(), so the same bits; what
   changes is the memory the products gather from (G' = B (R x) at 10^6 unknowns: R x at the touched dofs only, 55%
   of a 12.6 MB primal vector; docs/scale.md, "The projector's cost"). */
PetscErrorCode FETIRowSumApplyCompact(FETIRowSum &rs, const PetscInt dcols[], const PetscScalar xc[], const PetscScalar ga[], Vec y)
{
  PetscFunctionBegin;
  PetscCheck(ga || rs.ghosted.empty(), PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "FETIRowSumApplyCompact: the ghost values are needed");
  PetscCall(SumAllRows(rs, xc, dcols, ga, y));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FETIRowSumDestroy(FETIRowSum &rs)
{
  PetscFunctionBegin;
  PetscCall(MatDestroy(&rs.A));
  PetscCall(VecScatterDestroy(&rs.scatter));
  PetscCall(VecDestroy(&rs.ghosts));
  rs.Ad = rs.Ao = nullptr;
  rs.garray     = nullptr;
  PetscCallCXX(std::vector<PetscInt>().swap(rs.split));
  PetscCallCXX(std::vector<PetscInt>().swap(rs.ghosted));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* M = Gt' W Gt with W = diag(w.^2) (w = NULL: the identity), the coarse matrix G G' (or G_A G_A' of a row
   subset), summed for every entry over the dual rows in increasing order. Gt: dual x coarse (AIJ). */
PetscErrorCode FETIAssembleCoarseMatrix(Mat Gt, Vec w, Mat *M)
{
  MPI_Comm                 comm = PetscObjectComm((PetscObject)Gt);
  Mat                      G, *sub;
  FETIRowSum               rows; /* G's rows in the canonical order */
  IS                       isrow, iscol;
  PetscInt                 nc, ncl, cstart, nd, mrows;
  std::vector<PetscInt>    need, dnz, onz, touched;
  std::vector<PetscScalar> acc, wr;
  std::vector<char>        used;

  PetscFunctionBegin;
  PetscCall(MatGetSize(Gt, &nd, &nc));
  PetscCall(MatGetLocalSize(Gt, NULL, &ncl));
  PetscCall(MatTranspose(Gt, MAT_INITIAL_MATRIX, &G));
  PetscCall(FETIRowSumCreate(G, PETSC_FALSE, rows));
  PetscCall(MatDestroy(&G));
  PetscCall(MatGetOwnershipRange(rows.A, &cstart, NULL));
  PetscCall(MatGetLocalSize(rows.A, &mrows, NULL));
  /* the dual rows r that the local coarse rows touch, and those rows of Gt (all columns) */
  const PetscInt    *dia, *dja, *oia = nullptr, *oja = nullptr;
  const PetscScalar *da = nullptr, *oa = nullptr;
  PetscInt           dcstart = rows.cstart;
  PetscCall(CSR(rows.Ad, &dia, &dja, &da));
  if (rows.Ao) PetscCall(CSR(rows.Ao, &oia, &oja, &oa));
  { /* marked in a table of all dual rows and read back in order: each row is reached from ~12 coarse rows, so
       sorting the list with repetitions cost more than the rest of the assembly */
    std::vector<char> mark(nd, 0);
    for (PetscInt i = 0; i < mrows; i++) {
      for (PetscInt k = dia[i]; k < dia[i + 1]; k++) mark[dcstart + dja[k]] = 1;
      if (oia)
        for (PetscInt k = oia[i]; k < oia[i + 1]; k++) mark[rows.garray[oja[k]]] = 1;
    }
    for (PetscInt r = 0; r < nd; r++)
      if (mark[r]) PetscCallCXX(need.push_back(r));
  }
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)need.size(), need.data(), PETSC_COPY_VALUES, &isrow));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, nc, 0, 1, &iscol));
  PetscCall(MatCreateSubMatrices(Gt, 1, &isrow, &iscol, MAT_INITIAL_MATRIX, &sub));
  PetscCall(ISDestroy(&iscol));
  PetscCallCXX(wr.assign(need.size(), 1.0));
  if (w) { /* w at the needed rows */
    Vec                wl;
    VecScatter         sc;
    const PetscScalar *a;
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, (PetscInt)need.size(), &wl));
    PetscCall(VecScatterCreate(w, isrow, wl, NULL, &sc));
    PetscCall(VecScatterBegin(sc, w, wl, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(sc, w, wl, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(wl, &a));
    for (size_t k = 0; k < need.size(); k++) wr[k] = a[k];
    PetscCall(VecRestoreArrayRead(wl, &a));
    PetscCall(VecScatterDestroy(&sc));
    PetscCall(VecDestroy(&wl));
  }
  PetscCall(ISDestroy(&isrow));

  /* row i of M: for r in increasing order, acc[j] += (w_r G(i,r)) (w_r Gt(r,j)) */
  const PetscInt    *sia, *sja;
  const PetscScalar *sa = nullptr;
  PetscCall(CSR(sub[0], &sia, &sja, &sa));
  PetscCallCXX(acc.assign(nc, 0.0));
  PetscCallCXX(used.assign(nc, 0));
  std::vector<std::vector<PetscInt>>    rowcols(mrows);
  std::vector<std::vector<PetscScalar>> rowvals(mrows);
  PetscCallCXX(dnz.assign(mrows, 0));
  PetscCallCXX(onz.assign(mrows, 0));
  auto position = [&](PetscInt r) { return (PetscInt)(std::lower_bound(need.begin(), need.end(), r) - need.begin()); };
  for (PetscInt i = 0; i < mrows; i++) {
    touched.clear(); /* the columns row i reaches; the capacity is reused from row to row */
    auto term = [&](PetscInt r, PetscScalar g) {
      const PetscInt p = position(r);
      for (PetscInt k = sia[p]; k < sia[p + 1]; k++) {
        const PetscInt j = sja[k];
        if (!used[j]) {
          used[j] = 1;
          touched.push_back(j);
        }
        acc[j] += (wr[p] * g) * (wr[p] * sa[k]);
      }
    };
    if (oia)
      for (PetscInt k = oia[i]; k < rows.split[i]; k++) term(rows.garray[oja[k]], oa[k]);
    for (PetscInt k = dia[i]; k < dia[i + 1]; k++) term(dcstart + dja[k], da[k]);
    if (oia)
      for (PetscInt k = rows.split[i]; k < oia[i + 1]; k++) term(rows.garray[oja[k]], oa[k]);
    std::sort(touched.begin(), touched.end());
    for (PetscInt j : touched) {
      PetscCallCXX(rowcols[i].push_back(j));
      PetscCallCXX(rowvals[i].push_back(acc[j]));
      if (j >= cstart && j < cstart + ncl) dnz[i]++;
      else onz[i]++;
      acc[j]  = 0;
      used[j] = 0;
    }
  }
  PetscCall(MatDestroySubMatrices(1, &sub));
  PetscCall(FETIRowSumDestroy(rows));

  PetscCall(MatCreate(comm, M));
  PetscCall(MatSetSizes(*M, ncl, ncl, nc, nc));
  PetscCall(MatSetType(*M, MATAIJ));
  PetscCall(MatSeqAIJSetPreallocation(*M, 0, dnz.data()));
  PetscCall(MatMPIAIJSetPreallocation(*M, 0, dnz.data(), 0, onz.data()));
  for (PetscInt i = 0; i < mrows; i++) {
    const PetscInt row = cstart + i;
    PetscCall(MatSetValues(*M, 1, &row, (PetscInt)rowcols[i].size(), rowcols[i].data(), rowvals[i].data(), INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(*M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatSetOption(*M, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(*M, MAT_SPD, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}
