/* Progress of a scene's setup and solve: the caller's hook (ContactSceneSetProgress()) and the durations of the
   phases that the summary reports (ContactSceneSummary.time_phases). */
#include "sceneimpl.h"

/*@C
  ContactSceneSetProgress - A hook told how the setup and the solve progress: the meshes and FEM, the contact
  rows, every phase of `FETISetUp()` (subdomains counted), the contact problem, then the solve with each outer
  iteration and its largest residual against the tolerance.

  Logically Collective

  Input Parameters:
+ scene - the scene
. fn    - the hook (NULL: none)
- ctx   - its context

  Notes:
  The library prints nothing; the conefeti program installs a printer (-progress, docs/output.md). The scene
  times its phases whether a hook is set or not: `ContactSceneGetSummary()` reports the durations.

  Level: intermediate

.seealso: `ConeFETIProgressFn`, `ConeFETIProgressInfo`, `ContactModelSetProgress()`, `ContactSceneGetSummary()`
@*/
PetscErrorCode ContactSceneSetProgress(ContactScene scene, ConeFETIProgressFn fn, void *ctx)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(scene, CONTACTSCENE_CLASSID, 1);
  scene->impl->progressfn  = fn;
  scene->impl->progressctx = ctx;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ContactSceneProgress_Private(const ConeFETIProgressInfo *info, void *ctx)
{
  Scene_Impl &impl = *static_cast<ContactScene>(ctx)->impl;

  PetscFunctionBegin;
  /* a phase may end in parts (none does yet): the durations add up; a new solve starts its own */
  if (info->phase == CONEFETI_PHASE_SOLVE && !info->done && info->iteration == 0) impl.time_phases[CONEFETI_PHASE_SOLVE] = 0;
  if (info->done) impl.time_phases[info->phase] += info->time;
  if (impl.progressfn) PetscCall(impl.progressfn(info, impl.progressctx));
  PetscFunctionReturn(PETSC_SUCCESS);
}
