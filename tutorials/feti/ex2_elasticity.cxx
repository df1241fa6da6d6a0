/* Tutorial and benchmark driver: linear elasticity of a clamped cube by FETI, or by PETSc's
   single-domain solvers on the same mesh.

   What it does
     The cube (0,1)^3 meshed by n^3 hexahedra (6 tetrahedra each) is clamped on x = 0, pulled and
     sheared on x = 1 and loaded by gravity. -solver feti cuts it into p^3 subdomains (structured) or
     n_s METIS parts and solves by projected CG on P F P; -solver gamg solves the assembled global system
     by CG + GAMG with the rigid-body near-null space; -solver cholesky by a direct MUMPS Cholesky.
     It prints one line "RESULT key=value ..." (times in seconds, memory in bytes) for scripts/bench-feti.py.
     Exit status: 0 when the solve converged, 2 when it did not (RESULT then says converged=false), as the
     conefeti driver.

   Sample runs
     ./feti_ex2_elasticity -cells 24 -fem_subdomains 3,3,3 -feti_ksp_monitor -log_view
     mpiexec -n 2 ./feti_ex2_elasticity -cells 32 -fem_subdomains 4,4,4 -fem_dirichlet primal -feti_pc_type lumped
     mpiexec -n 2 ./feti_ex2_elasticity -cells 32 -fem_subdomains 4,4,4 -solver gamg
     ./feti_ex2_elasticity -cells 24 -fem_decomposition metis -fem_subdomains 20 -feti_sub_pc_factor_mat_solver_type mumps

   What to expect
     For a fixed subdomain size (cells / p) the FETI iteration count stays nearly constant as the
     number of subdomains grows (numerical scalability); time per F product is about two sparse
     triangular solves per subdomain. The setup time of FETI excludes the preconditioner's factorizations, which happen in the first solve. */
#include <conefeti.h>
#include <sys/resource.h>

static PetscErrorCode Gravity(const PetscReal x[3], PetscReal f[3], void *ctx)
{
  (void)x;
  (void)ctx;
  f[0] = f[1] = 0;
  f[2]        = -7850 * 9.81;
  return PETSC_SUCCESS;
}

/* Peak resident set size summed over the ranks */
static PetscErrorCode PeakRSS(PetscLogDouble *bytes)
{
  struct rusage usage;

  PetscFunctionBeginUser;
  getrusage(RUSAGE_SELF, &usage);
  *bytes = 1024.0 * (PetscLogDouble)usage.ru_maxrss;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, bytes, 1, MPIU_PETSCLOGDOUBLE, MPI_SUM, PETSC_COMM_WORLD));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  FEM                fem;
  PetscInt           n = 16, body, its = 0, nprimal = 0, ndual = 0, ncoarse = 0, nsub = 0, nglobal;
  PetscReal          lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, t[3] = {2e7, 5e6, 0};
  const char *const  solvers[] = {"feti", "gamg", "cholesky"};
  PetscInt           solver    = 0;
  PetscLogDouble     t0, tsetup = 0, tsolve = 0, tF = 0, rss, tfactor = 0, tkplus = 0;
  PetscBool          isfeti, isgamg;
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Linear elasticity of a clamped cube by FETI, GAMG or Cholesky"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscLogDefaultBegin()); /* event times for the RESULT line */
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Cube benchmark options", NULL);
  PetscCall(PetscOptionsBoundedInt("-cells", "Hexahedra per side of the cube", NULL, n, &n, NULL, 1));
  /* a list, not a string: a misspelt solver ran Cholesky and printed RESULT solver=<the misspelling> */
  PetscCall(PetscOptionsEList("-solver", "FETI, CG + GAMG on the assembled system, or a direct Cholesky (MUMPS)", NULL, solvers, 3, solvers[solver], &solver, NULL));
  PetscOptionsEnd();
  isfeti = solver == 0 ? PETSC_TRUE : PETSC_FALSE;
  isgamg = solver == 1 ? PETSC_TRUE : PETSC_FALSE;

  PetscCall(PetscTime(&t0));
  {
    PetscInt cells[3] = {n, n, n};
    PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
    PetscCall(FEMAddBox(fem, lo, hi, cells, &body));
    PetscCall(FEMSetDirichlet(fem, body, "x0", NULL));
    PetscCall(FEMSetTraction(fem, body, "x1", t));
    PetscCall(FEMSetBodyForce(fem, body, Gravity, NULL));
    PetscCall(FEMSetFromOptions(fem));
    PetscCall(FEMSetUp(fem));
  }
  nglobal = 3 * (n + 1) * (n + 1) * (n + 1);
  if (isfeti) {
    FETI feti;
    KSP  ksp;
    Mat  F;
    Vec  lambda, u, x, y;
    PetscCall(FEMCreateFETI(fem, &feti));
    PetscCall(FETISetFromOptions(feti));
    PetscCall(FETISetUp(feti));
    PetscCall(FETIGetKSP(feti, &ksp));
    PetscCall(FETICreateVecs(feti, &u, &lambda, NULL));
    PetscCall(PetscTime(&tsetup));
    tsetup -= t0;
    PetscCall(PetscTime(&t0));
    PetscCall(FETISolveLinear(feti, lambda, u));
    PetscCall(PetscTime(&tsolve));
    tsolve -= t0;
    PetscCall(KSPGetIterationNumber(ksp, &its));
    PetscCall(KSPGetConvergedReason(ksp, &reason));
    /* time per F product, measured alone */
    PetscCall(FETIGetOperators(feti, &F, NULL, NULL, NULL));
    PetscCall(VecDuplicate(lambda, &x));
    PetscCall(VecDuplicate(lambda, &y));
    PetscCall(VecSet(x, 1.0));
    PetscCall(PetscTime(&t0));
    for (int k = 0; k < 10; k++) PetscCall(MatMult(F, x, y));
    PetscCall(PetscTime(&tF));
    tF = (tF - t0) / 10;
    PetscCall(FETIGetSizes(feti, &nprimal, &ndual, &ncoarse));
    {
      /* subdomain factorizations (all of them, incl. the Dirichlet preconditioner's) and one K+ application, maximum over ranks */
      PetscEventPerfInfo info;
      PetscCall(PetscLogEventGetPerfInfo(0, FETI_Factorization, &info));
      tfactor = info.time;
      PetscCall(PetscLogEventGetPerfInfo(0, FETI_ApplyKplus, &info));
      tkplus = info.count ? info.time / info.count : 0;
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &tfactor, 1, MPIU_PETSCLOGDOUBLE, MPI_MAX, PETSC_COMM_WORLD));
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &tkplus, 1, MPIU_PETSCLOGDOUBLE, MPI_MAX, PETSC_COMM_WORLD));
    }
    PetscCall(FETIGetNumSubdomains(feti, &nsub, NULL, NULL));
    PetscCall(VecDestroy(&x));
    PetscCall(VecDestroy(&y));
    PetscCall(VecDestroy(&u));
    PetscCall(VecDestroy(&lambda));
    PetscCall(FETIDestroy(&feti));
  } else {
    Mat K;
    Vec f, u;
    KSP ksp;
    PC  pc;
    PetscCall(FEMAssembleGlobal(fem, &K, &f));
    PetscCall(VecDuplicate(f, &u));
    PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
    PetscCall(KSPSetOptionsPrefix(ksp, "global_"));
    PetscCall(KSPSetOperators(ksp, K, K));
    PetscCall(KSPGetPC(ksp, &pc));
    if (isgamg) {
      Vec          coords;
      MatNullSpace nearnull;
      PetscCall(FEMCreateGlobalCoordinates(fem, &coords));
      PetscCall(MatNullSpaceCreateRigidBody(coords, &nearnull));
      PetscCall(MatSetNearNullSpace(K, nearnull));
      PetscCall(MatNullSpaceDestroy(&nearnull));
      PetscCall(VecDestroy(&coords));
      PetscCall(KSPSetType(ksp, KSPCG));
      PetscCall(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
      PetscCall(KSPSetTolerances(ksp, 1e-8, PETSC_DEFAULT, PETSC_DEFAULT, 10000));
      PetscCall(PCSetType(pc, PCGAMG));
    } else {
      PetscCall(KSPSetType(ksp, KSPPREONLY));
      PetscCall(PCSetType(pc, PCCHOLESKY));
      PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    }
    PetscCall(KSPSetFromOptions(ksp));
    PetscCall(KSPSetUp(ksp));
    PetscCall(PetscTime(&tsetup));
    tsetup -= t0;
    PetscCall(PetscTime(&t0));
    PetscCall(KSPSolve(ksp, f, u));
    PetscCall(PetscTime(&tsolve));
    tsolve -= t0;
    PetscCall(KSPGetIterationNumber(ksp, &its));
    PetscCall(KSPGetConvergedReason(ksp, &reason));
    nprimal = nglobal;
    PetscCall(KSPDestroy(&ksp));
    PetscCall(VecDestroy(&u));
    PetscCall(VecDestroy(&f));
    PetscCall(MatDestroy(&K));
  }
  PetscCall(PeakRSS(&rss));
  if (reason <= 0) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "NOT CONVERGED: %s after %d iterations (KSP prefix %s)\n", KSPConvergedReasons[reason], (int)its, isfeti ? "feti_" : "global_"));
  PetscCall(
      PetscPrintf(PETSC_COMM_WORLD,
                  "RESULT solver=%s cells=%d unknowns=%d primal=%d dual=%d coarse=%d subdomains=%d iterations=%d converged=%s setup=%.3f solve=%.3f Fproduct=%.5f factor=%.3f Kplus=%.5f rss=%.0f\n",
                  solvers[solver], (int)n, (int)nglobal, (int)nprimal, (int)ndual, (int)ncoarse, (int)nsub, (int)its, reason > 0 ? "true" : "false", (double)tsetup, (double)tsolve, (double)tF,
                  (double)tfactor, (double)tkplus, (double)rss));
  PetscCall(FEMDestroy(&fem));
  PetscCall(PetscFinalize());
  return reason > 0 ? 0 : 2; /* as the conefeti driver: 2 when the solve did not converge */
}
