/* The coarse matrix A = G G' solved in two halves and a separator (-feti_coarse_mode split).

   Why: a coarse solve reads the whole Cholesky factor twice (forward and back) and little else, so it is bound by
   memory traffic. In redundant mode every rank reads its own copy of the whole factor for every solve, and on a
   machine whose cores share the memory bus two ranks take as long as one (docs/scale.md, "Two ranks: where the
   time goes"). Here a vertex separator S of A's graph (METIS) splits the unknowns into two parts I_0, I_1 that do
   not couple, and A is factored by blocks in the order I_0, I_1, S:

       A = [ P_0'L_0      0      0  ] [ L_0'P_0    0      M_0 ]      L_p L_p' = P_p A_pp P_p'   (CHOLMOD, part p alone)
           [    0      P_1'L_1   0  ] [    0    L_1'P_1   M_1 ]      M_p = L_p^-1 P_p A_pS       (sparse, n_p x n_S)
           [  M_0'       M_1'   L_S ] [    0       0     L_S' ]      L_S L_S' = A_SS - M_0'M_0 - M_1'M_1   (dense)

   A solve is then z_p = L_p^-1 P_p b_p for each part, x_S = (L_S L_S')^-1 (b_S - M_0'z_0 - M_1'z_1), and
   x_p = P_p' L_p^-T (z_p - M_p x_S). On two or more ranks rank 0 does part 0 and rank 1 part 1 (one reduction of
   n_S values, and one collective that hands the parts' solutions to all); the separator's dense solve is done by
   every rank. Each of the two reads about half of the factor instead of all of it. Each part is ordered by CAMD
   together with S, S constrained last, so that M_p (the fill into S's rows) stays small. On one rank the same arithmetic runs for both parts
   in turn, so the results are the same bits on any number of ranks: the separator and both factors come from the
   same gathered matrix, and the two parts' sums M_0'z_0 + M_1'z_1 are added in the same order (a sum of two terms,
   or of two terms and zeros, does not depend on the order of the MPI reduction). */
#include <conefeti/private/fetiimpl.h>
#include <petscblaslapack.h>
#include <metis.h>
#include <cholmod.h>
#include <cholmod_camd.h>
#include <algorithm>
#include <climits>

struct FETICoarseSplit {
  MPI_Comm                 comm = MPI_COMM_NULL;
  PetscMPIInt              size = 1, rank = 0;
  PetscInt                 N = 0;
  std::vector<PetscInt>    part[2];                  /* the original indices of I_0 and I_1, increasing */
  std::vector<PetscInt>    sep;                      /* those of S */
  std::vector<PetscInt>    sloc;                     /* the position in S of each unknown, -1 outside S */
  bool                     here[2] = {false, false}; /* the parts this rank solves */
  bool                     started = false;
  cholmod_common           cc;
  cholmod_factor          *L[2]   = {nullptr, nullptr};
  cholmod_dense           *rhs[2] = {nullptr, nullptr}, *X[2] = {nullptr, nullptr}, *Y[2] = {nullptr, nullptr}, *E[2] = {nullptr, nullptr};
  std::vector<PetscInt>    perm[2]; /* row i of L_p is the unknown part[p][perm[p][i]] */
  std::vector<PetscInt>    mptr[2], mcol[2];
  std::vector<PetscScalar> mval[2]; /* M_p by rows (CSR, n_p x n_S) */
  std::vector<PetscScalar> LS;      /* L_S, column-major n_S x n_S (lower triangle) */
  std::vector<PetscScalar> c[2], t, buf;
  std::vector<PetscMPIInt> counts, displs;
  PetscMPIInt              nSmpi  = 0;
  double                   lnz[2] = {0, 0};
};

/* The separator and the two parts of A's graph; deterministic (METIS with a fixed seed). A graph METIS cannot
   split (no edges, or too small) keeps every unknown in part 0 and an empty separator. */
static PetscErrorCode SplitGraph(Mat A, FETICoarseSplit &s)
{
  const PetscInt *ia, *ja;
  PetscInt        n;
  PetscBool       done;

  PetscFunctionBegin;
  PetscCall(MatGetRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "-feti_coarse_mode split: the coarse matrix does not give its structure (MatGetRowIJ())");
  std::vector<idx_t> xadj(n + 1, 0), adjncy, where(n, 0);
  PetscCallCXX(adjncy.reserve(ia[n]));
  for (PetscInt i = 0; i < n; i++) {
    for (PetscInt k = ia[i]; k < ia[i + 1]; k++)
      if (ja[k] != i) adjncy.push_back((idx_t)ja[k]);
    xadj[i + 1] = (idx_t)adjncy.size();
  }
  {
    PetscInt nr; /* MatRestoreRowIJ() may clear its size argument */
    PetscCall(MatRestoreRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja, &done));
  }
  if (n >= 4 && !adjncy.empty()) {
    idx_t nv = (idx_t)n, sepsize = 0, options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 7; /* the same split on every rank and every run */
    if (METIS_ComputeVertexSeparator(&nv, xadj.data(), adjncy.data(), NULL, options, &sepsize, where.data()) != METIS_OK) where.assign(n, 0);
  }
  { /* a guard: no coupling may cross the separator */
    PetscInt cross = 0;
    for (PetscInt i = 0; i < n; i++)
      for (idx_t k = xadj[i]; k < xadj[i + 1]; k++)
        if (where[i] != 2 && where[adjncy[k]] != 2 && where[i] != where[adjncy[k]]) cross++;
    PetscCheck(!cross, PETSC_COMM_SELF, PETSC_ERR_PLIB, "-feti_coarse_mode split: METIS's separator leaves %" PetscInt_FMT " couplings between the two parts", cross);
  }
  PetscCallCXX(s.sloc.assign(n, -1));
  for (PetscInt i = 0; i < n; i++) {
    if (where[i] == 2) {
      s.sloc[i] = (PetscInt)s.sep.size();
      PetscCallCXX(s.sep.push_back(i));
    } else PetscCallCXX(s.part[where[i] == 1 ? 1 : 0].push_back(i));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* CHOLMOD's factor of A(part, part) and M = L^-1 P A(part, S) by rows; *failed: not positive definite */
static PetscErrorCode FactorPart(Mat A, FETICoarseSplit &s, int p, PetscBool *failed)
{
  const std::vector<PetscInt> &I = s.part[p];
  const PetscInt               n = (PetscInt)I.size(), nS = (PetscInt)s.sep.size();
  const PetscInt              *ia, *ja;
  const PetscScalar           *va;
  PetscScalar                 *v;
  std::vector<PetscInt>        loc(s.N, -1);

  PetscFunctionBegin;
  *failed = PETSC_FALSE;
  PetscCallCXX(s.c[p].assign(nS, 0.0));
  if (!n) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt k = 0; k < n; k++) loc[I[k]] = k;
  PetscCall(MatSeqAIJGetCSRAndMemType(A, &ia, &ja, &v, NULL));
  va = v;
  /* A(I, I), upper triangle by columns: A is symmetric, so column j is row j */
  size_t nnz = 0;
  for (PetscInt k = 0; k < n; k++)
    for (PetscInt e = ia[I[k]]; e < ia[I[k] + 1]; e++)
      if (loc[ja[e]] >= 0 && loc[ja[e]] <= k) nnz++;
  PetscCheck(nnz <= (size_t)INT_MAX, PETSC_COMM_SELF, PETSC_ERR_SUP, "-feti_coarse_mode split: %zu entries of a part exceed CHOLMOD's int indices", nnz);
  cholmod_sparse *App = cholmod_allocate_sparse((size_t)n, (size_t)n, nnz, 1, 1, 1, CHOLMOD_REAL, &s.cc);
  PetscCheck(App, PETSC_COMM_SELF, PETSC_ERR_MEM, "-feti_coarse_mode split: CHOLMOD could not allocate a part of the coarse matrix (%" PetscInt_FMT " unknowns)", n);
  {
    int    *cp = (int *)App->p, *ri = (int *)App->i;
    double *cv = (double *)App->x;
    size_t  t  = 0;
    for (PetscInt k = 0; k < n; k++) {
      cp[k] = (int)t;
      /* rows increasing within a column (CHOLMOD's sorted form): the local order follows the global one */
      for (PetscInt e = ia[I[k]]; e < ia[I[k] + 1]; e++)
        if (loc[ja[e]] >= 0 && loc[ja[e]] <= k) {
          ri[t] = (int)loc[ja[e]];
          cv[t] = PetscRealPart(va[e]);
          t++;
        }
    }
    cp[n] = (int)t;
  }
  {
    /* The ordering of the part: CAMD on the part and the separator together, the separator constrained last. The
       fill into the separator's rows of that factor is M, so this keeps M small (at the brick's 10^6 unknowns half
       the entries of M under CHOLMOD's own ordering of the part alone, for about the same entries of L_0 + L_1). */
    const std::vector<PetscInt> &sloc = s.sloc;
    std::vector<int>             col, cmember(n + nS, 0), eperm(n + nS), uperm;
    size_t                       enz = App->nzmax;
    for (PetscInt k = 0; k < nS; k++)
      for (PetscInt e = ia[s.sep[k]]; e < ia[s.sep[k] + 1]; e++)
        if (loc[ja[e]] >= 0 || (sloc[ja[e]] >= 0 && sloc[ja[e]] <= k)) enz++;
    PetscCheck(enz <= (size_t)INT_MAX, PETSC_COMM_SELF, PETSC_ERR_SUP, "-feti_coarse_mode split: %zu entries of a part and the separator exceed CHOLMOD's int indices", enz);
    cholmod_sparse *Ext = cholmod_allocate_sparse((size_t)(n + nS), (size_t)(n + nS), enz, 1, 1, 1, CHOLMOD_PATTERN, &s.cc);
    if (!Ext) cholmod_free_sparse(&App, &s.cc);
    PetscCheck(Ext, PETSC_COMM_SELF, PETSC_ERR_MEM, "-feti_coarse_mode split: CHOLMOD could not allocate the pattern of a part and the separator");
    int   *cp = (int *)Ext->p, *ri = (int *)Ext->i;
    size_t t = 0;
    for (PetscInt k = 0; k < n; k++) { /* the part's columns as in App */
      cp[k] = (int)t;
      for (int e = ((int *)App->p)[k]; e < ((int *)App->p)[k + 1]; e++) ri[t++] = ((int *)App->i)[e];
    }
    for (PetscInt k = 0; k < nS; k++) { /* separator column k: its rows in the part, then in the separator up to k */
      cp[n + k] = (int)t;
      col.clear();
      for (PetscInt e = ia[s.sep[k]]; e < ia[s.sep[k] + 1]; e++) {
        if (loc[ja[e]] >= 0) col.push_back((int)loc[ja[e]]);
        else if (sloc[ja[e]] >= 0 && sloc[ja[e]] <= k) col.push_back((int)(n + sloc[ja[e]]));
      }
      std::sort(col.begin(), col.end());
      for (int r : col) ri[t++] = r;
      cmember[n + k] = 1;
    }
    cp[n + nS]        = (int)t;
    const int ordered = cholmod_camd(Ext, NULL, 0, cmember.data(), eperm.data(), &s.cc);
    cholmod_free_sparse(&Ext, &s.cc);
    if (!ordered) cholmod_free_sparse(&App, &s.cc);
    PetscCheck(ordered, PETSC_COMM_SELF, PETSC_ERR_LIB, "-feti_coarse_mode split: CHOLMOD's CAMD ordering failed (status %d)", s.cc.status);
    for (int q : eperm)
      if (q < n) uperm.push_back(q);
    s.cc.nmethods           = 1;
    s.cc.method[0].ordering = CHOLMOD_GIVEN;
    s.L[p]                  = cholmod_analyze_p(App, uperm.data(), NULL, 0, &s.cc);
  }
  if (!s.L[p]) cholmod_free_sparse(&App, &s.cc);
  PetscCheck(s.L[p], PETSC_COMM_SELF, PETSC_ERR_LIB, "-feti_coarse_mode split: CHOLMOD's analysis of a part of the coarse matrix failed (status %d)", s.cc.status);
  const int ok = cholmod_factorize(App, s.L[p], &s.cc);
  cholmod_free_sparse(&App, &s.cc);
  PetscCheck(ok, PETSC_COMM_SELF, PETSC_ERR_LIB, "-feti_coarse_mode split: CHOLMOD's factorization of a part of the coarse matrix failed (status %d)", s.cc.status);
  if (s.cc.status == CHOLMOD_NOT_POSDEF || s.L[p]->minor < (size_t)n) {
    *failed = PETSC_TRUE;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCheck(s.L[p]->is_ll, PETSC_COMM_SELF, PETSC_ERR_LIB, "-feti_coarse_mode split: CHOLMOD returned an L D L' factor where L L' was asked for");
  s.lnz[p] = s.cc.lnz;
  {
    const int *P = (const int *)s.L[p]->Perm;
    PetscCallCXX(s.perm[p].assign(P, P + n));
  }
  std::vector<PetscInt> inv(n); /* the row of L_p of each unknown of the part */
  for (PetscInt i = 0; i < n; i++) inv[s.perm[p][i]] = i;
  /* M = L^-1 P A(I, S), a block of columns at a time (dense), kept where not exactly zero */
  std::vector<std::vector<std::pair<PetscInt, PetscScalar>>> rows(n);
  const PetscInt                                             block = 64;
  cholmod_dense                                             *B = NULL, *Xb = NULL, *Yb = NULL, *Eb = NULL;
  for (PetscInt c0 = 0; c0 < nS; c0 += block) {
    const PetscInt nc = PetscMin(block, nS - c0);
    if (!B || (PetscInt)B->ncol != nc) {
      if (B) cholmod_free_dense(&B, &s.cc);
      B = cholmod_allocate_dense((size_t)n, (size_t)nc, (size_t)n, CHOLMOD_REAL, &s.cc);
      PetscCheck(B, PETSC_COMM_SELF, PETSC_ERR_MEM, "-feti_coarse_mode split: CHOLMOD could not allocate %" PetscInt_FMT " x %" PetscInt_FMT " values", n, nc);
    }
    double *b = (double *)B->x;
    std::fill(b, b + (size_t)n * nc, 0.0);
    for (PetscInt j = 0; j < nc; j++) { /* column j: A(I, S[c0 + j]) = A(S[c0 + j], I)' */
      const PetscInt g = s.sep[c0 + j];
      for (PetscInt e = ia[g]; e < ia[g + 1]; e++)
        if (loc[ja[e]] >= 0) b[(size_t)j * n + inv[loc[ja[e]]]] = PetscRealPart(va[e]);
    }
    if (!cholmod_solve2(CHOLMOD_L, s.L[p], B, NULL, &Xb, NULL, &Yb, &Eb, &s.cc)) {
      for (cholmod_dense **d : {&B, &Xb, &Yb, &Eb})
        if (*d) cholmod_free_dense(d, &s.cc);
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "-feti_coarse_mode split: CHOLMOD's triangular solve failed (status %d)", s.cc.status);
    }
    const double *x = (const double *)Xb->x;
    for (PetscInt j = 0; j < nc; j++)
      for (PetscInt i = 0; i < n; i++)
        if (x[(size_t)j * n + i] != 0.0) rows[i].emplace_back(c0 + j, x[(size_t)j * n + i]);
  }
  for (cholmod_dense **d : {&B, &Xb, &Yb, &Eb})
    if (*d) cholmod_free_dense(d, &s.cc);
  PetscCallCXX(s.mptr[p].assign(n + 1, 0));
  for (PetscInt i = 0; i < n; i++) s.mptr[p][i + 1] = s.mptr[p][i] + (PetscInt)rows[i].size();
  PetscCallCXX(s.mcol[p].resize(s.mptr[p][n]));
  PetscCallCXX(s.mval[p].resize(s.mptr[p][n]));
  for (PetscInt i = 0; i < n; i++)
    for (size_t k = 0; k < rows[i].size(); k++) {
      s.mcol[p][s.mptr[p][i] + k] = rows[i][k].first;
      s.mval[p][s.mptr[p][i] + k] = rows[i][k].second;
    }
  s.rhs[p] = cholmod_allocate_dense((size_t)n, 1, (size_t)n, CHOLMOD_REAL, &s.cc);
  PetscCheck(s.rhs[p], PETSC_COMM_SELF, PETSC_ERR_MEM, "-feti_coarse_mode split: CHOLMOD could not allocate a vector of %" PetscInt_FMT " values", n);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* T += M_p' M_p, lower triangle of the column-major n_S x n_S T; the rows of M in order */
static void AddGram(const FETICoarseSplit &s, int p, std::vector<PetscScalar> &T)
{
  const PetscInt nS = (PetscInt)s.sep.size(), n = (PetscInt)s.part[p].size();
  for (PetscInt i = 0; i < n && !s.mptr[p].empty(); i++)
    for (PetscInt a = s.mptr[p][i]; a < s.mptr[p][i + 1]; a++)
      for (PetscInt b = s.mptr[p][i]; b < s.mptr[p][i + 1]; b++)
        if (s.mcol[p][a] >= s.mcol[p][b]) T[(size_t)s.mcol[p][b] * nS + s.mcol[p][a]] += s.mval[p][a] * s.mval[p][b];
}

/*
  FETICoarseSplitCreate - factors the gathered coarse matrix (SeqAIJ, the same on every rank) by two parts and a
  separator; collective on comm. *failed: A is not positive definite (singular). The caller owns *split.
*/
PetscErrorCode FETICoarseSplitCreate(MPI_Comm comm, Mat A, FETICoarseSplit **split, PetscBool *failed)
{
  FETICoarseSplit *s;
  PetscInt         nS;
  PetscBool        bad[2] = {PETSC_FALSE, PETSC_FALSE};
  PetscMPIInt      gbad;

  PetscFunctionBegin;
  PetscCallCXX(s = new FETICoarseSplit);
  *split  = s;
  s->comm = comm;
  PetscCallMPI(MPI_Comm_size(comm, &s->size));
  PetscCallMPI(MPI_Comm_rank(comm, &s->rank));
  PetscCall(MatGetSize(A, &s->N, NULL));
  PetscCall(SplitGraph(A, *s));
  nS         = (PetscInt)s->sep.size();
  s->here[0] = s->size == 1 || s->rank == 0;
  s->here[1] = s->size == 1 || s->rank == 1;
  cholmod_start(&s->cc);
  s->started     = true;
  s->cc.print    = 0; /* errors come back as statuses, reported below */
  s->cc.final_ll = 1; /* L L' also where CHOLMOD picks a simplicial factor (else L D L', and CHOLMOD_L would leave D out) */
  /* T = M_0'M_0 + M_1'M_1 (lower triangle), the same bits on one rank and on several: each part's sum by itself,
     then the two added (on several ranks by the reduction, to which ranks from 2 up add zeros) */
  std::vector<PetscScalar> T((size_t)nS * nS, 0.0), T1;
  PetscErrorCode           ierr = PETSC_SUCCESS;
  for (int p = 0; p < 2 && !ierr; p++)
    if (s->here[p]) {
      /* an error inside a part happens on one rank only: it is printed there and passed on to all below */
      ierr = FactorPart(A, *s, p, &bad[p]);
      if (!ierr && !bad[p]) {
        if (s->size == 1 && p == 1) { /* one rank: part 1's sum by itself too, added below */
          PetscCallCXX(T1.assign(T.size(), 0.0));
          AddGram(*s, 1, T1);
        } else AddGram(*s, p, T);
      }
    }
  {
    PetscMPIInt state[2] = {(PetscMPIInt)ierr, bad[0] || bad[1] ? 1 : 0}, all[2];
    PetscCallMPI(MPIU_Allreduce(state, all, 2, MPI_INT, MPI_MAX, comm));
    PetscCheck(!all[0], comm, (PetscErrorCode)all[0], "-feti_coarse_mode split: the factorization of a part of the coarse matrix failed (the message above says why)");
    gbad = all[1];
  }
  *failed = gbad ? PETSC_TRUE : PETSC_FALSE;
  if (*failed) PetscFunctionReturn(PETSC_SUCCESS);
  if (s->size == 1) {
    for (size_t k = 0; k < T.size() && !T1.empty(); k++) T[k] = T[k] + T1[k];
  } else if (nS) {
    PetscMPIInt count;
    PetscCall(PetscMPIIntCast((PetscInt64)T.size(), &count));
    PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, T.data(), count, MPIU_SCALAR, MPIU_SUM, comm));
  }
  /* L_S L_S' = A_SS - T */
  {
    const PetscInt              *ia, *ja;
    const PetscScalar           *va;
    PetscScalar                 *v;
    const std::vector<PetscInt> &sloc = s->sloc;
    PetscCall(MatSeqAIJGetCSRAndMemType(A, &ia, &ja, &v, NULL));
    va = v;
    PetscCallCXX(s->LS.assign((size_t)nS * nS, 0.0));
    for (PetscInt a = 0; a < nS; a++) /* row S[a], entries (a, b) with b <= a */
      for (PetscInt e = ia[s->sep[a]]; e < ia[s->sep[a] + 1]; e++) {
        const PetscInt b = sloc[ja[e]];
        if (b >= 0 && b <= a) s->LS[(size_t)b * nS + a] = va[e];
      }
    for (PetscInt b = 0; b < nS; b++)
      for (PetscInt a = b; a < nS; a++) s->LS[(size_t)b * nS + a] -= T[(size_t)b * nS + a];
    if (nS) {
      PetscBLASInt bn, info = 0;
      PetscCall(PetscBLASIntCast(nS, &bn));
      PetscCallBLAS("LAPACKpotrf", LAPACKpotrf_("L", &bn, s->LS.data(), &bn, &info));
      PetscCheck(info >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "-feti_coarse_mode split: LAPACK potrf argument %d is wrong", (int)-info);
      if (info > 0) *failed = PETSC_TRUE; /* the same on every rank: the same numbers */
    }
  }
  PetscCallCXX(s->t.assign(nS, 0.0));
  PetscCall(PetscMPIIntCast(nS, &s->nSmpi));
  if (s->size > 1) { /* the parts' solutions travel from ranks 0 and 1 to all */
    PetscCallCXX(s->counts.assign(s->size, 0));
    PetscCallCXX(s->displs.assign(s->size, 0));
    PetscCall(PetscMPIIntCast((PetscInt)s->part[0].size(), &s->counts[0]));
    PetscCall(PetscMPIIntCast((PetscInt)s->part[1].size(), &s->counts[1]));
    s->displs[1] = s->counts[0];
    PetscCallCXX(s->buf.assign(s->part[0].size() + s->part[1].size(), 0.0));
  }
  PetscCall(PetscInfo(NULL,
                      "FETI: -feti_coarse_mode split: %" PetscInt_FMT " coarse unknowns = %zu + %zu in two parts + %" PetscInt_FMT
                      " in the separator; L_0 %.0f, L_1 %.0f, M %zu + %zu entries (0 where another rank has that part)\n",
                      s->N, s->part[0].size(), s->part[1].size(), nS, s->lnz[0], s->lnz[1], s->mval[0].size(), s->mval[1].size()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* forward half of part p: z_p = L_p^-1 P_p b_p, c_p = M_p' z_p */
static PetscErrorCode ForwardPart(FETICoarseSplit &s, int p, const PetscScalar *b)
{
  const PetscInt n = (PetscInt)s.part[p].size();

  PetscFunctionBegin;
  std::fill(s.c[p].begin(), s.c[p].end(), 0.0);
  if (!n) PetscFunctionReturn(PETSC_SUCCESS);
  double *r = (double *)s.rhs[p]->x;
  for (PetscInt i = 0; i < n; i++) r[i] = PetscRealPart(b[s.part[p][s.perm[p][i]]]);
  PetscCheck(cholmod_solve2(CHOLMOD_L, s.L[p], s.rhs[p], NULL, &s.X[p], NULL, &s.Y[p], &s.E[p], &s.cc), PETSC_COMM_SELF, PETSC_ERR_LIB,
             "-feti_coarse_mode split: CHOLMOD's triangular solve failed (status %d)", s.cc.status);
  const double *z = (const double *)s.X[p]->x;
  for (PetscInt i = 0; i < n; i++)
    for (PetscInt a = s.mptr[p][i]; a < s.mptr[p][i + 1]; a++) s.c[p][s.mcol[p][a]] += s.mval[p][a] * z[i];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* backward half of part p: x_p = P_p' L_p^-T (z_p - M_p x_S), written at the part's unknowns of x */
static PetscErrorCode BackwardPart(FETICoarseSplit &s, int p, PetscScalar *x)
{
  const PetscInt n = (PetscInt)s.part[p].size();

  PetscFunctionBegin;
  if (!n) PetscFunctionReturn(PETSC_SUCCESS);
  const double *z = (const double *)s.X[p]->x;
  double       *r = (double *)s.rhs[p]->x;
  for (PetscInt i = 0; i < n; i++) {
    double sum = 0;
    for (PetscInt a = s.mptr[p][i]; a < s.mptr[p][i + 1]; a++) sum += s.mval[p][a] * s.t[s.mcol[p][a]];
    r[i] = z[i] - sum;
  }
  PetscCheck(cholmod_solve2(CHOLMOD_Lt, s.L[p], s.rhs[p], NULL, &s.X[p], NULL, &s.Y[p], &s.E[p], &s.cc), PETSC_COMM_SELF, PETSC_ERR_LIB,
             "-feti_coarse_mode split: CHOLMOD's triangular solve failed (status %d)", s.cc.status);
  const double *y = (const double *)s.X[p]->x;
  for (PetscInt i = 0; i < n; i++) x[s.part[p][s.perm[p][i]]] = y[i];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*
  FETICoarseSplitSolve - x = A^-1 b, b and x of the full coarse length on every rank (x may not alias b);
  collective on the communicator of FETICoarseSplitCreate(). CHOLMOD's triangular solves on a factor that exists
  fail only on a broken library; such an error ends the run on the rank where it happens.
*/
PetscErrorCode FETICoarseSplitSolve(FETICoarseSplit *s, const PetscScalar *b, PetscScalar *x)
{
  const PetscInt nS = (PetscInt)s->sep.size();

  PetscFunctionBegin;
  for (int p = 0; p < 2; p++)
    if (s->here[p]) PetscCall(ForwardPart(*s, p, b));
  /* t = b_S - (M_0'z_0 + M_1'z_1) */
  if (s->size == 1) {
    for (PetscInt k = 0; k < nS; k++) s->t[k] = s->c[0][k] + s->c[1][k];
  } else if (nS) { /* ranks from 2 up add zeros */
    if (s->rank < 2) std::copy(s->c[s->rank].begin(), s->c[s->rank].end(), s->t.begin());
    else std::fill(s->t.begin(), s->t.end(), 0.0);
    PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, s->t.data(), s->nSmpi, MPIU_SCALAR, MPIU_SUM, s->comm));
  }
  for (PetscInt k = 0; k < nS; k++) s->t[k] = b[s->sep[k]] - s->t[k];
  if (nS) {
    PetscBLASInt bn, one = 1, info = 0;
    PetscCall(PetscBLASIntCast(nS, &bn));
    PetscCallBLAS("LAPACKpotrs", LAPACKpotrs_("L", &bn, &one, s->LS.data(), &bn, s->t.data(), &bn, &info));
    PetscCheck(!info, PETSC_COMM_SELF, PETSC_ERR_LIB, "-feti_coarse_mode split: LAPACK potrs failed (info %d)", (int)info);
  }
  for (PetscInt k = 0; k < nS; k++) x[s->sep[k]] = s->t[k];
  for (int p = 0; p < 2; p++)
    if (s->here[p]) PetscCall(BackwardPart(*s, p, x));
  if (s->size > 1) { /* ranks 0 and 1 hand their parts to all, in the parts' own order */
    const PetscInt n0 = (PetscInt)s->part[0].size(), n1 = (PetscInt)s->part[1].size();
    PetscScalar   *send = s->buf.data() + (s->rank == 1 ? n0 : 0);
    if (s->rank < 2)
      for (PetscInt k = 0; k < (s->rank ? n1 : n0); k++) send[k] = x[s->part[s->rank][k]];
    PetscCallMPI(MPI_Allgatherv(MPI_IN_PLACE, 0, MPIU_SCALAR, s->buf.data(), s->counts.data(), s->displs.data(), MPIU_SCALAR, s->comm));
    for (int p = 0; p < 2; p++)
      if (!s->here[p])
        for (PetscInt k = 0; k < (p ? n1 : n0); k++) x[s->part[p][k]] = s->buf[(p ? n0 : 0) + k];
  }
  PetscCall(PetscLogFlops(4.0 * (s->lnz[0] * s->here[0] + s->lnz[1] * s->here[1]) + 4.0 * (double)(s->mval[0].size() + s->mval[1].size()) + 2.0 * (double)nS * nS));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* What the split is: its sizes and what this rank stores */
PetscErrorCode FETICoarseSplitView(FETICoarseSplit *s, PetscViewer viewer)
{
  PetscFunctionBegin;
  PetscCall(PetscViewerASCIIPrintf(viewer, "split: %" PetscInt_FMT " coarse unknowns = %zu + %zu in two parts that do not couple + %zu in a separator (METIS); %s\n", s->N, s->part[0].size(),
                                   s->part[1].size(), s->sep.size(), s->size == 1 ? "one rank solves both parts" : "rank 0 solves part 0, rank 1 part 1, every rank the separator"));
  PetscCall(PetscViewerASCIIPrintf(viewer, "rank 0: CHOLMOD factor entries %.0f + %.0f, separator coupling M %zu + %zu entries, dense separator factor %zu x %zu\n", s->lnz[0], s->lnz[1],
                                   s->mval[0].size(), s->mval[1].size(), s->sep.size(), s->sep.size()));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FETICoarseSplitDestroy(FETICoarseSplit **split)
{
  FETICoarseSplit *s = *split;

  PetscFunctionBegin;
  if (!s) PetscFunctionReturn(PETSC_SUCCESS);
  if (s->started) {
    for (int p = 0; p < 2; p++) {
      if (s->L[p]) cholmod_free_factor(&s->L[p], &s->cc);
      if (s->rhs[p]) cholmod_free_dense(&s->rhs[p], &s->cc);
      if (s->X[p]) cholmod_free_dense(&s->X[p], &s->cc);
      if (s->Y[p]) cholmod_free_dense(&s->Y[p], &s->cc);
      if (s->E[p]) cholmod_free_dense(&s->E[p], &s->cc);
    }
    cholmod_finish(&s->cc);
  }
  delete s;
  *split = NULL;
  PetscFunctionReturn(PETSC_SUCCESS);
}
