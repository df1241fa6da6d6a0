/* Package initialization and version of conefeti. */
#pragma once

#include <petscvec.h>

#define CONEFETI_VERSION_MAJOR 0
#define CONEFETI_VERSION_MINOR 1
#define CONEFETI_VERSION_PATCH 0

PETSC_EXTERN PetscErrorCode ConeFETIInitializePackage(void);
PETSC_EXTERN PetscErrorCode ConeFETIFinalizePackage(void);
PETSC_EXTERN PetscErrorCode ConeFETIGetVersion(PetscInt *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode ConeFETISlepcInitializeIfNeeded(void);
PETSC_EXTERN PetscErrorCode ConeFETIVecFingerprint(Vec, char[17]);
/*E
  ConeFETIPhase - A phase of a setup or solve that reports progress (`ConeFETIProgressFn`).

  Values:
+ CONEFETI_PHASE_MESH            - the scene's bodies: meshes, FEM assembly and decomposition (`ContactSceneSetUp()`)
. CONEFETI_PHASE_CONTACT_ROWS    - contact nodes, the rigid-motion check, the FETI problem with the contact rows (`ContactModelSetUp()`)
. CONEFETI_PHASE_KERNELS         - subdomain kernels and fixing dofs (`FETISetUp()`, counted per subdomain)
. CONEFETI_PHASE_MEMORY          - the memory estimate against the budget
. CONEFETI_PHASE_COARSE          - the global load, R, the B sums, the coarse matrix GG' and its factor
. CONEFETI_PHASE_FACTORIZATION   - the subdomain Cholesky factors (counted per subdomain)
. CONEFETI_PHASE_EXPLICIT        - the dense (K+)_bb blocks (counted per subdomain; only with -feti_kplus_explicit)
. CONEFETI_PHASE_OPERATORS       - the shells F, G, P, Q and the vectors h, e, lambda~
. CONEFETI_PHASE_CONTACT_PROBLEM - the dual contact problem, its solvers and the ||F|| estimate (`ContactModelSetUp()`)
- CONEFETI_PHASE_SOLVE           - the solve with primal recovery (`ContactModelSolve()`; its events carry the outer iterations)

  Level: intermediate

.seealso: `ConeFETIProgressInfo`, `ConeFETIProgressFn`, `ConeFETIPhases`
E*/
typedef enum {
  CONEFETI_PHASE_MESH,
  CONEFETI_PHASE_CONTACT_ROWS,
  CONEFETI_PHASE_KERNELS,
  CONEFETI_PHASE_MEMORY,
  CONEFETI_PHASE_COARSE,
  CONEFETI_PHASE_FACTORIZATION,
  CONEFETI_PHASE_EXPLICIT,
  CONEFETI_PHASE_OPERATORS,
  CONEFETI_PHASE_CONTACT_PROBLEM,
  CONEFETI_PHASE_SOLVE,
  CONEFETI_PHASE_COUNT
} ConeFETIPhase;
/* the phases' keys (as in the summary's JSON "time_phases"), then "ConeFETIPhase", "CONEFETI_PHASE_", NULL */
PETSC_EXTERN const char *const ConeFETIPhases[];
/* the phases in words, for a progress line ("factorizing subdomains") */
PETSC_EXTERN const char *const ConeFETIPhaseDescriptions[];

/*S
  ConeFETIProgressInfo - What a progress report says (`ConeFETIProgressFn`).

  Fields:
+ phase       - the phase
. description - the phase in words (`ConeFETIPhaseDescriptions`)
. done        - PETSC_TRUE once: the phase has ended, and time is its duration
. k, n        - k of n items of this rank done (subdomains; n = 0: the phase is not counted)
. step        - solve: the Coulomb successive approximation (MSA) running, from 1; 0 otherwise
. iteration   - solve: the outer iteration of the current solve that just ended, from 1 (0: none yet)
. residual    - solve: the largest residual after that iteration, on the scale of the solver's relative tolerance
. tol         - solve: that tolerance (the solve stops when residual <= tol)
- time        - seconds since the phase began on this rank

  Level: intermediate

.seealso: `ConeFETIProgressFn`, `ConeFETIPhase`, `ContactSceneSetProgress()`, `ContactModelSetProgress()`, `FETISetProgress()`
S*/
typedef struct {
  ConeFETIPhase  phase;
  const char    *description;
  PetscBool      done;
  PetscInt       k, n;
  PetscInt       step, iteration;
  PetscReal      residual, tol;
  PetscLogDouble time;
} ConeFETIProgressInfo;

/*S
  ConeFETIProgressFn - A caller's progress hook: fn(info, ctx), called when a phase begins, after each counted item or outer iteration, and when the phase ends.

  Notes:
  Called on every rank with that rank's counts, not collectively: it must not communicate. The
  library prints nothing itself; the conefeti program installs a printer (docs/output.md). A call costs a
  function call: rate-limit anything expensive (terminal output) in the hook.

  Level: intermediate

.seealso: `ConeFETIProgressInfo`, `ContactSceneSetProgress()`, `ContactModelSetProgress()`, `ContactProblemSetProgress()`, `FETISetProgress()`
S*/
typedef PetscErrorCode (*ConeFETIProgressFn)(const ConeFETIProgressInfo *, void *);

/* The plugin entry point PETSc looks up after -dll_append libconefeti.so */
PETSC_EXTERN PetscErrorCode PetscDLLibraryRegister_conefeti(void);
