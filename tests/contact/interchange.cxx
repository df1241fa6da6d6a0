/* The FETI interchange file with a contact pairing, read back: FETILoadContact() gives a fresh FETI object
   (which knows nothing of the code that wrote the file) and the contact nodes of a fresh ContactProblem;
   the Coulomb problem is solved as the writer solved it and the RESULT line carries the same fields as
   tutorials/contact/ex3_usercontact.cxx's (converged, fingerprints of the multipliers and of u), so that
   tests/tools/same-results.sh compares the two runs to the last bit. Run with -file <name>. A bad file
   must end in an error naming it (the error tests in CMakeLists.txt). */
#include <conefeti.h>

int main(int argc, char **argv)
{
  FETI              feti;
  ContactProblem    cp;
  PetscViewer       viewer;
  Mat               F, Q;
  Vec               h, e, lt, lambda, u, alpha, w;
  ContactStatistics st;
  PetscInt          n, nall;
  char              file[PETSC_MAX_PATH_LEN] = "", fl[17], fu[17];
  PetscBool         set;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "A FETI contact problem read from an interchange file"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-file", file, sizeof(file), &set));
  PetscCheck(set, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "give the file to read with -file <name>");
  PetscCall(FETICreate(PETSC_COMM_WORLD, &feti));
  PetscCall(ContactProblemCreate(PETSC_COMM_WORLD, &cp));
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_READ, &viewer));
  PetscCall(FETILoadContact(feti, cp, viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(FETISetFromOptions(feti));
  PetscCall(FETISetUp(feti));
  PetscCall(FETIGetOperators(feti, &F, NULL, NULL, &Q));
  PetscCall(FETIGetRHS(feti, &h, &e));
  PetscCall(FETIGetParticularSolution(feti, &lt));
  PetscCall(ContactProblemSetOperator(cp, F, h));
  PetscCall(ContactProblemSetProjector(cp, Q, lt));
  PetscCall(ContactProblemSetFromOptions(cp));
  PetscCall(ContactProblemGetNodes(cp, &n, NULL, NULL, NULL, NULL, NULL));
  PetscCall(MPIU_Allreduce(&n, &nall, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s: %d contact nodes\n", file, (int)nall));
  PetscCall(FETICreateVecs(feti, &u, &lambda, &alpha));
  PetscCall(VecCopy(lt, lambda));
  PetscCall(ContactProblemSolve(cp, lambda));
  PetscCall(ContactProblemGetStatistics(cp, &st));
  PetscCall(VecDuplicate(lambda, &w));
  PetscCall(ContactProblemGetEqualityMultiplier(cp, w));
  PetscCall(FETIComputeAlphaFromEquality(feti, w, alpha));
  PetscCall(FETIRecoverPrimal(feti, lambda, alpha, u));
  PetscCall(ConeFETIVecFingerprint(lambda, fl));
  PetscCall(ConeFETIVecFingerprint(u, fu));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "RESULT converged=%s lambda=%s u=%s\n", st.converged ? "true" : "false", fl, fu));
  PetscCall(VecDestroy(&w));
  PetscCall(VecDestroy(&alpha));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&lambda));
  PetscCall(ContactProblemDestroy(&cp));
  PetscCall(FETIDestroy(&feti));
  PetscCall(PetscFinalize());
  return 0;
}
