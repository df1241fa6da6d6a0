/* The library's side of progress reports (ConeFETIProgressFn, conefeti/sys.h): an object keeps the
   caller's hook and the phase it is in; these helpers time the phase and call the hook. */
#pragma once

#include <conefeti/sys.h>

struct ConeFETIProgress {
  ConeFETIProgressFn   fn  = nullptr;
  void                *ctx = nullptr;
  ConeFETIProgressInfo info{};
  PetscLogDouble       t0 = 0;
};

/* phase begins: n items to count (0: none) */
PETSC_INTERN PetscErrorCode ConeFETIProgressBegin_Private(ConeFETIProgress &, ConeFETIPhase, PetscInt);
/* a phase another object began and ends (the solve around a contact problem's iterations): timed from here, not announced */
PETSC_INTERN PetscErrorCode ConeFETIProgressEnter_Private(ConeFETIProgress &, ConeFETIPhase);
/* k items done */
PETSC_INTERN PetscErrorCode ConeFETIProgressStep_Private(ConeFETIProgress &, PetscInt);
/* an outer iteration of a solve ended (step: MSA step or 0) */
PETSC_INTERN PetscErrorCode ConeFETIProgressIterate_Private(ConeFETIProgress &, PetscInt, PetscInt, PetscReal, PetscReal);
/* the phase ends */
PETSC_INTERN PetscErrorCode ConeFETIProgressEnd_Private(ConeFETIProgress &);
