/* Per-layer package initialization, called by ConeFETIInitializePackage() only.
   Each layer registers its own types, classes and log events in src/<layer>/<layer>package.cxx. */
#pragma once

#include <petscsys.h>

PETSC_INTERN PetscErrorCode ConeFETIQPInitializePackage(void);
PETSC_INTERN PetscErrorCode ConeFETIQPFinalizePackage(void);
PETSC_INTERN PetscErrorCode ConeFETIFETIInitializePackage(void);
PETSC_INTERN PetscErrorCode ConeFETIFETIFinalizePackage(void);
PETSC_INTERN PetscErrorCode ConeFETIFEMInitializePackage(void);
PETSC_INTERN PetscErrorCode ConeFETIFEMFinalizePackage(void);
PETSC_INTERN PetscErrorCode ConeFETIContactInitializePackage(void);
PETSC_INTERN PetscErrorCode ConeFETIContactFinalizePackage(void);
PETSC_INTERN PetscErrorCode ConeFETIIOInitializePackage(void);
PETSC_INTERN PetscErrorCode ConeFETIIOFinalizePackage(void);
