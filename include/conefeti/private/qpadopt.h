/* The QP setters keep their arguments on the Tao/KSP too (PetscObjectCompose), so that a type
   created later (-tao_type mpgp after TaoSetType(tao, TAOMPRGP), -ksp_type mpgp after KSPMPRGP)
   adopts them instead of silently solving without its constraints. */
#pragma once

#include <conefeti/qp.h>
#include <conefeti/compat.h>

/* called at the end of each QP type's create function */
PETSC_INTERN PetscErrorCode TaoQPAdoptComposed_Private(Tao);
PETSC_INTERN PetscErrorCode KSPQPAdoptComposed_Private(KSP);

/* a real kept on the object for a type created later (the norm estimate); *found: whether one was kept */
PETSC_INTERN PetscErrorCode QPComposeReal_Private(PetscObject, const char[], PetscReal);
PETSC_INTERN PetscErrorCode QPQueryReal_Private(PetscObject, const char[], PetscReal *, PetscBool *);
