/* Shared pieces of the QP benchmark programs (obstacle.cxx, disks.cxx): how each solver is set up
   to stop, how its Hessian products and time are measured, and the one JSON line a run prints.

   Measuring, the same way for every solver:
   - time: wall clock of TaoSolve() alone (for mprgp/mpgp it includes the ||A|| estimate), and the
     CPU time the process spent in it (the largest over the ranks), which is less disturbed when the
     machine is shared;
   - Hessian products: for mprgp/mpgp from TaoQPGetCounters() (the solver's own products and the
     ||A|| estimate's, reported apart and added in the total); for TAO's own solvers the number of
     MatMult calls PETSc's log records during TaoSolve() (products with the Hessian, with its
     submatrices in active-set subsolves, and the one product inside every objective/gradient
     evaluation). When a solver also multiplies by other matrices (constraint Jacobians in almm and
     pdipm) the log cannot tell them apart, and the count is the number of objective/gradient
     evaluations instead (one product each), as the "products_source" field says;
   - accuracy: the program, not the solver, computes the projected gradient at the returned point
     (after projecting it onto the feasible set and snapping entries within a relative distance
     -bench_snap of the boundary onto it, so that interior-point iterates are judged by the same
     formula); see each program for the formula of its set. */
#pragma once

#include <conefeti.h>
#include <petsctao.h>
#include <ctime>
#include <string>

/* Work counted while one TaoSolve() runs. */
struct BenchCounts {
  PetscLogStage  stage  = -1;
  PetscLogEvent  mult   = -1;
  int            mults0 = 0, mults = 0; /* MatMult calls logged during the solve */
  PetscInt       callbacks = 0;         /* objective/gradient evaluations (one product each) */
  PetscLogDouble time      = 0;         /* wall clock */
  PetscLogDouble cpu       = 0;         /* CPU time of this process, max over ranks */
};

/* CPU time of the process (all its threads) in seconds. */
static inline PetscLogDouble BenchCPUTime(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (PetscLogDouble)ts.tv_sec + 1e-9 * (PetscLogDouble)ts.tv_nsec;
}

/* The real options must be finite and in range, checked before anything is built: a NaN or an infinity
   would surface deep inside the solver (SLEPc's norm estimate, "indefinite matrix") or as NaN results. */
static inline PetscErrorCode BenchCheckReal(const char *name, PetscReal value, PetscReal lo, PetscBool loopen, PetscReal hi, PetscBool hiopen, const char *meaning)
{
  const PetscBool ok = (PetscBool)(!PetscIsInfOrNanReal(value) && (loopen ? value > lo : value >= lo) && (hiopen ? value < hi : value <= hi));

  PetscFunctionBeginUser;
  if (hi >= PETSC_MAX_REAL) PetscCheck(ok, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "%s %g: must be a finite number %s %g (%s)", name, (double)value, loopen ? ">" : ">=", (double)lo, meaning);
  else
    PetscCheck(ok, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "%s %g: must be a finite number in %s%g, %g%s (%s)", name, (double)value, loopen ? "(" : "[", (double)lo, (double)hi, hiopen ? ")" : "]",
               meaning);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The options every benchmark program shares: the target and how the result is measured */
static inline PetscErrorCode BenchCheckOptions(PetscReal rtol, PetscReal factor, PetscReal snap)
{
  PetscFunctionBeginUser;
  PetscCall(BenchCheckReal("-bench_rtol", rtol, 0, PETSC_TRUE, 1, PETSC_TRUE, "the target |gP| <= rtol |b| is relative"));
  PetscCall(BenchCheckReal("-bench_own_factor", factor, 0, PETSC_TRUE, PETSC_MAX_REAL, PETSC_FALSE, "it scales the solver's own tolerance"));
  PetscCall(BenchCheckReal("-bench_snap", snap, 0, PETSC_FALSE, 1, PETSC_TRUE, "a relative distance to the boundary"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Is this one of conefeti's QP types (which have counters and a |b|-relative stopping test)? */
static inline PetscBool BenchIsConeFETIType(Tao tao)
{
  PetscBool ours;

  PetscCallAbort(PETSC_COMM_WORLD, PetscObjectTypeCompareAny((PetscObject)tao, &ours, TAOMPRGP, TAOMPGP, ""));
  return ours;
}

/* Stopping rule for the benchmark target |gP| <= rtol |b|: conefeti's types get it directly
   (-tao_gttol is relative to |b| there); TAO's own solvers get the absolute tolerance
   -tao_gatol = factor * rtol * |b| on their own residual (which is |gP| for blmvm, bncg, gpcg, tron,
   and an interior-point residual for bqpip), with factor <= 1 tuned by the benchmark script so that
   the independently measured |gP| meets the target. Options given on the command line win. */
static inline PetscErrorCode BenchSetStoppingRule(Tao tao, PetscReal rtol, PetscReal factor, PetscReal bnorm)
{
  PetscFunctionBeginUser;
  if (BenchIsConeFETIType(tao)) PetscCall(TaoSetTolerances(tao, 0.0, 0.0, factor * rtol));
  else PetscCall(TaoSetTolerances(tao, factor * rtol * bnorm, 0.0, 0.0));
  PetscCall(TaoSetMaximumIterations(tao, 1000000));
  PetscCall(TaoSetMaximumFunctionEvaluations(tao, 100000000));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode BenchCountsInitialize(BenchCounts *c)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogDefaultBegin()); /* the MatMult counts come from PETSc's log */
  PetscCall(PetscLogStageRegister("QP benchmark solve", &c->stage));
  PetscCall(PetscLogEventGetId("MatMult", &c->mult));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode BenchCountMults(BenchCounts *c, int *count)
{
  PetscEventPerfInfo info;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventGetPerfInfo(c->stage, c->mult, &info));
  *count = info.count;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* TaoSolve() in its own log stage, timed, with the MatMult calls counted. */
static inline PetscErrorCode BenchTimedSolve(Tao tao, BenchCounts *c)
{
  PetscLogDouble t0, t1, c0, c1;

  PetscFunctionBeginUser;
  PetscCall(BenchCountMults(c, &c->mults0));
  c->callbacks = 0;
  PetscCallMPI(MPI_Barrier(PetscObjectComm((PetscObject)tao)));
  PetscCall(PetscTime(&t0));
  c0 = BenchCPUTime();
  PetscCall(PetscLogStagePush(c->stage));
  PetscCall(TaoSolve(tao));
  PetscCall(PetscLogStagePop());
  c1 = BenchCPUTime();
  PetscCallMPI(MPI_Barrier(PetscObjectComm((PetscObject)tao)));
  PetscCall(PetscTime(&t1));
  c->time = t1 - t0;
  c->cpu  = c1 - c0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &c->cpu, 1, MPIU_PETSCLOGDOUBLE, MPI_MAX, PetscObjectComm((PetscObject)tao)));
  PetscCall(BenchCountMults(c, &c->mults));
  c->mults -= c->mults0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The same solve `repeat` times from the initial guess x0 (the ||A|| estimate cached on H is cleared
   each time, so mprgp/mpgp pay for it in every solve); keeps the shortest wall and CPU times, since
   the machine may be shared. The counts are those of the last solve (they do not change between solves). */
static inline PetscErrorCode BenchRepeatedSolve(Tao tao, Vec x, Vec x0, Mat H, PetscInt repeat, BenchCounts *c)
{
  PetscLogDouble best = PETSC_MAX_REAL, best_cpu = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < PetscMax(repeat, 1); k++) {
    PetscCall(VecCopy(x0, x));
    PetscCall(TaoQPResetCounters(tao));
    PetscCall(MatQPClearNormEstimate(H));
    PetscCall(BenchTimedSolve(tao, c));
    best     = PetscMin(best, c->time);
    best_cpu = PetscMin(best_cpu, c->cpu);
  }
  c->time = best;
  c->cpu  = best_cpu;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The accuracy of a returned point, measured by the program. */
struct BenchAccuracy {
  PetscReal gp        = 0; /* |gP| at the projected and snapped point */
  PetscReal objective = 0; /* q at that point */
  PetscReal moved     = 0; /* |x - that point|: infeasibility plus snapping */
  PetscInt  active    = 0; /* entries (bounds) or blocks (disks) on the boundary */
};

/* Prints the run as one JSON line (the benchmark script reads lines that start with {"bench").
   extra: more fields, already JSON-formatted, starting with a comma (or empty). */
static inline PetscErrorCode BenchReport(Tao tao, const char *problem, PetscInt n, PetscReal bnorm, PetscReal rtol, PetscReal factor, const BenchCounts *c, const BenchAccuracy *a,
                                         PetscBool count_callbacks, const std::string &extra)
{
  TaoType            type;
  TaoConvergedReason reason;
  PetscInt           its, kspits = 0, products, estimate = 0, solver_products;
  const char        *source;
  QPCounters         qc;

  PetscFunctionBeginUser;
  PetscCall(TaoGetType(tao, &type));
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCall(TaoGetIterationNumber(tao, &its));
  PetscCall(TaoGetLinearSolveIterations(tao, &kspits));
  if (BenchIsConeFETIType(tao)) {
    PetscCall(TaoQPGetCounters(tao, &qc));
    solver_products = qc.hessian_mults + qc.nested_hessian_mults;
    estimate        = qc.estimate_mults;
    source          = "counters";
  } else if (count_callbacks) {
    solver_products = c->callbacks;
    source          = "objective_gradient_calls";
  } else {
    solver_products = c->mults;
    source          = "log_matmult";
  }
  products = solver_products + estimate;
  /* an overflow or NaN must not pass the comparison below (inf <= rtol * inf is true) */
  const PetscBool finite = (PetscBool)(!PetscIsInfOrNanReal(a->gp) && !PetscIsInfOrNanReal(a->objective) && !PetscIsInfOrNanReal(bnorm) && bnorm > 0);
  PetscCall(PetscPrintf(
      PETSC_COMM_WORLD,
      "{\"bench\":\"qp\",\"problem\":\"%s\",\"solver\":\"%s\",\"n\":%" PetscInt_FMT ",\"iterations\":%" PetscInt_FMT ",\"ksp_iterations\":%" PetscInt_FMT ",\"hessian_products\":%" PetscInt_FMT
      ",\"solver_products\":%" PetscInt_FMT ",\"estimate_products\":%" PetscInt_FMT ",\"products_source\":\"%s\",\"log_matmults\":%d,\"objective_gradient_calls\":%" PetscInt_FMT
      ",\"time\":%.6f,\"cpu_time\":%.6f,\"reason\":\"%s\",\"target_rtol\":%.3e,\"own_factor\":%.3e,\"bnorm\":%.10e,\"gp\":%.6e,\"gp_rel\":%.6e,\"met\":%s,\"objective\":%.15e,"
      "\"moved\":%.3e,\"active\":%" PetscInt_FMT "%s}\n",
      problem, type, n, its, kspits, products, solver_products, estimate, source, c->mults, c->callbacks, (double)c->time, (double)c->cpu, TaoConvergedReasons[reason], (double)rtol, (double)factor,
      (double)bnorm, (double)a->gp, (double)(a->gp / bnorm), finite && a->gp <= rtol * bnorm ? "true" : "false", (double)a->objective, (double)a->moved, a->active, extra.c_str()));
  PetscFunctionReturn(PETSC_SUCCESS);
}
