/* The FETI interchange file with a contact pairing, read back: FETILoadContact() gives a fresh FETI object
   (which knows nothing of the code that wrote the file) and the contact nodes of a fresh ContactProblem;
   the problem is solved as its writer solved it (one ContactProblemSolve() from the particular solution, then
   alpha and u) and the RESULT line carries the writer's fields (converged, fingerprints of the multipliers
   and of u), so that tests/tools/same-results.sh compares the two runs to the last bit.

     interchange -file <name>                              read and solve
     interchange -write_brick <name> -law <law> [-k <k>]    the paper's brick on a ContactModel (its own row
                                                           order, frictionless nodes without tangential rows,
                                                           Tresca bounds), written with FETIWriteContact() and
                                                           solved the same way

   The writer of tutorials/contact/ex3_usercontact.cxx prints the same RESULT line. A bad file must end in an
   error naming it (the error tests in CMakeLists.txt). */
#include <conefeti.h>

/* the bottom faces of the two free cubes, x > 1 */
static PetscErrorCode FreeBottom(const PetscReal c[3], const PetscReal n[3], PetscBool *tagged, void *ctx)
{
  (void)ctx;
  *tagged = (c[0] > 1.0 && n[2] < -0.5) ? PETSC_TRUE : PETSC_FALSE;
  return PETSC_SUCCESS;
}

/* One solve from the particular solution, the rigid-body amplitudes from the equality's multiplier, u; the RESULT line */
static PetscErrorCode SolveAndPrint(FETI feti, ContactProblem cp)
{
  Vec               lt, lambda, u, alpha, w;
  ContactStatistics st;
  char              fl[17], fu[17];

  PetscFunctionBeginUser;
  PetscCall(FETIGetParticularSolution(feti, &lt));
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
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode WriteBrick(const char *file, ContactLaw law, PetscInt k)
{
  FEM            fem;
  ContactModel   cm;
  ContactZone    z     = {};
  PetscReal      lo[3] = {0, 0, 0}, hi[3] = {3, 1, 1}, top[3] = {0, 0, -4e7}, end[3] = {2e6, 0, 0};
  PetscInt       cells[3] = {3 * k, k, k}, sub[3] = {3, 1, 1}, b;
  FETI           feti;
  ContactProblem cp;
  PetscViewer    viewer;

  PetscFunctionBeginUser;
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
  PetscCall(FEMAddBox(fem, lo, hi, cells, &b));
  PetscCall(FEMSetMaterial(fem, b, 21.2e10, 0.277));
  PetscCall(FEMSetDirichlet(fem, b, "x0", NULL));
  PetscCall(FEMSetTraction(fem, b, "z1", top));
  PetscCall(FEMSetTraction(fem, b, "x1", end));
  PetscCall(FEMTagFaces(fem, b, "contact", FreeBottom, NULL));
  PetscCall(FEMSetDecomposition(fem, b, FEM_DECOMPOSITION_STRUCTURED, sub));
  PetscCall(FEMSetDirichletMode(fem, FEM_DIRICHLET_PRIMAL)); /* the file then has Dirichlet dofs kept in the primal */
  PetscCall(FEMSetUp(fem));
  PetscCall(ContactModelCreate(fem, &cm));
  z.type = CONTACT_ZONE_FOUNDATION;
  z.body = b;
  PetscCall(PetscStrcpy(z.face, "contact"));
  z.point[2]  = -1e-3;
  z.normal[2] = 1;
  z.law       = law;
  z.coef      = law == CONTACT_TRESCA ? 2e6 : law == CONTACT_COULOMB ? 0.3 : 0; /* Tresca: a stress, nodal bounds from the areas */
  PetscCall(ContactModelAddZone(cm, &z));
  PetscCall(ContactModelSetFromOptions(cm));
  PetscCall(ContactModelSetUp(cm));
  PetscCall(ContactModelGetFETI(cm, &feti));
  PetscCall(ContactModelGetContactProblem(cm, &cp));
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_WRITE, &viewer));
  PetscCall(FETIWriteContact(feti, cp, viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(SolveAndPrint(feti, cp));
  PetscCall(ContactModelDestroy(&cm));
  PetscCall(FEMDestroy(&fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  FETI           feti;
  ContactProblem cp;
  PetscViewer    viewer;
  Mat            F, Q;
  Vec            h, e, lt;
  PetscInt       n, nall, k = 2;
  char           file[PETSC_MAX_PATH_LEN] = "";
  PetscBool      set, brick;
  ContactLaw     law = CONTACT_COULOMB;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "A FETI contact problem read from an interchange file"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-write_brick", file, sizeof(file), &brick));
  if (brick) {
    PetscCall(PetscOptionsGetEnum(NULL, NULL, "-law", ContactLaws, (PetscEnum *)&law, NULL));
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-k", &k, NULL));
    PetscCall(WriteBrick(file, law, k));
    PetscCall(PetscFinalize());
    return 0;
  }
  PetscCall(PetscOptionsGetString(NULL, NULL, "-file", file, sizeof(file), &set));
  PetscCheck(set, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "give the file to read with -file <name> (or -write_brick <name>)");
  PetscCall(FETICreate(PETSC_COMM_WORLD, &feti));
  PetscCall(ContactProblemCreate(PETSC_COMM_WORLD, &cp));
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, file, FILE_MODE_READ, &viewer));
  PetscCall(FETILoadContact(feti, cp, viewer));
  PetscCall(PetscViewerDestroy(&viewer));
  PetscCall(FETISetKplusExplicit(feti, PETSC_TRUE)); /* as the writer (the tutorial ex3_usercontact) does for a contact solve */
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
  PetscCall(SolveAndPrint(feti, cp));
  PetscCall(ContactProblemDestroy(&cp));
  PetscCall(FETIDestroy(&feti));
  PetscCall(PetscFinalize());
  return 0;
}
