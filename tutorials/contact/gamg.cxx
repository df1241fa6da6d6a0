/* gamg: the linear elasticity problem of a scene's mesh solved by CG + GAMG, the yardstick of scripts/bench-scale.py.

   The scene is read from the same options as the conefeti driver (-options_file petsc-options/brick.opts,
   -scene_refine k, -scene_body0_subdomains ...). ContactSceneSetUpFEM() builds its FEM only (meshes, supports,
   loads; no FETI operator), FEMAssembleGlobal() assembles the undecomposed stiffness K and load f (Dirichlet rows
   and columns as identity), and CG with GAMG and the rigid-body near-null space (from the node coordinates) solves
   K u = f to a relative residual of 1e-8 (-gamg_ksp_rtol; every -gamg_ksp_* and -gamg_pc_* option applies).

   The contact zones are ignored: no contact row, no foundation, the zone's face is free. So this is the linear
   elasticity problem the contact solve starts from, the same mesh and the same supports and loads; a scene whose
   bodies are held only by contact has no such problem: a body without any Dirichlet support ends the run with an
   error naming the body (twobodies.opts, stack.opts), and so does a body supported only in part (rollers that
   leave it a rigid motion, as stack.opts's slab), where K would be singular and CG's answer meaningless.
   The subdomain options are read (they must be valid) but do not matter here.

   Sample runs (from the repository root):
     build/tutorials/contact/gamg -options_file petsc-options/brick.opts -scene_refine 12
     mpiexec -n 2 build/tutorials/contact/gamg -options_file petsc-options/brick.opts -scene_refine 30 -gamg_ksp_monitor -log_view

   Output: one JSON line starting with {"gamg": with
     scene, ranks, n (unknowns without the Dirichlet dofs: the driver's n), n_global (with them), iter, converged,
     reason, residual (|f - K u| / |f|, recomputed), time_mesh (ContactSceneSetUpFEM()), time_assembly (K, f, the
     near-null space), time_setup (KSPSetUp(): the GAMG hierarchy), time_solve (KSPSolve()), time (their sum: from
     the options to the solution, as the driver's time_setup + time_solve), peak_rss (bytes, peak resident set
     size summed over the ranks, getrusage()), peak_rss_rank (the largest rank's) and bytes_per_unknown
     (peak_rss / n).
   Exit status: 0 when CG converged, 2 when it did not, as the conefeti driver; PETSc's error code for bad input. */
#include <conefeti.h>
#include <sys/resource.h>
#include <vector>

namespace {

/* peak resident set size of this process in bytes */
PetscLogDouble PeakRSS()
{
  struct rusage ru;
  if (getrusage(RUSAGE_SELF, &ru)) return 0;
  return 1024.0 * (PetscLogDouble)ru.ru_maxrss;
}

/* The contact zones are ignored, so only the Dirichlet supports hold the bodies: a body without any, or whose
   supports leave it a rigid motion (rollers on one side only), makes K singular and CG's answer meaningless.
   FEMComputeFreeRigidMotions() without further rows gives the motions no Dirichlet dof resists; no row couples the
   bodies, so each motion of its basis moves one body. A body that no Dirichlet dof holds has all 6 free (any dof
   holds the translation along its component). The conefeti driver's check (ContactModelSetUp()) also counts the
   contact zones and names the motions. */
PetscErrorCode CheckBodiesHeld(FEM fem)
{
  MPI_Comm   comm = PetscObjectComm((PetscObject)fem);
  PetscInt   nbodies, nfree;
  PetscReal *motions;

  PetscFunctionBegin;
  PetscCall(FEMGetNumBodies(fem, &nbodies));
  PetscCall(FEMComputeFreeRigidMotions(fem, 0, NULL, &nfree, &motions));
  std::vector<PetscInt> count(nbodies, 0);
  for (PetscInt j = 0; j < nfree; j++)
    for (PetscInt b = 0; b < nbodies; b++) {
      bool moves = false;
      for (int q = 0; q < 6; q++) moves = moves || motions[6 * nbodies * j + 6 * b + q] != 0;
      if (moves) {
        count[b]++;
        break;
      }
    }
  PetscCall(PetscFree(motions));
  for (PetscInt b = 0; b < nbodies; b++)
    PetscCheck(count[b] < 6, comm, PETSC_ERR_ARG_WRONG,
               "gamg: body %" PetscInt_FMT " has no Dirichlet support (-scene_body%" PetscInt_FMT "_fix): it is held only by contact, which this program ignores, so K is singular", b, b);
  for (PetscInt b = 0; b < nbodies; b++)
    PetscCheck(!count[b], comm, PETSC_ERR_ARG_WRONG,
               "gamg: the Dirichlet supports of body %" PetscInt_FMT " leave it %" PetscInt_FMT
               " free rigid motion%s (rollers on too few faces?): without its contact zones, which this program ignores, K is singular (the conefeti program names the motions)",
               b, count[b], count[b] > 1 ? "s" : "");
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode Main(int *status)
{
  MPI_Comm           comm = PETSC_COMM_WORLD;
  ContactScene       scene;
  FEM                fem;
  Mat                K;
  Vec                f, u, r, coords;
  IS                 dirichlet;
  MatNullSpace       nearnull;
  KSP                ksp;
  PC                 pc;
  PetscInt           nglobal, ndirichlet, its;
  PetscReal          fnorm, rnorm;
  PetscLogDouble     t0, t1, tmesh, tassembly, tsetup, tsolve, rss[2];
  PetscMPIInt        size;
  PetscBool          hasbody, help;
  const char        *name;
  KSPConvergedReason reason;

  PetscFunctionBegin;
  *status = 0;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(ContactSceneCreateFromOptions(comm, NULL, &scene));
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-scene_body0_cells", &hasbody));
  if (!hasbody) PetscCall(PetscOptionsHasName(NULL, NULL, "-scene_body0_mesh", &hasbody));
  PetscCheck(hasbody || help, comm, PETSC_ERR_ARG_WRONG, "gamg: no scene given; run with -options_file petsc-options/brick.opts (docs/scenes.md)");
  if (!hasbody) {
    PetscCall(ContactSceneDestroy(&scene));
    PetscFunctionReturn(PETSC_SUCCESS);
  }

  PetscCall(PetscTime(&t0));
  PetscCall(ContactSceneSetUpFEM(scene));
  PetscCall(ContactSceneGetFEM(scene, &fem));
  PetscCall(PetscTime(&t1));
  tmesh = t1 - t0;

  t0 = t1;
  PetscCall(FEMAssembleGlobal(fem, &K, &f));
  PetscCall(FEMGetGlobalDirichletDofs(fem, &dirichlet));
  PetscCall(ISGetSize(dirichlet, &ndirichlet));
  /* the contact zones are ignored, so only the Dirichlet supports hold the bodies: every body needs them */
  PetscCheck(ndirichlet > 0, comm, PETSC_ERR_ARG_WRONG, "gamg: the scene has no Dirichlet support (-scene_body<b>_fix): without its contact zones, which this program ignores, K is singular");
  PetscCall(CheckBodiesHeld(fem));
  PetscCall(FEMCreateGlobalCoordinates(fem, &coords));
  PetscCall(ISDestroy(&dirichlet));
  PetscCall(MatNullSpaceCreateRigidBody(coords, &nearnull));
  PetscCall(MatSetNearNullSpace(K, nearnull));
  PetscCall(MatNullSpaceDestroy(&nearnull));
  PetscCall(VecDestroy(&coords));
  PetscCall(PetscTime(&t1));
  tassembly = t1 - t0;

  PetscCall(KSPCreate(comm, &ksp));
  PetscCall(KSPSetOptionsPrefix(ksp, "gamg_"));
  PetscCall(KSPSetOperators(ksp, K, K));
  PetscCall(KSPSetType(ksp, KSPCG));
  PetscCall(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
  PetscCall(KSPSetTolerances(ksp, 1e-8, PETSC_DEFAULT, PETSC_DEFAULT, 10000));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCGAMG));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCall(VecDuplicate(f, &u));
  PetscCall(PetscTime(&t0));
  PetscCall(KSPSetUp(ksp));
  PetscCall(PetscTime(&t1));
  tsetup = t1 - t0;
  t0     = t1;
  PetscCall(KSPSolve(ksp, f, u));
  PetscCall(PetscTime(&t1));
  tsolve = t1 - t0;
  PetscCall(KSPGetIterationNumber(ksp, &its));
  PetscCall(KSPGetConvergedReason(ksp, &reason));

  /* the residual recomputed, not the KSP's recurrence */
  PetscCall(VecDuplicate(f, &r));
  PetscCall(MatMult(K, u, r));
  PetscCall(VecAYPX(r, -1.0, f));
  PetscCall(VecNorm(r, NORM_2, &rnorm));
  PetscCall(VecNorm(f, NORM_2, &fnorm));
  PetscCall(VecGetSize(f, &nglobal));

  rss[0] = rss[1] = PeakRSS();
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &rss[0], 1, MPIU_PETSCLOGDOUBLE, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &rss[1], 1, MPIU_PETSCLOGDOUBLE, MPI_MAX, comm));
  PetscCall(ContactSceneGetName(scene, &name));
  {
    const PetscInt n = nglobal - ndirichlet;
    PetscCall(PetscPrintf(comm,
                          "{\"gamg\": \"cg+gamg\", \"scene\": \"%s\", \"ranks\": %d, \"n\": %" PetscInt_FMT ", \"n_global\": %" PetscInt_FMT ", \"iter\": %" PetscInt_FMT
                          ", \"converged\": %s, \"reason\": \"%s\", \"residual\": %.6e, \"time_mesh\": %.4f, \"time_assembly\": %.4f, \"time_setup\": %.4f, \"time_solve\": %.4f, "
                          "\"time\": %.4f, \"peak_rss\": %.0f, \"peak_rss_rank\": %.0f, \"bytes_per_unknown\": %.1f}\n",
                          name, (int)size, n, nglobal, its, reason > 0 ? "true" : "false", KSPConvergedReasons[reason], (double)(fnorm > 0 ? rnorm / fnorm : rnorm), (double)tmesh, (double)tassembly,
                          (double)tsetup, (double)tsolve, (double)(tmesh + tassembly + tsetup + tsolve), (double)rss[0], (double)rss[1], (double)(n > 0 ? rss[0] / n : 0)));
  }
  *status = reason > 0 ? 0 : 2;
  PetscCall(VecDestroy(&r));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&f));
  PetscCall(MatDestroy(&K));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(ContactSceneDestroy(&scene));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

int main(int argc, char **argv)
{
  int status = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "gamg: a scene's linear elasticity problem (contact zones ignored) by CG + GAMG (tutorials/contact/gamg.cxx)\n"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(Main(&status));
  PetscCall(PetscFinalize());
  return status;
}
