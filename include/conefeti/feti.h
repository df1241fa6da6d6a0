/* Layer feti: FETI operators (F, G, projector, generalized inverse) as MATSHELLs from subdomain data.

   The FETI object knows nothing about meshes. Its input, per subdomain s owned by this rank:
     K_s  sequential stiffness matrix (SEQAIJ or SEQSBAIJ, block size 3, dofs interleaved x,y,z per node),
     f_s  sequential load vector,
     node coordinates (for the 6 rigid-body modes) or a user kernel basis R_s,
     optionally the dofs where u is prescribed and kept in the primal (FETI with Dirichlet kept in the primal;
     u = 0 there unless values are given: then they are lifted, f - K u_D);
   and globally
     B    MPIAIJ constraint matrix: rows are the multipliers, columns the global primal vector
          (the concatenation of all subdomains' dofs, each rank owning its own subdomains' dofs),
     c    right-hand side of B u = c (zero for gluing and Dirichlet, the gap for contact),
     a kind per row of B (FETIRowKind).
   Dual problem (docs/feti.md): min 1/2 l'F l - l'h  s.t.  G l = e, with F = B K+ B', h = B K+ f - c,
   G = R'B', e = R'f; primal recovery u = K+(f - B'l) + R alpha. */
#pragma once

#include <petscksp.h>
#include <conefeti/sys.h>

/*S
  FETI - A FETI (finite element tearing and interconnecting) dual problem built from subdomain data:
  the operators F = B K+ B', G = R'B', the orthogonal projector P = I - G'(GG')^-1 G, K+, the
  right-hand sides h and e, and primal recovery.

  Level: beginner

.seealso: `FETICreate()`, `FETISetSubdomains()`, `FETISetConstraints()`, `FETISetUp()`, `FETISolveLinear()`
S*/
typedef struct _p_FETI *FETI;

/*E
  FETIRowKind - What a row of the constraint matrix B expresses.

$ FETI_ROW_GLUING              - continuity between copies of a node in different subdomains (B u = 0)
$ FETI_ROW_DIRICHLET           - a zero displacement component imposed by a multiplier (Total FETI)
$ FETI_ROW_CONTACT_NORMAL      - non-penetration N u <= gap (multiplier >= 0)
$ FETI_ROW_CONTACT_TANGENTIAL  - a tangential direction of a friction pair

  Level: beginner

.seealso: `FETISetConstraints()`, `FETIGetConstraints()`
E*/
typedef enum {
  FETI_ROW_GLUING,
  FETI_ROW_DIRICHLET,
  FETI_ROW_CONTACT_NORMAL,
  FETI_ROW_CONTACT_TANGENTIAL
} FETIRowKind;
PETSC_EXTERN const char *const FETIRowKinds[];

/*E
  FETIKplusType - How F = B K+ B' applies K+ in each subdomain.

$ FETI_KPLUS_AUTO     - per subdomain, after its factorization: a dense block (K+)_bb where it holds at most
$                       -feti_kplus_memory_ratio times the entries of the sparse factor (and is read faster than the factor twice), the factor elsewhere
$ FETI_KPLUS_EXPLICIT - dense blocks (K+)_bb in every subdomain whose block is not larger than twice its factor
$ FETI_KPLUS_IMPLICIT - two sparse triangular solves with the factor in every subdomain

  Level: intermediate

.seealso: `FETISetKplusType()`, `FETIGetKplusType()`, `FETISetKplusExplicit()`
E*/
typedef enum {
  FETI_KPLUS_AUTO,
  FETI_KPLUS_EXPLICIT,
  FETI_KPLUS_IMPLICIT
} FETIKplusType;
PETSC_EXTERN const char *const FETIKplusTypes[];

/*E
  FETIKplusPrecision - In which precision the subdomains' sparse factors are stored for the F products.

$ FETI_KPLUS_PRECISION_DOUBLE - as the factorization made them (the default)
$ FETI_KPLUS_PRECISION_SINGLE - PETSc's block Cholesky factors (subdomains up to 3000 dofs by default) are copied to float
$                               storage after the factorization and the double factor is freed; the solves sum in double.
$                               F products use them as they are; K+ x for h, the primal recovery and explicit blocks is
$                               refined against Kreg in double. Factors of other packages (CHOLMOD, MUMPS) stay double.

  Level: advanced

.seealso: `FETISetKplusPrecision()`, `FETIGetKplusPrecision()`, `FETISetKplusType()`
E*/
typedef enum {
  FETI_KPLUS_PRECISION_DOUBLE,
  FETI_KPLUS_PRECISION_SINGLE
} FETIKplusPrecision;
PETSC_EXTERN const char *const FETIKplusPrecisions[];

PETSC_EXTERN PetscClassId  FETI_CLASSID;
PETSC_EXTERN PetscLogEvent FETI_SetUp, FETI_Assembly, FETI_Factorization, FETI_MultF, FETI_CoarseSolve, FETI_ApplyKplus, FETI_PrimalRecovery, FETI_Preconditioner;

/* Preconditioner types for the projected CG on P F P, applied as P M^-1 P (-feti_pc_type) */
#define PCFETILUMPED    "lumped"
#define PCFETIDIRICHLET "dirichlet"
PETSC_EXTERN PetscErrorCode PCFETISetProjected(PC, PetscBool);

PETSC_EXTERN PetscErrorCode FETICreate(MPI_Comm, FETI *);
PETSC_EXTERN PetscErrorCode FETIDestroy(FETI *);
PETSC_EXTERN PetscErrorCode FETISetSubdomains(FETI, PetscInt, const Mat[], const Vec[]);
PETSC_EXTERN PetscErrorCode FETISetSubdomainCoordinates(FETI, PetscInt, Vec);
PETSC_EXTERN PetscErrorCode FETISetSubdomainKernel(FETI, PetscInt, Mat);
PETSC_EXTERN PetscErrorCode FETISetSubdomainDirichletDofs(FETI, PetscInt, IS);
PETSC_EXTERN PetscErrorCode FETISetSubdomainDirichletValues(FETI, PetscInt, Vec);
PETSC_EXTERN PetscErrorCode FETISetConstraints(FETI, Mat, Vec, const FETIRowKind[]);
PETSC_EXTERN PetscErrorCode FETISetOptionsPrefix(FETI, const char[]);
PETSC_EXTERN PetscErrorCode FETIAppendOptionsPrefix(FETI, const char[]);
PETSC_EXTERN PetscErrorCode FETISetFromOptions(FETI);
PETSC_EXTERN PetscErrorCode FETISetUp(FETI);
PETSC_EXTERN PetscErrorCode FETIView(FETI, PetscViewer);
PETSC_EXTERN PetscErrorCode FETIViewFromOptions(FETI, PetscObject, const char[]);

PETSC_EXTERN PetscErrorCode FETIGetNumSubdomains(FETI, PetscInt *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode FETIGetSubdomainOffset(FETI, PetscInt, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode FETIGetSizes(FETI, PetscInt *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode FETIGetCoarseSolveCount(FETI, PetscInt *);
PETSC_EXTERN PetscErrorCode FETIGetSubdomainKernel(FETI, PetscInt, Mat *);
PETSC_EXTERN PetscErrorCode FETIGetSubdomainFixingDofs(FETI, PetscInt, IS *);

PETSC_EXTERN PetscErrorCode FETIGetOperators(FETI, Mat *, Mat *, Mat *, Mat *);
PETSC_EXTERN PetscErrorCode FETIGetGeneralizedInverse(FETI, Mat *);
PETSC_EXTERN PetscErrorCode FETIGetKernel(FETI, Mat *);
PETSC_EXTERN PetscErrorCode FETIGetGt(FETI, Mat *);
PETSC_EXTERN PetscErrorCode FETIGetRHS(FETI, Vec *, Vec *);
PETSC_EXTERN PetscErrorCode FETIGetParticularSolution(FETI, Vec *);
PETSC_EXTERN PetscErrorCode FETIGetConstraints(FETI, Mat *, Vec *, const FETIRowKind **);
PETSC_EXTERN PetscErrorCode FETIGetLoad(FETI, Vec *);
PETSC_EXTERN PetscErrorCode FETICreateVecs(FETI, Vec *, Vec *, Vec *);
PETSC_EXTERN PetscErrorCode FETIApplyK(FETI, Vec, Vec);
PETSC_EXTERN PetscErrorCode FETIApplyCoarseInverse(FETI, Vec, Vec);

PETSC_EXTERN PetscErrorCode FETIComputeAlpha(FETI, Vec, Vec, Vec);
PETSC_EXTERN PetscErrorCode FETIComputeAlphaFromEquality(FETI, Vec, Vec);
PETSC_EXTERN PetscErrorCode FETIRecoverPrimal(FETI, Vec, Vec, Vec);
PETSC_EXTERN PetscErrorCode FETIGetKSP(FETI, KSP *);
PETSC_EXTERN PetscErrorCode FETISetKplusExplicit(FETI, PetscBool);
PETSC_EXTERN PetscErrorCode FETISetProgress(FETI, ConeFETIProgressFn, void *);
PETSC_EXTERN PetscErrorCode FETIGetKplusExplicit(FETI, PetscBool *, PetscBool *);
PETSC_EXTERN PetscErrorCode FETISetKplusType(FETI, FETIKplusType);
PETSC_EXTERN PetscErrorCode FETIGetKplusType(FETI, FETIKplusType *, PetscInt *);
PETSC_EXTERN PetscErrorCode FETISetKplusMemoryRatio(FETI, PetscReal);
PETSC_EXTERN PetscErrorCode FETISetKplusPrecision(FETI, FETIKplusPrecision);
PETSC_EXTERN PetscErrorCode FETIGetKplusPrecision(FETI, FETIKplusPrecision *, PetscInt *, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode FETISetKplusRefine(FETI, PetscBool);
PETSC_EXTERN PetscErrorCode FETIGetKplusRefine(FETI, PetscBool *);
PETSC_EXTERN PetscErrorCode FETISetKplusSpeedup(FETI, PetscReal);
PETSC_EXTERN PetscErrorCode FETISetKplusMemoryBudget(FETI, PetscReal);
PETSC_EXTERN PetscErrorCode FETIGetMemoryEstimate(FETI, PetscReal *, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode FETIGetMemoryBudget(MPI_Comm, const char[], PetscReal *, PetscBool *);
PETSC_EXTERN PetscErrorCode FETIEstimateFactorMemory(PetscReal, PetscReal, PetscReal *);
PETSC_EXTERN PetscErrorCode FETISolveLinear(FETI, Vec, Vec);

PETSC_EXTERN PetscErrorCode FETIWrite(FETI, PetscViewer);
PETSC_EXTERN PetscErrorCode FETILoad(FETI, PetscViewer);
