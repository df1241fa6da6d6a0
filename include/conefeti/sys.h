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
/* The plugin entry point PETSc looks up after -dll_append libconefeti.so */
PETSC_EXTERN PetscErrorCode PetscDLLibraryRegister_conefeti(void);
