/* peers: a scene's frictionless contact problem solved the way a PETSc user would try first, beside conefeti,
   judged by one measure that does not depend on the solver.

   The primal problem is the undecomposed one: K u = f with K and f from FEMAssembleGlobal() (Dirichlet rows
   as identity) and, at each contact node of a rigid plane whose normal is a coordinate axis, a simple bound
   on one displacement component, u_n >= -gap. That is a bound-constrained QP, which PETSc solves with SNES VI
   (-peers_solver snes -snes_type vinewtonrsls) or TAO (-peers_solver tao -tao_type tron|gpcg|bqpip|blmvm|bnls),
   each with the KSP and PC of -ksp_type, -pc_type (CG + ML or GAMG with the rigid-body near-null space, or a
   sparse Cholesky; TRON, GPCG and BQPIP read -ksp_* and -pc_* unprefixed, BNLS -tao_bnk_ksp_*, -tao_bnk_pc_*;
   GAMG stops with an error inside TRON and VI in PETSc 3.18, docs/peers.md). -peers_solver conefeti solves the same scene with the FETI contact solver instead
   (ContactSceneSolve(), what the conefeti driver runs). The contact nodes, their normals and gaps are read
   from the scene's ContactModel: the normal rows of the FETI constraints (B u <= c) and ContactModelGetNodes().

   Sample runs (from the repository root; the scene options are those of the conefeti driver):
     peers -options_file petsc-options/brick-frictionless.opts -scene_refine 8 -peers_solver tao -tao_type tron -ksp_type cg -pc_type ml
     peers -options_file petsc-options/brick-frictionless.opts -peers_solver snes -snes_type vinewtonrsls -ksp_type preonly -pc_type cholesky
     peers -options_file petsc-options/brick-frictionless.opts -peers_solver conefeti -contact_rtol 1e-10 -peers_save ref.bin
     peers -options_file petsc-options/brick-frictionless.opts -peers_solver tao -tao_type gpcg -peers_reference ref.bin
     peers -options_file petsc-options/brick-frictionless.opts -peers_solver tao -tao_type bqpip -peers_free_bound 1   (finite bounds)
     peers -options_file petsc-options/brick-frictionless.opts -help      (every option, the solvers' too)

   The accuracy measure, computed from the global displacement u alone (for conefeti: its primal solution,
   copies averaged by FEMPrimalToGlobal()), with the reaction r = K u - f and u_n the bounded component:
     penetration     max (-(u_n + gap))_+ / max|u|
     normal_sign     max (-r_n)_+ / max|r_n|                     (the plane pushes, never pulls)
     complementarity max |r_n (u_n + gap)| / (max|r_n| max|u|)  (no force across an open gap)
     equilibrium     max |r_i| over every other dof / max(|f|, |K u|)
     error_u         |u - u_ref| / |u_ref| against -peers_reference (a tight solve saved with -peers_save)
   The solver's own verdict is printed beside it: a solve it calls converged whose largest residual exceeds
   -peers_acceptance is a wrong answer.

   Output: a few lines, then one JSON line starting with {"peers": (fields: docs/peers.md).
   Exit status: 0 when the solver converged and the largest residual is within -peers_acceptance; 2 when
   either is not so; another non-zero status (PETSc's error code) for bad input, after a message naming the
   option or file. */
#include <conefeti.h>
#include <conefeti/compat.h>
#include <petscsnes.h>
#include <petsctao.h>
#include <string>
#include <sys/resource.h>

namespace {

typedef enum {
  PEERS_CONEFETI,
  PEERS_SNES,
  PEERS_TAO
} PeersSolver;
const char *const PeersSolvers[] = {"conefeti", "snes", "tao"};

/* the bound-constrained primal problem of a scene */
struct Primal {
  Mat       K  = nullptr;
  Vec       f  = nullptr;
  Vec       lb = nullptr, ub = nullptr; /* the bounds: +-infinity except at the contact dofs */
  Vec       sign = nullptr;             /* +1 or -1 at a contact node's bounded dof (u_n = sign u), 0 elsewhere */
  Vec       gap  = nullptr;             /* the gap at the bounded dofs */
  PetscInt  n = 0, ncontact = 0;        /* unknowns without Dirichlet dofs (the driver's n), contact nodes */
  PetscReal free_bound = 0;             /* the bound of the unbounded dofs: 0 for +-PETSC_INFINITY, else +-free_bound */
};

/* the accuracy measure of a displacement */
struct Measures {
  PetscReal penetration = 0, normal_sign = 0, complementarity = 0, equilibrium = 0, max = 0, error_u = -1;
  PetscInt  pressed = 0; /* contact nodes with r_n > 1e-6 max|r_n| */
};

/* The bounds from the scene's contact model: node j of ContactModelGetNodes() has the normal multiplier
   ContactProblemGetNodes() lists j-th, whose row of the FETI constraints B u <= c is -nu' on the node's dofs and
   whose c is the gap (docs/contact.md). A row whose direction is not a coordinate axis, or that touches two
   bodies, is not a simple bound. */
PetscErrorCode BuildBounds(ContactScene scene, Primal &p)
{
  FEM                fem;
  ContactModel       cm;
  ContactProblem     cp;
  ContactPipeline    pipeline;
  FETI               feti;
  Mat                B;
  Vec                c;
  const FETIRowKind *kinds;
  const PetscInt    *normal, *body, *node;
  const PetscScalar *ca = nullptr;
  PetscInt           nloc, nloc2, rstart, rend, ndir;
  IS                 dirichlet;
  MPI_Comm           comm = PetscObjectComm((PetscObject)scene);

  PetscFunctionBegin;
  PetscCall(ContactSceneGetFEM(scene, &fem));
  PetscCall(ContactSceneGetContactModel(scene, &cm));
  PetscCall(ContactModelGetPipeline(cm, &pipeline));
  PetscCheck(pipeline == CONTACT_PIPELINE_FRICTIONLESS, comm, PETSC_ERR_SUP,
             "peers: the scene's pipeline is %s; the bound-constrained peers solve frictionless contact only (-scene_zone<z>_law frictionless, e.g. petsc-options/brick-frictionless.opts)",
             ContactPipelines[pipeline]);
  PetscCall(ContactModelGetFETI(cm, &feti));
  PetscCall(ContactModelGetContactProblem(cm, &cp));
  PetscCall(FETIGetConstraints(feti, &B, &c, &kinds));
  PetscCall(ContactProblemGetNodes(cp, &nloc, &normal, NULL, NULL, NULL, NULL));
  PetscCall(ContactModelGetNodes(cm, &nloc2, &body, &node, NULL, NULL));
  PetscCheck(nloc == nloc2, PETSC_COMM_SELF, PETSC_ERR_PLIB, "peers: %" PetscInt_FMT " contact nodes but %" PetscInt_FMT " normal multipliers on this rank", nloc2, nloc);
  PetscCall(MatGetOwnershipRange(B, &rstart, &rend));
  if (c) PetscCall(VecGetArrayRead(c, &ca));

  PetscCall(FEMAssembleGlobal(fem, &p.K, &p.f));
  PetscCall(VecDuplicate(p.f, &p.sign));
  PetscCall(VecDuplicate(p.f, &p.gap));
  PetscCall(VecDuplicate(p.f, &p.lb));
  PetscCall(VecDuplicate(p.f, &p.ub));
  PetscCall(VecSet(p.sign, 0.0));
  PetscCall(VecSet(p.gap, 0.0));
  for (PetscInt j = 0; j < nloc; j++) {
    const PetscInt     row = normal[j];
    PetscInt           ncols, offset;
    const PetscInt    *cols;
    const PetscScalar *vals;
    PetscReal          dir[3] = {0, 0, 0}, norm;
    PetscInt           axis   = 0;

    PetscCheck(row >= rstart && row < rend && kinds[row - rstart] == FETI_ROW_CONTACT_NORMAL, PETSC_COMM_SELF, PETSC_ERR_PLIB, "peers: multiplier %" PetscInt_FMT " is not a local normal contact row",
               row);
    PetscCall(MatGetRow(B, row, &ncols, &cols, &vals));
    for (PetscInt k = 0; k < ncols; k++) dir[cols[k] % 3] += PetscRealPart(vals[k]); /* 3 dofs per node in every subdomain */
    PetscCall(MatRestoreRow(B, row, &ncols, &cols, &vals));
    norm = PetscSqrtReal(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    PetscCheck(norm > 0, PETSC_COMM_SELF, PETSC_ERR_SUP,
               "peers: the contact row of node %" PetscInt_FMT " of body %" PetscInt_FMT " couples two bodies; the peers solve contact with a rigid plane only", node[j], body[j]);
    for (PetscInt a = 1; a < 3; a++)
      if (PetscAbsReal(dir[a]) > PetscAbsReal(dir[axis])) axis = a;
    for (PetscInt a = 0; a < 3; a++)
      PetscCheck(a == axis || PetscAbsReal(dir[a]) <= 1e-12 * norm, PETSC_COMM_SELF, PETSC_ERR_SUP,
                 "peers: the plane's normal (%g, %g, %g) at node %" PetscInt_FMT " of body %" PetscInt_FMT " is not a coordinate axis; a simple bound needs -scene_zone<z>_normal along x, y or z",
                 (double)(-dir[0] / norm), (double)(-dir[1] / norm), (double)(-dir[2] / norm), node[j], body[j]);
    PetscCall(FEMGetBodyNodeOffset(fem, body[j], &offset));
    const PetscInt dof = 3 * (offset + node[j]) + axis;
    /* the row is -nu': u_n = nu . u = -sign(dir) u_axis */
    PetscCall(VecSetValue(p.sign, dof, dir[axis] > 0 ? -1.0 : 1.0, INSERT_VALUES));
    PetscCall(VecSetValue(p.gap, dof, ca ? ca[row - rstart] : 0.0, INSERT_VALUES));
  }
  if (c) PetscCall(VecRestoreArrayRead(c, &ca));
  for (Vec v : {p.sign, p.gap}) {
    PetscCall(VecAssemblyBegin(v));
    PetscCall(VecAssemblyEnd(v));
  }
  PetscCall(MPIU_Allreduce(&nloc, &p.ncontact, 1, MPIU_INT, MPI_SUM, comm));

  /* u_n >= -gap: a lower bound on u_axis where nu = +e_axis, an upper bound where nu = -e_axis */
  {
    const PetscScalar *s, *g;
    PetscScalar       *l, *u;
    PetscInt           nl;
    PetscCall(VecGetLocalSize(p.f, &nl));
    PetscCall(VecGetArrayRead(p.sign, &s));
    PetscCall(VecGetArrayRead(p.gap, &g));
    PetscCall(VecGetArray(p.lb, &l));
    PetscCall(VecGetArray(p.ub, &u));
    for (PetscInt i = 0; i < nl; i++) {
      l[i] = PetscRealPart(s[i]) > 0 ? -g[i] : (p.free_bound > 0 ? -p.free_bound : PETSC_NINFINITY);
      u[i] = PetscRealPart(s[i]) < 0 ? g[i] : (p.free_bound > 0 ? p.free_bound : PETSC_INFINITY);
    }
    PetscCall(VecRestoreArray(p.ub, &u));
    PetscCall(VecRestoreArray(p.lb, &l));
    PetscCall(VecRestoreArrayRead(p.gap, &g));
    PetscCall(VecRestoreArrayRead(p.sign, &s));
  }

  PetscCall(VecGetSize(p.f, &p.n));
  PetscCall(FEMGetGlobalDirichletDofs(fem, &dirichlet));
  PetscCall(ISGetSize(dirichlet, &ndir));
  PetscCall(ISDestroy(&dirichlet));
  p.n -= ndir;

  /* the rigid-body near-null space, which GAMG and ML use (the others ignore it) */
  {
    Vec          coords;
    MatNullSpace nsp;
    PetscCall(FEMCreateGlobalCoordinates(fem, &coords));
    PetscCall(MatNullSpaceCreateRigidBody(coords, &nsp));
    PetscCall(MatSetNearNullSpace(p.K, nsp));
    PetscCall(MatNullSpaceDestroy(&nsp));
    PetscCall(VecDestroy(&coords));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode PrimalDestroy(Primal &p)
{
  PetscFunctionBegin;
  PetscCall(MatDestroy(&p.K));
  for (Vec *v : {&p.f, &p.lb, &p.ub, &p.sign, &p.gap}) PetscCall(VecDestroy(v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the accuracy measure of u (see the header), and its error against uref when given */
PetscErrorCode Measure(const Primal &p, Vec u, Vec uref, Measures &m)
{
  Vec                r;
  const PetscScalar *ua, *ra, *sa, *ga;
  PetscReal          U, F, KU, pen = 0, neg = 0, comp = 0, eq = 0, R = 0;
  PetscInt           nl;
  MPI_Comm           comm = PetscObjectComm((PetscObject)u);

  PetscFunctionBegin;
  PetscCall(VecDuplicate(u, &r));
  PetscCall(MatMult(p.K, u, r));
  PetscCall(VecNorm(r, NORM_INFINITY, &KU));
  PetscCall(VecAXPY(r, -1.0, p.f));
  PetscCall(VecNorm(u, NORM_INFINITY, &U));
  PetscCall(VecNorm(p.f, NORM_INFINITY, &F));
  PetscCall(VecGetLocalSize(u, &nl));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(r, &ra));
  PetscCall(VecGetArrayRead(p.sign, &sa));
  PetscCall(VecGetArrayRead(p.gap, &ga));
  for (PetscInt i = 0; i < nl; i++) {
    const PetscReal s = PetscRealPart(sa[i]);
    if (s != 0) R = PetscMax(R, PetscAbsReal(s * PetscRealPart(ra[i])));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &R, 1, MPIU_REAL, MPIU_MAX, comm));
  m.pressed = 0;
  for (PetscInt i = 0; i < nl; i++) {
    const PetscReal s = PetscRealPart(sa[i]);
    if (s != 0) {
      const PetscReal d = s * PetscRealPart(ua[i]) + PetscRealPart(ga[i]), rn = s * PetscRealPart(ra[i]);
      pen  = PetscMax(pen, -d);
      neg  = PetscMax(neg, -rn);
      comp = PetscMax(comp, PetscAbsReal(rn * d));
      if (rn > 1e-6 * R) m.pressed++;
    } else eq = PetscMax(eq, PetscAbsReal(PetscRealPart(ra[i])));
  }
  PetscCall(VecRestoreArrayRead(p.gap, &ga));
  PetscCall(VecRestoreArrayRead(p.sign, &sa));
  PetscCall(VecRestoreArrayRead(r, &ra));
  PetscCall(VecRestoreArrayRead(u, &ua));
  {
    PetscReal v[4] = {pen, neg, comp, eq};
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, v, 4, MPIU_REAL, MPIU_MAX, comm));
    pen = v[0], neg = v[1], comp = v[2], eq = v[3];
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &m.pressed, 1, MPIU_INT, MPI_SUM, comm));
  /* a vanishing scale (no load, no contact force) is replaced by 1: the residuals are then absolute */
  if (U == 0) U = 1;
  if (R == 0) R = 1;
  const PetscReal Fs = PetscMax(F, KU) > 0 ? PetscMax(F, KU) : 1;
  m.penetration      = PetscMax(pen, 0) / U;
  m.normal_sign      = PetscMax(neg, 0) / R;
  m.complementarity  = comp / (R * U);
  m.equilibrium      = eq / Fs;
  m.max              = PetscMax(PetscMax(m.penetration, m.normal_sign), PetscMax(m.complementarity, m.equilibrium));
  if (uref) {
    PetscReal nd, nr;
    PetscCall(VecWAXPY(r, -1.0, uref, u));
    PetscCall(VecNorm(r, NORM_2, &nd));
    PetscCall(VecNorm(uref, NORM_2, &nr));
    m.error_u = nr > 0 ? nd / nr : nd;
  }
  PetscCall(VecDestroy(&r));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* SNES: F(u) = K u - f, Jacobian K (assembled once) */
PetscErrorCode SNESResidual(SNES, Vec x, Vec F, void *ctx)
{
  const Primal *p = (const Primal *)ctx;

  PetscFunctionBegin;
  PetscCall(MatMult(p->K, x, F));
  PetscCall(VecAXPY(F, -1.0, p->f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SNESJacobianConstant(SNES, Vec, Mat, Mat, void *)
{
  PetscFunctionBegin;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* TAO: 1/2 u'Ku - f'u, gradient K u - f, Hessian K */
PetscErrorCode TaoObjectiveGradient(Tao, Vec x, PetscReal *obj, Vec g, void *ctx)
{
  const Primal *p = (const Primal *)ctx;
  PetscScalar   xg, xf;

  PetscFunctionBegin;
  PetscCall(MatMult(p->K, x, g));
  PetscCall(VecDot(x, g, &xg));
  PetscCall(VecDot(x, p->f, &xf));
  *obj = 0.5 * PetscRealPart(xg) - PetscRealPart(xf);
  PetscCall(VecAXPY(g, -1.0, p->f));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode TaoHessianConstant(Tao, Vec, Mat, Mat, void *)
{
  PetscFunctionBegin;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* what one solve did */
struct Run {
  std::string    name, ksp = "-", pc = "-", reason;
  PetscBool      converged  = PETSC_FALSE;
  PetscInt       iterations = 0, linear_iterations = -1, products = -1;
  PetscLogDouble setup = 0, solve = 0;         /* wall-clock seconds */
  PetscLogDouble cpu_setup = 0, cpu_solve = 0; /* CPU seconds of the process (the largest over the ranks): less sensitive to a shared machine's load */
};

/* user + system CPU seconds of this process so far */
PetscLogDouble CPUSeconds()
{
  struct rusage ru;
  if (getrusage(RUSAGE_SELF, &ru)) return 0;
  return (PetscLogDouble)ru.ru_utime.tv_sec + 1e-6 * (PetscLogDouble)ru.ru_utime.tv_usec + (PetscLogDouble)ru.ru_stime.tv_sec + 1e-6 * (PetscLogDouble)ru.ru_stime.tv_usec;
}

/* MatMult calls of every matrix during the solve stage: the products with K, and on the multigrid's coarser levels */
PetscErrorCode CountProducts(PetscLogStage stage, PetscInt *count)
{
  PetscLogEvent      ev;
  PetscEventPerfInfo info;

  PetscFunctionBegin;
  PetscCall(PetscLogEventGetId("MatMult", &ev));
  PetscCall(PetscLogEventGetPerfInfo(stage, ev, &info));
  *count = info.count;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, count, 1, MPIU_INT, MPI_MAX, PETSC_COMM_WORLD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode DescribeKSP(KSP ksp, Run &run)
{
  KSPType type;
  PC      pc;
  PCType  pctype;

  PetscFunctionBegin;
  PetscCall(KSPGetType(ksp, &type));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCGetType(pc, &pctype));
  run.ksp = type ? type : "-";
  run.pc  = pctype ? pctype : "-";
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolveSNES(Primal &p, Vec u, PetscLogStage stage, Run &run)
{
  SNES                snes;
  KSP                 ksp;
  SNESType            type;
  SNESConvergedReason reason;
  Vec                 r;
  PetscLogDouble      t0, t1;

  PetscFunctionBegin;
  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetType(snes, SNESVINEWTONRSLS));
  PetscCall(VecDuplicate(p.f, &r)); /* given, or the VI solvers look for it in a DM the problem does not have */
  PetscCall(SNESSetFunction(snes, r, SNESResidual, &p));
  PetscCall(VecDestroy(&r));
  PetscCall(SNESSetJacobian(snes, p.K, p.K, SNESJacobianConstant, &p));
  PetscCall(SNESVISetVariableBounds(snes, p.lb, p.ub));
  PetscCall(SNESSetFromOptions(snes));
  PetscCall(SNESGetType(snes, &type));
  PetscCheck(std::string(type).rfind("vi", 0) == 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-snes_type %s: the bounds need a variational-inequality SNES (vinewtonrsls or vinewtonssls)", type);
  PetscCall(VecSet(u, 0.0)); /* feasible: every gap is >= 0 */
  PetscCall(PetscLogStagePush(stage));
  run.cpu_solve = CPUSeconds();
  PetscCall(PetscTime(&t0));
  PetscCall(SNESSolve(snes, NULL, u));
  PetscCall(PetscTime(&t1));
  run.cpu_solve = CPUSeconds() - run.cpu_solve;
  PetscCall(PetscLogStagePop());
  run.solve = t1 - t0;
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetIterationNumber(snes, &run.iterations));
  PetscCall(SNESGetLinearSolveIterations(snes, &run.linear_iterations));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(DescribeKSP(ksp, run));
  run.name      = std::string("snes ") + type;
  run.converged = reason > 0 ? PETSC_TRUE : PETSC_FALSE;
  run.reason    = SNESConvergedReasons[reason];
  PetscCall(SNESDestroy(&snes));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolveTao(Primal &p, Vec u, PetscLogStage stage, Run &run)
{
  Tao                tao;
  KSP                ksp;
  TaoType            type;
  TaoConvergedReason reason;
  PetscLogDouble     t0, t1;

  PetscFunctionBegin;
  PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
  PetscCall(TaoSetType(tao, TAOTRON));
  PetscCall(TaoSetSolution(tao, u));
  PetscCall(TaoSetObjectiveAndGradient(tao, NULL, TaoObjectiveGradient, &p));
  PetscCall(TaoSetHessian(tao, p.K, p.K, TaoHessianConstant, &p));
  PetscCall(TaoSetVariableBounds(tao, p.lb, p.ub));
  PetscCall(TaoSetFromOptions(tao));
  PetscCall(TaoGetType(tao, &type));
  PetscCall(VecSet(u, 0.0));
  PetscCall(PetscLogStagePush(stage));
  run.cpu_solve = CPUSeconds();
  PetscCall(PetscTime(&t0));
  PetscCall(TaoSolve(tao));
  PetscCall(PetscTime(&t1));
  run.cpu_solve = CPUSeconds() - run.cpu_solve;
  PetscCall(PetscLogStagePop());
  run.solve = t1 - t0;
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCall(TaoGetIterationNumber(tao, &run.iterations));
  PetscCall(TaoGetLinearSolveIterations(tao, &run.linear_iterations));
  PetscCall(TaoGetKSP(tao, &ksp));
  if (ksp) PetscCall(DescribeKSP(ksp, run));
  run.name      = std::string("tao ") + type;
  run.converged = reason > 0 ? PETSC_TRUE : PETSC_FALSE;
  run.reason    = TaoConvergedReasons[reason];
  PetscCall(TaoDestroy(&tao));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode SolveConeFETI(ContactScene scene, Vec u, Run &run, ContactSceneSummary &s)
{
  FEM          fem;
  ContactModel cm;
  Vec          uprimal;

  PetscFunctionBegin;
  run.cpu_solve = CPUSeconds();
  PetscCall(ContactSceneSolve(scene));
  run.cpu_solve = CPUSeconds() - run.cpu_solve;
  PetscCall(ContactSceneGetSummary(scene, &s));
  PetscCall(ContactSceneGetFEM(scene, &fem));
  PetscCall(ContactSceneGetContactModel(scene, &cm));
  PetscCall(ContactModelGetSolution(cm, NULL, &uprimal));
  PetscCall(FEMPrimalToGlobal(fem, uprimal, u));
  run.name              = "conefeti";
  run.ksp               = "smalxe+mprgp";
  run.pc                = "feti";
  run.setup             = s.time_setup;
  run.solve             = s.time_solve;
  run.iterations        = s.iter;
  run.linear_iterations = -1;
  run.products          = s.n_A; /* F products (two subdomain solves each), not K products */
  run.converged         = s.converged;
  run.reason            = s.reason;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* JSON strings here are solver names and PETSc reasons; only quotes and backslashes need escaping */
std::string Quote(const std::string &s)
{
  std::string q = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') q += '\\';
    q += ch;
  }
  return q + "\"";
}

PetscErrorCode Main(int *status)
{
  ContactScene        scene;
  ContactSceneSummary summary{};
  Primal              p;
  Measures            m;
  Run                 run;
  Vec                 u, uref = nullptr;
  PetscInt            solver                        = PEERS_TAO;
  PetscReal           acceptance                    = 1e-5;
  char                reference[PETSC_MAX_PATH_LEN] = "", save[PETSC_MAX_PATH_LEN] = "";
  PetscBool           hasref = PETSC_FALSE, hassave = PETSC_FALSE, help, hasbody;
  PetscLogStage       stage;
  PetscLogDouble      t0, t1, cpu;
  const char         *name;
  MPI_Comm            comm = PETSC_COMM_WORLD;

  PetscFunctionBegin;
  *status = 0;
  PetscCall(ConeFETIInitializePackage());
  PetscOptionsBegin(comm, NULL, "peers: the frictionless primal problem by SNES VI or TAO, or by conefeti", "peers");
  PetscCall(PetscOptionsEList("-peers_solver", "Who solves: conefeti (FETI, ContactSceneSolve()), snes (-snes_type vinewtonrsls|vinewtonssls) or tao (-tao_type tron|gpcg|bqpip|blmvm|bnls)", "peers",
                              PeersSolvers, 3, PeersSolvers[solver], &solver, NULL));
  PetscCall(PetscOptionsString("-peers_reference", "PETSc binary file with the reference displacement (written by -peers_save); prints its relative error", "peers", reference, reference,
                               sizeof(reference), &hasref));
  PetscCall(PetscOptionsString("-peers_save", "Write the displacement to this PETSc binary file (global layout of FEMAssembleGlobal())", "peers", save, save, sizeof(save), &hassave));
  PetscCall(PetscOptionsReal("-peers_acceptance", "A solve is right only when its largest mechanical residual is at most this", "peers", acceptance, &acceptance, NULL));
  PetscCall(PetscOptionsReal("-peers_free_bound", "Bounds -b <= u_i <= b on the dofs without a contact bound (0: PETSC_NINFINITY, PETSC_INFINITY, TAO's documented 'no bound', which BQPIP mishandles)",
                             "peers", p.free_bound, &p.free_bound, NULL));
  PetscOptionsEnd();
  PetscCheck(p.free_bound >= 0 && !PetscIsInfOrNanReal(p.free_bound), comm, PETSC_ERR_ARG_OUTOFRANGE, "-peers_free_bound must be 0 (no bound) or a positive displacement, got %g",
             (double)p.free_bound);
  PetscCheck(!hasref || reference[0], comm, PETSC_ERR_ARG_WRONG, "-peers_reference needs a file name");
  PetscCheck(!hassave || save[0], comm, PETSC_ERR_ARG_WRONG, "-peers_save needs a file name");
  PetscCheck(acceptance > 0 && !PetscIsInfOrNanReal(acceptance), comm, PETSC_ERR_ARG_OUTOFRANGE, "-peers_acceptance must be a positive number, got %g", (double)acceptance);

  PetscCall(ContactSceneCreateFromOptions(comm, NULL, &scene));
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-scene_body0_cells", &hasbody));
  PetscCheck(hasbody || help, comm, PETSC_ERR_ARG_WRONG, "peers: no scene given; run with -options_file petsc-options/brick-frictionless.opts (docs/scenes.md)");
  if (!hasbody) {
    PetscCall(ContactSceneDestroy(&scene));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  cpu = CPUSeconds();
  PetscCall(ContactSceneSetUp(scene)); /* the FEM, and the contact nodes with their normals and gaps */
  if (solver == PEERS_CONEFETI) run.cpu_setup = CPUSeconds() - cpu;

  /* setup of a peer: the assembled K and f, the bounds, the near-null space (its PC is set up inside the solve) */
  cpu = CPUSeconds();
  PetscCall(PetscTime(&t0));
  PetscCall(BuildBounds(scene, p));
  PetscCall(PetscTime(&t1));
  if (solver != PEERS_CONEFETI) run.cpu_setup = CPUSeconds() - cpu;
  PetscCall(VecDuplicate(p.f, &u));
  if (hasref) {
    PetscViewer viewer;
    PetscInt    nref, nu;
    PetscCall(PetscViewerBinaryOpen(comm, reference, FILE_MODE_READ, &viewer));
    PetscCall(VecCreate(comm, &uref));
    PetscCall(VecLoad(uref, viewer));
    PetscCall(PetscViewerDestroy(&viewer));
    PetscCall(VecGetSize(uref, &nref));
    PetscCall(VecGetSize(u, &nu));
    PetscCheck(nref == nu, comm, PETSC_ERR_ARG_SIZ, "-peers_reference %s: %" PetscInt_FMT " entries, the scene has %" PetscInt_FMT " (another mesh?)", reference, nref, nu);
    { /* into the layout of u */
      Vec        v;
      VecScatter sc;
      IS         is;
      PetscInt   lo, hi;
      PetscCall(VecDuplicate(u, &v));
      PetscCall(VecGetOwnershipRange(v, &lo, &hi));
      PetscCall(ISCreateStride(comm, hi - lo, lo, 1, &is));
      PetscCall(VecScatterCreate(uref, is, v, NULL, &sc));
      PetscCall(VecScatterBegin(sc, uref, v, INSERT_VALUES, SCATTER_FORWARD));
      PetscCall(VecScatterEnd(sc, uref, v, INSERT_VALUES, SCATTER_FORWARD));
      PetscCall(VecScatterDestroy(&sc));
      PetscCall(ISDestroy(&is));
      PetscCall(VecDestroy(&uref));
      uref = v;
    }
  }

  PetscCall(PetscLogStageRegister("peers solve", &stage));
  if (solver == PEERS_CONEFETI) PetscCall(SolveConeFETI(scene, u, run, summary));
  else {
    run.setup = t1 - t0;
    if (solver == PEERS_SNES) PetscCall(SolveSNES(p, u, stage, run));
    else PetscCall(SolveTao(p, u, stage, run));
    PetscCall(CountProducts(stage, &run.products));
  }
  PetscCall(Measure(p, u, uref, m));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &run.cpu_setup, 1, MPI_DOUBLE, MPI_MAX, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &run.cpu_solve, 1, MPI_DOUBLE, MPI_MAX, comm));
  if (hassave) {
    PetscViewer viewer;
    PetscCall(PetscViewerBinaryOpen(comm, save, FILE_MODE_WRITE, &viewer));
    PetscCall(VecView(u, viewer));
    PetscCall(PetscViewerDestroy(&viewer));
  }

  const PetscBool right = (PetscBool)(m.max <= acceptance && !PetscIsInfOrNanReal(m.max));
  PetscCall(ContactSceneGetName(scene, &name));
  PetscCall(PetscPrintf(comm, "peers: %s (ksp %s, pc %s) on %s: n = %" PetscInt_FMT ", %" PetscInt_FMT " contact nodes, %" PetscInt_FMT " pressed\n", run.name.c_str(), run.ksp.c_str(), run.pc.c_str(),
                        name, p.n, p.ncontact, m.pressed));
  PetscCall(PetscPrintf(comm, "  solver: %s after %" PetscInt_FMT " iterations (%" PetscInt_FMT " linear, %" PetscInt_FMT " %s); setup %.3f s, solve %.3f s (CPU %.3f s + %.3f s)\n",
                        run.reason.c_str(), run.iterations, run.linear_iterations, run.products, solver == PEERS_CONEFETI ? "F products" : "MatMult", run.setup, run.solve, run.cpu_setup,
                        run.cpu_solve));
  PetscCall(PetscPrintf(comm, "  mechanics: penetration %.1e, normal sign %.1e, complementarity %.1e, equilibrium %.1e; largest %.1e %s %.0e: %s\n", (double)m.penetration, (double)m.normal_sign,
                        (double)m.complementarity, (double)m.equilibrium, (double)m.max, right ? "<=" : ">", (double)acceptance, right ? "right" : "WRONG"));
  if (uref) PetscCall(PetscPrintf(comm, "  error against %s: |u - u_ref|/|u_ref| = %.2e\n", reference, (double)m.error_u));
  {
    char line[2048];
    PetscCall(PetscSNPrintf(line, sizeof(line),
                            "{\"peers\":{\"solver\":%s,\"ksp\":%s,\"pc\":%s,\"n\":%" PetscInt_FMT ",\"contact_nodes\":%" PetscInt_FMT ",\"pressed\":%" PetscInt_FMT ",\"iterations\":%" PetscInt_FMT
                            ",\"linear_iterations\":%" PetscInt_FMT ",\"products\":%" PetscInt_FMT
                            ",\"time_setup\":%.6g,\"time_solve\":%.6g,\"cpu_setup\":%.6g,\"cpu_solve\":%.6g,\"solver_converged\":%s,\"reason\":%s,"
                            "\"penetration\":%.6e,\"normal_sign\":%.6e,\"complementarity\":%.6e,\"equilibrium\":%.6e,\"residual_max\":%.6e,\"acceptance\":%.6e,\"right\":%s,\"error_u\":%.6e}}",
                            Quote(run.name).c_str(), Quote(run.ksp).c_str(), Quote(run.pc).c_str(), p.n, p.ncontact, m.pressed, run.iterations, run.linear_iterations, run.products, run.setup,
                            run.solve, run.cpu_setup, run.cpu_solve, run.converged ? "true" : "false", Quote(run.reason).c_str(), (double)m.penetration, (double)m.normal_sign,
                            (double)m.complementarity, (double)m.equilibrium, (double)m.max, (double)acceptance, right ? "true" : "false", (double)m.error_u));
    PetscCall(PetscPrintf(comm, "%s\n", line));
  }
  *status = run.converged && right ? 0 : 2;
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&uref));
  PetscCall(PrimalDestroy(p));
  PetscCall(ContactSceneDestroy(&scene));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

int main(int argc, char **argv)
{
  int status = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "peers: a scene's frictionless contact problem by SNES VI or TAO, beside conefeti (tutorials/contact/peers.cxx)\n"));
  PetscCall(PetscLogDefaultBegin()); /* the MatMult count of the solve stage */
  PetscCall(Main(&status));
  PetscCall(PetscFinalize());
  return status;
}
