/* FETI layer package: registers the feti layer's classes and log events. */
#include <conefeti/private/package.h>
#include <conefeti/private/compat.h>

PetscErrorCode ConeFETIFETIInitializePackage(void)
{
  PetscFunctionBegin;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIFETIFinalizePackage(void)
{
  PetscFunctionBegin;
  PetscFunctionReturn(PETSC_SUCCESS);
}
