/* The direct solver of a coarse matrix (G G', or G_A G_A' for a row subset), options prefix feti_coarse_.
   Four ways to spread it over the ranks (-feti_coarse_mode):
     single     the matrix is gathered on rank 0, factored there once and only there; a solve gathers the
                right-hand side there and sends the solution back. One copy of the factor in all, and the
                same numbers as on one rank (the gathered matrix is the same, entry for entry).
     redundant  every rank gathers the matrix, factors its own copy and solves for all of the solution: one
                collective per solve (the gather of the right-hand side), a factor per rank, and the whole
                solution on every rank, from which G' forms R x at the dofs of other ranks' subdomains that
                B reads without receiving them (fetioperators.cxx). Its options prefix is feti_coarse_redundant_.
     parallel   a parallel Cholesky (MUMPS unless -feti_coarse_pc_factor_mat_solver_type says otherwise)
                on all ranks: the factor is distributed, for coarse problems too large for one rank; the
                rounding then depends on the distribution.
     split      every rank gathers the matrix; a METIS separator splits it into two parts, which rank 0 and rank 1
                solve, one each, and a small dense separator that every rank solves (feticoarsesplit.cxx): each of
                two ranks reads half of the factor per solve, and every rank keeps the whole solution as in
                redundant mode. CHOLMOD whatever the package options say. One rank runs both parts, so the numbers
                are the same on any number of ranks (not those of the other modes).
     auto       (default) split from -feti_coarse_split_dim (1000) and redundant below it, both for a coarse dimension
                below -feti_coarse_redundant_dim (10 000), single below
                -feti_coarse_parallel_dim (50 000), parallel from there. Why redundant for small coarse problems
                (docs/scale.md, "Two ranks: where the time goes"): with single every other rank waits for each of
                rank 0's coarse solves (on the brick at 2 ranks about 4 per F product, 1440 in a solve), and the
                gather and the send back are two messages where redundant sends one; a factor of dimension 10 000
                takes some 50 MB per rank, and every rank factors the same gathered matrix as single would, so the
                numbers stay those of one rank (the fingerprints match on 1, 2 and 3 ranks). Why parallel above the next switch (docs/scale.md, "Past this machine"): the
                single factor's entries grow like Ns^1.5 and its flops like Ns^2.2 in the floating subdomains Ns (measured: at Ns = 6912 it took 0.4 GB and
                26 s on rank 0 while every other rank waited), and at 10^8 unknowns (Ns ~ 1.5e5 at H/h = 6)
                tens of gigabytes: no rank holds it, so the factor must be distributed. Below the switch,
                single (and redundant) keep the results bit for bit those of one rank. Why split from 1000 on
                (docs/scale.md, "The coarse solves split between two ranks"): a coarse solve is bound by reading
                the factor, which both ranks did in full in redundant mode (through one shared memory bus on the
                machine of the measurements); below 1000 the one more collective per solve costs more than it saves.
   On one rank all but split are one sequential Cholesky; split runs its two parts in turn there. */
#include <conefeti/private/fetiimpl.h>

const char *const FETICoarseModes[] = {"single", "redundant", "parallel", "auto", "split", "FETICoarseMode", "FETI_COARSE_", NULL};

/* a placeholder of the factored matrix's size: the factor lives on, the matrix it came from does not */
static PetscErrorCode ReleaseFactoredMatrix(KSP ksp)
{
  Mat      A, shell;
  PC       pc;
  PetscInt m, n, M, N;

  PetscFunctionBegin;
  PetscCall(KSPGetOperators(ksp, &A, NULL));
  PetscCall(MatGetLocalSize(A, &m, &n));
  PetscCall(MatGetSize(A, &M, &N));
  PetscCall(MatCreateShell(PetscObjectComm((PetscObject)ksp), m, n, M, N, NULL, &shell));
  PetscCall(PetscObjectSetName((PetscObject)shell, "coarse matrix (freed after its factorization)"));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetReusePreconditioner(pc, PETSC_TRUE));
  PetscCall(KSPSetOperators(ksp, shell, shell));
  PetscCall(MatDestroy(&shell));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* KSPPREONLY with a direct Cholesky of A, options prefix feti_coarse_; pc: its PC, to pick the package */
static PetscErrorCode CreateDirectKSP(MPI_Comm comm, Mat A, const char prefix[], KSP *ksp, PC *pc)
{
  PetscFunctionBegin;
  PetscCall(KSPCreate(comm, ksp));
  PetscCall(KSPSetErrorIfNotConverged(*ksp, PETSC_TRUE));
  PetscCall(KSPSetOperators(*ksp, A, A));
  PetscCall(KSPSetOptionsPrefix(*ksp, prefix));
  PetscCall(KSPSetType(*ksp, KSPPREONLY));
  PetscCall(KSPGetPC(*ksp, pc));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* All of A (here) or none of it, as a sequential matrix on this rank; collective */
static PetscErrorCode GatherMatrix(Mat A, PetscBool here, Mat **gathered)
{
  IS       rows;
  PetscInt N;

  PetscFunctionBegin;
  PetscCall(MatGetSize(A, &N, NULL));
  PetscCall(ISCreateStride(PETSC_COMM_SELF, here ? N : 0, 0, 1, &rows));
  PetscCall(MatCreateSubMatrices(A, 1, &rows, &rows, MAT_INITIAL_MATRIX, gathered));
  PetscCall(ISDestroy(&rows));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The scatter of a coarse vector to every rank (toall) or to rank 0, and the sequential x0, y0 it fills */
static PetscErrorCode CreateGatherScatter(Mat A, PetscBool toall, FETICoarseSolver &cs)
{
  Vec x;

  PetscFunctionBegin;
  PetscCall(MatCreateVecs(A, &x, NULL));
  if (toall) PetscCall(VecScatterCreateToAll(x, &cs.scatter, &cs.x0));
  else PetscCall(VecScatterCreateToZero(x, &cs.scatter, &cs.x0));
  PetscCall(VecDuplicate(cs.x0, &cs.y0));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Factor A (coarse x coarse, AIJ, SPD) as -feti_coarse_mode asks; *failed: A is singular */
PetscErrorCode FETICoarseSolverCreate(FETI feti, Mat A, FETICoarseSolver &cs, PetscBool *failed)
{
  FETI_Impl  &impl = *feti->impl;
  MPI_Comm    comm = PetscObjectComm((PetscObject)feti);
  PetscMPIInt size, rank;
  PetscInt    N;
  const char *prefix;
  char        coarseprefix[256];
  PC          pc;

  PetscFunctionBegin;
  PetscCall(FETICoarseSolverDestroy(cs));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)feti, &prefix));
  PetscCall(PetscSNPrintf(coarseprefix, sizeof(coarseprefix), "%sfeti_coarse_", prefix ? prefix : ""));
  PetscCall(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(A, MAT_SPD, PETSC_TRUE));
  PetscCall(MatGetSize(A, &N, NULL));
  cs.mode = impl.coarsemode;
  if (cs.mode == FETI_COARSE_AUTO) {
    if (N >= impl.coarseparalleldim) cs.mode = FETI_COARSE_PARALLEL;
    else if (N >= impl.coarseredundantdim) cs.mode = FETI_COARSE_SINGLE;
    else cs.mode = N >= impl.coarsesplitdim ? FETI_COARSE_SPLIT : FETI_COARSE_REDUNDANT;
  }
  /* on one rank every mode but split is one sequential Cholesky; split runs the same arithmetic as on several ranks
     (both parts in turn), so that its bits do not depend on the ranks */
  if (size == 1 && cs.mode != FETI_COARSE_SPLIT) cs.mode = FETI_COARSE_SINGLE;
  if (impl.coarsemode == FETI_COARSE_AUTO)
    PetscCall(PetscInfo(feti,
                        "-feti_coarse_mode auto: coarse dimension %" PetscInt_FMT " (-feti_coarse_split_dim %" PetscInt_FMT ", -feti_coarse_redundant_dim %" PetscInt_FMT
                        ", -feti_coarse_parallel_dim %" PetscInt_FMT "%s): %s\n",
                        N, impl.coarsesplitdim, impl.coarseredundantdim, impl.coarseparalleldim, impl.coarsesplitdim >= impl.coarseredundantdim ? "; no split: its switch is not below the next" : "",
                        FETICoarseModes[cs.mode]));
  if (cs.mode == FETI_COARSE_SPLIT) {
    Mat           *gathered;
    PetscErrorCode ierr;
    PetscCall(GatherMatrix(A, PETSC_TRUE, &gathered));
    ierr = FETICoarseSplitCreate(comm, gathered[0], &cs.split, failed);
    PetscCall(MatDestroySubMatrices(1, &gathered));
    PetscCall(ierr);
    if (size > 1) PetscCall(CreateGatherScatter(A, PETSC_TRUE, cs));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (cs.mode == FETI_COARSE_SINGLE || (cs.mode == FETI_COARSE_REDUNDANT && size > 1)) {
    /* single: rank 0 asks for every row and column, the others for nothing; redundant: every rank asks for all */
    const PetscBool here     = cs.mode == FETI_COARSE_REDUNDANT || rank == 0 ? PETSC_TRUE : PETSC_FALSE;
    Mat            *gathered = NULL, Aseq = A;
    PetscErrorCode  ierr = PETSC_SUCCESS;
    if (size > 1) {
      PetscCall(GatherMatrix(A, here, &gathered));
      Aseq = gathered[0];
      PetscCall(MatSetOption(Aseq, MAT_SYMMETRIC, PETSC_TRUE));
      PetscCall(MatSetOption(Aseq, MAT_SPD, PETSC_TRUE));
    }
    *failed = PETSC_FALSE;
    if (here) {
      char redundantprefix[256];
      /* redundant keeps the prefix PCREDUNDANT's inner solver had, feti_coarse_redundant_ */
      PetscCall(PetscSNPrintf(redundantprefix, sizeof(redundantprefix), "%sredundant_", coarseprefix));
      PetscCall(CreateDirectKSP(PETSC_COMM_SELF, Aseq, cs.mode == FETI_COARSE_REDUNDANT ? redundantprefix : coarseprefix, &cs.ksp, &pc));
      PetscCall(PCSetType(pc, PCCHOLESKY));
      PetscCall(PCFactorSetMatSolverType(pc, impl.subsolver));
      PetscCall(KSPSetFromOptions(cs.ksp));
      /* an error inside the package happens on one rank (single: rank 0 alone): it is printed there and passed on to all */
      ierr = FETIKSPSetUpFactorization(feti, cs.ksp, NULL, NULL, failed);
      if (!ierr) PetscCall(ReleaseFactoredMatrix(cs.ksp));
    }
    if (size > 1) {
      PetscMPIInt state[2] = {(PetscMPIInt)ierr, (PetscMPIInt)*failed}, all[2];
      PetscCallMPI(MPIU_Allreduce(state, all, 2, MPI_INT, MPI_MAX, comm));
      PetscCheck(!all[0], comm, (PetscErrorCode)all[0], "The factorization of the coarse matrix failed (-feti_coarse_mode %s; the message above says why)", FETICoarseModes[cs.mode]);
      *failed = all[1] ? PETSC_TRUE : PETSC_FALSE;
      PetscCall(MatDestroySubMatrices(1, &gathered));
      PetscCall(CreateGatherScatter(A, cs.mode == FETI_COARSE_REDUNDANT ? PETSC_TRUE : PETSC_FALSE, cs));
    } else PetscCall(ierr);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(CreateDirectKSP(comm, A, coarseprefix, &cs.ksp, &pc));
  /* parallel (redundant on one rank is single: the branch above) */
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSetFromOptions(cs.ksp));
  PetscCall(FETIKSPSetUpFactorization(feti, cs.ksp, NULL, NULL, failed));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = A^-1 x by the split solver, x and y of the full coarse length on this rank */
static PetscErrorCode SplitSolve(FETICoarseSplit *split, Vec x, Vec y)
{
  const PetscScalar *b;
  PetscScalar       *v;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(x, &b));
  PetscCall(VecGetArrayWrite(y, &v));
  PetscCall(FETICoarseSplitSolve(split, b, v));
  PetscCall(VecRestoreArrayWrite(y, &v));
  PetscCall(VecRestoreArrayRead(x, &b));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = A^-1 x. Redundant and split on several ranks: every rank gathers all of x, solves, and keeps all of the solution (y0) beside
   its own part in y; FETICoarseSolverGetFull() hands that copy to G' (fetioperators.cxx), which then needs no ghost
   values from the other ranks. */
PetscErrorCode FETICoarseSolverApply(FETICoarseSolver &cs, Vec x, Vec y)
{
  PetscFunctionBegin;
  cs.yid = -1;
  if (!cs.scatter) {
    if (cs.split) PetscCall(SplitSolve(cs.split, x, y)); /* one rank */
    else PetscCall(KSPSolve(cs.ksp, x, y));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(VecScatterBegin(cs.scatter, x, cs.x0, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(cs.scatter, x, cs.x0, INSERT_VALUES, SCATTER_FORWARD));
  if (cs.split) PetscCall(SplitSolve(cs.split, cs.x0, cs.y0));
  else if (cs.ksp) PetscCall(KSPSolve(cs.ksp, cs.x0, cs.y0));
  if (cs.mode == FETI_COARSE_REDUNDANT || cs.mode == FETI_COARSE_SPLIT) { /* the own part of the full solution: no message */
    const PetscScalar *all;
    PetscScalar       *mine;
    PetscInt           lo, hi;
    PetscCall(VecGetOwnershipRange(y, &lo, &hi));
    PetscCall(VecGetArrayRead(cs.y0, &all));
    PetscCall(VecGetArrayWrite(y, &mine));
    PetscCall(PetscArraycpy(mine, all + lo, hi - lo));
    PetscCall(VecRestoreArrayWrite(y, &mine));
    PetscCall(VecRestoreArrayRead(cs.y0, &all));
    PetscCall(PetscObjectGetId((PetscObject)y, &cs.yid));
    PetscCall(PetscObjectStateGet((PetscObject)y, &cs.ystate));
  } else {
    PetscCall(VecScatterBegin(cs.scatter, cs.y0, y, INSERT_VALUES, SCATTER_REVERSE));
    PetscCall(VecScatterEnd(cs.scatter, cs.y0, y, INSERT_VALUES, SCATTER_REVERSE));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* All of y on this rank when y is unchanged since the solve that gave it (redundant mode on several ranks), else NULL */
PetscErrorCode FETICoarseSolverGetFull(FETICoarseSolver &cs, Vec y, Vec *full)
{
  PetscInt64       id;
  PetscObjectState state;

  PetscFunctionBegin;
  *full = NULL;
  if (cs.yid < 0) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscObjectGetId((PetscObject)y, &id));
  PetscCall(PetscObjectStateGet((PetscObject)y, &state));
  if (id == cs.yid && state == cs.ystate) *full = cs.y0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FETICoarseSolverView(FETICoarseSolver &cs, PetscViewer viewer)
{
  PetscFunctionBegin;
  PetscCall(PetscViewerASCIIPrintf(viewer, "coarse solver (G G'), -feti_coarse_mode %s%s:\n", FETICoarseModes[cs.mode],
                                   cs.scatter && !cs.split ? (cs.mode == FETI_COARSE_REDUNDANT ? " (factored on every rank, rank 0's shown)" : " (factored on rank 0)") : ""));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  if (cs.split) PetscCall(FETICoarseSplitView(cs.split, viewer));
  else if (cs.scatter) {
    /* a sequential factor (single: on rank 0 only, cs.ksp is NULL elsewhere); rank 0's is shown */
    PetscViewer sub;
    PetscCall(PetscViewerGetSubViewer(viewer, PETSC_COMM_SELF, &sub));
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)viewer), &rank));
    if (cs.ksp && !rank) PetscCall(KSPView(cs.ksp, sub));
    PetscCall(PetscViewerRestoreSubViewer(viewer, PETSC_COMM_SELF, &sub));
  } else if (cs.ksp) PetscCall(KSPView(cs.ksp, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FETICoarseSolverDestroy(FETICoarseSolver &cs)
{
  PetscFunctionBegin;
  PetscCall(KSPDestroy(&cs.ksp));
  PetscCall(FETICoarseSplitDestroy(&cs.split));
  PetscCall(VecScatterDestroy(&cs.scatter));
  PetscCall(VecDestroy(&cs.x0));
  PetscCall(VecDestroy(&cs.y0));
  cs.yid = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}
