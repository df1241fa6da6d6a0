/* Layer qp: quadratic programming solvers on PETSc Mat/Vec.

   All solvers minimize q(x) = 1/2 x'Ax - b'x over a closed convex set that is separable: a
   product of blocks, each a free scalar, an interval (bounds), a 2D disk {|y - c| <= r} or a 3D
   second-order cone {|y_t| <= mu y_n} (SeparableSet). smalxe adds an equality C x = d.

   TAO types:  mprgp (bounds), mpgp (any SeparableSet), smalxe (SeparableSet and C x = d)
   KSP types:  mprgp, mpgp (the same algorithms through KSPSolve(A x = b); without constraints CG)

   Nothing here knows about FETI or mechanics. */
#pragma once

#include <petscksp.h>
#include <petsctao.h>

/* ---------------------------------------------------------------------------------------------
   SeparableSet: the feasible set, a product of blocks
   --------------------------------------------------------------------------------------------- */

/*S
  SeparableSet - A closed convex set that is a product of small blocks: free scalars, intervals
  [l, u] (bounds), 2D disks {|y - c| <= r} and 3D second-order cones {|y_t| <= mu y_n}.

  Level: beginner

  Notes:
  Entries of the vector that belong to no disk or cone block are scalar blocks, bounded by the
  optional vectors given to `SeparableSetSetBounds()` (infinite or absent bounds mean free). A block
  never straddles MPI ranks: all its entries are owned by one rank. Radii, centers and cone
  coefficients can be changed in place between solves without a new setup (the friction loop
  changes radii every outer step).

.seealso: `SeparableSetCreate()`, `SeparableSetAddDisks()`, `SeparableSetAddCones()`, `TaoQPSetConstraints()`, `KSPQPSetConstraints()`
S*/
typedef struct _p_SeparableSet *SeparableSet;

/*MC
  SEPARABLESET_DISK_RADIUS_MAX - The largest disk radius a `SeparableSet` takes, 1e150: the solvers square radii, and
  larger ones overflowed into NaN. A radius this large acts as no bound on any problem whose solution and data stay
  far below it (the contact layer holds slip bounds at it).

  Level: intermediate

.seealso: `SeparableSetAddDisks()`, `SeparableSetSetDiskRadii()`
M*/
#define SEPARABLESET_DISK_RADIUS_MAX 1e150

PETSC_EXTERN PetscClassId SEPARABLESET_CLASSID;

PETSC_EXTERN PetscErrorCode SeparableSetCreate(MPI_Comm, PetscInt, PetscInt, SeparableSet *);
PETSC_EXTERN PetscErrorCode SeparableSetDestroy(SeparableSet *);
PETSC_EXTERN PetscErrorCode SeparableSetView(SeparableSet, PetscViewer);
PETSC_EXTERN PetscErrorCode SeparableSetSetBounds(SeparableSet, Vec, Vec);
PETSC_EXTERN PetscErrorCode SeparableSetAddDisks(SeparableSet, PetscInt, const PetscInt[], const PetscReal[], const PetscReal[]);
PETSC_EXTERN PetscErrorCode SeparableSetAddCones(SeparableSet, PetscInt, const PetscInt[], const PetscReal[]);
PETSC_EXTERN PetscErrorCode SeparableSetSetDiskRadii(SeparableSet, const PetscReal[]);
PETSC_EXTERN PetscErrorCode SeparableSetSetDiskCenters(SeparableSet, const PetscReal[]);
PETSC_EXTERN PetscErrorCode SeparableSetSetConeCoefficients(SeparableSet, const PetscReal[]);
PETSC_EXTERN PetscErrorCode SeparableSetSetShift(SeparableSet, Vec);
PETSC_EXTERN PetscErrorCode SeparableSetGetLocalBlockCounts(SeparableSet, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode SeparableSetGetSizes(SeparableSet, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode SeparableSetHasCurvedBlocks(SeparableSet, PetscBool *);
PETSC_EXTERN PetscErrorCode SeparableSetIsUnconstrained(SeparableSet, PetscBool *);
PETSC_EXTERN PetscErrorCode SeparableSetProject(SeparableSet, Vec);
PETSC_EXTERN PetscErrorCode SeparableSetProjectedGradient(SeparableSet, Vec, Vec, Vec);
PETSC_EXTERN PetscErrorCode SeparableSetDistance(SeparableSet, Vec, PetscReal *);
PETSC_EXTERN PetscErrorCode SeparableSetCreateSubset(SeparableSet, IS, SeparableSet *);

/* ---------------------------------------------------------------------------------------------
   Counters: Hessian products and steps, machine independent
   --------------------------------------------------------------------------------------------- */

/*S
  QPCounters - Work done by a QP solver since it was created or its counters were reset.

  Fields:
+ solves                - number of solves
. iterations            - iterations of the solver itself (outer iterations for smalxe)
. hessian_mults         - products with the Hessian done by the solver itself
. nested_iterations     - iterations of nested solvers (smalxe's inner solver)
. nested_hessian_mults  - Hessian products done by nested solvers
. estimate_mults        - products spent estimating ||A|| (reported apart, as SLEPc's)
. cg_steps              - conjugate gradient steps
. expansion_steps       - expansion steps (feasible half step, then projected step)
. proportioning_steps   - proportioning steps
- pc_applications       - preconditioner applications (preconditioning in face, `TaoQPGetPC()`)

  Level: intermediate

  Notes:
  The total number of Hessian products, n_A in the seed paper, is hessian_mults + nested_hessian_mults.
  Counters accumulate over solves until `TaoQPResetCounters()` / `KSPQPResetCounters()`.

.seealso: `TaoQPGetCounters()`, `KSPQPGetCounters()`, `QPCountersView()`
S*/
typedef struct {
  PetscInt solves;
  PetscInt iterations;
  PetscInt hessian_mults;
  PetscInt nested_iterations;
  PetscInt nested_hessian_mults;
  PetscInt estimate_mults;
  PetscInt cg_steps;
  PetscInt expansion_steps;
  PetscInt proportioning_steps;
  PetscInt pc_applications;
} QPCounters;

PETSC_EXTERN PetscErrorCode QPCountersView(const QPCounters *, const char[], PetscViewer);
PETSC_EXTERN PetscErrorCode QPCountersViewJSON(const QPCounters *, const char[], PetscViewer);

/* ---------------------------------------------------------------------------------------------
   Norm estimate for the step length
   --------------------------------------------------------------------------------------------- */

/*E
  QPNormMethod - How ||A|| (for the fixed step length alpha = a/||A||) is estimated.

$ QP_NORM_SLEPC - a few Lanczos (Krylov-Schur) steps of SLEPc's EPS, plus the Ritz residual and a margin
$ QP_NORM_POWER - power iteration (fallback without SLEPc), plus a margin
$ QP_NORM_USER  - the value given by the user (`TaoQPSetNormEstimate()`), used as is

  Level: intermediate

.seealso: `MatQPEstimateNorm()`
E*/
typedef enum {
  QP_NORM_SLEPC,
  QP_NORM_POWER,
  QP_NORM_USER
} QPNormMethod;
PETSC_EXTERN const char *const QPNormMethods[];

PETSC_EXTERN PetscErrorCode MatQPEstimateNorm(Mat, QPNormMethod, PetscReal, const char[], PetscReal *, PetscInt *);
PETSC_EXTERN PetscErrorCode MatQPClearNormEstimate(Mat);

/* ---------------------------------------------------------------------------------------------
   TAO types
   --------------------------------------------------------------------------------------------- */

#define TAOMPRGP  "mprgp"
#define TAOMPGP   "mpgp"
#define TAOSMALXE "smalxe"

PETSC_EXTERN PetscErrorCode TaoQPSetConstraints(Tao, SeparableSet);
PETSC_EXTERN PetscErrorCode TaoQPGetConstraints(Tao, SeparableSet *);
PETSC_EXTERN PetscErrorCode TaoQPSetLinearTerm(Tao, Vec);
PETSC_EXTERN PetscErrorCode TaoQPSetNormEstimate(Tao, PetscReal);
PETSC_EXTERN PetscErrorCode TaoQPGetNormEstimate(Tao, PetscReal *);
PETSC_EXTERN PetscErrorCode TaoQPGetCounters(Tao, QPCounters *);
PETSC_EXTERN PetscErrorCode TaoQPGetPC(Tao, PC *);
PETSC_EXTERN PetscErrorCode TaoQPSetExpansionProjCG(Tao, PetscBool);
PETSC_EXTERN PetscErrorCode TaoQPSetExpansionLagged(Tao, PetscBool);
PETSC_EXTERN PetscErrorCode TaoQPResetCounters(Tao);

PETSC_EXTERN PetscErrorCode TaoSMALXESetEqualityConstraints(Tao, Mat, Vec);
PETSC_EXTERN PetscErrorCode TaoSMALXESetProjector(Tao, Mat, Vec);
PETSC_EXTERN PetscErrorCode TaoSMALXEGetSubsolver(Tao, Tao *);
PETSC_EXTERN PetscErrorCode TaoSMALXESetBlocks(Tao, PetscInt, const IS[]);
PETSC_EXTERN PetscErrorCode TaoSMALXEGetBlockSubsolver(Tao, PetscInt, Tao *);
PETSC_EXTERN PetscErrorCode TaoSMALXESetPreSolve(Tao, PetscErrorCode (*)(Tao, PetscInt, Vec, void *), void *);
PETSC_EXTERN PetscErrorCode TaoSMALXEGetEqualityMultiplier(Tao, Vec);
PETSC_EXTERN PetscErrorCode TaoSMALXEGetFeasibility(Tao, PetscReal *);
PETSC_EXTERN PetscErrorCode TaoSMALXEGetMultiplierGrowth(Tao, Vec, PetscInt *);
PETSC_EXTERN PetscErrorCode TaoSMALXEGetOuterTolerances(Tao, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode TaoSMALXESetConsistencyCheck(Tao, PetscErrorCode (*)(Tao, Vec, PetscBool *, void *), void *);
PETSC_EXTERN PetscErrorCode TaoSMALXEGetStagnated(Tao, PetscBool *);
PETSC_EXTERN PetscErrorCode TaoSMALXEGetStalled(Tao, PetscBool *);
PETSC_EXTERN PetscErrorCode TaoSMALXEGetInnerLimited(Tao, PetscInt *);
PETSC_EXTERN PetscErrorCode TaoSMALXESetAnderson(Tao, PetscInt, PetscInt);
PETSC_EXTERN PetscErrorCode TaoSMALXESetPenaltyPreconditioner(Tao, PetscBool);
PETSC_EXTERN PetscErrorCode TaoSMALXESetExactStop(Tao, PetscBool);
PETSC_EXTERN PetscErrorCode TaoSMALXESetProjectedPreconditioner(Tao, PC);
PETSC_EXTERN PetscErrorCode TaoSMALXEGetProjectedPreconditioner(Tao, PC *);

/* ---------------------------------------------------------------------------------------------
   KSP types: the same algorithms through KSPSolve(A x = b), i.e. min 1/2 x'Ax - b'x
   --------------------------------------------------------------------------------------------- */

#define KSPMPRGP "mprgp"
#define KSPMPGP  "mpgp"

PETSC_EXTERN PetscErrorCode KSPQPSetConstraints(KSP, SeparableSet);
PETSC_EXTERN PetscErrorCode KSPQPGetConstraints(KSP, SeparableSet *);
PETSC_EXTERN PetscErrorCode KSPMPRGPSetBounds(KSP, Vec, Vec);
PETSC_EXTERN PetscErrorCode KSPQPSetNormEstimate(KSP, PetscReal);
PETSC_EXTERN PetscErrorCode KSPQPGetCounters(KSP, QPCounters *);
PETSC_EXTERN PetscErrorCode KSPQPResetCounters(KSP);
