/* The conefeti program's progress printer: the library reports phases and outer iterations through a hook
   (ContactSceneSetProgress()); this file decides how they look. On a terminal one line is rewritten in place
   (at most ten times a second, so that printing costs nothing next to the work); in a log (stdout not a
   terminal) one line per completed phase with its time; with -quiet or -progress none, nothing. Rank 0 prints. */
#include "driver.h"
#include <petsctime.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unistd.h>

namespace {

struct Printer {
  DriverProgressMode   mode = DRIVER_PROGRESS_NONE;
  PetscMPIInt          rank = 0, size = 1;
  PetscLogDouble       last  = -1; /* when the terminal line was last written */
  size_t               width = 0;  /* characters on the terminal line */
  ConeFETIProgressInfo solve{};    /* the last outer iteration, for the log line of the solve */
};

Printer printer;
bool    launched = false; /* DriverProgressNoteLauncher() */

std::string Residual(PetscReal v)
{
  char buf[32];
  if (std::isfinite((double)v)) snprintf(buf, sizeof(buf), "%.1e", (double)v);
  else snprintf(buf, sizeof(buf), "not finite");
  return buf;
}

/* "setup: factorizing subdomains 412/1536" or "solve: Coulomb step 2, outer 7, residual 3.2e-05 / tol 1e-06" */
std::string Describe(const ConeFETIProgressInfo &info)
{
  std::string line = info.phase == CONEFETI_PHASE_SOLVE ? "solve: " : "setup: ";
  char        buf[160];
  if (info.phase == CONEFETI_PHASE_SOLVE && info.iteration > 0) {
    if (info.step > 0) line += "Coulomb step " + std::to_string((long long)info.step) + ", ";
    snprintf(buf, sizeof(buf), "outer %lld, residual %s / tol %.0e", (long long)info.iteration, Residual(info.residual).c_str(), (double)info.tol);
    line += buf;
    return line;
  }
  line += info.description;
  if (info.n > 0) {
    snprintf(buf, sizeof(buf), " %lld/%lld%s", (long long)info.k, (long long)info.n, printer.size > 1 ? " on rank 0" : "");
    line += buf;
  }
  return line;
}

PetscErrorCode WriteTerminal(const std::string &line)
{
  PetscFunctionBegin;
  const size_t pad = printer.width > line.size() ? printer.width - line.size() : 0;
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, PETSC_STDOUT, "\r%s%*s", line.c_str(), (int)pad, ""));
  fflush(PETSC_STDOUT);
  printer.width = line.size();
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Print(const ConeFETIProgressInfo *info, void *)
{
  PetscFunctionBegin;
  if (printer.rank || printer.mode == DRIVER_PROGRESS_NONE) PetscFunctionReturn(PETSC_SUCCESS);
  if (info->phase == CONEFETI_PHASE_SOLVE && info->iteration > 0) printer.solve = *info;
  if (printer.mode == DRIVER_PROGRESS_LOG) {
    char        buf[64];
    std::string line;
    if (!info->done) PetscFunctionReturn(PETSC_SUCCESS);
    snprintf(buf, sizeof(buf), "%.3f s", (double)info->time);
    if (info->phase == CONEFETI_PHASE_SOLVE) { /* "solve: 1.234 s, outer 7, residual ... / tol ...": how it ended */
      line = std::string("solve: ") + buf;
      if (printer.solve.iteration > 0) line += ", " + Describe(printer.solve).substr(strlen("solve: "));
    } else line = Describe(*info) + ": " + buf;
    PetscCall(PetscFPrintf(PETSC_COMM_SELF, PETSC_STDOUT, "%s\n", line.c_str()));
    fflush(PETSC_STDOUT);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  /* terminal: a phase's beginning always shows (it may take long); counts and iterations at most every 0.1 s */
  const PetscBool begins = (PetscBool)(!info->done && info->k == 0 && info->iteration == 0);
  PetscLogDouble  now;
  if (info->done) PetscFunctionReturn(PETSC_SUCCESS); /* the next phase's line replaces it */
  PetscCall(PetscTime(&now));
  if (!begins && printer.last >= 0 && now - printer.last < 0.1) PetscFunctionReturn(PETSC_SUCCESS);
  printer.last = now;
  PetscCall(WriteTerminal(Describe(*info)));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/* Before MPI_Init() (which sets the same variables in a process started alone): whether an MPI launcher started us */
void DriverProgressNoteLauncher(void) { launched = getenv("OMPI_COMM_WORLD_SIZE") || getenv("PMI_SIZE") || getenv("PMIX_RANK") || getenv("PMI_RANK"); }

/* Install the printer on the scene: mode auto picks the terminal form when stdout is a terminal, else the log form */
PetscErrorCode DriverProgressSet(ContactScene scene, DriverProgressMode mode)
{
  MPI_Comm comm = PetscObjectComm((PetscObject)scene);

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &printer.rank));
  PetscCallMPI(MPI_Comm_size(comm, &printer.size));
  if (mode == DRIVER_PROGRESS_AUTO) {
    /* an MPI launcher (OpenMPI's mpiexec) gives the processes a pseudo-terminal whatever its own stdout is (a
       file, a pipe): under a launcher, the log form, which reads well in both */
    int tty = 0;
    if (!printer.rank) tty = !launched && isatty(fileno(PETSC_STDOUT));
    PetscCallMPI(MPI_Bcast(&tty, 1, MPI_INT, 0, comm));
    mode = tty ? DRIVER_PROGRESS_TERMINAL : DRIVER_PROGRESS_LOG;
  }
  printer.mode = mode;
  if (mode != DRIVER_PROGRESS_NONE) PetscCall(ContactSceneSetProgress(scene, Print, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Before other output: the terminal line is blanked out, so that what follows starts on a clean line */
PetscErrorCode DriverProgressClear(void)
{
  PetscFunctionBegin;
  if (printer.rank || printer.mode != DRIVER_PROGRESS_TERMINAL || !printer.width) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(PetscFPrintf(PETSC_COMM_SELF, PETSC_STDOUT, "\r%*s\r", (int)printer.width, ""));
  fflush(PETSC_STDOUT);
  printer.width = 0;
  printer.last  = -1;
  PetscFunctionReturn(PETSC_SUCCESS);
}
