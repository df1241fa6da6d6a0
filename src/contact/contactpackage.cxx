/* Contact layer package: the ContactProblem class and its log events. */
#include <conefeti/private/contactimpl.h>
#include <conefeti/private/package.h>

PetscErrorCode ConeFETIContactInitializePackage(void)
{
  PetscFunctionBegin;
  PetscCall(PetscClassIdRegister("ContactProblem", &CONTACTPROBLEM_CLASSID));
  PetscCall(PetscClassIdRegister("ContactModel", &CONTACTMODEL_CLASSID));
  PetscCall(PetscLogEventRegister("ContactSolve", CONTACTPROBLEM_CLASSID, &CONTACT_Solve));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIContactFinalizePackage(void)
{
  PetscFunctionBegin;
  PetscFunctionReturn(PETSC_SUCCESS);
}
