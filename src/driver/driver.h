/* The conefeti program's own pieces besides main() (src/driver/conefeti.cxx): its error report and the
   check of the -options_file chain. Not part of the library. */
#pragma once
#include <petscsys.h>
#include <conefeti/compat.h>
#include <string>

/* errors.cxx: one message per error instead of PETSc's traceback */
PetscErrorCode DriverErrorHandlerPush(void);
int            DriverErrorReport(PetscErrorCode, MPI_Comm);

/* optionsfiles.cxx: the -options_file chain of the command line, checked before PetscInitialize() */
bool DriverCheckOptionsFiles(int, char **, std::string *);
