/* The direct solver of a coarse matrix (G G', or G_A G_A' for a row subset), options prefix feti_coarse_.
   Three ways to spread it over the ranks (-feti_coarse_mode):
     single     the matrix is gathered on rank 0, factored there once and only there; a solve gathers the
                right-hand side there and sends the solution back. One copy of the factor in all, and the
                same numbers as on one rank (the gathered matrix is the same, entry for entry).
     redundant  every rank factors its own copy (PCREDUNDANT) and solves without sending the solution:
                a little less communication, a factor per rank.
     parallel   a parallel Cholesky (MUMPS unless -feti_coarse_pc_factor_mat_solver_type says otherwise)
                on all ranks: the factor is distributed, for coarse problems too large for one rank; the
                rounding then depends on the distribution.
     auto       (default) redundant for a coarse dimension below -feti_coarse_redundant_dim (10 000), single below
                -feti_coarse_parallel_dim (50 000), parallel from there. Why redundant for small coarse problems
                (docs/scale.md, "Two ranks: where the time goes"): with single every other rank waits for each of
                rank 0's coarse solves (on the brick at 2 ranks about 4 per F product, 1440 in a solve), and the
                gather and the send back are two messages where redundant sends one; a factor of dimension 10 000
                takes some 50 MB per rank, and every rank factors the same gathered matrix as single would, so the
                numbers stay those of one rank (the fingerprints match on 1, 2 and 3 ranks). Why parallel above the next switch (docs/scale.md, "Past this machine"): the
                single factor's entries grow like Ns^1.5 and its flops like Ns^2.2 in the floating subdomains Ns (measured: at Ns = 6912 it took 0.4 GB and
                26 s on rank 0 while every other rank waited), and at 10^8 unknowns (Ns ~ 1.5e5 at H/h = 6)
                tens of gigabytes: no rank holds it, so the factor must be distributed. Below the switch,
                single (and redundant) keep the results bit for bit those of one rank.
   On one rank all four are one sequential Cholesky. */
#include <conefeti/private/fetiimpl.h>

const char *const FETICoarseModes[] = {"single", "redundant", "parallel", "auto", "FETICoarseMode", "FETI_COARSE_", NULL};

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

/* Factor A (coarse x coarse, AIJ, SPD) as -feti_coarse_mode asks; *failed: A is singular */
PetscErrorCode FETICoarseSolverCreate(FETI feti, Mat A, FETICoarseSolver &cs, PetscBool *failed)
{
  FETI_Impl  &impl = *feti->impl;
  MPI_Comm    comm = PetscObjectComm((PetscObject)feti);
  PetscMPIInt size, rank;
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
  cs.mode = size == 1 ? FETI_COARSE_SINGLE : impl.coarsemode;
  if (cs.mode == FETI_COARSE_AUTO) {
    PetscInt N;
    PetscCall(MatGetSize(A, &N, NULL));
    cs.mode = N >= impl.coarseparalleldim ? FETI_COARSE_PARALLEL : (N < impl.coarseredundantdim ? FETI_COARSE_REDUNDANT : FETI_COARSE_SINGLE);
    PetscCall(PetscInfo(feti, "-feti_coarse_mode auto: coarse dimension %" PetscInt_FMT " (-feti_coarse_redundant_dim %" PetscInt_FMT ", -feti_coarse_parallel_dim %" PetscInt_FMT "): %s\n", N,
                        impl.coarseredundantdim, impl.coarseparalleldim, FETICoarseModes[cs.mode]));
  }
  if (cs.mode == FETI_COARSE_SINGLE) {
    Mat           *gathered = NULL, Aseq = A;
    IS             rows;
    PetscInt       N;
    PetscErrorCode ierr = PETSC_SUCCESS;
    PetscCall(MatGetSize(A, &N, NULL));
    if (size > 1) { /* rank 0 asks for every row and column, the others for nothing */
      PetscCall(ISCreateStride(PETSC_COMM_SELF, rank ? 0 : N, 0, 1, &rows));
      PetscCall(MatCreateSubMatrices(A, 1, &rows, &rows, MAT_INITIAL_MATRIX, &gathered));
      PetscCall(ISDestroy(&rows));
      Aseq = gathered[0];
      PetscCall(MatSetOption(Aseq, MAT_SYMMETRIC, PETSC_TRUE));
      PetscCall(MatSetOption(Aseq, MAT_SPD, PETSC_TRUE));
    }
    *failed = PETSC_FALSE;
    if (rank == 0) {
      PetscCall(CreateDirectKSP(PETSC_COMM_SELF, Aseq, coarseprefix, &cs.ksp, &pc));
      PetscCall(PCSetType(pc, PCCHOLESKY));
      PetscCall(PCFactorSetMatSolverType(pc, impl.subsolver));
      PetscCall(KSPSetFromOptions(cs.ksp));
      /* an error inside the package happens on rank 0 alone: it is printed there and passed on to all */
      ierr = FETIKSPSetUpFactorization(feti, cs.ksp, NULL, NULL, failed);
      if (!ierr) PetscCall(ReleaseFactoredMatrix(cs.ksp));
    }
    if (size > 1) {
      PetscMPIInt state[2] = {(PetscMPIInt)ierr, (PetscMPIInt)*failed};
      PetscCallMPI(MPI_Bcast(state, 2, MPI_INT, 0, comm));
      PetscCheck(!state[0], comm, (PetscErrorCode)state[0], "The factorization of the coarse matrix on rank 0 failed (-feti_coarse_mode single; the message above says why)");
      *failed = state[1] ? PETSC_TRUE : PETSC_FALSE;
      PetscCall(MatDestroySubMatrices(1, &gathered));
      {
        Vec x;
        PetscCall(MatCreateVecs(A, &x, NULL));
        PetscCall(VecScatterCreateToZero(x, &cs.scatter, &cs.x0));
        PetscCall(VecDuplicate(cs.x0, &cs.y0));
        PetscCall(VecDestroy(&x));
      }
    } else PetscCall(ierr);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(CreateDirectKSP(comm, A, coarseprefix, &cs.ksp, &pc));
  if (cs.mode == FETI_COARSE_REDUNDANT) {
    KSP inner;
    PC  innerpc;
    PetscCall(PCSetType(pc, PCREDUNDANT));
    PetscCall(PCRedundantGetKSP(pc, &inner));
    PetscCall(KSPGetPC(inner, &innerpc));
    PetscCall(PCSetType(innerpc, PCCHOLESKY));
    PetscCall(PCFactorSetMatSolverType(innerpc, impl.subsolver));
  } else {
    PetscCall(PCSetType(pc, PCCHOLESKY));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  }
  PetscCall(KSPSetFromOptions(cs.ksp));
  PetscCall(FETIKSPSetUpFactorization(feti, cs.ksp, NULL, NULL, failed));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = A^-1 x */
PetscErrorCode FETICoarseSolverApply(FETICoarseSolver &cs, Vec x, Vec y)
{
  PetscFunctionBegin;
  if (!cs.scatter) {
    PetscCall(KSPSolve(cs.ksp, x, y));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(VecScatterBegin(cs.scatter, x, cs.x0, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(cs.scatter, x, cs.x0, INSERT_VALUES, SCATTER_FORWARD));
  if (cs.ksp) PetscCall(KSPSolve(cs.ksp, cs.x0, cs.y0));
  PetscCall(VecScatterBegin(cs.scatter, cs.y0, y, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(cs.scatter, cs.y0, y, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FETICoarseSolverView(FETICoarseSolver &cs, PetscViewer viewer)
{
  PetscFunctionBegin;
  PetscCall(PetscViewerASCIIPrintf(viewer, "coarse solver (G G'), -feti_coarse_mode %s%s:\n", FETICoarseModes[cs.mode], cs.scatter ? " (factored on rank 0)" : ""));
  PetscCall(PetscViewerASCIIPushTab(viewer));
  if (cs.scatter) { /* the factor exists on rank 0 only (cs.ksp is NULL elsewhere) */
    PetscViewer sub;
    PetscCall(PetscViewerGetSubViewer(viewer, PETSC_COMM_SELF, &sub));
    if (cs.ksp) PetscCall(KSPView(cs.ksp, sub));
    PetscCall(PetscViewerRestoreSubViewer(viewer, PETSC_COMM_SELF, &sub));
  } else if (cs.ksp) PetscCall(KSPView(cs.ksp, viewer));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FETICoarseSolverDestroy(FETICoarseSolver &cs)
{
  PetscFunctionBegin;
  PetscCall(KSPDestroy(&cs.ksp));
  PetscCall(VecScatterDestroy(&cs.scatter));
  PetscCall(VecDestroy(&cs.x0));
  PetscCall(VecDestroy(&cs.y0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
