/* FEM layer package: registers the fem layer's classes and log events. */
#include <conefeti/private/package.h>
#include <conefeti/private/compat.h>

PetscErrorCode ConeFETIFEMInitializePackage(void)
{
  PetscFunctionBegin;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIFEMFinalizePackage(void)
{
  PetscFunctionBegin;
  PetscFunctionReturn(PETSC_SUCCESS);
}
