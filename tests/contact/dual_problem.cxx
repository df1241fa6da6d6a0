/* The contact pipelines on a dual contact problem without FETI (a random "Delassus" operator).

   F = Q D Q' (3 multipliers per contact node: normal, tangent 1, tangent 2), h random, optional
   equality G l = e with orthonormal rows (given in projector form, as FETI does). Checks:
   - the pipeline follows the content: frictionless -> no disks and no mpgp products;
   - frictionless and Tresca solutions equal direct mprgp / mpgp (TAO) solutions of the same QP, and so do
     Tresca solutions with friction squares (ContactProblemAddPolygonNodes(), k = 2) those of the box;
   - Coulomb: msa, merged and monolithic reach the same multipliers, which satisfy the Coulomb
     conditions checked independently: |l_t,k| <= F l_n,k and the projected gradient of the Tresca
     problem with g = F l_n (radii from the solution itself) is small.
   With -equality_form general the equality is given as G, e (ContactProblemSetEquality(), the form for a
   dual problem that comes from elsewhere than FETI) instead of the projector Q = G'G and lt = G'e; the
   Tresca multipliers must then also equal those of the projector form.
   Options: -nodes <n>, -friction <F>, -equality <m>, -cond <c>, -equality_form <projector,general>. */
#include "../qp/knownqp.h"

struct Dual {
  Mat                   F = nullptr, Q = nullptr;
  Vec                   h = nullptr, lt = nullptr;
  Mat                   G = nullptr; /* set: the equality goes in as G l = e (general form) */
  Vec                   e = nullptr;
  std::vector<PetscInt> normal, t1, t2;
};

/* Q x = G'(G x) for G with orthonormal rows given as OrderedRows */
static PetscErrorCode ProjectorMult(Mat Qm, Vec x, Vec y)
{
  Mat G;
  Vec gx;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(Qm, &G));
  PetscCall(MatCreateVecs(G, NULL, &gx));
  PetscCall(MatMult(G, x, gx));
  PetscCall(MatMultTranspose(G, gx, y));
  PetscCall(VecDestroy(&gx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CreateDual(PetscInt nodes, PetscReal cond, PetscInt m, Dual *D, KnownQP *qp)
{
  PetscInt rstart, rend;

  PetscFunctionBeginUser;
  /* reuse the known-QP generator for F (a shell with rank-independent products) and G; h is ours */
  PetscCall(KnownQPCreate(PETSC_COMM_WORLD, "bounds", nodes / 2, cond, 1.0, m, qp));
  D->F = qp->A;
  PetscCall(MatCreateVecs(D->F, &D->h, NULL));
  PetscCall(VecGetOwnershipRange(D->h, &rstart, &rend));
  TestRandom rnd(777);
  PetscInt   N;
  PetscCall(VecGetSize(D->h, &N));
  for (PetscInt i = 0; i < N; i++) {
    const double v = (i % 3 == 0) ? rnd.range(-0.5, 2.0) : rnd.range(-1.5, 1.5); /* normals mostly pushed into contact */
    if (i >= rstart && i < rend) PetscCall(VecSetValue(D->h, i, v, INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(D->h));
  PetscCall(VecAssemblyEnd(D->h));
  for (PetscInt i = rstart; i < rend; i += 3) {
    D->normal.push_back(i);
    D->t1.push_back(i + 1);
    D->t2.push_back(i + 2);
  }
  if (m > 0) {
    PetscInt n;
    PetscCall(VecGetLocalSize(D->h, &n));
    PetscCall(MatCreateShell(PETSC_COMM_WORLD, n, n, N, N, qp->C, &D->Q));
    PetscCall(MatShellSetOperation(D->Q, MATOP_MULT, (void (*)(void))ProjectorMult));
    PetscCall(VecDuplicate(D->h, &D->lt));
    PetscCall(MatMultTranspose(qp->C, qp->d, D->lt)); /* G lt = G G' d = d */
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode SolveContact(Dual *D, ContactLaw law, PetscReal coef, const char *algorithm, Vec lambda, ContactStatistics *st, Vec w = NULL, PetscBool square = PETSC_FALSE)
{
  ContactProblem         cp;
  std::vector<PetscReal> c(D->normal.size(), coef);
  std::vector<PetscInt>  tang;

  PetscFunctionBeginUser;
  PetscCall(ContactProblemCreate(PETSC_COMM_WORLD, &cp));
  PetscCall(ContactProblemSetOperator(cp, D->F, D->h));
  if (D->G) PetscCall(ContactProblemSetEquality(cp, D->G, D->e));
  else if (D->Q) PetscCall(ContactProblemSetProjector(cp, D->Q, D->lt));
  if (square) { /* friction polygon of 2 directions: the two tangential multipliers, each bounded by sin(pi/4) g */
    for (size_t k = 0; k < D->t1.size(); k++) tang.insert(tang.end(), {D->t1[k], D->t2[k]});
    PetscCall(ContactProblemAddPolygonNodes(cp, law, (PetscInt)D->normal.size(), 2, D->normal.data(), tang.data(), c.data()));
  } else PetscCall(ContactProblemAddNodes(cp, law, (PetscInt)D->normal.size(), D->normal.data(), D->t1.data(), D->t2.data(), c.data()));
  if (algorithm) PetscCall(PetscOptionsSetValue(NULL, "-contact_coulomb_algorithm", algorithm));
  PetscCall(ContactProblemSetFromOptions(cp));
  PetscCall(VecSet(lambda, 0.0));
  PetscCall(ContactProblemSolve(cp, lambda));
  PetscCall(ContactProblemGetStatistics(cp, st));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "RESULT law=%s algorithm=%s pipeline=%s Iter=%" PetscInt_FMT " nA=%" PetscInt_FMT " qpp=%" PetscInt_FMT " qpq=%" PetscInt_FMT " other=%" PetscInt_FMT "\n",
                        ContactLaws[law], algorithm ? algorithm : "-", ContactPipelines[st->pipeline], st->outer_iterations, st->products_qpp + st->products_qpq + st->products_other, st->products_qpp,
                        st->products_qpq, st->products_other));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  %s\n", st->reason));
  PetscCheck(st->converged, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "contact solve did not converge: %s", st->reason);
  if (w) PetscCall(ContactProblemGetEqualityMultiplier(cp, w));
  PetscCall(ContactProblemDestroy(&cp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Reference: the same QP solved directly by TAO smalxe (or mpgp/mprgp without equality) over a set built here. */
static PetscErrorCode SolveReference(Dual *D, KnownQP *qp, PetscBool disks, PetscReal radius, Vec x, PetscReal box = 0)
{
  SeparableSet          set;
  Vec                   lb, ub = NULL;
  Tao                   tao;
  PetscInt              n, N;
  std::vector<PetscInt> idx;
  std::vector<double>   r;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(D->h, &n));
  PetscCall(VecGetSize(D->h, &N));
  PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, n, N, &set));
  PetscCall(VecDuplicate(D->h, &lb));
  PetscCall(VecSet(lb, PETSC_NINFINITY));
  for (PetscInt i : D->normal) PetscCall(VecSetValue(lb, i, 0.0, INSERT_VALUES));
  if (box > 0) { /* -box <= l_t1, l_t2 <= box */
    PetscCall(VecDuplicate(D->h, &ub));
    PetscCall(VecSet(ub, PETSC_INFINITY));
    for (size_t k = 0; k < D->t1.size(); k++)
      for (PetscInt i : {D->t1[k], D->t2[k]}) {
        PetscCall(VecSetValue(lb, i, -box, INSERT_VALUES));
        PetscCall(VecSetValue(ub, i, box, INSERT_VALUES));
      }
    PetscCall(VecAssemblyBegin(ub));
    PetscCall(VecAssemblyEnd(ub));
  }
  PetscCall(VecAssemblyBegin(lb));
  PetscCall(VecAssemblyEnd(lb));
  PetscCall(SeparableSetSetBounds(set, lb, ub));
  if (disks) {
    for (size_t k = 0; k < D->t1.size(); k++) {
      idx.insert(idx.end(), {D->t1[k], D->t2[k]});
      r.push_back(radius);
    }
    PetscCall(SeparableSetAddDisks(set, (PetscInt)r.size(), idx.data(), NULL, r.data()));
  }
  PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
  PetscCall(TaoSetType(tao, D->Q ? TAOSMALXE : (disks ? TAOMPGP : TAOMPRGP)));
  PetscCall(TaoSetOptionsPrefix(tao, "ref_"));
  PetscCall(TaoSetSolution(tao, x));
  PetscCall(TaoSetHessian(tao, D->F, D->F, NULL, NULL));
  PetscCall(TaoQPSetLinearTerm(tao, D->h));
  PetscCall(TaoQPSetConstraints(tao, set));
  if (D->Q) PetscCall(TaoSMALXESetEqualityConstraints(tao, qp->C, qp->d));
  PetscCall(TaoSetTolerances(tao, 0, 0, 1e-11));
  PetscCall(VecSet(x, 0.0));
  PetscCall(TaoSolve(tao));
  PetscCall(TaoDestroy(&tao));
  PetscCall(VecDestroy(&lb));
  PetscCall(VecDestroy(&ub));
  PetscCall(SeparableSetDestroy(&set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RelDiff(Vec a, Vec b, PetscReal *d)
{
  Vec       e;
  PetscReal na, ne;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(a, &e));
  PetscCall(VecWAXPY(e, -1.0, b, a));
  PetscCall(VecNorm(e, NORM_2, &ne));
  PetscCall(VecNorm(a, NORM_2, &na));
  *d = ne / na;
  PetscCall(VecDestroy(&e));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Coulomb conditions, independently: cone and the projected gradient with radii F l_n */
static PetscErrorCode CheckCoulomb(Dual *D, PetscReal F, Vec l, Vec w, PetscReal tol)
{
  const PetscScalar    *a;
  PetscInt              rstart, n, N;
  PetscReal             cone = 0, lnmax = 0, gpn, hn;
  SeparableSet          set;
  Vec                   lb, g, gp;
  std::vector<PetscInt> idx;
  std::vector<double>   r;

  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(l, &rstart, NULL));
  PetscCall(VecGetLocalSize(l, &n));
  PetscCall(VecGetSize(l, &N));
  PetscCall(VecGetArrayRead(l, &a));
  for (size_t k = 0; k < D->normal.size(); k++) {
    const PetscReal ln = PetscRealPart(a[D->normal[k] - rstart]), tn = PetscHypotReal(PetscRealPart(a[D->t1[k] - rstart]), PetscRealPart(a[D->t2[k] - rstart]));
    cone  = PetscMax(cone, tn - F * PetscMax(ln, 0));
    lnmax = PetscMax(lnmax, ln);
    idx.insert(idx.end(), {D->t1[k], D->t2[k]});
    r.push_back(F * PetscMax(ln, 0));
  }
  PetscCall(VecRestoreArrayRead(l, &a));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &cone, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &lnmax, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, n, N, &set));
  PetscCall(VecDuplicate(l, &lb));
  PetscCall(VecSet(lb, PETSC_NINFINITY));
  for (PetscInt i : D->normal) PetscCall(VecSetValue(lb, i, 0.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(lb));
  PetscCall(VecAssemblyEnd(lb));
  PetscCall(SeparableSetSetBounds(set, lb, NULL));
  PetscCall(SeparableSetAddDisks(set, (PetscInt)r.size(), idx.data(), NULL, r.data()));
  PetscCall(VecDuplicate(l, &g));
  PetscCall(VecDuplicate(l, &gp));
  PetscCall(MatMult(D->F, l, g));
  PetscCall(VecAXPY(g, -1.0, D->h));
  if (D->Q) PetscCall(VecAXPY(g, 1.0, w)); /* the gradient of the Lagrangian: F l - h + G'mu */
  /* natural residual |l - P(l - g/L)| L with L = ||F||: continuous in l, unlike the projected
     gradient, which jumps when a block sits a hair inside a disk whose radius moved with l_n */
  {
    PetscReal L;
    PetscCall(MatQPEstimateNorm(D->F, QP_NORM_POWER, 0.0, NULL, &L, NULL));
    PetscCall(VecWAXPY(gp, -1.0 / L, g, l));
    PetscCall(SeparableSetProject(set, gp));
    PetscCall(VecAYPX(gp, -1.0, l));
    PetscCall(VecNorm(gp, NORM_2, &gpn));
    gpn *= L;
  }
  PetscCall(VecNorm(D->h, NORM_2, &hn));
  PetscCall(
      PetscPrintf(PETSC_COMM_WORLD, "  Coulomb check: max(|l_t| - F l_n) = %.2e (max l_n %.3g), natural residual / |h| with radii F l_n = %.2e\n", (double)cone, (double)lnmax, (double)(gpn / hn)));
  PetscCheck(cone <= tol * lnmax, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "friction cone violated by %g", (double)cone);
  PetscCheck(gpn <= tol * hn, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "not a Coulomb solution: natural residual %g |h|", (double)(gpn / hn));
  PetscCall(VecDestroy(&g));
  PetscCall(VecDestroy(&gp));
  PetscCall(VecDestroy(&lb));
  PetscCall(SeparableSetDestroy(&set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Dual              D;
  KnownQP           qp;
  PetscInt          nodes = 20, m = 0;
  PetscReal         friction = 0.3, cond = 10, diff;
  Vec               l, ref, lm[3], w;
  ContactStatistics st;
  const char       *algs[3]  = {"msa", "merged", "monolithic"};
  char              form[32] = "projector";

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Contact pipelines on a dual problem"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-nodes", &nodes, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-equality", &m, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-friction", &friction, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-cond", &cond, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-equality_form", form, sizeof(form), NULL));
  PetscCheck(!strcmp(form, "projector") || !strcmp(form, "general"), PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-equality_form must be projector or general, got %s", form);
  PetscCheck(nodes % 2 == 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-nodes must be even");
  PetscCall(CreateDual(nodes, cond, m, &D, &qp));
  PetscCall(VecDuplicate(D.h, &l));
  PetscCall(VecDuplicate(D.h, &ref));
  if (!strcmp(form, "general")) {
    PetscCheck(m > 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-equality_form general needs -equality <m> with m > 0");
    D.G = qp.C;
    D.e = qp.d;
  }

  /* frictionless: no tangential multipliers, no mpgp */
  PetscCall(SolveContact(&D, CONTACT_FRICTIONLESS, 0, NULL, l, &st));
  PetscCheck(st.pipeline == CONTACT_PIPELINE_FRICTIONLESS && st.products_qpq == 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "frictionless problem ran %s with %" PetscInt_FMT " mpgp products",
             ContactPipelines[st.pipeline], st.products_qpq);
  PetscCall(SolveReference(&D, &qp, PETSC_FALSE, 0, ref));
  PetscCall(RelDiff(ref, l, &diff));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  frictionless vs direct solve: %.2e\n", (double)diff));
  PetscCheck(diff <= 1e-5, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "frictionless solution differs from the direct solve by %g", (double)diff);

  /* Tresca with slip bound 0.2 */
  PetscCall(SolveContact(&D, CONTACT_TRESCA, 0.2, NULL, l, &st));
  PetscCheck(st.pipeline == CONTACT_PIPELINE_TRESCA && st.outer_iterations >= 1, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Tresca problem ran %s", ContactPipelines[st.pipeline]);
  PetscCall(SolveReference(&D, &qp, PETSC_TRUE, 0.2, ref));
  PetscCall(RelDiff(ref, l, &diff));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  Tresca vs direct solve: %.2e\n", (double)diff));
  PetscCheck(diff <= 1e-5, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Tresca solution differs from the direct solve by %g", (double)diff);
  if (D.G) { /* general form against projector form */
    D.G = nullptr;
    PetscCall(SolveContact(&D, CONTACT_TRESCA, 0.2, NULL, ref, &st));
    D.G = qp.C;
    PetscCall(RelDiff(ref, l, &diff));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  Tresca general (G, e) vs projector form: %.2e\n", (double)diff));
    PetscCheck(diff <= 1e-5, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Tresca solution with G, e differs from the projector form by %g", (double)diff);
  }

  /* Tresca with friction squares (ContactProblemAddPolygonNodes(), k = 2): bounds only (mprgp), and the box
     |l_t1|, |l_t2| <= sin(pi/4) 0.2 solved directly; the solve's own KKT check judges the box */
  PetscCall(SolveContact(&D, CONTACT_TRESCA, 0.2, NULL, l, &st, NULL, PETSC_TRUE));
  PetscCheck(st.pipeline == CONTACT_PIPELINE_TRESCA && st.products_qpq == 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Tresca squares ran %s with %" PetscInt_FMT " mpgp products",
             ContactPipelines[st.pipeline], st.products_qpq);
  PetscCall(SolveReference(&D, &qp, PETSC_FALSE, 0, ref, 0.2 * PetscSinReal(PETSC_PI / 4)));
  PetscCall(RelDiff(ref, l, &diff));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  Tresca squares vs direct box solve: %.2e\n", (double)diff));
  PetscCheck(diff <= 1e-5, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Tresca solution with friction squares differs from the direct box solve by %g", (double)diff);

  /* Coulomb: three algorithms, one solution */
  PetscCall(VecDuplicate(D.h, &w));
  for (int a = 0; a < 3; a++) {
    PetscCall(VecDuplicate(D.h, &lm[a]));
    PetscCall(SolveContact(&D, CONTACT_COULOMB, friction, algs[a], lm[a], &st, w));
    PetscCall(CheckCoulomb(&D, friction, lm[a], w, 1e-5));
  }
  PetscCall(VecDestroy(&w));
  for (int a = 1; a < 3; a++) {
    PetscCall(RelDiff(lm[0], lm[a], &diff));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  Coulomb %s vs msa: %.2e\n", algs[a], (double)diff));
    PetscCheck(diff <= 1e-4, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Coulomb %s differs from msa by %g", algs[a], (double)diff);
  }
  for (int a = 0; a < 3; a++) PetscCall(VecDestroy(&lm[a]));
  PetscCall(VecDestroy(&l));
  PetscCall(VecDestroy(&ref));
  PetscCall(VecDestroy(&D.h));
  PetscCall(VecDestroy(&D.lt));
  PetscCall(MatDestroy(&D.Q));
  PetscCall(KnownQPDestroy(&qp));
  PetscCall(PetscFinalize());
  return 0;
}
