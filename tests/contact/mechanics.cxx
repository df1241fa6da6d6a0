/* Contact mechanics on FETI, judged on the mechanics (docs/contact.md, "Judging a solution"), not on the solver's
   own residual. -case selects one property:

   frictionless_vs_primal  the frictionless brick equals an independent primal solve: the assembled
                           undecomposed K with the bounds u_z >= -gap at the contact nodes, by TAO's
                           own gpcg (no conefeti solver involved), to 1e-6 relative in displacement
   pressure                nu = 0, a free block on the foundation under a uniform top pressure p,
                           Coulomb F: the contact pressure is p at every contact node (1e-6)
   stick_shear             the same with a uniform shear tau = 0.5 F p (top shear plus the complementary
                           shear on the faces x = 0, 1, so that the exact stress state is homogeneous):
                           every node sticks and carries pressure p and tangential stress tau (1e-6)
   twobodies_pressure      two nu = 0 blocks stacked, node to node, the upper one pressed by p: the
                           interface carries p at every node (1e-6)
   no_equilibrium          tau = 2 F p: no equilibrium exists; the solve must end with the stated
                           reason, not with a result
   residuals               the brick with -law tresca|coulomb: every mechanical residual <= 1e-6
   algorithms              the brick with Coulomb friction by msa, merged and monolithic: one solution
                           (multipliers and displacements agree to 1e-5 relative)
   pipeline                prints the pipeline and the counts (frictionless: no tangential rows, no
                           mpgp products; no zone: the linear FETI solve)
   polygon                 the brick with -law tresca|coulomb, its friction disks replaced by polygons of k = 2
                           and 4 directions (-contact_friction_polygon): each solve converges, has k tangential
                           rows per contact node and only mprgp products, its tangential multipliers lie in their
                           bounds sin(pi/(2k)) g and its tangential forces in the disk (the polygon is inscribed),
                           and the displacements come closer to the disk solution's as k grows

   Every case prints RESULT lines with counts and rounded norms (compared across rank counts). */
#include <conefeti.h>
#include <conefeti/compat.h>
#include <string>
#include <vector>

static PetscErrorCode BrickContactFace(const PetscReal c[3], const PetscReal n[3], PetscBool *tagged, void *)
{
  *tagged = (c[0] > 1.0 && n[2] < -0.5) ? PETSC_TRUE : PETSC_FALSE;
  return PETSC_SUCCESS;
}

struct Scene {
  FEM          fem = nullptr;
  ContactModel cm  = nullptr;
  PetscInt     body;
};

/* the paper's brick (as tutorials/contact/brick.cxx): clamped at x = 0, 3 cubes, foundation 1e-3 below the bottom of x > 1 */
static PetscErrorCode CreateBrick(PetscInt k, ContactLaw law, PetscReal coef, PetscBool zone_on, Scene *s)
{
  PetscReal   lo[3] = {0, 0, 0}, hi[3] = {3, 1, 1}, top[3] = {0, 0, -4e7}, end[3] = {2e6, 0, 0};
  PetscInt    cells[3] = {3 * k, k, k}, sub[3] = {3, 1, 1};
  ContactZone z = {};

  PetscFunctionBeginUser;
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &s->fem));
  PetscCall(FEMAddBox(s->fem, lo, hi, cells, &s->body));
  PetscCall(FEMSetMaterial(s->fem, s->body, 21.2e10, 0.277));
  PetscCall(FEMSetDirichlet(s->fem, s->body, "x0", NULL));
  PetscCall(FEMSetTraction(s->fem, s->body, "z1", top));
  PetscCall(FEMSetTraction(s->fem, s->body, "x1", end));
  PetscCall(FEMTagFaces(s->fem, s->body, "contact", BrickContactFace, NULL));
  PetscCall(FEMSetDecomposition(s->fem, s->body, FEM_DECOMPOSITION_STRUCTURED, sub));
  PetscCall(FEMSetDirichletMode(s->fem, FEM_DIRICHLET_PRIMAL));
  PetscCall(FEMSetUp(s->fem));
  PetscCall(ContactModelCreate(s->fem, &s->cm));
  if (zone_on) {
    z.type = CONTACT_ZONE_FOUNDATION;
    z.body = s->body;
    PetscCall(PetscStrcpy(z.face, "contact"));
    z.point[2]  = -1e-3;
    z.normal[2] = 1;
    z.law       = law;
    z.coef      = coef;
    PetscCall(ContactModelAddZone(s->cm, &z));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* nu = 0 block (0,1)x(0,1)x(0,0.5) resting on the foundation z = 0; Total FETI, floating. The loads are
   those of the homogeneous stress state sigma_zz = -p, sigma_xz = tau: top (tau, 0, -p), and on the
   faces x = 1 and x = 0 the complementary shear (0, 0, +-tau) that balances the moment of the top
   shear; the foundation must then carry p and tau at every node. */
static PetscErrorCode CreateBlock(PetscReal p, PetscReal tau, PetscReal F, Scene *s)
{
  PetscReal   lo[3] = {0, 0, 0}, hi[3] = {1, 1, 0.5}, top[3] = {tau, 0, -p}, right[3] = {0, 0, tau}, left[3] = {0, 0, -tau};
  PetscInt    cells[3] = {4, 4, 2}, sub[3] = {2, 2, 1};
  ContactZone z = {};

  PetscFunctionBeginUser;
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &s->fem));
  PetscCall(FEMAddBox(s->fem, lo, hi, cells, &s->body));
  PetscCall(FEMSetMaterial(s->fem, s->body, 2.1e11, 0.0));
  PetscCall(FEMSetTraction(s->fem, s->body, "z1", top));
  if (tau != 0) {
    PetscCall(FEMSetTraction(s->fem, s->body, "x1", right));
    PetscCall(FEMSetTraction(s->fem, s->body, "x0", left));
  }
  PetscCall(FEMSetDecomposition(s->fem, s->body, FEM_DECOMPOSITION_STRUCTURED, sub));
  PetscCall(FEMSetDirichletMode(s->fem, FEM_DIRICHLET_MULTIPLIERS));
  PetscCall(FEMSetUp(s->fem));
  PetscCall(ContactModelCreate(s->fem, &s->cm));
  z.type = CONTACT_ZONE_FOUNDATION;
  z.body = s->body;
  PetscCall(PetscStrcpy(z.face, "z0"));
  z.normal[2] = 1;
  z.law       = CONTACT_COULOMB;
  z.coef      = F;
  PetscCall(ContactModelAddZone(s->cm, &z));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* two nu = 0 blocks stacked node to node: the lower one (0,1)^2x(0,0.5) clamped at its bottom, the
   upper one (0,1)^2x(0.5,1) floating and pressed by p on top; METIS decomposition, Total FETI */
static PetscErrorCode CreateTwoBlocks(PetscReal p, PetscReal F, Scene *s)
{
  PetscReal   lo0[3] = {0, 0, 0}, hi0[3] = {1, 1, 0.5}, lo1[3] = {0, 0, 0.5}, hi1[3] = {1, 1, 1}, top[3] = {0, 0, -p};
  PetscInt    cells[3] = {4, 4, 2}, b0, b1, parts = 3;
  ContactZone z = {};

  PetscFunctionBeginUser;
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &s->fem));
  PetscCall(FEMAddBox(s->fem, lo0, hi0, cells, &b0));
  PetscCall(FEMAddBox(s->fem, lo1, hi1, cells, &b1));
  for (PetscInt b : {b0, b1}) {
    PetscCall(FEMSetMaterial(s->fem, b, 2.1e11, 0.0));
    PetscCall(FEMSetDecomposition(s->fem, b, FEM_DECOMPOSITION_METIS, &parts));
  }
  PetscCall(FEMSetDirichlet(s->fem, b0, "z0", NULL));
  PetscCall(FEMSetTraction(s->fem, b1, "z1", top));
  PetscCall(FEMSetDirichletMode(s->fem, FEM_DIRICHLET_MULTIPLIERS));
  PetscCall(FEMSetUp(s->fem));
  PetscCall(ContactModelCreate(s->fem, &s->cm));
  z.type       = CONTACT_ZONE_BODIES;
  z.body       = b1;
  z.other_body = b0;
  PetscCall(PetscStrcpy(z.face, "z0"));
  PetscCall(PetscStrcpy(z.other_face, "z1"));
  z.law  = CONTACT_COULOMB;
  z.coef = F;
  PetscCall(ContactModelAddZone(s->cm, &z));
  s->body = b1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DestroyScene(Scene *s)
{
  PetscFunctionBeginUser;
  PetscCall(ContactModelDestroy(&s->cm));
  PetscCall(FEMDestroy(&s->fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode SolveScene(Scene *s, ContactStatistics *st, PetscBool require_convergence)
{
  PetscFunctionBeginUser;
  PetscCall(ContactModelSetFromOptions(s->cm));
  PetscCall(ContactModelSetUp(s->cm));
  PetscCall(ContactModelSolve(s->cm));
  PetscCall(ContactModelGetStatistics(s->cm, st));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  %s: %s\n", ContactPipelines[st->pipeline], st->reason));
  if (require_convergence) PetscCheck(st->converged, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "the contact solve did not converge: %s", st->reason);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode PrintResult(const char *name, Scene *s, const ContactStatistics *st)
{
  Vec       lambda, u;
  PetscReal nl, nu;
  PetscInt  m;
  char      fl[17], fu[17];

  PetscFunctionBeginUser;
  PetscCall(ContactModelGetSolution(s->cm, &lambda, &u));
  PetscCall(ConeFETIVecFingerprint(lambda, fl));
  PetscCall(ConeFETIVecFingerprint(u, fu));
  PetscCall(VecNorm(lambda, NORM_2, &nl));
  PetscCall(VecNorm(u, NORM_2, &nu));
  PetscCall(VecGetSize(lambda, &m));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "RESULT %s pipeline=%s m=%" PetscInt_FMT " Iter=%" PetscInt_FMT " qpp=%" PetscInt_FMT " qpq=%" PetscInt_FMT " other=%" PetscInt_FMT " |l|=%.6e |u|=%.6e l=%s u=%s\n", name,
                        ContactPipelines[st->pipeline], m, st->outer_iterations, st->products_qpp, st->products_qpq, st->products_other, (double)nl, (double)nu, fl, fu));
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

struct PrimalCtx {
  Mat K;
  Vec f;
};

static PetscErrorCode PrimalObjGrad(Tao, Vec x, PetscReal *obj, Vec g, void *ptr)
{
  PrimalCtx  *c = (PrimalCtx *)ptr;
  PetscScalar xg, xf;

  PetscFunctionBeginUser;
  PetscCall(MatMult(c->K, x, g));
  PetscCall(VecDot(x, g, &xg));
  PetscCall(VecDot(x, c->f, &xf));
  *obj = 0.5 * PetscRealPart(xg) - PetscRealPart(xf);
  PetscCall(VecAXPY(g, -1.0, c->f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode PrimalHess(Tao, Vec, Mat, Mat, void *)
{
  PetscFunctionBeginUser;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the frictionless brick against the undecomposed primal problem min 1/2 u'Ku - f'u, u_z >= -gap on the contact nodes */
static PetscErrorCode CaseFrictionlessVsPrimal(PetscInt k)
{
  Scene              s;
  ContactStatistics  st;
  PrimalCtx          c;
  Vec                lb, ub, x, ufeti, lambda, uprimal;
  Tao                tao;
  PetscInt           n, offset, rstart, rend;
  const PetscInt    *nodes;
  const PetscReal   *areas, *normals;
  PetscReal          diff;
  TaoConvergedReason reason;

  PetscFunctionBeginUser;
  PetscCall(CreateBrick(k, CONTACT_FRICTIONLESS, 0, PETSC_TRUE, &s));
  PetscCall(SolveScene(&s, &st, PETSC_TRUE));
  PetscCall(PrintResult("frictionless", &s, &st));
  PetscCall(FEMAssembleGlobal(s.fem, &c.K, &c.f));
  PetscCall(MatCreateVecs(c.K, &x, &lb));
  PetscCall(VecDuplicate(lb, &ub));
  PetscCall(VecDuplicate(lb, &ufeti));
  PetscCall(VecSet(lb, PETSC_NINFINITY));
  PetscCall(VecSet(ub, PETSC_INFINITY));
  PetscCall(VecGetOwnershipRange(lb, &rstart, &rend));
  PetscCall(FEMGetTaggedNodes(s.fem, s.body, "contact", &n, &nodes, &areas, &normals));
  PetscCall(FEMGetBodyNodeOffset(s.fem, s.body, &offset));
  for (PetscInt i = 0; i < n; i++) {
    const PetscInt dof = 3 * (offset + nodes[i]) + 2;
    if (dof >= rstart && dof < rend) PetscCall(VecSetValue(lb, dof, -1e-3, INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(lb));
  PetscCall(VecAssemblyEnd(lb));
  /* TAO's gpcg: an implementation independent of conefeti's solvers */
  PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
  PetscCall(TaoSetType(tao, TAOGPCG));
  PetscCall(TaoSetOptionsPrefix(tao, "primal_"));
  PetscCall(TaoSetSolution(tao, x));
  PetscCall(TaoSetObjectiveAndGradient(tao, NULL, PrimalObjGrad, &c));
  PetscCall(TaoSetHessian(tao, c.K, c.K, PrimalHess, &c));
  PetscCall(TaoSetVariableBounds(tao, lb, ub));
  PetscCall(TaoSetTolerances(tao, 0, 0, 1e-12));
  PetscCall(TaoSetMaximumIterations(tao, 1000));
  PetscCall(TaoSetFromOptions(tao));
  PetscCall(VecSet(x, 0.0));
  PetscCall(TaoSolve(tao));
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCheck(reason > 0, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "the independent primal solve did not converge (%s)", TaoConvergedReasons[reason]);
  PetscCall(ContactModelGetSolution(s.cm, &lambda, &uprimal));
  PetscCall(FEMPrimalToGlobal(s.fem, uprimal, ufeti));
  PetscCall(RelDiff(x, ufeti, &diff));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  displacement: FETI contact vs primal gpcg, relative difference %.2e (asserted <= 1e-6)\n", (double)diff));
  PetscCheck(diff <= 1e-6, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the FETI contact solution differs from the primal solve by %g", (double)diff);
  PetscCall(TaoDestroy(&tao));
  for (Vec *v : {&x, &lb, &ub, &ufeti, &c.f}) PetscCall(VecDestroy(v));
  PetscCall(MatDestroy(&c.K));
  PetscCall(DestroyScene(&s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the nu = 0 block (or two stacked blocks): pressure p and tangential stress tau at every contact node, all stick */
static PetscErrorCode CaseBlock(PetscReal tau_over_Fp, PetscBool expect_equilibrium, PetscBool twobodies = PETSC_FALSE)
{
  const PetscReal   p = 1e7, F = 0.3, tau = tau_over_Fp * F * p;
  Scene             s;
  ContactStatistics st;
  PetscInt          n;
  ContactResiduals  r;

  PetscFunctionBeginUser;
  if (twobodies) PetscCall(CreateTwoBlocks(p, F, &s));
  else PetscCall(CreateBlock(p, tau, F, &s));
  PetscCall(SolveScene(&s, &st, expect_equilibrium));
  if (!expect_equilibrium) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "RESULT no_equilibrium converged=%d\n", (int)st.converged));
    PetscCheck(!st.converged && strstr(st.reason, "no equilibrium"), PETSC_COMM_WORLD, PETSC_ERR_PLIB, "a shear of 2 F p must end without equilibrium, got: %s", st.reason);
    PetscCall(DestroyScene(&s));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PrintResult(tau > 0 ? "stick_shear" : "pressure", &s, &st));
  PetscCall(ContactModelGetNodes(s.cm, &n, NULL, NULL, NULL, NULL));
  std::vector<PetscReal>         pressure(n), traction(3 * n), slip(3 * n);
  std::vector<ContactNodeStatus> status(n);
  PetscCall(ContactModelGetNodeStates(s.cm, pressure.data(), traction.data(), slip.data(), status.data()));
  PetscReal perr = 0, terr = 0;
  PetscInt  nstick = 0, total = n;
  for (PetscInt i = 0; i < n; i++) {
    perr = PetscMax(perr, PetscAbsReal(pressure[i] - p) / p);
    /* the friction traction on the block opposes the applied shear: -traction = -tau e_x */
    if (tau > 0) terr = PetscMax(terr, PetscSqrtReal(PetscSqr(traction[3 * i] - tau) + PetscSqr(traction[3 * i + 1]) + PetscSqr(traction[3 * i + 2])) / tau);
    if (status[i] == CONTACT_NODE_STICK) nstick++;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &perr, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &terr, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nstick, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &total, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(ContactModelComputeResiduals(s.cm, &r));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  %" PetscInt_FMT " contact nodes: max |pressure - p|/p = %.2e, max |tangential stress - tau|/tau = %.2e, %" PetscInt_FMT " stick; largest residual %.1e\n",
                        total, (double)perr, (double)terr, nstick, (double)r.max));
  PetscCheck(perr <= 1e-6, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "contact pressure differs from p by %g relative", (double)perr);
  if (tau > 0) {
    PetscCheck(terr <= 1e-6, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "tangential stress differs from tau by %g relative", (double)terr);
    PetscCheck(nstick == total, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "only %" PetscInt_FMT " of %" PetscInt_FMT " nodes stick under tau = F p / 2", nstick, total);
  }
  PetscCall(DestroyScene(&s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CaseResiduals(PetscInt k, ContactLaw law)
{
  Scene             s;
  ContactStatistics st;
  ContactResiduals  r;

  PetscFunctionBeginUser;
  PetscCall(CreateBrick(k, law, law == CONTACT_TRESCA ? 4e6 : 0.3, PETSC_TRUE, &s));
  PetscCall(SolveScene(&s, &st, PETSC_TRUE));
  PetscCall(PrintResult(ContactLaws[law], &s, &st));
  PetscCall(ContactModelComputeResiduals(s.cm, &r));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "  residuals: equilibrium %.1e gluing %.1e penetration %.1e sign %.1e complementarity %.1e cone %.1e slip %.1e; nodes %" PetscInt_FMT " separated, %" PetscInt_FMT
                        " stick, %" PetscInt_FMT " slip\n",
                        (double)r.equilibrium, (double)r.gluing, (double)r.penetration, (double)r.normal_sign, (double)r.complementarity, (double)r.friction_cone, (double)r.slip_rule, r.counts[0],
                        r.counts[1], r.counts[2]));
  PetscCheck(r.max <= 1e-6, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "a mechanical residual is %g > 1e-6", (double)r.max);
  PetscCheck(law != CONTACT_COULOMB || (r.counts[0] > 0 && r.counts[1] > 0 && r.counts[2] > 0), PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the brick scene should have separated, stick and slip nodes");
  PetscCall(DestroyScene(&s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CaseAlgorithms(PetscInt k)
{
  const char *alg[3] = {"msa", "merged", "monolithic"};
  Vec         l0 = NULL, u0 = NULL;

  PetscFunctionBeginUser;
  for (int a = 0; a < 3; a++) {
    Scene             s;
    ContactStatistics st;
    Vec               l, u;
    PetscCall(PetscOptionsSetValue(NULL, "-contact_coulomb_algorithm", alg[a]));
    PetscCall(CreateBrick(k, CONTACT_COULOMB, 0.3, PETSC_TRUE, &s));
    PetscCall(SolveScene(&s, &st, PETSC_TRUE));
    PetscCall(PrintResult(alg[a], &s, &st));
    PetscCall(ContactModelGetSolution(s.cm, &l, &u));
    if (!a) {
      PetscCall(VecDuplicate(l, &l0));
      PetscCall(VecDuplicate(u, &u0));
      PetscCall(VecCopy(l, l0));
      PetscCall(VecCopy(u, u0));
    } else {
      PetscReal dl, du;
      PetscCall(RelDiff(l0, l, &dl));
      PetscCall(RelDiff(u0, u, &du));
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  %s vs msa: multipliers %.2e, displacements %.2e (asserted <= 1e-5)\n", alg[a], (double)dl, (double)du));
      PetscCheck(dl <= 1e-5 && du <= 1e-5, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%s and msa reach different solutions (%g, %g)", alg[a], (double)dl, (double)du);
    }
    PetscCall(DestroyScene(&s));
  }
  PetscCall(VecDestroy(&l0));
  PetscCall(VecDestroy(&u0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CasePipeline(PetscInt k, const char *law)
{
  Scene              s;
  ContactStatistics  st;
  PetscBool          none = !strcmp(law, "none") ? PETSC_TRUE : PETSC_FALSE;
  ContactLaw         l    = !strcmp(law, "coulomb") ? CONTACT_COULOMB : (!strcmp(law, "tresca") ? CONTACT_TRESCA : CONTACT_FRICTIONLESS);
  PetscInt           m, rows[4] = {0, 0, 0, 0};
  FETI               feti;
  Mat                B;
  Vec                c;
  const FETIRowKind *kinds;

  PetscFunctionBeginUser;
  /* a misspelled law would otherwise be checked as frictionless */
  PetscCheck(none || !strcmp(law, "coulomb") || !strcmp(law, "tresca") || !strcmp(law, "frictionless"), PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-law %s: use none, frictionless, tresca or coulomb",
             law);
  PetscCall(CreateBrick(k, l, l == CONTACT_TRESCA ? 4e6 : 0.3, none ? PETSC_FALSE : PETSC_TRUE, &s));
  PetscCall(SolveScene(&s, &st, PETSC_TRUE));
  PetscCall(PrintResult(law, &s, &st));
  PetscCall(ContactModelGetFETI(s.cm, &feti));
  PetscCall(FETIGetConstraints(feti, &B, &c, &kinds));
  PetscCall(MatGetLocalSize(B, &m, NULL));
  for (PetscInt i = 0; i < m; i++) rows[kinds[i]]++;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, rows, 4, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(
      PetscPrintf(PETSC_COMM_WORLD, "RESULT rows gluing=%" PetscInt_FMT " dirichlet=%" PetscInt_FMT " normal=%" PetscInt_FMT " tangential=%" PetscInt_FMT "\n", rows[0], rows[1], rows[2], rows[3]));
  if (none) PetscCheck(st.pipeline == CONTACT_PIPELINE_LINEAR && rows[2] + rows[3] == 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "no zone must give the linear pipeline without contact rows");
  if (l == CONTACT_FRICTIONLESS && !none)
    PetscCheck(st.pipeline == CONTACT_PIPELINE_FRICTIONLESS && rows[3] == 0 && st.products_qpq == 0 && rows[2] > 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB,
               "a frictionless scene must have no tangential rows (%" PetscInt_FMT ") and spend no mpgp products (%" PetscInt_FMT ")", rows[3], st.products_qpq);
  if (l == CONTACT_COULOMB) PetscCheck(st.pipeline == CONTACT_PIPELINE_COULOMB && rows[3] == 2 * rows[2], PETSC_COMM_WORLD, PETSC_ERR_PLIB, "a Coulomb scene needs two tangential rows per normal row");
  if (l == CONTACT_TRESCA)
    PetscCheck(st.pipeline == CONTACT_PIPELINE_TRESCA && rows[2] > 0 && rows[3] == 2 * rows[2] && st.products_qpq > 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB,
               "a Tresca scene must run the Tresca pipeline (got %s) with two tangential rows per normal row (%" PetscInt_FMT " normal, %" PetscInt_FMT " tangential) solved by mpgp (%" PetscInt_FMT
               " products)",
               ContactPipelines[st.pipeline], rows[2], rows[3], st.products_qpq);
  PetscCall(DestroyScene(&s));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the disk solution, then k = 2 and 4 */
static PetscErrorCode CasePolygon(PetscInt k, ContactLaw law)
{
  Vec       u0 = NULL;
  PetscReal err[2];

  PetscFunctionBeginUser;
  for (PetscInt p : {0, 2, 4}) {
    Scene              s;
    ContactStatistics  st;
    ContactResiduals   r;
    ContactProblem     cp;
    Vec                l, u;
    char               name[32];
    PetscInt           n, kk, rows[4] = {0, 0, 0, 0}, m, nfriction = 0;
    const PetscInt    *normal, *tang;
    const ContactLaw  *laws;
    const PetscScalar *la;
    FETI               feti;
    Mat                B;
    Vec                c;
    const FETIRowKind *kinds;
    PetscReal          lnmax = 0, worst[2] = {0, 0}; /* largest excess over the box, over the disk */

    PetscCall(PetscOptionsSetValue(NULL, "-contact_friction_polygon", std::to_string(p).c_str()));
    PetscCall(CreateBrick(k, law, law == CONTACT_TRESCA ? 4e6 : 0.3, PETSC_TRUE, &s));
    PetscCall(SolveScene(&s, &st, PETSC_TRUE));
    PetscCall(PetscSNPrintf(name, sizeof(name), "%s_polygon%" PetscInt_FMT, ContactLaws[law], p));
    PetscCall(PrintResult(name, &s, &st));
    PetscCall(ContactModelGetSolution(s.cm, &l, &u));
    PetscCall(ContactModelComputeResiduals(s.cm, &r));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  largest residual %.1e (%s); against the disk law %.1e; nodes %" PetscInt_FMT " separated, %" PetscInt_FMT " stick, %" PetscInt_FMT " slip\n",
                          (double)r.max, ContactChecks[r.worst], (double)r.approximation, r.counts[0], r.counts[1], r.counts[2]));
    PetscCheck(r.max <= 1e-6, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "a mechanical residual is %g > 1e-6", (double)r.max);
    if (!p) {
      PetscCall(VecDuplicate(u, &u0));
      PetscCall(VecCopy(u, u0));
      PetscCall(DestroyScene(&s));
      continue;
    }
    /* k tangential rows per normal row, only bound-constrained (mprgp) products */
    PetscCall(ContactModelGetFETI(s.cm, &feti));
    PetscCall(FETIGetConstraints(feti, &B, &c, &kinds));
    PetscCall(MatGetLocalSize(B, &m, NULL));
    for (PetscInt i = 0; i < m; i++) rows[kinds[i]]++;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, rows, 4, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    PetscCheck(rows[3] == p * rows[2] && st.products_qpq == 0 && st.products_qpp > 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB,
               "polygon %" PetscInt_FMT ": %" PetscInt_FMT " tangential rows for %" PetscInt_FMT " normal rows, %" PetscInt_FMT " mpgp products (want k per normal row, none)", p, rows[3], rows[2],
               st.products_qpq);
    /* the multipliers: |m_j| <= sin(pi/2k) g, and the force sum_j m_j d_j inside the disk of radius g */
    PetscCall(ContactModelGetContactProblem(s.cm, &cp));
    PetscCall(ContactProblemGetNodes(cp, &n, &normal, NULL, NULL, &laws, NULL));
    PetscCall(ContactProblemGetFrictionPolygon(cp, &kk, &tang));
    PetscCheck(kk == p, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the contact problem has polygons of %" PetscInt_FMT " directions, not %" PetscInt_FMT, kk, p);
    std::vector<PetscReal> g(n);
    PetscCall(ContactProblemGetSlipBounds(cp, l, g.data()));
    PetscCall(VecGetArrayRead(l, &la));
    PetscInt rstart;
    PetscCall(VecGetOwnershipRange(l, &rstart, NULL));
    for (PetscInt j = 0; j < n; j++) {
      PetscReal t[2] = {0, 0};
      lnmax          = PetscMax(lnmax, PetscRealPart(la[normal[j] - rstart]));
      if (laws[j] == CONTACT_FRICTIONLESS) continue;
      for (PetscInt q = 0; q < p; q++) {
        const PetscReal mq = PetscRealPart(la[tang[j * p + q] - rstart]), a = PETSC_PI * q / p;
        worst[0] = PetscMax(worst[0], PetscAbsReal(mq) - PetscSinReal(PETSC_PI / (2 * p)) * g[j]);
        t[0] += mq * PetscCosReal(a);
        t[1] += mq * PetscSinReal(a);
      }
      worst[1] = PetscMax(worst[1], PetscSqrtReal(t[0] * t[0] + t[1] * t[1]) - g[j]);
      nfriction++;
    }
    PetscCall(VecRestoreArrayRead(l, &la));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &lnmax, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, worst, 2, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nfriction, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    PetscCall(RelDiff(u0, u, &err[p / 2 - 1]));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                          "  polygon %" PetscInt_FMT ": %" PetscInt_FMT
                          " friction nodes, largest excess over the bounds %.1e and over the disk %.1e of the largest pressure; |u - u_disk| / |u_disk| = %.3e\n",
                          p, nfriction, (double)(worst[0] / lnmax), (double)(worst[1] / lnmax), (double)err[p / 2 - 1]));
    PetscCheck(nfriction > 0 && worst[0] <= 1e-6 * lnmax && worst[1] <= 1e-6 * lnmax, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "polygon %" PetscInt_FMT ": tangential multipliers outside the polygon", p);
    PetscCall(DestroyScene(&s));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "  error against the disks: k = 2 %.3e, k = 4 %.3e (asserted: k = 4 closer)\n", (double)err[0], (double)err[1]));
  PetscCheck(err[1] < err[0] && err[0] > 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the octagon's solution is not closer to the disks' than the square's");
  PetscCall(VecDestroy(&u0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char     c[64] = "pipeline", law[32] = "frictionless";
  PetscInt k = 4;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Contact mechanics on FETI"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", c, sizeof(c), NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-law", law, sizeof(law), NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-k", &k, NULL));
  std::string s(c);
  if (s == "frictionless_vs_primal") PetscCall(CaseFrictionlessVsPrimal(k));
  else if (s == "pressure") PetscCall(CaseBlock(0.0, PETSC_TRUE));
  else if (s == "stick_shear") PetscCall(CaseBlock(0.5, PETSC_TRUE));
  else if (s == "twobodies_pressure") PetscCall(CaseBlock(0.0, PETSC_TRUE, PETSC_TRUE));
  else if (s == "no_equilibrium") PetscCall(CaseBlock(2.0, PETSC_FALSE));
  else if (s == "residuals") PetscCall(CaseResiduals(k, !strcmp(law, "tresca") ? CONTACT_TRESCA : CONTACT_COULOMB));
  else if (s == "algorithms") PetscCall(CaseAlgorithms(k));
  else if (s == "pipeline") PetscCall(CasePipeline(k, law));
  else if (s == "polygon") PetscCall(CasePolygon(k, !strcmp(law, "tresca") ? CONTACT_TRESCA : CONTACT_COULOMB));
  else SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "unknown -case %s", c);
  PetscCall(PetscFinalize());
  return 0;
}
