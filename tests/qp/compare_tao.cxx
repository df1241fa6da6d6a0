/* mprgp agrees with TAO's own bound-constrained solvers (bqpip, gpcg, blmvm) on the same QP.

   A bound-constrained QP with a known solution (knownqp.h, kind box: l < u everywhere); each TAO type solves it
   with its own stopping rule tightened; every solution must agree with mprgp's to 1e-6 relative,
   and mprgp's with the known solution to 1e-8. Prints one line per solver with its iterations. */
#include "knownqp.h"
#include "quadratic.h"

int main(int argc, char **argv)
{
  KnownQP   qp;
  Vec       xref, x, e;
  PetscReal err, nref;
  Quadratic ctx;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "mprgp agrees with bqpip, gpcg, blmvm"));
  PetscCall(ConeFETIInitializePackage());
  /* bqpip needs finite bounds: the infinite ones become +-100, far from the solution (|x*| <= 1.5) */
  PetscCall(KnownQPCreate(PETSC_COMM_WORLD, "box", 20, 100, 1.0, 0, &qp, 100.0, PETSC_FALSE));
  ctx = {qp.A, qp.b};
  PetscCall(VecDuplicate(qp.xstar, &xref));
  PetscCall(VecDuplicate(qp.xstar, &x));
  PetscCall(VecDuplicate(qp.xstar, &e));
  for (const char *type : {TAOMPRGP, TAOBQPIP, TAOGPCG, TAOBLMVM}) {
    Tao                tao;
    TaoConvergedReason reason;
    PetscInt           its;
    Vec                sol = std::string(type) == TAOMPRGP ? xref : x;
    PetscCall(VecSet(sol, 0.0));
    PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
    PetscCall(TaoSetType(tao, type));
    PetscCall(TaoSetSolution(tao, sol));
    PetscCall(TaoSetObjectiveAndGradient(tao, NULL, QuadraticObjectiveGradient, &ctx));
    PetscCall(TaoSetHessian(tao, qp.A, qp.A, QuadraticHessian, &ctx));
    PetscCall(TaoSetVariableBounds(tao, qp.lb, qp.ub));
    /* each solver's own criterion, tight enough for 1e-6 agreement; bqpip's residual (which includes
       the complementarity with the far bounds) levels off near 1e-7, blmvm's near 1e-9 */
    const std::string t(type);
    PetscCall(TaoSetTolerances(tao, t == TAOBQPIP ? 1e-6 : (t == TAOBLMVM ? 1e-8 : 1e-10), 0.0, t == TAOMPRGP ? 1e-11 : 0.0));
    PetscCall(TaoSetMaximumIterations(tao, 20000));
    PetscCall(TaoSetMaximumFunctionEvaluations(tao, 100000));
    PetscCall(TaoSetFromOptions(tao));
    PetscCall(TaoSolve(tao));
    PetscCall(TaoGetConvergedReason(tao, &reason));
    PetscCall(TaoGetIterationNumber(tao, &its));
    PetscCall(KnownQPError(&qp, sol, &err));
    if (sol == x) {
      PetscCall(VecWAXPY(e, -1.0, xref, x));
      PetscCall(VecNorm(e, NORM_2, &err));
      PetscCall(VecNorm(xref, NORM_2, &nref));
      err /= nref;
    }
    PetscCall(
        PetscPrintf(PETSC_COMM_WORLD, "%-6s %-16s %5" PetscInt_FMT " iterations, relative difference %s %.2e\n", type, TaoConvergedReasons[reason], its, sol == x ? "to mprgp" : "to x*", (double)err));
    PetscCheck(reason > 0, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "%s did not converge (%s)", type, TaoConvergedReasons[reason]);
    PetscCheck(err <= (sol == x ? 1e-6 : 1e-8), PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%s: relative difference %g too large", type, (double)err);
    PetscCall(TaoDestroy(&tao));
  }
  PetscCall(VecDestroy(&xref));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&e));
  PetscCall(KnownQPDestroy(&qp));
  PetscCall(PetscFinalize());
  return 0;
}
