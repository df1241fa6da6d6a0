/* Solves a QP with a known solution (knownqp.h) by one of the conefeti QP solvers and checks
   the result against the known solution.

   Options:
     -kind bounds|disks|cones|mixed|disk_radius0|boundary_zero_multiplier|cone_apex
     -solver tao_mprgp|tao_mpgp|ksp_mprgp|ksp_mpgp|tao_smalxe
     -units <n>   number of 6-entry units        -cond <c>   condition number of A
     -scale <s>   A and b scaled by s             -equality <m>  rows of C x = d (tao_smalxe)
     -rtol <r>    stopping tolerance |gP| <= r |b|
     -blocks      tao_smalxe: inner solves as a Gauss-Seidel sweep over two blocks (disk entries, the rest)
     -equality_routines  tao_smalxe: give C x = d through TAO's equality-constraint routines
     -tol <t>     asserted bound on |x - x*| / |x*|
     -seed <s>    seed of the generator (default 12345): another random matrix, solution and multipliers with the
                  same layout and spectrum (the benchmark's spread over seeds)
     -matrix shell|dense|aij  how A is stored (default shell, whose products are the same on any number of
                  ranks): an assembled A (aij) lets TAO mprgp/mpgp choose a preconditioner in face by default
     -prefix <p>  options prefix of the Tao or KSP (as the contact layer gives smalxe contact_): its
                  options are then -<p>tao_*, and error messages must name them so
     -resolve     TAO solvers: solve again from the solution (a warm start) and print that solve's
                  iteration count as "RESOLVE its=<n>" (smalxe: with -tao_recycle_history it also keeps
                  the multiplier of the equality); the checks below apply to the second solution

   Assertions (each can fail):
   - x is feasible (distance to the set <= 1e-12 (1 + |x|));
   - |x - x*| <= 1.01 |gP(x)| / lambda_min(A) + 1e-12 |x*|, with gP computed afresh from A x - b: for a
     strongly convex QP over a convex set this bound holds at every feasible x, so a point the solver
     wrongly calls converged cannot pass (without equality constraints);
   - |x - x*| / |x*| <= tol.
   Prints one RESULT line with iteration and product counts (compared across rank counts). */
#include "knownqp.h"

/* TAO's equality-constraint interface: c(x) = C x - d, Jacobian C */
static PetscErrorCode EqualityConstraints(Tao, Vec x, Vec c, void *ctx)
{
  KnownQP *qp = (KnownQP *)ctx;

  PetscFunctionBeginUser;
  PetscCall(MatMult(qp->C, x, c));
  PetscCall(VecAXPY(c, -1.0, qp->d));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode EqualityJacobian(Tao, Vec, Mat, Mat, void *)
{
  PetscFunctionBeginUser;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* two index sets: the entries of disk blocks, and all the others */
static PetscErrorCode DiskAndRestBlocks(KnownQP *qp, IS blocks[2])
{
  PetscInt              rstart, rend;
  std::vector<PetscInt> disk, rest;
  Vec                   marker;
  const PetscScalar    *m;

  PetscFunctionBeginUser;
  /* mark disk entries through the set: project a vector far outside every disk... simpler: use the layout rule */
  PetscCall(VecGetOwnershipRange(qp->xstar, &rstart, &rend));
  PetscCall(VecDuplicate(qp->xstar, &marker));
  PetscCall(VecSet(marker, 1e6));
  PetscCall(SeparableSetProject(qp->set, marker)); /* disk entries come back bounded, free scalars stay at 1e6 */
  PetscCall(VecGetArrayRead(marker, &m));
  for (PetscInt i = rstart; i < rend; i++) {
    /* in the "mixed" layout each unit is [disk, disk, cone, cone, cone, scalar] */
    if ((i % 6) < 2) disk.push_back(i);
    else rest.push_back(i);
  }
  PetscCall(VecRestoreArrayRead(marker, &m));
  PetscCall(VecDestroy(&marker));
  PetscCall(ISCreateGeneral(PETSC_COMM_WORLD, (PetscInt)rest.size(), rest.data(), PETSC_COPY_VALUES, &blocks[0]));
  PetscCall(ISCreateGeneral(PETSC_COMM_WORLD, (PetscInt)disk.size(), disk.data(), PETSC_COPY_VALUES, &blocks[1]));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  KnownQP     qp;
  char        kind[64] = "bounds", solver[64] = "tao_mpgp", prefix[64] = "", matrix[64] = "shell";
  PetscInt    units = 20, m = 0, its = 0, seed = 12345;
  PetscReal   cond = 100, scale = 1, rtol = 1e-10, tol = 1e-6, err, dist, xnorm, xsnorm, gpnorm, bound, bnorm;
  Vec         x, g, gp;
  QPCounters  counters;
  std::string reason;
  PetscBool   blocks = PETSC_FALSE, routines = PETSC_FALSE, resolve = PETSC_FALSE;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "QP with a known solution"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-kind", kind, sizeof(kind), NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-solver", solver, sizeof(solver), NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-units", &units, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-equality", &m, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-seed", &seed, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-cond", &cond, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-scale", &scale, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-rtol", &rtol, NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-tol", &tol, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-blocks", &blocks, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-equality_routines", &routines, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-resolve", &resolve, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-prefix", prefix, sizeof(prefix), NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-matrix", matrix, sizeof(matrix), NULL));
  {
    const std::string mt(matrix);
    PetscCheck(mt == "shell" || mt == "dense" || mt == "aij", PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-matrix %s: must be shell, dense or aij", matrix);
    PetscCall(KnownQPCreate(PETSC_COMM_WORLD, kind, units, cond, scale, m, &qp, PETSC_INFINITY, mt == "shell" ? PETSC_TRUE : PETSC_FALSE, (uint64_t)seed));
    if (mt == "aij") PetscCall(MatConvert(qp.A, MATAIJ, MAT_INPLACE_MATRIX, &qp.A));
  }
  PetscCall(VecDuplicate(qp.xstar, &x));
  PetscCall(VecSet(x, 0.0));
  PetscCall(VecNorm(qp.b, NORM_2, &bnorm));

  std::string s(solver);
  if (s.rfind("tao_", 0) == 0) {
    Tao                tao;
    TaoConvergedReason r;
    PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
    if (prefix[0]) PetscCall(TaoSetOptionsPrefix(tao, prefix));
    PetscCall(TaoSetType(tao, s.substr(4).c_str()));
    PetscCall(TaoSetSolution(tao, x));
    PetscCall(TaoSetHessian(tao, qp.A, qp.A, NULL, NULL));
    PetscCall(TaoQPSetLinearTerm(tao, qp.b));
    PetscCall(TaoQPSetConstraints(tao, qp.set));
    PetscCall(TaoSetTolerances(tao, 0.0, 0.0, rtol));
    if (m > 0 && !routines) PetscCall(TaoSMALXESetEqualityConstraints(tao, qp.C, qp.d));
    if (m > 0 && routines) {
      Vec c;
      PetscCall(VecDuplicate(qp.d, &c));
      PetscCall(TaoSetEqualityConstraintsRoutine(tao, c, EqualityConstraints, &qp));
      PetscCall(TaoSetJacobianEqualityRoutine(tao, qp.C, qp.C, EqualityJacobian, &qp));
      PetscCall(VecDestroy(&c));
    }
    if (blocks) {
      IS is[2];
      PetscCheck(std::string(kind) == "mixed", PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-blocks needs -kind mixed");
      PetscCall(DiskAndRestBlocks(&qp, is));
      PetscCall(TaoSMALXESetBlocks(tao, 2, is));
      PetscCall(ISDestroy(&is[0]));
      PetscCall(ISDestroy(&is[1]));
    }
    PetscCall(TaoSetFromOptions(tao));
    PetscCall(TaoSolve(tao));
    PetscCall(TaoGetConvergedReason(tao, &r));
    PetscCall(TaoGetIterationNumber(tao, &its));
    PetscCall(TaoQPGetCounters(tao, &counters));
    reason = TaoConvergedReasons[r];
    PetscCheck(r > 0, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "TAO did not converge: %s", reason.c_str());
    if (resolve) {
      PetscInt again;
      PetscCall(TaoSolve(tao));
      PetscCall(TaoGetConvergedReason(tao, &r));
      PetscCall(TaoGetIterationNumber(tao, &again));
      PetscCheck(r > 0, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "TAO did not converge when solving again: %s", TaoConvergedReasons[r]);
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "RESOLVE its=%" PetscInt_FMT " reason=%s\n", again, TaoConvergedReasons[r]));
    }
    PetscCall(TaoDestroy(&tao));
  } else {
    KSP                ksp;
    KSPConvergedReason r;
    PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
    if (prefix[0]) PetscCall(KSPSetOptionsPrefix(ksp, prefix));
    PetscCall(KSPSetType(ksp, s.substr(4).c_str()));
    PetscCall(KSPSetOperators(ksp, qp.A, qp.A));
    PetscCall(KSPQPSetConstraints(ksp, qp.set));
    PetscCall(KSPSetTolerances(ksp, rtol, 0.0, PETSC_DEFAULT, 100000));
    PetscCall(KSPSetFromOptions(ksp));
    PetscCall(KSPSolve(ksp, qp.b, x));
    PetscCall(KSPGetConvergedReason(ksp, &r));
    PetscCall(KSPGetIterationNumber(ksp, &its));
    PetscCall(KSPQPGetCounters(ksp, &counters));
    reason = KSPConvergedReasons[r];
    PetscCheck(r > 0, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "KSP did not converge: %s", reason.c_str());
    PetscCall(KSPDestroy(&ksp));
  }

  /* independent checks */
  PetscCall(VecNorm(x, NORM_2, &xnorm));
  PetscCall(SeparableSetDistance(qp.set, x, &dist));
  PetscCheck(dist <= 1e-12 * (1 + xnorm), PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the solution is not feasible: distance to the set %g", (double)dist);
  PetscCall(VecDuplicate(x, &g));
  PetscCall(VecDuplicate(x, &gp));
  PetscCall(MatMult(qp.A, x, g));
  PetscCall(VecAXPY(g, -1.0, qp.b));
  PetscCall(SeparableSetProjectedGradient(qp.set, x, g, gp));
  PetscCall(VecNorm(gp, NORM_2, &gpnorm));
  PetscCall(KnownQPError(&qp, x, &err));
  PetscCall(VecNorm(qp.xstar, NORM_2, &xsnorm));
  bound = 1.01 * gpnorm / (qp.lambda_min * xsnorm) + 1e-12; /* relative */
  PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                        "RESULT kind=%s solver=%s cond=%g scale=%g its=%" PetscInt_FMT " hessian_mults=%" PetscInt_FMT " nested=%" PetscInt_FMT " cg=%" PetscInt_FMT " expansion=%" PetscInt_FMT
                        " proportioning=%" PetscInt_FMT " reason=%s\n",
                        kind, solver, (double)cond, (double)scale, its, counters.hessian_mults, counters.nested_hessian_mults, counters.cg_steps, counters.expansion_steps,
                        counters.proportioning_steps, reason.c_str()));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "error |x - x*|/|x*| = %.2e (asserted <= %.1e), |gP|/|b| = %.2e, strong-convexity bound on the error %.2e\n", (double)err, (double)tol,
                        (double)(gpnorm / bnorm), (double)bound));
  if (m == 0) PetscCheck(err <= bound, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "error %g exceeds the strong-convexity bound %g: the returned point is not the minimizer", (double)err, (double)bound);
  PetscCheck(err <= tol, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "error %g exceeds the asserted tolerance %g", (double)err, (double)tol);
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&g));
  PetscCall(VecDestroy(&gp));
  PetscCall(KnownQPDestroy(&qp));
  PetscCall(PetscFinalize());
  return 0;
}
