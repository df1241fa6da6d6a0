/* The conefeti program's error report: the message of the error and one line of hint, not PETSc's
   report of some 55 lines.

   PETSc's default handler (PetscTraceBackErrorHandler()) prints, for every error, a banner, the PETSc
   version, the configure line (about 1500 characters), one line per function of the traceback and,
   when the error reaches main(), the table of options; PetscError() then calls MPI_Abort() because it
   was called from main() (PETSCABORT), and Open MPI adds its own banner of 8 lines, even in a run
   without mpiexec. The line that names the option, file or value is buried in the middle. Here a
   handler only records the error's message, main() runs the program in a function that returns the
   error, and DriverErrorReport() prints the message once and ends the run with exit status 1.
   -traceback keeps PETSc's handler and report. */
#include "driver.h"
#include <conefeti.h>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>
#include <unistd.h>

namespace {

/* The error being raised. Its first call to the handler (PETSC_ERROR_INITIAL) carries the message, the
   calls up the stack (PETSC_ERROR_REPEAT) carry none. A later initial error replaces the record: an
   error caught and raised again with a message naming the file (ContactSceneWriteOutput()) is the one
   that reaches main(). Fixed storage: the handler may run out of memory. */
struct ErrorRecord {
  bool           set;
  PetscErrorCode code;
  char           message[4096];
  char           where[512]; /* the function of the first call, for an error without a message */
} record;

PetscErrorCode RecordError(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm;
  (void)ctx;
  if (p == PETSC_ERROR_INITIAL || !record.set) {
    record.set  = true;
    record.code = n;
    snprintf(record.message, sizeof(record.message), "%s", p == PETSC_ERROR_INITIAL && mess ? mess : "");
    snprintf(record.where, sizeof(record.where), "%s() at %s:%d", fun ? fun : "?", file ? file : "?", line);
  }
  return n;
}

/* How long a failed rank waits for the others to fail too (a collective error, raised on every rank,
   usually within milliseconds) before it reports alone and aborts the run (an error on one rank leaves
   the others waiting in a collective call, forever). */
const double agree_seconds = 5.0;

void PrintRecord(PetscErrorCode ierr, const char *prefix)
{
  const char *text = NULL;
  char        message[sizeof(record.message)];
  size_t      len;

  if (!record.set) { /* an error code returned without PetscError(): nothing was recorded */
    record.code       = ierr;
    record.message[0] = 0;
    snprintf(record.where, sizeof(record.where), "main()");
  }
  (void)PetscErrorMessage(record.code, &text, NULL);
  snprintf(message, sizeof(message), "%s", record.message);
  for (len = strlen(message); len && (message[len - 1] == '\n' || message[len - 1] == ' '); len--) message[len - 1] = 0;
  fflush(stdout);
  if (message[0]) fprintf(PETSC_STDERR, "%sconefeti: error: %s\n", prefix, message);
  else fprintf(PETSC_STDERR, "%sconefeti: error: %s in %s\n", prefix, text ? text : "unknown error", record.where);
  fprintf(PETSC_STDERR, "%sconefeti: (PETSc error %d: %s; -traceback prints PETSc's full report)\n", prefix, (int)record.code, text ? text : "unknown");
  fflush(PETSC_STDERR);
}

/* A valid scene without a unique solution (ContactModelSetUp() finds a rigid motion nothing resists: no
   equilibrium, or no unique displacement) is reported as a solve that did not converge, as the solver's own
   "no equilibrium" is: the sentence on standard output after "NOT CONVERGED: ", a JSON line that says
   converged false and which check failed, and exit status 2 (docs/output.md) */
void PrintNotConverged(void)
{
  std::string reason;
  size_t      len = strlen(record.message);
  while (len && (record.message[len - 1] == '\n' || record.message[len - 1] == ' ')) len--;
  for (size_t i = 0; i < len; i++) {
    const unsigned char ch = (unsigned char)record.message[i];
    if (ch == '"' || ch == '\\') reason += '\\', reason += (char)ch;
    else if (ch < 0x20) reason += ' ';
    else reason += (char)ch;
  }
  fflush(PETSC_STDERR);
  printf("NOT CONVERGED: %.*s\n", (int)len, record.message);
  printf("{\"conefeti\":\"%d.%d.%d\",\"converged\":false,\"failed_check\":\"free_rigid_motion\",\"reason\":\"%s\"}\n", CONEFETI_VERSION_MAJOR, CONEFETI_VERSION_MINOR, CONEFETI_VERSION_PATCH,
         reason.c_str());
  fflush(stdout);
}

/* After the report, the run ends with status 1 even if a library crashes or hangs while MPI ends: HDF5
   closes the files left open from MPI_Finalize(), and on a file whose writes failed it crashes
   (H5F__close_cb(), 1 rank) or waits forever in a collective close (2 ranks). The error is reported
   already; a second report, of a crash, would only hide it. */
void EndAfterReport(int sig)
{
  (void)sig;
  _exit(1);
}

} // namespace

/* Replace PETSc's error handler by the one that records the message (main() has read -traceback) */
PetscErrorCode DriverErrorHandlerPush(void)
{
  PetscFunctionBegin;
  record.set = false;
  PetscCall(PetscPushErrorHandler(RecordError, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Report the error ierr that ended the run on this rank and end MPI; returns the exit status (1, the
   run's; 0 on the ranks that leave the report to rank 0).

   comm is a duplicate of the world communicator, used for nothing else: the failed ranks meet there in
   a nonblocking barrier. When every rank failed (a collective error), rank 0 prints its message and all
   finalize MPI. When some rank has not failed within agree_seconds (an error on one rank), each failed
   rank prints its message, marked with its rank, and aborts the run. */
int DriverErrorReport(PetscErrorCode ierr, MPI_Comm comm)
{
  PetscMPIInt size = 1, rank = 0;
  int         all = 1;
  char        prefix[32];

  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  if (size > 1) {
    MPI_Request  request;
    const double start = MPI_Wtime();

    all = 0;
    if (MPI_Ibarrier(comm, &request) == MPI_SUCCESS) {
      while (!all && MPI_Wtime() - start < agree_seconds) {
        if (MPI_Test(&request, &all, MPI_STATUS_IGNORE) != MPI_SUCCESS) break;
        if (!all) usleep(1000);
      }
    }
  }
  if (all) {
    const bool notconverged = record.set && record.code == PETSC_ERR_NOT_CONVERGED;
    if (rank == 0) {
      if (notconverged) PrintNotConverged();
      else PrintRecord(ierr, "");
    }
    /* the other ranks end with status 0 once rank 0 has printed: a rank that ends with a non-zero status
       makes mpiexec kill the others at once, and rank 0's message, still on its way through mpiexec,
       was sometimes lost. Rank 0's status 1 is the run's (mpiexec returns the first non-zero status). */
    MPI_Barrier(comm);
    (void)PetscPopSignalHandler();
    (void)signal(SIGSEGV, EndAfterReport);
    (void)signal(SIGBUS, EndAfterReport);
    (void)signal(SIGALRM, EndAfterReport);
    (void)alarm((unsigned)(2 * agree_seconds));
    MPI_Finalize();
    return rank == 0 ? (notconverged ? 2 : 1) : 0;
  }
  snprintf(prefix, sizeof(prefix), "[rank %d] ", (int)rank);
  PrintRecord(ierr, prefix);
  MPI_Abort(MPI_COMM_WORLD, 1);
  return 1;
}
