/* A ContactProblem used the wrong way must stop with a PETSc error that says what is wrong, never a crash, a read
   past a vector's end or a silent change of the problem. -case <name> selects one mistake on a small dual problem
   (F = diag(1..9), 3 Coulomb nodes; run on one rank); the error ends the program and a test checks its message; a case
   that does not fail prints that the mistake was accepted and exits with 0, which fails the test. Case
   prefix_after_type is no mistake: it prints the prefixes a test checks. */
#include <conefeti.h>
#include <cstring>

static PetscErrorCode Problem(ContactProblem *cp, Mat *F, Vec *h)
{
  PetscFunctionBeginUser;
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, 9, 9, 1, NULL, 0, NULL, F));
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, 9, h));
  for (PetscInt i = 0; i < 9; i++) {
    PetscCall(MatSetValue(*F, i, i, 1.0 + i, INSERT_VALUES));
    PetscCall(VecSetValue(*h, i, i % 3 ? 0.5 : -1.0, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(*F, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*F, MAT_FINAL_ASSEMBLY));
  PetscCall(VecAssemblyBegin(*h));
  PetscCall(VecAssemblyEnd(*h));
  PetscCall(ContactProblemCreate(PETSC_COMM_WORLD, cp));
  PetscCall(ContactProblemSetOperator(*cp, *F, *h));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode AddCoulombNodes(ContactProblem cp)
{
  const PetscInt  normal[3] = {0, 3, 6}, t1[3] = {1, 4, 7}, t2[3] = {2, 5, 8};
  const PetscReal F[3] = {0.3, 0.3, 0.3};

  PetscFunctionBeginUser;
  PetscCall(ContactProblemAddNodes(cp, CONTACT_COULOMB, 3, normal, t1, t2, F));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RunCase(const char *name, PetscBool *mistake)
{
  ContactProblem cp;
  Mat            F;
  Vec            h;

  PetscFunctionBeginUser;
  *mistake = PETSC_TRUE;
  PetscCall(Problem(&cp, &F, &h));
  if (!strcmp(name, "nodes_without_normal")) PetscCall(ContactProblemAddNodes(cp, CONTACT_FRICTIONLESS, 3, NULL, NULL, NULL, NULL)); /* was a SEGV */
  else if (!strcmp(name, "nodes_of_no_law")) {
    const PetscInt normal[1] = {0};
    PetscCall(ContactProblemAddNodes(cp, (ContactLaw)7, 1, normal, NULL, NULL, NULL));
  } else if (!strcmp(name, "equality_without_matrix")) PetscCall(ContactProblemSetEquality(cp, NULL, h));              /* was accepted: no equality */
  else if (!strcmp(name, "operator_without_h")) PetscCall(ContactProblemSetOperator(cp, F, NULL));                     /* was a SEGV */
  else if (!strcmp(name, "projector_without_matrix")) PetscCall(ContactProblemSetProjector(cp, NULL, h));              /* dropped the equality, "converged" */
  else if (!strcmp(name, "projector_without_particular_solution")) PetscCall(ContactProblemSetProjector(cp, F, NULL)); /* was a SEGV at the solve */
  else if (!strcmp(name, "slip_bounds_of_a_node_off_the_rank")) {
    const PetscInt  normal[1] = {100}, t1[1] = {101}, t2[1] = {102};
    const PetscReal coef[1] = {0.3};
    Vec             l;
    PetscReal       bounds[1];
    PetscCall(ContactProblemAddNodes(cp, CONTACT_COULOMB, 1, normal, t1, t2, coef));
    PetscCall(VecDuplicate(h, &l));
    PetscCall(ContactProblemGetSlipBounds(cp, l, bounds)); /* before the setup validates the nodes: read past l (SEGV) */
  } else if (!strcmp(name, "solve_from_nan")) {
    Vec l;
    PetscCall(AddCoulombNodes(cp));
    PetscCall(VecDuplicate(h, &l));
    PetscCall(VecSet(l, 0.0));
    PetscCall(VecSetValue(l, 1, PETSC_MAX_REAL * 10, INSERT_VALUES)); /* an infinity: came back as 4.5e307 or NaN */
    PetscCall(VecAssemblyBegin(l));
    PetscCall(VecAssemblyEnd(l));
    PetscCall(ContactProblemSolve(cp, l));
  } else if (!strcmp(name, "equality_columns_not_those_of_F") || !strcmp(name, "projector_not_the_size_of_F")) {
    /* G with 8 columns for the 9 multipliers of F: was caught only in the solve, by smalxe, as "C has 8 columns, the
       solution has 9 entries", names the user never gave */
    const bool projector = !strcmp(name, "projector_not_the_size_of_F");
    Mat        G;
    Vec        e, l;
    PetscCall(MatCreateDense(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, projector ? 8 : 2, 8, NULL, &G));
    for (PetscInt i = 0; i < (projector ? 8 : 2); i++) PetscCall(MatSetValue(G, i, i, 1.0, INSERT_VALUES));
    PetscCall(MatAssemblyBegin(G, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(G, MAT_FINAL_ASSEMBLY));
    PetscCall(MatCreateVecs(G, projector ? &e : NULL, projector ? NULL : &e));
    PetscCall(VecSet(e, 0.0));
    if (projector) PetscCall(ContactProblemSetProjector(cp, G, e));
    else PetscCall(ContactProblemSetEquality(cp, G, e));
    PetscCall(AddCoulombNodes(cp));
    PetscCall(VecDuplicate(h, &l));
    PetscCall(VecSet(l, 0.0));
    PetscCall(ContactProblemSolve(cp, l));
  } else if (!strcmp(name, "operator_not_symmetric") || !strncmp(name, "projector_not_a_projector", 25)) {
    /* F plus a lower triangle, or Q = -I on the first 3 multipliers (Q(Qx) = -Qx) ended with smalxe's "is the Hessian
       positive semidefinite on the feasible set?"; Q = e_i e_4' (i < 3, Q(Qx) = 0) with "no equilibrium found: the loads
       exceed what supports and friction carry". The program prints the statistics' reason when the solve ends. */
    const bool        skew = !strcmp(name, "operator_not_symmetric"), nilpotent = !strcmp(name, "projector_not_a_projector_nilpotent");
    Mat               A, Q;
    Vec               l, lt, hp;
    ContactStatistics st;
    PetscCall(MatCreateDense(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, 9, 9, NULL, &A));
    for (PetscInt i = 0; i < 9; i++) {
      PetscCall(MatSetValue(A, i, i, 1.0 + i, INSERT_VALUES));
      for (PetscInt j = 0; skew && j < i; j++) PetscCall(MatSetValue(A, i, j, 2.0, INSERT_VALUES));
    }
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
    PetscCall(VecDuplicate(h, &hp));
    for (PetscInt i = 0; i < 9; i++) PetscCall(VecSetValue(hp, i, 1 + PetscSinReal((PetscReal)i), INSERT_VALUES)); /* normal loads that press */
    PetscCall(VecAssemblyBegin(hp));
    PetscCall(VecAssemblyEnd(hp));
    PetscCall(ContactProblemDestroy(&cp));
    PetscCall(ContactProblemCreate(PETSC_COMM_WORLD, &cp));
    PetscCall(ContactProblemSetOperator(cp, A, hp));
    if (!skew) {
      PetscCall(MatCreateDense(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, 9, 9, NULL, &Q));
      for (PetscInt i = 0; i < 3; i++) PetscCall(MatSetValue(Q, i, nilpotent ? 4 : i, nilpotent ? 1.0 : -1.0, INSERT_VALUES));
      PetscCall(MatAssemblyBegin(Q, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(Q, MAT_FINAL_ASSEMBLY));
      PetscCall(VecDuplicate(h, &lt));
      PetscCall(VecSet(lt, 0.0));
      PetscCall(ContactProblemSetProjector(cp, Q, lt));
      PetscCall(MatDestroy(&Q));
      PetscCall(VecDestroy(&lt));
    }
    PetscCall(AddCoulombNodes(cp));
    PetscCall(ContactProblemSetFromOptions(cp));
    PetscCall(VecDuplicate(h, &l));
    PetscCall(VecSet(l, 0.0));
    PetscCall(ContactProblemSolve(cp, l));
    PetscCall(ContactProblemGetStatistics(cp, &st));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "converged %d: %s\n", (int)st.converged, st.reason));
    PetscCall(MatDestroy(&A));
    PetscCall(VecDestroy(&l));
    PetscCall(VecDestroy(&hp));
    *mistake = st.converged ? PETSC_TRUE : PETSC_FALSE;
  } else if (!strcmp(name, "tao_before_setup")) {
    Tao tao;
    PetscCall(ContactProblemGetTao(cp, &tao)); /* was NULL without a word */
  } else if (!strcmp(name, "slip_bounds_of_a_short_vector")) {
    Vec       l;
    PetscReal bounds[3];
    PetscCall(AddCoulombNodes(cp));
    PetscCall(ContactProblemSetUp(cp));
    PetscCall(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, 4, &l));
    PetscCall(ContactProblemGetSlipBounds(cp, l, bounds)); /* read past the end of l */
  } else if (!strcmp(name, "algorithm_after_setup")) {
    PetscCall(AddCoulombNodes(cp));
    PetscCall(ContactProblemSetFromOptions(cp));
    PetscCall(ContactProblemSetUp(cp));
    PetscCall(PetscOptionsSetValue(NULL, "-contact_coulomb_algorithm", "merged")); /* ran merged on monolithic's solver */
    PetscCall(ContactProblemSetFromOptions(cp));
  } else if (!strcmp(name, "prefixed")) { /* a bad value of a prefixed option: the error names the option as given */
    PetscCall(ContactProblemSetOptionsPrefix(cp, "my_"));
    PetscCall(AddCoulombNodes(cp));
    PetscCall(ContactProblemSetFromOptions(cp));
  } else if (!strcmp(name, "prefix_after_type")) {
    /* not a mistake: a prefix given after the type reaches the nested solver and its PC at TaoSetFromOptions(), as
       KSPSetOptionsPrefix() reaches the PC (they kept the prefix of their creation) */
    Tao         tao, sub;
    PC          pc;
    const char *subprefix, *pcprefix;
    PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
    PetscCall(TaoSetType(tao, TAOSMALXE));
    PetscCall(TaoSMALXEGetSubsolver(tao, &sub));
    PetscCall(TaoSetType(sub, TAOMPGP));
    PetscCall(TaoQPGetPC(sub, &pc));
    PetscCall(TaoSetOptionsPrefix(tao, "user_"));
    PetscCall(TaoSetFromOptions(tao));
    PetscCall(TaoGetOptionsPrefix(sub, &subprefix));
    PetscCall(PCGetOptionsPrefix(pc, &pcprefix));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "prefixes: subsolver %s, its PC %s\n", subprefix, pcprefix));
    PetscCall(TaoDestroy(&tao));
    *mistake = PETSC_FALSE;
  } else SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "unknown -case %s", name);
  PetscCall(ContactProblemDestroy(&cp));
  PetscCall(MatDestroy(&F));
  PetscCall(VecDestroy(&h));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char      name[64] = "";
  PetscBool mistake;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "A ContactProblem used the wrong way gives clear errors"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", name, sizeof(name), NULL));
  PetscCall(RunCase(name, &mistake)); /* the error ends the program here */
  if (mistake) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "case %s: the mistake was accepted\n", name));
  PetscCall(PetscFinalize());
  return 0;
}
