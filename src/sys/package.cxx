/* Package initialization: registers every type conefeti provides, once per PetscInitialize. */
#include <conefeti.h>
#include <conefeti/compat.h>
#include <conefeti/private/package.h>
#include <slepcsys.h>

static PetscBool conefeti_initialized = PETSC_FALSE;
static PetscBool conefeti_began_slepc = PETSC_FALSE;

/*@C
  ConeFETIFinalizePackage - Undo ConeFETIInitializePackage(); called by PetscFinalize().

  Level: developer

.seealso: `ConeFETIInitializePackage()`
@*/
PetscErrorCode ConeFETIFinalizePackage(void)
{
  PetscFunctionBegin;
  PetscCall(ConeFETIQPFinalizePackage());
  PetscCall(ConeFETIFETIFinalizePackage());
  PetscCall(ConeFETIFEMFinalizePackage());
  PetscCall(ConeFETIContactFinalizePackage());
  PetscCall(ConeFETIIOFinalizePackage());
  if (conefeti_began_slepc) {
    PetscBool finalized;
    PetscCall(SlepcFinalized(&finalized));
    if (!finalized) PetscCall(SlepcFinalize());
    conefeti_began_slepc = PETSC_FALSE;
  }
  conefeti_initialized = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ConeFETIInitializePackage - Register all conefeti types (TAO `mprgp`, `mpgp`, `smalxe`; KSP
  `mprgp`, `mpgp`), classes and log events. Safe to call more than once.

  Not Collective

  Notes:
  A program that links libconefeti calls this once after `PetscInitialize()`. A program that does
  not link it gets the same effect with `-dll_append /path/to/libconefeti.so` (command line,
  `PETSC_OPTIONS` or an options file): PETSc then calls `PetscDLLibraryRegister_conefeti()`.

  Level: beginner

.seealso: `ConeFETIFinalizePackage()`, `PetscDLLibraryRegister_conefeti()`
@*/
PetscErrorCode ConeFETIInitializePackage(void)
{
  PetscFunctionBegin;
  if (conefeti_initialized) PetscFunctionReturn(PETSC_SUCCESS);
  conefeti_initialized = PETSC_TRUE;
  PetscCall(ConeFETIQPInitializePackage());
  PetscCall(ConeFETIFETIInitializePackage());
  PetscCall(ConeFETIFEMInitializePackage());
  PetscCall(ConeFETIContactInitializePackage());
  PetscCall(ConeFETIIOInitializePackage());
  PetscCall(PetscRegisterFinalize(ConeFETIFinalizePackage));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ConeFETISlepcInitializeIfNeeded - Initialize SLEPc when the host program only initialized PETSc.

  Not Collective (but must be called on all ranks of PETSC_COMM_WORLD at the same point)

  Notes:
  conefeti calls this lazily before its first SLEPc use (the norm estimate), so that a PETSc
  program that loads the plugin with `-dll_append` need not know about SLEPc. SLEPc is then
  finalized together with PETSc.

  Level: developer

.seealso: `ConeFETIInitializePackage()`
@*/
PetscErrorCode ConeFETISlepcInitializeIfNeeded(void)
{
  PetscBool initialized;

  PetscFunctionBegin;
  PetscCall(SlepcInitialized(&initialized));
  if (!initialized) {
    PetscCall(SlepcInitialize(NULL, NULL, NULL, NULL));
    conefeti_began_slepc = PETSC_TRUE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ConeFETIGetVersion - Version of the conefeti library.

  Not Collective

  Output Parameters:
+ major - major version
. minor - minor version
- patch - patch level

  Level: beginner
@*/
PetscErrorCode ConeFETIGetVersion(PetscInt *major, PetscInt *minor, PetscInt *patch)
{
  PetscFunctionBegin;
  if (major) *major = CONEFETI_VERSION_MAJOR;
  if (minor) *minor = CONEFETI_VERSION_MINOR;
  if (patch) *patch = CONEFETI_VERSION_PATCH;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  PetscDLLibraryRegister_conefeti - Entry point PETSc calls when libconefeti.so is loaded with
  `-dll_append` or `-dll_prepend`; registers all conefeti types.

  Level: developer

.seealso: `ConeFETIInitializePackage()`
@*/
PetscErrorCode PetscDLLibraryRegister_conefeti(void)
{
  PetscFunctionBegin;
  PetscCall(ConeFETIInitializePackage());
  PetscFunctionReturn(PETSC_SUCCESS);
}
