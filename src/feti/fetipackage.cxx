/* FETI layer package: registers the FETI class, its log events and the FETI preconditioners. */
#include <conefeti/private/package.h>
#include <conefeti/private/fetiimpl.h>

PetscClassId  FETI_CLASSID;
PetscLogEvent FETI_ApplyG, FETI_ApplyGt;
PetscLogEvent FETI_SetUp, FETI_Assembly, FETI_Factorization, FETI_MultF, FETI_CoarseSolve, FETI_ApplyKplus, FETI_PrimalRecovery, FETI_Preconditioner;
PetscLogEvent FETI_Kernels, FETI_Reorder, FETI_PCSetUp;

static PetscBool feti_package_initialized = PETSC_FALSE;

PetscErrorCode ConeFETIFETIInitializePackage(void)
{
  PetscFunctionBegin;
  if (feti_package_initialized) PetscFunctionReturn(PETSC_SUCCESS);
  feti_package_initialized = PETSC_TRUE;
  PetscCall(KSPInitializePackage());
  PetscCall(PetscClassIdRegister("FETI", &FETI_CLASSID));
  PetscCall(PetscLogEventRegister("FETISetUp", FETI_CLASSID, &FETI_SetUp));
  PetscCall(PetscLogEventRegister("FETIAssembly", FETI_CLASSID, &FETI_Assembly));
  PetscCall(PetscLogEventRegister("FETIKernels", FETI_CLASSID, &FETI_Kernels));
  PetscCall(PetscLogEventRegister("FETIReorder", FETI_CLASSID, &FETI_Reorder));
  PetscCall(PetscLogEventRegister("FETIFactor", FETI_CLASSID, &FETI_Factorization));
  PetscCall(PetscLogEventRegister("FETI_MultF", FETI_CLASSID, &FETI_MultF));
  PetscCall(PetscLogEventRegister("FETIApplyKplus", FETI_CLASSID, &FETI_ApplyKplus));
  PetscCall(PetscLogEventRegister("FETICoarseSolve", FETI_CLASSID, &FETI_CoarseSolve));
  PetscCall(PetscLogEventRegister("FETIApplyG", FETI_CLASSID, &FETI_ApplyG));
  PetscCall(PetscLogEventRegister("FETIApplyGt", FETI_CLASSID, &FETI_ApplyGt));
  PetscCall(PetscLogEventRegister("FETIPrimalRecov", FETI_CLASSID, &FETI_PrimalRecovery));
  PetscCall(PetscLogEventRegister("FETIPCApply", FETI_CLASSID, &FETI_Preconditioner));
  PetscCall(PetscLogEventRegister("FETIPCSetUp", FETI_CLASSID, &FETI_PCSetUp));
  PetscCall(PCRegister(PCFETILUMPED, PCCreate_FETILumped));
  PetscCall(PCRegister(PCFETIDIRICHLET, PCCreate_FETIDirichlet));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIFETIFinalizePackage(void)
{
  PetscFunctionBegin;
  feti_package_initialized = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
