/* io layer package: the ContactScene class and its log events. */
#include "sceneimpl.h"
#include <conefeti/private/package.h>

PetscErrorCode ConeFETIIOInitializePackage(void)
{
  PetscFunctionBegin;
  PetscCall(PetscClassIdRegister("ContactScene", &CONTACTSCENE_CLASSID));
  PetscCall(PetscLogEventRegister("ContactSceneSetUp", CONTACTSCENE_CLASSID, &CONTACTSCENE_SetUp));
  PetscCall(PetscLogEventRegister("ContactSceneSolve", CONTACTSCENE_CLASSID, &CONTACTSCENE_Solve));
  PetscCall(PetscLogEventRegister("ContactSceneSummary", CONTACTSCENE_CLASSID, &CONTACTSCENE_Summary));
  PetscCall(PetscLogEventRegister("ContactSceneOutput", CONTACTSCENE_CLASSID, &CONTACTSCENE_Output));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIIOFinalizePackage(void)
{
  PetscFunctionBegin;
  PetscFunctionReturn(PETSC_SUCCESS);
}
