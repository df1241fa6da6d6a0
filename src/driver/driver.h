/* The conefeti program's own pieces besides main() (src/driver/conefeti.cxx): its error report and the
   check of the -options_file chain. Not part of the library. */
#pragma once
#include <petscsys.h>
#include <conefeti/compat.h>
#include <conefeti/io.h>
#include <string>

/* errors.cxx: one message per error instead of PETSc's traceback */
PetscErrorCode DriverErrorHandlerPush(void);
int            DriverErrorReport(PetscErrorCode, MPI_Comm);

/* progress.cxx: the printer of the library's progress reports (-progress, -quiet) */
typedef enum {
  DRIVER_PROGRESS_AUTO,
  DRIVER_PROGRESS_TERMINAL,
  DRIVER_PROGRESS_LOG,
  DRIVER_PROGRESS_NONE
} DriverProgressMode;
PetscErrorCode DriverProgressSet(ContactScene, DriverProgressMode);
PetscErrorCode DriverProgressClear(void);
void           DriverProgressNoteLauncher(void);

/* optionsfiles.cxx: the -options_file chain of the command line, checked before PetscInitialize() */
bool DriverCheckOptionsFiles(int, char **, std::string *);
