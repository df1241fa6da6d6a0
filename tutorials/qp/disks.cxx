/* disks: disk-constrained QP benchmark, the kind of QP Coulomb friction produces: a 2D vector field
   on a grid with a pointwise bound on its length, solved by mpgp or by TAO's general constrained
   solvers.

   What it does
   ------------
   On the unit square with an N x N grid of interior nodes (a DMDA with 2 dof per node), minimizes
     q(u) = 1/2 u'Au - b'u   subject to   |u(x_k)| <= r(x_k) at every node k,
   with A = (K + c h^2 I) (x) I_2, K the 5-point stencil [-1 -1 4 -1 -1] (h^2 times the Laplacian,
   zero Dirichlet values), c the shift (-shift), b = h^2 f with the load f = F (cos 2 pi y, sin 2 pi x)
   (-force F), and the disk radius r(x, y) = r0 (rmin + sin(pi x) sin(pi y)) (-radius r0,
   -radius_min rmin): small near the boundary and largest in the middle, like a friction bound
   mu * (normal pressure) under a Hertz-like pressure. With the defaults about half the nodes end
   on their circle (slip) and the rest inside (stick).

   Solvers:
   - mpgp (conefeti): the disks as a SeparableSet (TaoQPSetConstraints), b by TaoQPSetLinearTerm();
     proportioning steps take the fixed length alpha (the default; -tao_mpgp_bb 1 first tries a
     Barzilai-Borwein length), and arc steps along the circles are on by default (-tao_mpgp_arc 0 gives
     Kucera's MPGP as published);
   - almm, pdipm (TAO): the constraints as c_k(u) = r_k^2 - |u_k|^2 >= 0 with their Jacobian (and, for
     pdipm, the Hessian of the Lagrangian A + 2 diag(lambda_k) I_2, factored by MUMPS at every iteration);
   - any other TAO type is given the same callbacks and may or may not cope.
   The program measures the projected gradient itself (bench.h): at the point projected onto the
   disks, with nodes within -bench_snap (relative) of their circle moved onto it, g = A u - b and per
   node gP = g inside the disk, g on the circle when -g points inwards, and g minus its outward normal
   component otherwise (0 when r = 0). One JSON line reports solver, n, iterations, Hessian products
   (objective/gradient evaluations for almm and pdipm, since the log's MatMult count there includes
   the Jacobian), time, |gP| and |gP|/|b|, objective, the number of nodes on their circle.

   Sample runs
   -----------
     disks -n 70 -tao_type mpgp
     disks -n 224 -tao_type mpgp                            # 100352 unknowns
     disks -n 224 -tao_type mpgp -tao_mpgp_arc 0            # without arc steps (Kucera's MPGP as published)
     disks -n 70 -tao_type pdipm
     disks -n 224 -tao_type mpgp -shift 0 -radius_min 0     # worse conditioned, pinned boundary nodes

   What to expect
   --------------
   mpgp meets the target: about 170 products at -n 70 and 1000 at -n 224 with its defaults, which for this
   assembled Hessian are ICC(0) in face, the projected CG expansion and Gamma = 2 (about 600 and 5200 with
   -tao_mpgp_pc_type none -tao_mpgp_expansion_projcg 0 -tao_mpgp_gamma 1, and without arc steps too about
   2000 and 20000, almost all of its iterations then being projected-gradient steps along the circles); TAO's almm
   does not reach the target (docs/qp-benchmark.md; run alone at -n 70 with -tao_monitor, its first subproblem was
   still running after several minutes), pdipm converges by its own residual in about 20 factorizations but
   its interior iterate does not pass the projected-gradient test. The numbers for all solvers are
   in docs/qp-benchmark.md. */
#include "bench.h"
#include <petscdmda.h>
#include <cmath>
#include <vector>

namespace {

struct AppCtx {
  PetscInt               N      = 70;
  PetscReal              shift  = 10.0;
  PetscReal              force  = 1.0;
  PetscReal              r0     = 0.01;
  PetscReal              rmin   = 0.2;
  PetscReal              scale  = 1.0;
  DM                     da     = nullptr;
  Mat                    A      = nullptr; /* used by the objective and the measurement */
  Vec                    b      = nullptr;
  PetscInt               nlocal = 0, rstart = 0; /* local nodes and the first owned entry */
  std::vector<PetscReal> radius;                 /* per local node */
  BenchCounts           *counts = nullptr;
};

PetscErrorCode BuildProblem(AppCtx *app)
{
  DMDALocalInfo   info;
  PetscScalar  ***bb;
  const PetscInt  N       = app->N;
  const PetscReal h       = 1.0 / (N + 1);
  PetscInt        fill[4] = {1, 0, 0, 1}; /* the two components couple only through the constraint */

  PetscFunctionBeginUser;
  PetscCall(DMDACreate2d(PETSC_COMM_WORLD, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DMDA_STENCIL_STAR, N, N, PETSC_DECIDE, PETSC_DECIDE, 2, 1, NULL, NULL, &app->da));
  PetscCall(DMDASetBlockFills(app->da, fill, fill));
  PetscCall(DMSetUp(app->da));
  PetscCall(DMCreateMatrix(app->da, &app->A));
  PetscCall(DMCreateGlobalVector(app->da, &app->b));
  PetscCall(VecGetOwnershipRange(app->b, &app->rstart, NULL));
  PetscCall(DMDAGetLocalInfo(app->da, &info));
  app->nlocal = info.xm * info.ym;
  PetscCallCXX(app->radius.resize(app->nlocal));
  PetscCall(DMDAVecGetArrayDOF(app->da, app->b, &bb));
  PetscInt k = 0;
  for (PetscInt j = info.ys; j < info.ys + info.ym; j++) {
    for (PetscInt i = info.xs; i < info.xs + info.xm; i++, k++) {
      const PetscReal x = (i + 1) * h, y = (j + 1) * h;
      for (PetscInt c = 0; c < 2; c++) {
        MatStencil     row = {0, j, i, c}, col[5];
        PetscScalar    v[5];
        PetscInt       nc    = 0;
        const PetscInt di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
        col[nc] = row;
        v[nc++] = app->scale * (4.0 + app->shift * h * h);
        for (int q = 0; q < 4; q++) {
          const PetscInt ii = i + di[q], jj = j + dj[q];
          if (ii < 0 || ii >= N || jj < 0 || jj >= N) continue;
          col[nc] = {0, jj, ii, c};
          v[nc++] = -app->scale;
        }
        PetscCall(MatSetValuesStencil(app->A, 1, &row, nc, col, v, INSERT_VALUES));
      }
      bb[j][i][0]    = app->scale * h * h * app->force * std::cos(2 * PETSC_PI * y);
      bb[j][i][1]    = app->scale * h * h * app->force * std::sin(2 * PETSC_PI * x);
      app->radius[k] = app->r0 * (app->rmin + std::sin(PETSC_PI * x) * std::sin(PETSC_PI * y));
    }
  }
  PetscCall(DMDAVecRestoreArrayDOF(app->da, app->b, &bb));
  PetscCall(MatAssemblyBegin(app->A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(app->A, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* q(u) = 1/2 u'Au - b'u and its gradient Au - b: one product with A. */
PetscErrorCode FormObjectiveGradient(Tao, Vec u, PetscReal *f, Vec g, void *ptr)
{
  AppCtx     *app = static_cast<AppCtx *>(ptr);
  PetscScalar ug, ub;

  PetscFunctionBeginUser;
  PetscCall(MatMult(app->A, u, g));
  PetscCall(VecAXPY(g, -1.0, app->b));
  PetscCall(VecDotBegin(u, g, &ug));
  PetscCall(VecDotBegin(u, app->b, &ub));
  PetscCall(VecDotEnd(u, g, &ug));
  PetscCall(VecDotEnd(u, app->b, &ub));
  *f = 0.5 * (PetscRealPart(ug) - PetscRealPart(ub));
  app->counts->callbacks++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FormObjective(Tao tao, Vec u, PetscReal *f, void *ptr)
{
  Vec g;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(u, &g));
  PetscCall(FormObjectiveGradient(tao, u, f, g, ptr));
  PetscCall(VecDestroy(&g));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* c_k(u) = r_k^2 - |u_k|^2 >= 0 */
PetscErrorCode FormConstraints(Tao, Vec u, Vec c, void *ptr)
{
  AppCtx            *app = static_cast<AppCtx *>(ptr);
  const PetscScalar *ua;
  PetscScalar       *ca;

  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayWrite(c, &ca));
  for (PetscInt k = 0; k < app->nlocal; k++) ca[k] = app->radius[k] * app->radius[k] - (ua[2 * k] * ua[2 * k] + ua[2 * k + 1] * ua[2 * k + 1]);
  PetscCall(VecRestoreArrayWrite(c, &ca));
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Jacobian of c: row k has -2 u_k in the columns of node k. */
PetscErrorCode FormConstraintJacobian(Tao, Vec u, Mat J, Mat, void *ptr)
{
  AppCtx            *app = static_cast<AppCtx *>(ptr);
  const PetscScalar *ua;
  PetscInt           crow;

  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(J, &crow, NULL));
  PetscCall(VecGetArrayRead(u, &ua));
  for (PetscInt k = 0; k < app->nlocal; k++) {
    const PetscInt    row = crow + k, cols[2] = {app->rstart + 2 * k, app->rstart + 2 * k + 1};
    const PetscScalar v[2] = {-2 * ua[2 * k], -2 * ua[2 * k + 1]};
    PetscCall(MatSetValues(J, 1, &row, 2, cols, v, INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Hessian of the Lagrangian q - lambda'c (TAO's sign convention, as in tao/constrained/tutorials/ex1.c):
   A + 2 diag(lambda_k) I_2. Without multipliers (types that do not use them) it is A. */
PetscErrorCode FormHessian(Tao tao, Vec, Mat H, Mat, void *ptr)
{
  AppCtx            *app = static_cast<AppCtx *>(ptr);
  Vec                DE = NULL, DI = NULL, d;
  const PetscScalar *la;
  PetscScalar       *da;
  PetscBool          pdipm;

  PetscFunctionBeginUser;
  PetscCall(MatCopy(app->A, H, SAME_NONZERO_PATTERN));
  PetscCall(PetscObjectTypeCompare((PetscObject)tao, TAOPDIPM, &pdipm));
  if (pdipm) PetscCall(TaoGetDualVariables(tao, &DE, &DI));
  if (DI) {
    PetscCall(VecDuplicate(app->b, &d));
    PetscCall(VecGetArrayRead(DI, &la));
    PetscCall(VecGetArrayWrite(d, &da));
    for (PetscInt k = 0; k < app->nlocal; k++) da[2 * k] = da[2 * k + 1] = 2 * la[k];
    PetscCall(VecRestoreArrayWrite(d, &da));
    PetscCall(VecRestoreArrayRead(DI, &la));
    PetscCall(MatDiagonalSet(H, d, ADD_VALUES));
    PetscCall(VecDestroy(&d));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The measurement of bench.h for disks: project, snap onto the circle, then gP, q, and the slip count. */
PetscErrorCode MeasureDisks(AppCtx *app, Vec u, PetscReal snap, BenchAccuracy *acc)
{
  Vec                ub, g, gp;
  const PetscScalar *ga;
  PetscScalar       *xa, *pa, ug, ubv;
  PetscInt           slip = 0;
  std::vector<char>  on;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(u, &ub));
  PetscCall(VecDuplicate(u, &g));
  PetscCall(VecDuplicate(u, &gp));
  PetscCall(VecCopy(u, ub));
  PetscCallCXX(on.assign(app->nlocal, 0));
  PetscCall(VecGetArray(ub, &xa));
  for (PetscInt k = 0; k < app->nlocal; k++) {
    const PetscReal r = app->radius[k], nz = std::hypot(PetscRealPart(xa[2 * k]), PetscRealPart(xa[2 * k + 1]));
    if (r == 0) xa[2 * k] = xa[2 * k + 1] = 0;
    else if (nz >= r * (1 - snap)) { /* on the circle from now on: hypot() of the scaled point may be r(1 - 1e-16) */ xa[2 * k] *= r / nz;
      xa[2 * k + 1] *= r / nz;
      on[k] = 1;
    }
  }
  PetscCall(VecRestoreArray(ub, &xa));
  PetscCall(MatMult(app->A, ub, g));
  PetscCall(VecAXPY(g, -1.0, app->b));
  PetscCall(VecGetArrayRead(ub, (const PetscScalar **)&xa));
  PetscCall(VecGetArrayRead(g, &ga));
  PetscCall(VecGetArray(gp, &pa));
  for (PetscInt k = 0; k < app->nlocal; k++) {
    const PetscReal r = app->radius[k], z[2] = {PetscRealPart(xa[2 * k]), PetscRealPart(xa[2 * k + 1])}, gg[2] = {PetscRealPart(ga[2 * k]), PetscRealPart(ga[2 * k + 1])};
    const PetscReal nz   = std::hypot(z[0], z[1]);
    PetscReal       p[2] = {gg[0], gg[1]};
    if (r == 0) p[0] = p[1] = 0;
    else if (on[k]) {
      const PetscReal nu[2] = {z[0] / nz, z[1] / nz}, dot = nu[0] * gg[0] + nu[1] * gg[1];
      if (dot < 0) {
        p[0] -= dot * nu[0];
        p[1] -= dot * nu[1];
      }
      slip++;
    }
    pa[2 * k]     = p[0];
    pa[2 * k + 1] = p[1];
  }
  PetscCall(VecRestoreArray(gp, &pa));
  PetscCall(VecRestoreArrayRead(g, &ga));
  PetscCall(VecRestoreArrayRead(ub, (const PetscScalar **)&xa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &slip, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(VecNorm(gp, NORM_2, &acc->gp));
  PetscCall(VecDot(ub, g, &ug));
  PetscCall(VecDot(ub, app->b, &ubv));
  acc->objective = 0.5 * (PetscRealPart(ug) - PetscRealPart(ubv));
  acc->active    = slip;
  PetscCall(VecAXPY(ub, -1.0, u));
  PetscCall(VecNorm(ub, NORM_2, &acc->moved));
  PetscCall(VecDestroy(&ub));
  PetscCall(VecDestroy(&g));
  PetscCall(VecDestroy(&gp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

int main(int argc, char **argv)
{
  AppCtx        app;
  BenchCounts   counts;
  BenchAccuracy acc;
  Tao           tao;
  Mat           H, J;
  Vec           u, u0, c, xl = NULL, xu = NULL;
  SeparableSet  set;
  PetscReal     rtol = 1e-6, factor = 1.0, snap = 1e-9, bnorm;
  PetscInt      n, repeat = 1, nnodes;
  PetscBool     ours, constrained;
  char          extra[256];

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Disk-constrained QP benchmark (friction-like), any TAO type\n"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(BenchCountsInitialize(&counts));
  app.counts = &counts;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Disk-constrained QP benchmark", "disks");
  /* 2 n^2 unknowns must fit PetscInt */
  PetscCall(PetscOptionsRangeInt("-n", "Interior grid nodes per direction (2 n^2 unknowns)", "disks", app.N, &app.N, NULL, 3, (PetscInt)PetscSqrtReal(PETSC_MAX_INT / 2.0)));
  PetscCall(PetscOptionsReal("-shift", "Shift c >= 0 of A = (K + c h^2 I) x I_2", "disks", app.shift, &app.shift, NULL));
  PetscCall(PetscOptionsReal("-force", "Load amplitude F (nonzero)", "disks", app.force, &app.force, NULL));
  PetscCall(PetscOptionsReal("-radius", "Radius scale r0 of r = r0 (rmin + sin(pi x) sin(pi y))", "disks", app.r0, &app.r0, NULL));
  PetscCall(PetscOptionsReal("-radius_min", "rmin in r = r0 (rmin + sin(pi x) sin(pi y)); 0 gives radii near 0 at the boundary", "disks", app.rmin, &app.rmin, NULL));
  PetscCall(PetscOptionsReal("-scale", "Multiply A and b by this factor > 0 (the solution and the relative target do not change)", "disks", app.scale, &app.scale, NULL));
  PetscCall(PetscOptionsReal("-bench_rtol", "Target: |projected gradient| <= rtol |b|, measured by this program", "disks", rtol, &rtol, NULL));
  PetscCall(PetscOptionsReal("-bench_own_factor", "The solver's own tolerance is factor * rtol (|b|-relative, or absolute times |b| for TAO's solvers)", "disks", factor, &factor, NULL));
  PetscCall(PetscOptionsReal("-bench_snap", "Nodes within relative distance snap of their circle count as on it when measuring", "disks", snap, &snap, NULL));
  PetscCall(PetscOptionsBoundedInt("-bench_repeat", "Solve this many times and report the shortest time", "disks", repeat, &repeat, NULL, 1));
  PetscOptionsEnd();
  /* A = scale (K + c h^2 I) x I_2 must be positive definite and b nonzero (the target is relative to |b|) */
  PetscCall(BenchCheckReal("-shift", app.shift, 0, PETSC_FALSE, PETSC_MAX_REAL, PETSC_FALSE, "A = K + c h^2 I must stay positive definite"));
  PetscCall(BenchCheckReal("-scale", app.scale, 0, PETSC_TRUE, PETSC_MAX_REAL, PETSC_FALSE, "A and b are multiplied by it"));
  PetscCheck(!PetscIsInfOrNanReal(app.force) && app.force != 0, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-force %g: must be a finite nonzero number (the target is relative to |b|)",
             (double)app.force);
  PetscCall(BenchCheckReal("-radius", app.r0, 0, PETSC_FALSE, PETSC_MAX_REAL, PETSC_FALSE, "a radius"));
  PetscCall(BenchCheckReal("-radius_min", app.rmin, 0, PETSC_FALSE, PETSC_MAX_REAL, PETSC_FALSE, "a relative radius"));
  PetscCall(BenchCheckOptions(rtol, factor, snap));

  PetscCall(BuildProblem(&app));
  PetscCall(VecNorm(app.b, NORM_2, &bnorm));
  PetscCall(VecGetSize(app.b, &n));
  nnodes = n / 2;
  PetscCall(MatDuplicate(app.A, MAT_COPY_VALUES, &H));
  PetscCall(VecDuplicate(app.b, &u));
  PetscCall(VecDuplicate(app.b, &u0));
  PetscCall(VecSet(u0, 0.0)); /* feasible: every solver starts from 0 */

  /* the disks for mpgp */
  {
    std::vector<PetscInt> idx(2 * app.nlocal);
    for (PetscInt k = 0; k < 2 * app.nlocal; k++) idx[k] = app.rstart + k;
    PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, 2 * app.nlocal, n, &set));
    PetscCall(SeparableSetAddDisks(set, app.nlocal, idx.data(), NULL, app.radius.data()));
  }
  /* the constraints c(u) >= 0 and their Jacobian for TAO's solvers */
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, app.nlocal, nnodes, &c));
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, app.nlocal, 2 * app.nlocal, nnodes, n, 2, NULL, 0, NULL, &J));
  PetscCall(MatSetOption(J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));

  PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
  PetscCall(TaoSetType(tao, TAOMPGP));
  PetscCall(TaoSetFromOptions(tao)); /* the type first: type-specific settings below are lost when the type changes */
  ours = BenchIsConeFETIType(tao);
  PetscCall(PetscObjectTypeCompareAny((PetscObject)tao, &constrained, TAOALMM, TAOPDIPM, TAOIPM, ""));
  PetscCall(TaoSetSolution(tao, u));
  PetscCall(TaoSetObjective(tao, FormObjective, &app));
  PetscCall(TaoSetObjectiveAndGradient(tao, NULL, FormObjectiveGradient, &app));
  PetscCall(TaoSetHessian(tao, H, H, FormHessian, &app));
  if (ours) {
    PetscCall(TaoQPSetConstraints(tao, set));
    PetscCall(TaoQPSetLinearTerm(tao, app.b));
  } else {
    /* infinite variable bounds: pdipm (PETSc 3.18) dereferences the bound vectors without checking them */
    PetscCall(VecDuplicate(u, &xl));
    PetscCall(VecDuplicate(u, &xu));
    PetscCall(VecSet(xl, PETSC_NINFINITY));
    PetscCall(VecSet(xu, PETSC_INFINITY));
    PetscCall(TaoSetVariableBounds(tao, xl, xu));
    PetscCall(TaoSetInequalityConstraintsRoutine(tao, c, FormConstraints, &app));
    PetscCall(TaoSetJacobianInequalityRoutine(tao, J, J, FormConstraintJacobian, &app));
  }
  if (!ours) { /* pdipm factors its KKT matrix: MUMPS, as in TAO's constrained tutorial ex1 */
    PetscBool pdipm;
    PetscCall(PetscObjectTypeCompare((PetscObject)tao, TAOPDIPM, &pdipm));
    if (pdipm) {
      KSP ksp;
      PC  pc;
      PetscCall(TaoGetKSP(tao, &ksp));
      PetscCall(KSPSetType(ksp, KSPPREONLY));
      PetscCall(KSPGetPC(ksp, &pc));
      PetscCall(PCSetType(pc, PCCHOLESKY));
      PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
      {
        /* MUMPS sizes its workspace from the first KKT matrix; the later ones fill in more (INFOG(1) = -9), and
           pdipm (PETSc 3.18) then repeats the failed step without end: 200% more room, unless given */
        PetscBool set;
        PetscCall(PetscOptionsHasName(NULL, NULL, "-mat_mumps_icntl_14", &set));
        if (!set) PetscCall(PetscOptionsSetValue(NULL, "-mat_mumps_icntl_14", "200"));
      }
      PetscCall(KSPSetFromOptions(ksp));
    }
  }
  PetscCall(BenchSetStoppingRule(tao, rtol, factor, bnorm));
  if (constrained) PetscCall(TaoSetConstraintTolerances(tao, factor * rtol * bnorm, 0.0));
  PetscCall(TaoSetFromOptions(tao)); /* command-line tolerances still win */

  PetscCall(BenchRepeatedSolve(tao, u, u0, H, repeat, &counts));
  PetscCall(MeasureDisks(&app, u, snap, &acc));
  PetscCall(PetscSNPrintf(extra, sizeof(extra), ",\"nodes\":%" PetscInt_FMT, nnodes));
  PetscCall(BenchReport(tao, "disks", n, bnorm, rtol, factor, &counts, &acc, ours ? PETSC_FALSE : PETSC_TRUE, extra));

  PetscCall(TaoDestroy(&tao));
  PetscCall(SeparableSetDestroy(&set));
  PetscCall(VecDestroy(&c));
  PetscCall(VecDestroy(&xl));
  PetscCall(VecDestroy(&xu));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&u0));
  PetscCall(MatDestroy(&H));
  PetscCall(MatDestroy(&app.A));
  PetscCall(VecDestroy(&app.b));
  PetscCall(DMDestroy(&app.da));
  PetscCall(PetscFinalize());
  return 0;
}
