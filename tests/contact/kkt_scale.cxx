/* The KKT check of a ContactProblem used alone judges the answer on the scale of the data that acts.

   -case far_gap: F = tridiag(-1, 4, -1) (n = 8), frictionless normal rows 0-4, free rows 5-7, h = 1 but for
   normal row 4, a separated node 1e9 from contact (h = -1e9). The gap entered the gradient's scale, which made
   every residual 1e9 times smaller: the multipliers 0 passed for the solution. The solver's test, relative to
   |P(h - F l~)| and so to the gap, passes at -contact_rtol far from the solution; the KKT check catches it and the
   tighter warm solves (-contact_refine_max) reach it: the solve must converge, after at least one tighter solve,
   to the solution (l = (4, 5, 5, 4)/11 on rows 0-3, 0 on row 4, (5, 6, 5)/14 on rows 5-7: row 4 carries no force,
   and the two blocks it separated solve T l = 1) within the acceptance, pass an independent KKT check (r = F l - h:
   r = 0 on free rows, l >= 0, r >= 0 and l r = 0 on normal rows, to 1e-6 of the data), and end with the solver's
   tolerance the user's again. With -contact_refine_max 0 the verdict is the check's "not converged" (the test
   registration matches it); -problem_prefix p puts the problem's options under a prefix.
   -case particular_off_range: the same F and rows, all h = 1 but row 4's (-1), the equality s'l = 1 (s the
   normalized ones vector) in projector form with Q = s s' and a particular solution lt = s + v, v orthogonal to s
   (s'lt = 1, lt not in range(Q)). The check measured |Q l - lt| instead of |Q l - Q lt| and called the solution
   not converged (0.71). Here the solve must converge and pass the independent check (with the equality's
   multiplier w = mu s, fitted).
   -case zero_reduced_rhs: F = I (n = 11), Coulomb nodes (0,1,2), (3,4,5), (6,7,8) with F = 0.3, h = 1 on the normal
   rows, and the total normal force l_0 + l_3 + l_6 = 1.5 in projector form: P(h - F lt) = 0, which made every
   tolerance of the solver 0 and ended the solve with "is the Hessian positive semidefinite?". The solution is
   l_n = 0.5 on each node, nothing else: it must converge to it.
   -fail_in_tighter_solve (with far_gap): a monitor of the solver fails (PETSC_ERR_USER) in the first tighter solve. The
   error must reach the program and leave the solver as the user set it (tolerance -contact_rtol, no recycled
   multiplier); the problem solved again (the monitor quiet) must converge as above.
   Prints the verdict, the independent residual, and "CORRECT". */
#include <conefeti.h>
#include <cmath>
#include <cstring>

static PetscErrorCode ZeroReducedRhs(void)
{
  const PetscInt     n = 11, normal[3] = {0, 3, 6}, t1[3] = {1, 4, 7}, t2[3] = {2, 5, 8};
  const PetscReal    coef[3] = {0.3, 0.3, 0.3};
  Mat                F, Q;
  Vec                h, l, lt;
  ContactProblem     cp;
  ContactStatistics  st;
  PetscReal          err = 0;
  const PetscScalar *la;

  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 1, NULL, &F)); /* assembled, as a user's F */
  for (PetscInt i = 0; i < n; i++) PetscCall(MatSetValue(F, i, i, 1.0, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(F, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(F, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 3, NULL, &Q)); /* Q = g g' / 3, g = e_0 + e_3 + e_6; AIJ: its products round to 1e-17 */
  for (PetscInt a = 0; a < 3; a++)
    for (PetscInt b = 0; b < 3; b++) PetscCall(MatSetValue(Q, normal[a], normal[b], 1.0 / 3, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(Q, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Q, MAT_FINAL_ASSEMBLY));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &h));
  PetscCall(VecDuplicate(h, &l));
  PetscCall(VecDuplicate(h, &lt));
  PetscCall(VecSet(h, 0.0));
  PetscCall(VecSet(lt, 0.0));
  for (PetscInt a = 0; a < 3; a++) {
    PetscCall(VecSetValue(h, normal[a], 1.0, INSERT_VALUES));
    PetscCall(VecSetValue(lt, normal[a], 0.5, INSERT_VALUES)); /* g'lt = 1.5 */
  }
  PetscCall(VecAssemblyBegin(h));
  PetscCall(VecAssemblyEnd(h));
  PetscCall(VecAssemblyBegin(lt));
  PetscCall(VecAssemblyEnd(lt));
  PetscCall(ContactProblemCreate(PETSC_COMM_SELF, &cp));
  PetscCall(ContactProblemSetOperator(cp, F, h));
  PetscCall(ContactProblemSetProjector(cp, Q, lt));
  PetscCall(ContactProblemAddNodes(cp, CONTACT_COULOMB, 3, normal, t1, t2, coef));
  PetscCall(ContactProblemSetFromOptions(cp));
  PetscCall(VecSet(l, 0.0));
  PetscCall(ContactProblemSolve(cp, l));
  PetscCall(ContactProblemGetStatistics(cp, &st));
  PetscCall(VecGetArrayRead(l, &la));
  for (PetscInt i = 0; i < n; i++) err = PetscMax(err, PetscAbsReal(PetscRealPart(la[i]) - (i % 3 == 0 && i < 9 ? 0.5 : 0.0)));
  PetscCall(VecRestoreArrayRead(l, &la));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "zero_reduced_rhs: %s (%s); largest error %.1e\n", st.converged ? "converged" : "not converged", st.reason, (double)err));
  if (st.converged && err <= 1e-8) PetscCall(PetscPrintf(PETSC_COMM_SELF, "CORRECT\n"));
  PetscCall(ContactProblemDestroy(&cp));
  PetscCall(MatDestroy(&F));
  PetscCall(MatDestroy(&Q));
  PetscCall(VecDestroy(&h));
  PetscCall(VecDestroy(&l));
  PetscCall(VecDestroy(&lt));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* fails once the solver runs below the user's tolerance 1e-6 (a tighter solve), while armed */
static PetscErrorCode FailInTighterSolve(Tao tao, void *ctx)
{
  PetscReal gttol;

  PetscFunctionBegin;
  PetscCall(TaoGetTolerances(tao, NULL, NULL, &gttol));
  PetscCheck(!*static_cast<PetscBool *>(ctx) || gttol >= 1e-6, PETSC_COMM_SELF, PETSC_ERR_USER, "the monitor fails in a tighter solve (tolerance %g), as asked", (double)gttol);
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  const PetscInt     n     = 8;
  char               c[64] = "far_gap", prefix[64] = "";
  Mat                F, Q                          = NULL;
  Vec                h, l, r, lt = NULL, s = NULL;
  ContactProblem     cp;
  ContactStatistics  st;
  const PetscInt     normal[5] = {0, 1, 2, 3, 4};
  PetscReal          worst = 0, mu = 0, err = 0, gttol = 0;
  PetscBool          fail     = PETSC_FALSE;
  const PetscReal    exact[8] = {4.0 / 11, 5.0 / 11, 5.0 / 11, 4.0 / 11, 0, 5.0 / 14, 6.0 / 14, 5.0 / 14}; /* far_gap's solution */
  const PetscScalar *la, *ra, *sa = NULL;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", c, sizeof(c), NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-problem_prefix", prefix, sizeof(prefix), NULL));
  const bool far = !strcmp(c, "far_gap");
  if (!strcmp(c, "zero_reduced_rhs")) {
    PetscCall(ZeroReducedRhs());
    PetscCall(PetscFinalize());
    return 0;
  }
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 3, NULL, &F));
  for (PetscInt i = 0; i < n; i++) {
    PetscCall(MatSetValue(F, i, i, 4.0, INSERT_VALUES));
    if (i > 0) PetscCall(MatSetValue(F, i, i - 1, -1.0, INSERT_VALUES));
    if (i < n - 1) PetscCall(MatSetValue(F, i, i + 1, -1.0, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(F, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(F, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(F, &l, &h));
  PetscCall(VecDuplicate(h, &r));
  PetscCall(VecSet(h, 1.0));
  PetscCall(VecSetValue(h, 4, far ? -1e9 : -1.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(h));
  PetscCall(VecAssemblyEnd(h));
  PetscCall(ContactProblemCreate(PETSC_COMM_SELF, &cp));
  if (prefix[0]) PetscCall(ContactProblemSetOptionsPrefix(cp, prefix));
  PetscCall(ContactProblemSetOperator(cp, F, h));
  PetscCall(ContactProblemAddNodes(cp, CONTACT_FRICTIONLESS, 5, normal, NULL, NULL, NULL));
  if (!far) { /* Q = s s', lt = s + v with v = e_0 - e_1 orthogonal to s */
    PetscCall(VecDuplicate(h, &s));
    PetscCall(VecSet(s, 1.0 / std::sqrt((PetscReal)n)));
    PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, &Q));
    for (PetscInt i = 0; i < n; i++)
      for (PetscInt j = 0; j < n; j++) PetscCall(MatSetValue(Q, i, j, 1.0 / n, INSERT_VALUES));
    PetscCall(MatAssemblyBegin(Q, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(Q, MAT_FINAL_ASSEMBLY));
    PetscCall(VecDuplicate(s, &lt));
    PetscCall(VecCopy(s, lt));
    PetscCall(VecSetValue(lt, 0, 1.0, ADD_VALUES));
    PetscCall(VecSetValue(lt, 1, -1.0, ADD_VALUES));
    PetscCall(VecAssemblyBegin(lt));
    PetscCall(VecAssemblyEnd(lt));
    PetscCall(ContactProblemSetProjector(cp, Q, lt));
  }
  PetscCall(ContactProblemSetFromOptions(cp));
  PetscCall(VecSet(l, 0.0));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-fail_in_tighter_solve", &fail, NULL));
  if (fail) {
    Tao            tao;
    PetscErrorCode ierr;
    PetscBool      recycle;
    PetscCall(ContactProblemSetUp(cp)); /* it creates the solver */
    PetscCall(ContactProblemGetTao(cp, &tao));
    PetscCall(TaoMonitorSet(tao, FailInTighterSolve, &fail, NULL));
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = ContactProblemSolve(cp, l);
    PetscCall(PetscPopErrorHandler());
    PetscCall(TaoGetTolerances(tao, NULL, NULL, &gttol));
    PetscCall(TaoGetRecycleHistory(tao, &recycle));
    PetscCheck(ierr == PETSC_ERR_USER && gttol == 1e-6 && !recycle, PETSC_COMM_SELF, PETSC_ERR_PLIB, "the solve returned %d (the monitor's error: %d); then tolerance %g (set: 1e-6), recycle %d",
               (int)ierr, (int)PETSC_ERR_USER, (double)gttol, (int)recycle);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "error in a tighter solve: state restored\n"));
    fail = PETSC_FALSE; /* the monitor quiet; solved again from the start */
    PetscCall(VecSet(l, 0.0));
  }
  PetscCall(ContactProblemSolve(cp, l));
  PetscCall(ContactProblemGetStatistics(cp, &st));
  {
    Tao tao; /* the tighter solves end with the user's tolerances (-contact_rtol 1e-6 by default) */
    PetscCall(ContactProblemGetTao(cp, &tao));
    PetscCall(TaoGetTolerances(tao, NULL, NULL, &gttol));
  }

  /* the independent check: r = F l - h (+ mu s with the equality's multiplier fitted on the free rows) */
  PetscCall(MatMult(F, l, r));
  PetscCall(VecAXPY(r, -1.0, h));
  PetscCall(VecGetArrayRead(l, &la));
  PetscCall(VecGetArrayRead(r, &ra));
  if (s) {
    PetscCall(VecGetArrayRead(s, &sa));
    for (PetscInt i = 5; i < n; i++) mu -= PetscRealPart(ra[i]) / (3 * PetscRealPart(sa[i])); /* r_i + mu s_i = 0 on the free rows */
  }
  for (PetscInt i = 0; i < n; i++) {
    err                = PetscMax(err, PetscAbsReal(PetscRealPart(la[i]) - exact[i]) / exact[1]); /* relative to the largest force */
    const PetscReal li = PetscRealPart(la[i]), ri = PetscRealPart(ra[i]) + (sa ? mu * PetscRealPart(sa[i]) : 0.0);
    if (i >= 5) worst = PetscMax(worst, PetscAbsReal(ri));
    else worst = PetscMax(worst, PetscMax(PetscMax(-li, -ri), PetscAbsReal(li * ri)));
  }
  if (s) {
    PetscReal sl;
    PetscCall(VecDot(s, l, &sl));
    worst = PetscMax(worst, PetscAbsReal(sl - 1.0));
    PetscCall(VecRestoreArrayRead(s, &sa));
  }
  PetscCall(VecRestoreArrayRead(l, &la));
  PetscCall(VecRestoreArrayRead(r, &ra));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s: %s, failed_check '%s', %" PetscInt_FMT " tighter solves, solver's tolerance after %g (%s); independent KKT residual %.1e", c,
                        st.converged ? "converged" : "not converged", st.failed_check, st.refinements, (double)gttol, st.reason, (double)worst));
  if (far) PetscCall(PetscPrintf(PETSC_COMM_SELF, ", largest error %.1e of the largest force", (double)err));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "\n"));
  if (st.converged && worst <= 1e-6 && (!far || (st.refinements > 0 && err <= st.acceptance && gttol == 1e-6))) PetscCall(PetscPrintf(PETSC_COMM_SELF, "CORRECT\n"));
  PetscCall(ContactProblemDestroy(&cp));
  PetscCall(MatDestroy(&F));
  PetscCall(MatDestroy(&Q));
  PetscCall(VecDestroy(&h));
  PetscCall(VecDestroy(&l));
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&lt));
  PetscCall(VecDestroy(&s));
  PetscCall(PetscFinalize());
  return 0;
}
