/* Private structures of the feti layer, shared between the files of src/feti. */
#pragma once

#include <petsc/private/petscimpl.h>
#include <conefeti/sys.h>
#include <conefeti/feti.h>
#include <conefeti/private/progress.h>
#include <conefeti/compat.h>

#include <cstdint>
#include <vector>

/* A subdomain's block Cholesky factor (U' D U, block size 3) with its values in float (fetifloatfactor.cxx) */
struct FETIFloatFactor {
  PetscInt                  nb = 0;          /* block rows (nodes); 0: no float factor */
  std::vector<std::int32_t> rowstart, col;   /* off-diagonal blocks of block row k: rowstart[k] .. rowstart[k+1]-1, their block columns */
  std::vector<float>        diag, off;       /* D_k^-1 and the off-diagonal blocks of -U, 9 numbers each, column-major */
  double                    doublebytes = 0; /* what PETSc's double factor it was copied from took */
};

/* One subdomain owned by this rank */
struct FETISubdomain {
  /* input */
  Mat K         = nullptr; /* user's K_s; released after setup when nobody else holds it */
  Vec f         = nullptr;
  Vec coords    = nullptr;
  Mat Ruser     = nullptr;
  IS  dirichlet = nullptr; /* dofs kept in the primal at a prescribed value (zero unless given) */
  Vec uD        = nullptr; /* the prescribed values (length n, read at the Dirichlet dofs), or NULL: zero */

  /* setup */
  PetscInt                 n = 0, offset = 0, localoffset = 0; /* dofs, first global primal dof, first dof in the rank's local array */
  PetscInt                 nkernel = 0, coarseoffset = 0;      /* kernel dimension, first global coarse index */
  std::vector<PetscScalar> R;                                  /* n x nkernel orthonormal kernel basis, column-major */
  std::vector<PetscInt>    fixing;                             /* dofs removed to regularize (sorted) */
  std::vector<PetscInt>    dirichletdofs;                      /* sorted */
  std::vector<PetscScalar> dirichletvalues;                    /* u at dirichletdofs after recovery; empty: all zero */
  std::vector<PetscInt>    removed;                            /* fixing and Dirichlet dofs, sorted */
  Mat                      Kreg       = nullptr;               /* K with removed rows/columns replaced by identity*diag */
  Mat                      correction = nullptr;               /* K_V - Kreg restricted to rows/cols of removed dofs (SeqAIJ) */
  PetscScalar              regdiag    = 1.0;                   /* the diagonal put at removed dofs */
  KSP                      ksp        = nullptr;               /* KSPPREONLY + PCCHOLESKY on Kreg, prefix feti_sub_ */
  Mat                      factor     = nullptr;               /* the KSP's factor when it is of Kreg permuted by nodes (borrowed), else NULL */
  std::vector<PetscInt>    perm, iperm;                        /* that permutation: row k of the factor is dof perm[k], dof i is row iperm[i]; empty: none */
  FETIFloatFactor          ffactor;                            /* -feti_kplus_precision single: the float copy that replaces that factor (factor is NULL then) */
  std::vector<PetscScalar> work;                               /* length n, for the refinement of the float solves */
  PetscReal                factorentries = -1;                 /* entries of the factor as MatGetInfo() measured them; -1: not measured */
  Vec                      x = nullptr, y = nullptr;           /* work vectors of length n (own storage) */
  Vec                      xa = nullptr, ya = nullptr;         /* vectors of length n without storage (VecPlaceArray) */

  /* preconditioner data (boundary = dofs touched by B); K_bb and K_ib are applied through K_V itself */
  IS                       boundary = nullptr, interior = nullptr;
  Mat                      Fii = nullptr; /* Cholesky factor of K_ii (K_ii itself is not kept); NULL once replaced by its float copy */
  FETIFloatFactor          fii;           /* -feti_dirichlet_pc_precision single: the float copy of a block Cholesky Fii */
  std::vector<PetscInt>    iimap;         /* Fii of PETSc's block Cholesky: row k is interior dof iimap[k] (its index in interior), -1 a padding dof; empty: Fii is of K_ii in interior order */
  std::vector<PetscScalar> iiwork;        /* length of that factor, for its solves */
  Vec                      wi = nullptr, wi2 = nullptr; /* the same length, for MatSolve() with the double block factor */
  Mat                      Kbi = nullptr;               /* K_bi (SeqAIJ): the boundary's coupling to the interior, a small part of K, for the Schur product's second half */
  Vec                      xi = nullptr, yi = nullptr;  /* interior-sized work vectors */
  Vec                      yb = nullptr;                /* boundary-sized work vector */

  /* explicit K+ on the dofs touched by B (-feti_kplus_explicit) */
  std::vector<PetscInt> kb;                          /* those dofs, without the removed ones */
  Mat                   Kplusbb = nullptr;           /* dense (K+)_bb */
  Vec                   kx = nullptr, ky = nullptr;  /* work vectors of length |kb| */
  PetscBool             schurfactor   = PETSC_FALSE; /* the subdomain's MUMPS factor holds the Schur complement on kb */
  PetscBool             kplusimplicit = PETSC_FALSE; /* blocks asked for (explicit or auto), but F uses the factor here (its block would be too large) */
};

/* y = A x with every row summed in increasing global column order: bitwise the same on any number of
   ranks (fetirowsum.cxx) */
struct FETIRowSum {
  Mat                   A      = nullptr;  /* the matrix (referenced), its AIJ copy or its transpose */
  Mat                   Ad     = nullptr;  /* diagonal block (MPIAIJ) or A itself (SeqAIJ) */
  Mat                   Ao     = nullptr;  /* off-diagonal block, columns compressed to garray (MPIAIJ) */
  const PetscInt       *garray = nullptr;  /* global columns of Ao, ascending */
  PetscInt              cstart = 0;        /* first local column */
  std::vector<PetscInt> split;             /* per row: Ao's entries before it have columns below cstart */
  std::vector<PetscInt> ghosted;           /* the rows with entries in Ao (summed once the ghosts arrived) */
  VecScatter            scatter = nullptr; /* x -> ghosts */
  Vec                   ghosts  = nullptr;
};

/* the direct solver of the coarse matrix (feticoarse.cxx) */
typedef enum {
  FETI_COARSE_SINGLE,
  FETI_COARSE_REDUNDANT,
  FETI_COARSE_PARALLEL,
  FETI_COARSE_AUTO, /* split from -feti_coarse_split_dim, redundant below it, both only below -feti_coarse_redundant_dim; single below -feti_coarse_parallel_dim, parallel from there (resolved in
                       FETICoarseSolverCreate()) */
  FETI_COARSE_SPLIT /* two parts and a separator, one part per rank (feticoarsesplit.cxx) */
} FETICoarseMode;
PETSC_INTERN const char *const FETICoarseModes[];
/* the two halves of a product with Q = G'(G G')^-1 G besides the coarse solve (-log_view) */
PETSC_INTERN PetscLogEvent FETI_ApplyG, FETI_ApplyGt;

/* setup events inside FETISetUp beside the public ones of feti.h: the subdomain kernels (rigid modes, fixing dofs,
   checks) and the node reordering of K_s for PETSc's block Cholesky */
PETSC_INTERN PetscLogEvent FETI_Kernels, FETI_Reorder;
/* the set-up of a FETI preconditioner (boundary masks; the Dirichlet preconditioner's interior factors), inside FETISetUp's event */
PETSC_INTERN PetscLogEvent FETI_PCSetUp;

/* v must be a vector of that space of the set-up FETI (the layout FETICreateVecs() gives): fn and arg name it in the error,
   before a wrong size is read or written past its end */
enum FETIVecSpace {
  FETI_VEC_PRIMAL,
  FETI_VEC_DUAL,
  FETI_VEC_COARSE
};
PETSC_INTERN PetscErrorCode FETICheckVec_Private(FETI, Vec, FETIVecSpace, const char[], const char[]);

struct FETICoarseSplit; /* feticoarsesplit.cxx */
PETSC_INTERN PetscErrorCode FETICoarseSplitCreate(MPI_Comm, Mat, FETICoarseSplit **, PetscBool *);
PETSC_INTERN PetscErrorCode FETICoarseSplitSolve(FETICoarseSplit *, const PetscScalar *, PetscScalar *);
PETSC_INTERN PetscErrorCode FETICoarseSplitView(FETICoarseSplit *, PetscViewer);
PETSC_INTERN PetscErrorCode FETICoarseSplitDestroy(FETICoarseSplit **);

struct FETICoarseSolver {
  FETICoarseMode   mode    = FETI_COARSE_SINGLE;
  KSP              ksp     = nullptr; /* single mode: on rank 0 only */
  VecScatter       scatter = nullptr; /* single mode on several ranks: to rank 0 and back; redundant and split: to every rank */
  Vec              x0 = nullptr, y0 = nullptr;
  PetscInt64       yid    = -1; /* redundant or split on several ranks: the (distributed) solution whose full copy y0 holds */
  PetscObjectState ystate = 0;
  FETICoarseSplit *split  = nullptr; /* split mode */
};

/* G and G' through R = Rhat T per subdomain: node coordinates and a 6 x k transform instead of R's stored rows
   (fetirigidrows.cxx) */
struct FETIRigidRows {
  PetscBool                use = PETSC_FALSE;
  std::vector<PetscInt>    subnode, subcoarse, subk; /* per local subdomain: its touched nodes subnode[s] .. subnode[s+1]-1, local coarse offset, k */
  std::vector<PetscScalar> T;                        /* per local subdomain 36 numbers: T(m, j) at 6 j + m, zero-padded to 6 columns */
  std::vector<PetscInt>    nodebase, rows;           /* per touched node: its first local primal dof; all three dofs of every touched node, increasing */
  std::vector<PetscScalar> xyz;                      /* per touched node: X, Y, Z as in FETIRigidBodyModes() */
  /* redundant or split coarse mode: B's ghost dofs (Bsum.garray) */
  std::vector<PetscScalar> gxyz, gT, gbeta; /* per ghost dof X, Y, Z; per ghost subdomain T (36) and a work beta (6) */
  std::vector<PetscInt>    gcomp, gsub;     /* per ghost dof: component, its subdomain in the tables below */
  std::vector<PetscInt>    gsubk, gsubcoarse;
  /* G' reads R x from a compact array, the touched nodes' dofs in the order of rows (FETISetUpRigidCompactColumns()) */
  PetscInt                 compact = 0; /* 0: not set up yet, 1: bcols and wc are set, -1: not available (B has a column outside rows) */
  std::vector<PetscInt>    bcols;       /* per entry of B's diagonal block: its column's position in rows */
  std::vector<PetscScalar> wc;          /* R x at rows (3 per touched node) */
};

struct FETI_Impl {
  std::vector<FETISubdomain> sub;
  Mat                        B = nullptr;
  FETIRowSum                 Bsum, Btsum; /* B and B' products, reproducible */
  Vec                        c = nullptr;
  std::vector<FETIRowKind>   kinds; /* local rows of B */

  PetscBool setupcalled     = PETSC_FALSE;
  PetscBool subdomainsgiven = PETSC_FALSE; /* FETISetSubdomains() was called: FETISetConstraints() may follow */
  PetscInt  nglobalsub = 0, firstsub = 0;
  PetscInt  nprimal = 0, nlocalprimal = 0, ncoarse = 0, nlocalcoarse = 0;

  /* options */
  PetscReal          kerneltol          = 1e-8;       /* -feti_kernel_tol */
  PetscReal          checktol           = 1e-6;       /* -feti_check_tol */
  PetscBool          check              = PETSC_TRUE; /* -feti_check */
  PetscInt           nfixingcandidates  = 8;          /* -feti_fixing_nodes */
  char               subsolver[64]      = "";
  FETIKplusType      kplustype          = FETI_KPLUS_IMPLICIT;         /* -feti_kplus, -feti_kplus_explicit */
  PetscReal          kplusratio         = 1.0;                         /* -feti_kplus_memory_ratio (auto): all blocks together at most this times all factors' entries */
  PetscReal          kplusspeedup       = 2.0;                         /* -feti_kplus_speedup (auto): a block must cut a subdomain's reads per F product by at least this */
  PetscReal          kplusbudget        = -1;                          /* -feti_kplus_memory_budget (auto): bytes all blocks may take (all ranks); negative: no such bound */
  FETIKplusPrecision kplusprecision     = FETI_KPLUS_PRECISION_DOUBLE; /* -feti_kplus_precision */
  PetscBool          kplusrefine        = PETSC_FALSE;                 /* -feti_kplus_refine: F products refine the float factors' solves to double accuracy (FETISetKplusRefine()) */
  FETIKplusPrecision pcprecision        = FETI_KPLUS_PRECISION_SINGLE; /* -feti_dirichlet_pc_precision: the Dirichlet preconditioner's block Cholesky factors of K_ii */
  PetscInt           npcsingle          = 0;                           /* after the Dirichlet preconditioner's setup: its interior factors (all ranks) stored in float */
  PetscInt           npcblock           = 0;                           /* ... of PETSc's block Cholesky, in float or double */
  PetscReal          pcfactorbytes      = 0;                           /* ... bytes (all ranks) of those block factors as kept */
  PetscReal          pcdoublebytes      = 0;                           /* ... the same in double */
  PetscInt           nkplussingle       = 0;                           /* after setup: subdomains (all ranks) whose factor is stored in float */
  PetscReal          kplusfactorbytes   = 0;                           /* after setup: bytes (all ranks) of the PETSc block Cholesky factors as kept (float copies or double factors) */
  PetscReal          kplusdoublebytes   = 0;                           /* the same factors in double, as PETSc stores them */
  PetscBool          kplusexplicit      = PETSC_FALSE;                 /* blocks may be built (before setup: kplustype is not implicit), are used in some subdomain (after) */
  PetscBool          kplusschur         = PETSC_TRUE;                  /* -feti_kplus_explicit_schur */
  FETICoarseMode     coarsemode         = FETI_COARSE_AUTO;            /* -feti_coarse_mode */
  PetscInt           coarseparalleldim  = 50000;                       /* -feti_coarse_parallel_dim: auto's switch from single to parallel */
  PetscInt           coarseredundantdim = 10000;                       /* -feti_coarse_redundant_dim: auto's switch from redundant to single */
  PetscInt           coarsesplitdim     = 1000;                        /* -feti_coarse_split_dim: auto's switch from redundant to split */
  PetscReal          coarsechecktol     = 1e-3;                        /* -feti_coarse_check_tol: the factors of G G' must solve a pseudo-random system to it (0: no check) */
  PetscInt           coarserefine       = PETSC_DECIDE;                /* -feti_coarse_refine: refinement steps per coarse solve (PETSC_DECIDE: from the coarse check) */
  PetscBool          rigidrows          = PETSC_TRUE;                  /* -feti_rigid_rows: G and G' through R = Rhat T where the kernels allow it */

  /* memory (fetimemory.cxx): estimates on this rank's node at setup, and whether the explicit K+ asked for was dropped for it */
  PetscReal memfactors = -1, memblocks = -1, membudget = -1; /* bytes; -1: not estimated (budget: unknown) */
  PetscBool kplusfallback      = PETSC_FALSE;
  PetscInt  nkplusimplicit     = 0;                          /* subdomains (all ranks) that keep the factor for F because their block would be larger */
  PetscInt  nkplusblocks       = 0;                          /* subdomains (all ranks) whose F products use a dense block (K+)_bb */
  PetscReal kplusfactorentries = -1, kplusblockentries = -1; /* auto: entries (all ranks) of the factors as measured after the factorizations, and of the blocks built (stored square) */

  /* global objects */
  Vec              f  = nullptr; /* primal load */
  Mat              R  = nullptr; /* primal x coarse, block diagonal kernel basis (MPIAIJ) */
  Mat              Gt = nullptr; /* B R, dual x coarse (MPIAIJ): built for the coarse matrix and dropped (FETIGetGt() builds it again) */
  FETICoarseSolver coarse;       /* of G G' (not kept once factored), prefix feti_coarse_ */
  Mat              F = nullptr, G = nullptr, P = nullptr, Q = nullptr, Kplus = nullptr, PFP = nullptr;
  Vec              h = nullptr, e = nullptr, lambdatilde = nullptr;
  KSP              ksp          = nullptr; /* prefix feti_ for FETISolveLinear() */
  Vec              boundarymask = nullptr; /* primal: 1 at dofs touched by B */

  /* G and G' through the rows of R at the dofs B touches (fetioperators.cxx, FETISetUpCoarseRows()): local primal
     index of each such row (increasing), CSR of those rows of R's diagonal block (local coarse columns) */
  std::vector<PetscInt>    grows, gptr, gcols, gfirst; /* gfirst: the first column of each kept row when every row's columns are consecutive (gcols then empty) */
  std::vector<PetscScalar> gvals;
  PetscBool                gpairs        = PETSC_FALSE;                  /* R's products sum each row in pairs (PETSc's inode kernel): so do ours */
  PetscBool                growsset      = PETSC_FALSE;                  /* FETISetUpCoarseRows() ran; grows empty then: PETSc's products */
  PetscInt                 ncoarsesolves = 0;                            /* coarse solves since FETISetUp() (FETIGetCoarseSolveCount()) */
  PetscInt                 coarsesteps   = 0;                            /* refinement steps of every coarse solve, as set up (FETIApplyCoarseInverse()) */
  PetscReal                coarseres0    = -1;                           /* the coarse check's |b - G G' x| / |b| without refinement (-1: not measured) */
  Vec                      wcr = nullptr, wcdy = nullptr, wdr = nullptr; /* refinement: coarse residual and correction, dual G' y */
  /* G' without B's ghost exchange (fetioperators.cxx, FETISetUpGhostCoarseRows()): the rows of R at B's ghost primal
     columns (Bsum.garray), CSR with global coarse columns, to compute R x there from a coarse solution every rank has
     in full (checked bit for bit against the exchange at its first use) */
  std::vector<PetscInt>    ghptr, ghcols;
  std::vector<PetscScalar> ghvals, ghbuf; /* ghbuf: R x at Bsum.garray */
  PetscInt                 ghostrows = 0; /* 0 not set up, 1 set up and not yet checked, 2 in use, -1 not used */
  FETIRigidRows            rigid;         /* set up with the rows above (FETISetUpCoarseRows()) */

  /* work vectors */
  Vec wp1 = nullptr, wp2 = nullptr, wd1 = nullptr, wd2 = nullptr, wc1 = nullptr, wc2 = nullptr;
  Vec wp3 = nullptr, wd3 = nullptr;                       /* for G and G' (R'B' x, B R x) and their callers, which may hold wp1, wp2 or wd2 */
  Vec rhs = nullptr, residual = nullptr, alpha = nullptr; /* FETISolveLinear(), FETIComputeAlpha(), FETIRecoverPrimal() */

  ConeFETIProgress progress;                      /* FETISetProgress() */
  PetscBool        progressmonitor = PETSC_FALSE; /* its KSP monitor is on the KSP of FETISolveLinear() */
  PetscReal        progressrnorm0  = 0;           /* that monitor's first residual norm */
};

struct _FETIOps {
  PetscErrorCode (*dummy)(void);
};

struct _p_FETI {
  PETSCHEADER(struct _FETIOps);
  FETI_Impl *impl;
};

/* fetikernel.cxx */
PETSC_INTERN PetscErrorCode FETIRigidBodyModes(Vec, PetscInt, std::vector<PetscScalar> &);
PETSC_INTERN PetscErrorCode FETIOrthonormalizeColumns(PetscInt, PetscInt *, std::vector<PetscScalar> &, PetscReal);
PETSC_INTERN PetscErrorCode FETIKernelVanishingOn(PetscInt, PetscInt *, std::vector<PetscScalar> &, const std::vector<PetscInt> &, PetscReal);
PETSC_INTERN PetscErrorCode FETIDirichletHold(Vec, PetscInt, const std::vector<PetscInt> &, PetscReal *);
PETSC_INTERN PetscErrorCode FETIChooseFixingDofs(PetscInt, PetscInt, const std::vector<PetscScalar> &, Vec, const std::vector<PetscInt> &, PetscInt, std::vector<PetscInt> &);

/* fetisubdomain.cxx */
PETSC_INTERN PetscErrorCode FETISubdomainSetUpKernel(FETI, FETISubdomain &, PetscInt);
PETSC_INTERN PetscErrorCode FETISubdomainSetUpFactorization(FETI, FETISubdomain &, PetscInt);
PETSC_INTERN PetscErrorCode FETISubdomainApplyK(FETISubdomain &, Vec, Vec);
PETSC_INTERN PetscErrorCode FETISubdomainApplyKplus(FETISubdomain &, Vec, Vec, PetscBool);
PETSC_INTERN PetscErrorCode FETISubdomainDestroy(FETISubdomain &);
/* K (SBAIJ, or AIJ of block size 3) as SBAIJ with its nodes permuted by a fill-reducing ordering, for PETSc's block Cholesky */
PETSC_INTERN PetscErrorCode FETIPermuteByNodes(Mat, MatOrderingType, std::vector<PetscInt> &, std::vector<PetscInt> &, Mat *);
/* the row of the subdomain's factor that holds dof i (for solves with the factor itself, FETISubdomainSetUpFactorization()) */
static inline PetscInt FETISubdomainFactorRow(const FETISubdomain &sd, PetscInt i) { return sd.iperm.empty() ? i : sd.iperm[i]; }

/* fetifloatfactor.cxx */
PETSC_INTERN PetscErrorCode FETIFloatFactorCreate(Mat, const char[], FETIFloatFactor &);
PETSC_INTERN PetscErrorCode FETIFloatFactorSolve(const FETIFloatFactor &, PetscScalar *);
PETSC_INTERN double         FETIFloatFactorBytes(const FETIFloatFactor &);

/* fetioperators.cxx */
PETSC_INTERN PetscErrorCode FETIApplyKplus(FETI, Vec, Vec, PetscBool);
PETSC_INTERN PetscErrorCode FETIApplyP(FETI, Vec, Vec);
PETSC_INTERN PetscErrorCode FETIApplyG(FETI, Vec, Vec);
PETSC_INTERN PetscErrorCode FETIApplyGt(FETI, Vec, Vec);
PETSC_INTERN PetscErrorCode FETICreateGt(FETI, Mat *);
PETSC_INTERN PetscErrorCode FETIKSPSetUpFactorization(FETI, KSP, PetscErrorCode (*)(void *), void *, PetscBool *);
/* the MATSHELLs F, P, Q, PFP, K+ and G, at the end of FETISetUp() (fetioperators.cxx) */
PETSC_INTERN PetscErrorCode FETICreateOperators_Private(FETI);

/* fetirigidrows.cxx */
PETSC_INTERN PetscErrorCode FETISetUpRigidRows(FETI, Mat, PetscInt);
PETSC_INTERN PetscErrorCode FETIRigidRowsApplyRt(FETI, const PetscScalar *, PetscScalar *);
PETSC_INTERN PetscErrorCode FETIRigidRowsApplyR(FETI, const PetscScalar *, PetscBool, PetscScalar *);
PETSC_INTERN PetscErrorCode FETISetUpRigidCompactColumns(FETI);
PETSC_INTERN PetscErrorCode FETISetUpRigidGhostRows(FETI, PetscBool *);
PETSC_INTERN PetscErrorCode FETIRigidRowsApplyGhosts(FETI, const PetscScalar *, PetscScalar *);

/* feticoarse.cxx */
PETSC_INTERN PetscErrorCode FETICoarseSolverCreate(FETI, Mat, FETICoarseSolver &, PetscBool *);
PETSC_INTERN PetscErrorCode FETICoarseSolverApply(FETICoarseSolver &, Vec, Vec);
PETSC_INTERN PetscErrorCode FETICoarseSolverGetFull(FETICoarseSolver &, Vec, Vec *);
PETSC_INTERN PetscErrorCode FETICoarseSolverView(FETICoarseSolver &, PetscViewer);
PETSC_INTERN PetscErrorCode FETICoarseSolverDestroy(FETICoarseSolver &);

/* fetiexplicitkplus.cxx */
PETSC_INTERN PetscErrorCode FETISetUpExplicitKplus(FETI);
PETSC_INTERN PetscErrorCode FETIApplyKplusOnBoundary(FETI, Vec, Vec);
PETSC_INTERN PetscErrorCode FETISubdomainSetSchurDofs(FETI, FETISubdomain &);
PETSC_INTERN PetscErrorCode FETISubdomainExplicitKplusFromSchur(FETISubdomain &, PetscInt);

/* fetimemory.cxx */
/* The largest subdomain (dofs) whose factor for F is PETSc's block Cholesky by default (fetisubdomain.cxx chooses
   it; fetimemory.cxx estimates its size) */
#define FETI_BLOCK_CHOLESKY_MAX_DOFS 3000

/* PetscValidHeaderSpecific() checks nothing in a PETSc built without debugging (as the packaged one is): a NULL
   FETI (FETICreate() forgotten) must still be an error naming the function, not a read through NULL */
#define FETIValidHeader(feti, arg)                                                                                                                                           \
  do {                                                                                                                                                                       \
    PetscValidHeaderSpecific(feti, FETI_CLASSID, arg);                                                                                                                       \
    PetscCheck(feti, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "%s(): the FETI object (parameter # %d) is NULL: call FETICreate() first", PETSC_FUNCTION_NAME, arg);              \
    PetscCheck(((PetscObject)(feti))->classid == FETI_CLASSID, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "%s(): parameter # %d is not a FETI object", PETSC_FUNCTION_NAME, arg); \
  } while (0)

PETSC_INTERN PetscErrorCode FETICheckMemory(FETI);
PETSC_INTERN PetscErrorCode FETISubdomainKplusCosts(FETI, FETISubdomain &, PetscReal *, PetscReal *, PetscBool *);
PETSC_INTERN PetscErrorCode FETIChooseKplusBlocks(FETI, const std::vector<PetscInt> &, const std::vector<PetscReal> &, const std::vector<PetscReal> &, const std::vector<PetscReal> &,
                                                  std::vector<char> &);

/* fetirowsum.cxx */
PETSC_INTERN PetscErrorCode FETICreateCoarseMatrix(FETI, Vec, Mat *);
PETSC_INTERN PetscErrorCode FETISetPseudoRandom_Private(Vec);
PETSC_INTERN PetscErrorCode FETIRowSumCreate(Mat, PetscBool, FETIRowSum &);
PETSC_INTERN PetscErrorCode FETIRowSumApply(FETIRowSum &, Vec, Vec);
PETSC_INTERN PetscErrorCode FETIRowSumApplyWithGhosts(FETIRowSum &, Vec, const PetscScalar *, Vec);
PETSC_INTERN PetscErrorCode FETIRowSumApplyRows(FETIRowSum &, Vec, PetscInt, const PetscInt[], Vec);
PETSC_INTERN PetscErrorCode FETIRowSumApplyCompact(FETIRowSum &, const PetscInt[], const PetscScalar[], const PetscScalar[], Vec);
PETSC_INTERN PetscErrorCode FETIRowSumDestroy(FETIRowSum &);
PETSC_INTERN PetscErrorCode FETIAssembleCoarseMatrix(Mat, Vec, Mat *);

/* fetipc.cxx */
PETSC_INTERN PetscErrorCode FETISetUpBoundaryMask(FETI);
PETSC_INTERN PetscErrorCode FETISetUpPreconditionerData(FETI, PetscBool);
PETSC_INTERN PetscErrorCode PCCreate_FETILumped(PC);
PETSC_INTERN PetscErrorCode PCCreate_FETIDirichlet(PC);
PETSC_INTERN PetscErrorCode FETIFromMat(Mat, FETI *);
