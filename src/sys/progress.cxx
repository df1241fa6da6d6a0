/* Progress reports: the phase names and the helpers with which FETI, the contact objects and the scene call
   their caller's hook (conefeti/sys.h, private/progress.h). The library never prints progress itself. */
#include <conefeti/private/progress.h>
#include <conefeti/compat.h>
#include <petsctime.h>

const char *const ConeFETIPhases[] = {"mesh",      "contact_rows",    "kernels", "memory",        "coarse",          "factorization", "explicit_kplus",
                                      "operators", "contact_problem", "solve",   "ConeFETIPhase", "CONEFETI_PHASE_", nullptr};

const char *const ConeFETIPhaseDescriptions[] = {"meshing and assembling the bodies", "contact nodes and rows", "subdomain kernels", "memory estimate", "coarse problem", "factorizing subdomains",
                                                 "explicit (K+)_bb of subdomains",    "operators F, G, P, Q",   "contact problem",   "starting",        nullptr};

static PetscErrorCode Call(ConeFETIProgress &p)
{
  PetscLogDouble now;

  PetscFunctionBegin;
  PetscCall(PetscTime(&now));
  p.info.time = now - p.t0;
  PetscCall(p.fn(&p.info, p.ctx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIProgressBegin_Private(ConeFETIProgress &p, ConeFETIPhase phase, PetscInt n)
{
  PetscFunctionBegin;
  if (!p.fn) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscTime(&p.t0));
  p.info             = ConeFETIProgressInfo{};
  p.info.phase       = phase;
  p.info.description = ConeFETIPhaseDescriptions[phase];
  p.info.n           = n;
  PetscCall(Call(p));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIProgressEnter_Private(ConeFETIProgress &p, ConeFETIPhase phase)
{
  PetscFunctionBegin;
  if (!p.fn) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscTime(&p.t0));
  p.info             = ConeFETIProgressInfo{};
  p.info.phase       = phase;
  p.info.description = ConeFETIPhaseDescriptions[phase];
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIProgressStep_Private(ConeFETIProgress &p, PetscInt k)
{
  PetscFunctionBegin;
  if (!p.fn) PetscFunctionReturn(PETSC_SUCCESS);
  p.info.k = k;
  PetscCall(Call(p));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIProgressIterate_Private(ConeFETIProgress &p, PetscInt step, PetscInt iteration, PetscReal residual, PetscReal tol)
{
  PetscFunctionBegin;
  if (!p.fn) PetscFunctionReturn(PETSC_SUCCESS);
  p.info.step      = step;
  p.info.iteration = iteration;
  p.info.residual  = residual;
  p.info.tol       = tol;
  PetscCall(Call(p));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIProgressEnd_Private(ConeFETIProgress &p)
{
  PetscFunctionBegin;
  if (!p.fn) PetscFunctionReturn(PETSC_SUCCESS);
  p.info.done = PETSC_TRUE;
  PetscCall(Call(p));
  p.info.done = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}
