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

/* A body whose Dirichlet supports leave it a rigid motion (rollers on one side only) makes K singular: CG's answer
   would be meaningless. Its free motions are the null space of the 6 x 6 Gram matrix of its rigid-body modes
   (translations, rotations about its centroid scaled by its radius) at its Dirichlet dofs: a motion that no
   Dirichlet dof sees is free, as K r = 0 away from them. The conefeti driver's check names the motions and also
   counts the contact zones. */
PetscErrorCode CheckFreeRigidMotions(FEM fem, IS dirichlet, Vec coords)
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)fem);
  PetscInt           nbodies, nlocal, cstart;
  const PetscInt    *dofs;
  const PetscScalar *x;

  PetscFunctionBegin;
  PetscCall(FEMGetNumBodies(fem, &nbodies));
  std::vector<PetscInt>  first(nbodies), count(nbodies);
  std::vector<PetscReal> frame(5 * nbodies, 0), gram(36 * nbodies, 0); /* per body: centroid sums, node count, radius */
  for (PetscInt b = 0; b < nbodies; b++) {
    PetscCall(FEMGetBodyNodeOffset(fem, b, &first[b]));
    PetscCall(FEMGetBodyNodes(fem, b, &count[b], NULL));
  }
  const auto bodyof = [&](PetscInt node) {
    for (PetscInt b = 0; b < nbodies; b++)
      if (node >= first[b] && node < first[b] + count[b]) return b;
    return (PetscInt)-1;
  };
  PetscCall(VecGetOwnershipRange(coords, &cstart, NULL));
  PetscCall(VecGetLocalSize(coords, &nlocal));
  PetscCall(VecGetArrayRead(coords, &x));
  for (PetscInt i = 0; i < nlocal / 3; i++) {
    const PetscInt b = bodyof(cstart / 3 + i);
    if (b < 0) continue;
    for (int c = 0; c < 3; c++) frame[5 * b + c] += PetscRealPart(x[3 * i + c]);
    frame[5 * b + 3] += 1;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, frame.data(), (PetscMPIInt)frame.size(), MPIU_REAL, MPIU_SUM, comm));
  for (PetscInt b = 0; b < nbodies; b++)
    for (int c = 0; c < 3; c++) frame[5 * b + c] /= PetscMax(frame[5 * b + 3], 1.0);
  for (PetscInt i = 0; i < nlocal / 3; i++) {
    const PetscInt b = bodyof(cstart / 3 + i);
    if (b < 0) continue;
    for (int c = 0; c < 3; c++) frame[5 * b + 4] = PetscMax(frame[5 * b + 4], PetscAbsReal(PetscRealPart(x[3 * i + c]) - frame[5 * b + c]));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, frame.data(), (PetscMPIInt)frame.size(), MPIU_REAL, MPIU_MAX, comm)); /* only the radii change: the rest is equal on every rank */
  PetscCall(ISGetLocalSize(dirichlet, &nlocal));
  PetscCall(ISGetIndices(dirichlet, &dofs));
  for (PetscInt i = 0; i < nlocal; i++) {
    const PetscInt  node = dofs[i] / 3, c = dofs[i] % 3, b = bodyof(node);
    const PetscReal L = PetscMax(frame[5 * b + 4], PETSC_SMALL);
    PetscReal       y[3], w[6] = {0, 0, 0, 0, 0, 0};
    if (b < 0) continue;
    for (int k = 0; k < 3; k++) y[k] = PetscRealPart(x[dofs[i] - c - cstart + k]) - frame[5 * b + k];
    w[c] = 1; /* the translation along c; the rotation about axis k moves the node by e_k x y */
    w[3] = c == 1 ? -y[2] / L : c == 2 ? y[1] / L : 0;
    w[4] = c == 0 ? y[2] / L : c == 2 ? -y[0] / L : 0;
    w[5] = c == 0 ? -y[1] / L : c == 1 ? y[0] / L : 0;
    for (int p = 0; p < 6; p++)
      for (int q = 0; q < 6; q++) gram[36 * b + 6 * p + q] += w[p] * w[q];
  }
  PetscCall(ISRestoreIndices(dirichlet, &dofs));
  PetscCall(VecRestoreArrayRead(coords, &x));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, gram.data(), (PetscMPIInt)gram.size(), MPIU_REAL, MPIU_SUM, comm));
  for (PetscInt b = 0; b < nbodies; b++) {
    PetscReal *A = &gram[36 * b], amax = 0;
    PetscInt   nfree   = 6;
    bool       used[6] = {false, false, false, false, false, false};
    for (int p = 0; p < 6; p++) amax = PetscMax(amax, A[7 * p]);
    if (amax <= 0) continue; /* no Dirichlet dof: Main() names the body */
    /* its rank by Cholesky with diagonal pivoting: each pivot above roundoff is one motion held */
    for (int step = 0; step < 6; step++) {
      int j = -1;
      for (int p = 0; p < 6; p++)
        if (!used[p] && (j < 0 || A[7 * p] > A[7 * j])) j = p;
      if (A[7 * j] <= 1e-12 * amax) break;
      used[j] = true;
      nfree--;
      for (int p = 0; p < 6; p++)
        for (int q = 0; q < 6; q++)
          if (!used[p] && !used[q]) A[6 * p + q] -= A[6 * p + j] * A[6 * j + q] / A[7 * j];
    }
    PetscCheck(!nfree, comm, PETSC_ERR_ARG_WRONG,
               "gamg: the Dirichlet supports of body %" PetscInt_FMT " leave it %" PetscInt_FMT
               " free rigid motion%s (rollers on too few faces?): without its contact zones, which this program ignores, K is singular (the conefeti program names the motions)",
               b, nfree, nfree > 1 ? "s" : "");
  }
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
  /* the contact zones are ignored, so only the Dirichlet supports hold the bodies: every body needs one */
  PetscCheck(ndirichlet > 0, comm, PETSC_ERR_ARG_WRONG, "gamg: the scene has no Dirichlet support (-scene_body<b>_fix): without its contact zones, which this program ignores, K is singular");
  {
    PetscInt        nbodies, nlocal;
    const PetscInt *dofs;
    PetscCall(FEMGetNumBodies(fem, &nbodies));
    std::vector<PetscInt> held(nbodies, 0), first(nbodies, 0), count(nbodies, 0);
    for (PetscInt b = 0; b < nbodies; b++) {
      PetscCall(FEMGetBodyNodeOffset(fem, b, &first[b]));
      PetscCall(FEMGetBodyNodes(fem, b, &count[b], NULL));
    }
    PetscCall(ISGetLocalSize(dirichlet, &nlocal));
    PetscCall(ISGetIndices(dirichlet, &dofs));
    for (PetscInt i = 0; i < nlocal; i++)
      for (PetscInt b = 0; b < nbodies; b++)
        if (dofs[i] / 3 >= first[b] && dofs[i] / 3 < first[b] + count[b]) held[b] = 1;
    PetscCall(ISRestoreIndices(dirichlet, &dofs));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, held.data(), (PetscMPIInt)nbodies, MPIU_INT, MPI_MAX, comm));
    for (PetscInt b = 0; b < nbodies; b++)
      PetscCheck(held[b], comm, PETSC_ERR_ARG_WRONG,
                 "gamg: body %" PetscInt_FMT " has no Dirichlet support (-scene_body%" PetscInt_FMT "_fix): it is held only by contact, which this program ignores, so K is singular", b, b);
  }
  PetscCall(FEMCreateGlobalCoordinates(fem, &coords));
  PetscCall(CheckFreeRigidMotions(fem, dirichlet, coords));
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
