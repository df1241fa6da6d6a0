/* FEM layer package: registers the FEM class and its log events. */
#include <conefeti/private/package.h>
#include <conefeti/private/femimpl.h>

PetscClassId  FEM_CLASSID;
PetscLogEvent FEM_SetUp, FEM_Assembly, FEM_Decompose;

static PetscBool fem_package_initialized = PETSC_FALSE;

PetscErrorCode ConeFETIFEMInitializePackage(void)
{
  PetscFunctionBegin;
  if (fem_package_initialized) PetscFunctionReturn(PETSC_SUCCESS);
  fem_package_initialized = PETSC_TRUE;
  PetscCall(PetscClassIdRegister("FEM", &FEM_CLASSID));
  PetscCall(PetscLogEventRegister("FEMSetUp", FEM_CLASSID, &FEM_SetUp));
  PetscCall(PetscLogEventRegister("FEMAssembly", FEM_CLASSID, &FEM_Assembly));
  PetscCall(PetscLogEventRegister("FEMDecompose", FEM_CLASSID, &FEM_Decompose));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIFEMFinalizePackage(void)
{
  PetscFunctionBegin;
  fem_package_initialized = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
