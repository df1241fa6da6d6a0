/* The text of a PETSc error caught with PetscReturnErrorHandler, for an error of our own that names what failed */
#pragma once

#include <petscsys.h>
#include <string>

/* its specific message (else its generic one) on one line: trailing newlines and blanks removed, inner newlines as
   blanks */
static inline std::string ConeFETIErrorText(PetscErrorCode ierr)
{
  const char *text     = NULL;
  char       *specific = NULL;
  (void)PetscErrorMessage(ierr, &text, &specific);
  std::string why = specific && specific[0] ? specific : (text ? text : "unknown error");
  while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
  for (char &ch : why)
    if (ch == '\n') ch = ' ';
  return why;
}
