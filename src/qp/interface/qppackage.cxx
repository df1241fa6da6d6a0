/* QP layer package: registers the QP solver types, classes and log events. */
#include <conefeti/private/package.h>
#include <conefeti/private/compat.h>

PetscErrorCode ConeFETIQPInitializePackage(void)
{
  PetscFunctionBegin;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIQPFinalizePackage(void)
{
  PetscFunctionBegin;
  PetscFunctionReturn(PETSC_SUCCESS);
}
