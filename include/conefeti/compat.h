/* PETSc version compatibility: conefeti is written against PETSc 3.18 (Debian 12) and kept ready for
   newer releases. Everything version-dependent lives here, nowhere else; the library, the driver,
   the tutorials and the tests all use these names. The header is public (installed, included by
   conefeti.h) so that a program built against an installed conefeti compiles the same way. */
#pragma once

#include <petscsys.h>

/* PetscErrorCode became an enum with PETSC_SUCCESS in 3.19; returning it keeps C++ happy on both. */
#if PETSC_VERSION_LT(3, 19, 0) && !defined(PETSC_SUCCESS)
#  define PETSC_SUCCESS 0
#endif

/* PetscOptionItems became a non-pointer typedef in 3.22: the type of PetscOptionsObject, the
   argument of XXXSetFromOptions_YYY() and whatever stores it. */
#if PETSC_VERSION_LT(3, 22, 0)
#  define CONEFETI_OPTIONS_ITEMS PetscOptionItems *
#else
#  define CONEFETI_OPTIONS_ITEMS PetscOptionItems
#endif

/* PetscAssertPointer() replaced PetscAssertPointer() in 3.20 (the old name is deprecated there and
   later removed). Before 3.20 it maps to PetscAssertPointer(), which petsc/private/petscimpl.h
   defines: a file using it includes that header (directly or through a PETSc *impl.h), as before. */
#if PETSC_VERSION_LT(3, 20, 0) && !defined(PetscAssertPointer)
#  define PetscAssertPointer(h, arg) PetscValidPointer(h, arg)
#endif

/* TaoSetMonitor() was renamed TaoMonitorSet() in 3.21 (the old name later removed); same arguments. */
#if PETSC_VERSION_LT(3, 21, 0) && !defined(TaoMonitorSet)
#  define TaoMonitorSet(tao, fn, ctx, destroy) TaoSetMonitor(tao, fn, ctx, destroy)
#endif
