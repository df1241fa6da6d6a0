/* feti_file_rewrite -in <file> -out <file> -how v1|version3|out_of_range|swap_rows: one rewrite of tests/feti/fetifile.h, for
   the tests that give the readers old and bad files. */
#include "fetifile.h"

int main(int argc, char **argv)
{
  char in[PETSC_MAX_PATH_LEN] = "", out[PETSC_MAX_PATH_LEN] = "", how[32] = "";

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Rewrite a FETI interchange file"));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-in", in, sizeof(in), NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-out", out, sizeof(out), NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-how", how, sizeof(how), NULL));
  PetscCheck(in[0] && out[0] && how[0], PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "usage: feti_file_rewrite -in <file> -out <file> -how v1|version3|out_of_range|swap_rows");
  PetscCall(FETIFileRewrite(in, out, how));
  PetscCall(PetscFinalize());
  return 0;
}
