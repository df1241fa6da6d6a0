/* conefeti: FETI domain decomposition for 3D contact problems with Coulomb friction,
   delivered as PETSc plugins (TAO types mprgp, mpgp, smalxe; KSP types mprgp, mpgp).

   A program that links libconefeti includes this header and calls ConeFETIInitializePackage()
   once after PetscInitialize(). An unmodified PETSc program gets the same solver types with
   -dll_append /path/to/libconefeti.so. conefeti/compat.h gives the names that differ between PETSc
   releases (PETSC_SUCCESS before 3.19, ...), so a program that uses them builds on each. */
#pragma once

#include <conefeti/compat.h>
#include <conefeti/sys.h>
#include <conefeti/qp.h>
#include <conefeti/feti.h>
#include <conefeti/fem.h>
#include <conefeti/contact.h>
#include <conefeti/io.h>
