/* QPCounters: human and machine-readable views of the work a QP solver did. */
#include <conefeti/qp.h>
#include <conefeti/compat.h>

/*@C
  QPCountersView - Print QP counters in human-readable form.

  Collective on the viewer

  Input Parameters:
+ c      - the counters
. name   - a label (e.g. the solver type), or NULL
- viewer - an ASCII viewer

  Level: intermediate

.seealso: `QPCounters`, `QPCountersViewJSON()`, `TaoQPGetCounters()`
@*/
PetscErrorCode QPCountersView(const QPCounters *c, const char name[], PetscViewer viewer)
{
  PetscFunctionBegin;
  PetscCall(PetscViewerASCIIPrintf(viewer, "%s%sHessian products: %" PetscInt_FMT " own + %" PetscInt_FMT " nested = %" PetscInt_FMT " (norm estimate: %" PetscInt_FMT " more)\n", name ? name : "",
                                   name ? " " : "", c->hessian_mults, c->nested_hessian_mults, c->hessian_mults + c->nested_hessian_mults, c->estimate_mults));
  PetscCall(PetscViewerASCIIPrintf(
      viewer, "%s%ssolves %" PetscInt_FMT ", iterations %" PetscInt_FMT " (nested %" PetscInt_FMT "): CG %" PetscInt_FMT ", expansion %" PetscInt_FMT ", proportioning %" PetscInt_FMT "\n",
      name ? name : "", name ? " " : "", c->solves, c->iterations, c->nested_iterations, c->cg_steps, c->expansion_steps, c->proportioning_steps));
  if (c->pc_applications) PetscCall(PetscViewerASCIIPrintf(viewer, "%s%spreconditioner applications: %" PetscInt_FMT "\n", name ? name : "", name ? " " : "", c->pc_applications));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  QPCountersViewJSON - Print QP counters as one JSON object on one line, for scripts and tables.

  Collective on the viewer

  Input Parameters:
+ c      - the counters
. name   - value of the "solver" field, or NULL
- viewer - an ASCII viewer

  Notes:
  Fields: solver, solves, iterations, hessian_mults, nested_iterations, nested_hessian_mults,
  total_hessian_mults, estimate_mults, cg_steps, expansion_steps, proportioning_steps, pc_applications.

  Level: intermediate

.seealso: `QPCounters`, `QPCountersView()`
@*/
PetscErrorCode QPCountersViewJSON(const QPCounters *c, const char name[], PetscViewer viewer)
{
  PetscFunctionBegin;
  PetscCall(PetscViewerASCIIPrintf(viewer,
                                   "{\"solver\": \"%s\", \"solves\": %" PetscInt_FMT ", \"iterations\": %" PetscInt_FMT ", \"hessian_mults\": %" PetscInt_FMT ", \"nested_iterations\": %" PetscInt_FMT
                                   ", \"nested_hessian_mults\": %" PetscInt_FMT ", \"total_hessian_mults\": %" PetscInt_FMT ", \"estimate_mults\": %" PetscInt_FMT ", \"cg_steps\": %" PetscInt_FMT
                                   ", \"expansion_steps\": %" PetscInt_FMT ", \"proportioning_steps\": %" PetscInt_FMT ", \"pc_applications\": %" PetscInt_FMT "}\n",
                                   name ? name : "", c->solves, c->iterations, c->hessian_mults, c->nested_iterations, c->nested_hessian_mults, c->hessian_mults + c->nested_hessian_mults,
                                   c->estimate_mults, c->cg_steps, c->expansion_steps, c->proportioning_steps, c->pc_applications));
  PetscFunctionReturn(PETSC_SUCCESS);
}
