/* Compatibility layer: conefeti is written against PETSc 3.18 (Debian 12) and kept ready for
   newer releases. Everything version-dependent lives here, nowhere else. */
#pragma once

#include <petscsys.h>

/* PetscErrorCode became an enum with PETSC_SUCCESS in 3.19; returning it keeps C++ happy on both. */
#if PETSC_VERSION_LT(3, 19, 0) && !defined(PETSC_SUCCESS)
#  define PETSC_SUCCESS 0
#endif

/* PetscOptionItems became a non-pointer typedef in 3.22. */
#if PETSC_VERSION_LT(3, 22, 0)
#  define CONEFETI_OPTIONS_ITEMS PetscOptionItems *
#else
#  define CONEFETI_OPTIONS_ITEMS PetscOptionItems
#endif
