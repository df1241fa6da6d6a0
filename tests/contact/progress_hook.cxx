/* The progress hook's contract, seen by a program that sets it on a scene (ContactSceneSetProgress()): every phase
   begins before it reports counts or iterations and ends once; the setup phases come in the order of FETISetUp()
   and the contact model; counted phases reach k = n, with k never decreasing; outer iterations count up within a
   solve (or an MSA step) with finite residuals and a positive tolerance; the summary's time_phases are the sums of
   the durations the hook saw on this rank (rank 0's: the summary's). The scene comes from the options
   (e.g. -options_file petsc-options/brick.opts). Prints "progress hook: ... checks passed" or fails.

   -fail_at_solve k: the hook fails (PETSC_ERR_USER) at the first outer iteration of the k-th solve (k = 2: the
   first tighter solve of ContactModelSolve()). The error must reach the program, and leave the model's state as the
   user set it: the contact solver's tolerance -contact_rtol, no recycled multiplier, and the F products' refinement of
   float factors off. The same scene solved again (the hook quiet) must then converge as a first solve does. Prints
   "error in solve k: state restored, solved again: ..." or fails. */
#include <conefeti.h>

#include <cmath>
#include <vector>

struct Seen {
  std::vector<ConeFETIPhase> ended;     /* phases in the order they ended */
  PetscInt                   open = -1; /* the phase begun and not ended (-1: none) */
  PetscInt                   k = 0, iteration = 0, step = 0;
  PetscInt                   iterations                 = 0; /* outer iterations reported */
  PetscLogDouble             time[CONEFETI_PHASE_COUNT] = {};
  PetscInt                   checks                     = 0;
  PetscInt                   solves = 0, fail_at_solve = 0; /* solves begun; the one whose first outer iteration fails */
};

static PetscErrorCode Hook(const ConeFETIProgressInfo *info, void *ctx)
{
  Seen &s = *static_cast<Seen *>(ctx);

  PetscFunctionBegin;
  PetscCheck(info->phase >= 0 && info->phase < CONEFETI_PHASE_COUNT && info->description, PETSC_COMM_SELF, PETSC_ERR_PLIB, "a report of no known phase (%d)", (int)info->phase);
  PetscCheck(info->time >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "phase %s: negative time %g", ConeFETIPhases[info->phase], info->time);
  if (info->phase == CONEFETI_PHASE_SOLVE && info->iteration > 0) { /* an outer iteration: within the solve */
    PetscCheck(s.open == CONEFETI_PHASE_SOLVE, PETSC_COMM_SELF, PETSC_ERR_PLIB, "an outer iteration outside the solve phase");
    if (info->step != s.step || info->iteration <= s.iteration) s.iteration = 0; /* a new MSA step or a tighter re-solve starts again */
    if (s.iteration == 0 && info->step <= 1) s.solves++;
    PetscCheck(s.solves != s.fail_at_solve, PETSC_COMM_SELF, PETSC_ERR_USER, "the hook fails in solve %d, as asked", (int)s.solves);
    PetscCheck(info->iteration == s.iteration + 1 || s.iteration == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "outer iteration %d after %d", (int)info->iteration, (int)s.iteration);
    PetscCheck(std::isfinite((double)info->residual) && info->residual >= 0 && info->tol > 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "outer iteration %d: residual %g, tol %g", (int)info->iteration,
               (double)info->residual, (double)info->tol);
    s.iteration = info->iteration;
    s.step      = info->step;
    s.iterations++;
    s.checks++;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (info->done) {
    PetscCheck(s.open == info->phase, PETSC_COMM_SELF, PETSC_ERR_PLIB, "phase %s ends, but %s is the one begun", ConeFETIPhases[info->phase], s.open >= 0 ? ConeFETIPhases[s.open] : "none");
    PetscCheck(info->k == info->n, PETSC_COMM_SELF, PETSC_ERR_PLIB, "phase %s ends at %d of %d", ConeFETIPhases[info->phase], (int)info->k, (int)info->n);
    s.ended.push_back(info->phase);
    s.time[info->phase] += info->time;
    s.open = -1;
  } else if (s.open != info->phase) { /* a phase begins */
    PetscCheck(s.open < 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "phase %s begins while %s is not done", ConeFETIPhases[info->phase], s.open >= 0 ? ConeFETIPhases[s.open] : "");
    PetscCheck(info->k == 0 && info->iteration == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "phase %s begins at k = %d", ConeFETIPhases[info->phase], (int)info->k);
    s.open      = info->phase;
    s.k         = 0;
    s.iteration = 0;
    s.step      = 0;
  } else { /* a count */
    PetscCheck(info->n > 0 && info->k >= s.k && info->k <= info->n, PETSC_COMM_SELF, PETSC_ERR_PLIB, "phase %s: k = %d after %d, of n = %d", ConeFETIPhases[info->phase], (int)info->k, (int)s.k,
               (int)info->n);
    s.k = info->k;
  }
  s.checks++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  ContactScene        scene;
  ContactSceneSummary summary;
  Seen                seen;
  PetscMPIInt         rank;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "progress hook contract\n"));
  PetscCall(ConeFETIInitializePackage());
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-fail_at_solve", &seen.fail_at_solve, NULL));
  PetscCall(ContactSceneCreateFromOptions(PETSC_COMM_WORLD, NULL, &scene));
  PetscCall(ContactSceneSetProgress(scene, Hook, &seen));
  if (seen.fail_at_solve > 0) {
    PetscErrorCode    ierr;
    ContactModel      cm;
    ContactProblem    cp;
    ContactStatistics st;
    Tao               tao;
    FETI              feti;
    PetscReal         rtol = 1e-6, gttol;
    PetscBool         recycle, refine;
    char              verdict[64];
    PetscCall(PetscOptionsGetReal(NULL, NULL, "-contact_rtol", &rtol, NULL));
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = ContactSceneSolve(scene);
    PetscCall(PetscPopErrorHandler());
    PetscCheck(ierr == PETSC_ERR_USER, PETSC_COMM_SELF, PETSC_ERR_PLIB, "the solve returned %d, not the hook's error %d", (int)ierr, (int)PETSC_ERR_USER);
    PetscCall(ContactSceneGetContactModel(scene, &cm));
    PetscCall(ContactModelGetContactProblem(cm, &cp));
    PetscCall(ContactProblemGetTao(cp, &tao));
    PetscCall(TaoGetTolerances(tao, NULL, NULL, &gttol));
    PetscCall(TaoGetRecycleHistory(tao, &recycle));
    PetscCall(ContactModelGetFETI(cm, &feti));
    PetscCall(FETIGetKplusRefine(feti, &refine));
    const PetscInt failed = seen.solves;
    PetscCheck(failed == seen.fail_at_solve && gttol == rtol && !recycle && !refine, PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "after the error in solve %d of %d: tolerance %g (set: %g), recycle %d, refine %d", (int)seen.fail_at_solve, (int)failed, (double)gttol, (double)rtol, (int)recycle, (int)refine);
    seen = Seen{}; /* the hook quiet, its bookkeeping from the start */
    PetscCall(ContactSceneSolve(scene));
    PetscCall(ContactModelGetStatistics(cm, &st));
    PetscCall(PetscSNPrintf(verdict, sizeof(verdict), "%s, %d tighter solves", st.converged ? "converged" : "not converged", (int)st.refinements));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "error in solve %d: state restored, solved again: %s\n", (int)failed, verdict));
    PetscCall(ContactSceneDestroy(&scene));
    PetscCall(PetscFinalize());
    return 0;
  }
  PetscCall(ContactSceneSolve(scene));
  { /* -write_output name: ContactSceneWriteOutput() from the library, as a program of the user's calls it */
    char      name[PETSC_MAX_PATH_LEN];
    PetscBool write = PETSC_FALSE;
    PetscCall(PetscOptionsGetString(NULL, NULL, "-write_output", name, sizeof(name), &write));
    if (write) PetscCall(ContactSceneWriteOutput(scene, name));
  }
  PetscCall(ContactSceneGetSummary(scene, &summary));
  PetscCheck(seen.open < 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "phase %s never ended", ConeFETIPhases[seen.open]);
  /* the setup phases in the order they run; every phase at most once (the contact problem only with contact) */
  for (size_t i = 1; i < seen.ended.size(); i++)
    PetscCheck(seen.ended[i] > seen.ended[i - 1], PETSC_COMM_SELF, PETSC_ERR_PLIB, "phase %s ended after %s", ConeFETIPhases[seen.ended[i]], ConeFETIPhases[seen.ended[i - 1]]);
  for (ConeFETIPhase p : {CONEFETI_PHASE_MESH, CONEFETI_PHASE_CONTACT_ROWS, CONEFETI_PHASE_KERNELS, CONEFETI_PHASE_MEMORY, CONEFETI_PHASE_COARSE, CONEFETI_PHASE_FACTORIZATION,
                          CONEFETI_PHASE_OPERATORS, CONEFETI_PHASE_SOLVE}) {
    bool found = false;
    for (ConeFETIPhase q : seen.ended) found = found || q == p;
    PetscCheck(found, PETSC_COMM_SELF, PETSC_ERR_PLIB, "phase %s was not reported", ConeFETIPhases[p]);
  }
  PetscCheck(seen.iterations > 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "no outer iteration was reported");
  if (!rank) /* the summary holds rank 0's durations */
    for (int p = 0; p < CONEFETI_PHASE_COUNT; p++)
      PetscCheck(summary.time_phases[p] == (PetscReal)seen.time[p], PETSC_COMM_SELF, PETSC_ERR_PLIB, "time_phases.%s = %g, the hook saw %g", ConeFETIPhases[p], (double)summary.time_phases[p],
                 seen.time[p]);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "progress hook: %d phases, %d outer iterations, %d checks passed\n", (int)seen.ended.size(), (int)seen.iterations, (int)seen.checks));
  PetscCall(ContactSceneDestroy(&scene));
  PetscCall(PetscFinalize());
  return 0;
}
