/* Tutorial: an existing PETSc finite-element code hands its own subdomain matrices to FETI.

   What it does
     Plays the part of "your FEM code": it meshes a bar (0,L) x (0,1) x (0,1) with hexahedra split into
     tetrahedra, cuts it into slabs along x (the subdomains, spread over the ranks), assembles each
     slab's stiffness matrix K_s and load f_s with its own loops, and builds the constraint matrix B:
     one row per component at every node shared by two neighbouring slabs (u_left - u_right = 0,
     scaled by 1/sqrt(2) so that the rows are orthonormal) and one identity row per component at the
     clamped end x = 0 (Total FETI). Then it gives FETI exactly these pieces:

       FETISetSubdomains(feti, nlocal, K, f)        K_s: SEQAIJ (or SEQSBAIJ), block size 3, x,y,z per node
       FETISetSubdomainCoordinates(feti, s, xyz)     -> the 6 rigid-body modes (or FETISetSubdomainKernel())
       FETISetConstraints(feti, B, c, kinds)         B: MPIAIJ, columns = all slabs' dofs, slab by slab

     and solves. Nothing of conefeti's own mesh layer is used; the element matrix comes from
     FEMElementStiffness() only to keep the file short, any element routine does.

   Sample runs
     mpiexec -n 2 ./feti_ex1_handoff -slabs 4 -feti_ksp_monitor -feti_view
     mpiexec -n 3 ./feti_ex1_handoff -slabs 6 -cells 6 -feti_pc_type lumped -feti_sub_pc_factor_mat_solver_type mumps

   What to expect
     With the default -cells 4 the projected CG converges in 8 iterations with the default (Dirichlet)
     preconditioner for every -slabs from 2 to 16; with -feti_pc_type lumped it takes 13, 14, 15 and 15
     iterations and with -feti_pc_type none 38, 43, 44 and 44 for -slabs 2, 4, 8 and 16 (./feti_ex1_handoff
     -slabs s [-feti_pc_type lumped|none]). The tip deflection printed at the end converges towards the beam
     value as the mesh is refined. A long bar of slabs of one cell (-slabs 1024 -cells 1) has an ill-conditioned coarse
     problem; FETI refines its coarse solves then (-info :feti says how many steps) and CG still takes 8 iterations.
     When the solve does not converge (e.g. -feti_ksp_max_it 2) it says so instead of printing
     a deflection and exits with status 2, as the conefeti driver. */
#include <conefeti.h>

#include <vector>

struct Bar {
  PetscInt  slabs, cells; /* slabs along x, each cells x cells x cells hexahedra */
  PetscReal E, nu, load;  /* load: downward traction on the free end x = L */
};

/* Your element loop: stiffness and load of one slab, with slab-local node numbering i-major as above */
static PetscErrorCode AssembleSlab(const Bar &bar, PetscInt s, Mat *K, Vec *f, Vec *coords)
{
  const PetscInt  nc = bar.cells, nx = nc + 1, nn = nx * nx * nx;
  const PetscReal h     = 1.0 / nc;
  auto            local = [&](PetscInt i, PetscInt j, PetscInt k) { return i + nx * (j + nx * k); };
  PetscScalar    *x, *fa;

  PetscFunctionBeginUser;
  PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, 3 * nn, 3 * nn, 81, NULL, K));
  PetscCall(MatSetBlockSize(*K, 3)); /* FETI needs block size 3, dofs x,y,z per node */
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * nn, f));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * nn, coords));
  PetscCall(VecGetArray(*coords, &x));
  for (PetscInt k = 0; k < nx; k++)
    for (PetscInt j = 0; j < nx; j++)
      for (PetscInt i = 0; i < nx; i++) {
        x[3 * local(i, j, k) + 0] = (s * nc + i) * h;
        x[3 * local(i, j, k) + 1] = j * h;
        x[3 * local(i, j, k) + 2] = k * h;
      }
  /* six tetrahedra per hexahedron along its main diagonal (a conforming split) */
  const PetscInt tets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  for (PetscInt k = 0; k < nc; k++)
    for (PetscInt j = 0; j < nc; j++)
      for (PetscInt i = 0; i < nc; i++)
        for (const auto &t : tets) {
          PetscInt  v[4];
          PetscReal X[12], Ke[144], V;
          for (PetscInt a = 0; a < 4; a++) {
            const PetscInt c = t[a];
            v[a]             = local(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
            for (PetscInt d = 0; d < 3; d++) X[3 * a + d] = PetscRealPart(x[3 * v[a] + d]);
          }
          /* orient positively */
          const PetscReal e1[3] = {X[3] - X[0], X[4] - X[1], X[5] - X[2]}, e2[3] = {X[6] - X[0], X[7] - X[1], X[8] - X[2]}, e3[3] = {X[9] - X[0], X[10] - X[1], X[11] - X[2]};
          const PetscReal det = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) - e1[1] * (e2[0] * e3[2] - e2[2] * e3[0]) + e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
          if (det < 0) {
            std::swap(v[1], v[2]);
            for (PetscInt d = 0; d < 3; d++) std::swap(X[3 + d], X[6 + d]);
          }
          PetscCall(FEMElementStiffness(X, bar.E, bar.nu, Ke, &V));
          PetscCall(MatSetValuesBlocked(*K, 4, v, 4, v, Ke, ADD_VALUES));
        }
  PetscCall(VecRestoreArray(*coords, &x));
  PetscCall(MatAssemblyBegin(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*K, MAT_FINAL_ASSEMBLY));
  /* traction on the free end: lumped to the end face nodes (corner 1/4, edge 1/2, inner 1 of h^2) */
  PetscCall(VecGetArray(*f, &fa));
  if (s == bar.slabs - 1)
    for (PetscInt k = 0; k < nx; k++)
      for (PetscInt j = 0; j < nx; j++) {
        const PetscReal w = (j == 0 || j == nc ? 0.5 : 1.0) * (k == 0 || k == nc ? 0.5 : 1.0);
        fa[3 * local(nc, j, k) + 2] -= bar.load * w * h * h;
      }
  PetscCall(VecRestoreArray(*f, &fa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Bar                      bar = {4, 4, 2.1e11, 0.3, 1e6};
  PetscMPIInt              size, rank;
  PetscInt                 first, nlocal, ndofslab, nlocalrows = 0, firstrow;
  std::vector<Mat>         K;
  std::vector<Vec>         f, coords;
  std::vector<FETIRowKind> kinds;
  Mat                      B;
  FETI                     feti;
  Vec                      lambda, u;
  KSP                      ksp;
  PetscInt                 its;
  KSPConvergedReason       reason;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "FETI from your own subdomain matrices"));
  PetscCall(ConeFETIInitializePackage());
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Bar options", NULL);
  PetscCall(PetscOptionsBoundedInt("-slabs", "Subdomains (slabs along x)", NULL, bar.slabs, &bar.slabs, NULL, 1));
  PetscCall(PetscOptionsBoundedInt("-cells", "Hexahedra per slab side", NULL, bar.cells, &bar.cells, NULL, 1));
  PetscOptionsEnd();
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCheck(bar.slabs >= size, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-slabs %d: need at least one slab per rank (%d ranks)", (int)bar.slabs, size);
  {
    /* all slabs' dofs are numbered by PetscInt (counted in floating point, which does not overflow) */
    const double dofs = 3.0 * bar.slabs * ((double)bar.cells + 1) * ((double)bar.cells + 1) * ((double)bar.cells + 1);
    PetscCheck(dofs <= PETSC_MAX_INT, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-slabs %d -cells %d: %.4g dofs do not fit %d-bit PetscInt indices (at most %d)", (int)bar.slabs, (int)bar.cells,
               dofs, (int)(8 * sizeof(PetscInt)), (int)PETSC_MAX_INT);
  }

  /* 1. subdomains of this rank: contiguous slabs; the primal vector is all slabs' dofs, slab after slab */
  first    = (bar.slabs * rank) / size;
  nlocal   = (bar.slabs * (rank + 1)) / size - first;
  ndofslab = 3 * (bar.cells + 1) * (bar.cells + 1) * (bar.cells + 1);
  K.resize(nlocal);
  f.resize(nlocal);
  coords.resize(nlocal);
  for (PetscInt s = 0; s < nlocal; s++) PetscCall(AssembleSlab(bar, first + s, &K[s], &f[s], &coords[s]));

  /* 2. B: this rank owns the rows of the interfaces to the right of its slabs and, on the first slab, the clamped end */
  const PetscInt nface = (bar.cells + 1) * (bar.cells + 1);
  for (PetscInt s = first; s < first + nlocal; s++) {
    if (s == 0) nlocalrows += 3 * nface;
    if (s < bar.slabs - 1) nlocalrows += 3 * nface;
  }
  PetscCallMPI(MPI_Scan(&nlocalrows, &firstrow, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  firstrow -= nlocalrows;
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, nlocalrows, nlocal * ndofslab, PETSC_DETERMINE, bar.slabs * ndofslab, 2, NULL, 1, NULL, &B));
  {
    PetscInt row = firstrow;
    for (PetscInt s = first; s < first + nlocal; s++) {
      const PetscInt nx = bar.cells + 1;
      for (PetscInt k = 0; k < nx; k++)
        for (PetscInt j = 0; j < nx; j++)
          for (PetscInt c = 0; c < 3; c++) {
            const PetscInt left = s * ndofslab + 3 * (0 + nx * (j + nx * k)) + c; /* node i = 0 of slab s */
            if (s == 0) {                                                         /* clamped end: u = 0 */
              PetscCall(MatSetValue(B, row++, left, 1.0, INSERT_VALUES));
              kinds.push_back(FETI_ROW_DIRICHLET);
            }
            if (s < bar.slabs - 1) { /* glue node i = cells of slab s to node i = 0 of slab s+1 */
              const PetscInt mine = s * ndofslab + 3 * (bar.cells + nx * (j + nx * k)) + c, next = (s + 1) * ndofslab + 3 * (0 + nx * (j + nx * k)) + c;
              PetscCall(MatSetValue(B, row, mine, 1.0 / PetscSqrtReal(2.0), INSERT_VALUES));
              PetscCall(MatSetValue(B, row++, next, -1.0 / PetscSqrtReal(2.0), INSERT_VALUES));
              kinds.push_back(FETI_ROW_GLUING);
            }
          }
    }
  }
  PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));

  /* 3. hand everything to FETI; it keeps references, so release ours (K is then regularized in place) */
  PetscCall(FETICreate(PETSC_COMM_WORLD, &feti));
  PetscCall(FETISetSubdomains(feti, nlocal, K.data(), f.data()));
  for (PetscInt s = 0; s < nlocal; s++) {
    PetscCall(FETISetSubdomainCoordinates(feti, s, coords[s]));
    PetscCall(MatDestroy(&K[s]));
    PetscCall(VecDestroy(&f[s]));
    PetscCall(VecDestroy(&coords[s]));
  }
  PetscCall(FETISetConstraints(feti, B, NULL, kinds.data()));
  PetscCall(MatDestroy(&B));
  PetscCall(FETISetFromOptions(feti));
  PetscCall(FETISetUp(feti));

  /* 4. solve and look at the result: u is in your own slab-by-slab numbering */
  PetscCall(FETICreateVecs(feti, &u, &lambda, NULL));
  PetscCall(FETISolveLinear(feti, lambda, u));
  PetscCall(FETIGetKSP(feti, &ksp));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  if (reason <= 0)
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%d slabs of %d^3 cells: NOT CONVERGED: %s after %d CG iterations\n", (int)bar.slabs, (int)bar.cells, KSPConvergedReasons[reason], (int)its));
  else {
    PetscReal tip = 0;
    PetscInt  lo, hi, nx = bar.cells + 1;
    PetscCall(VecGetOwnershipRange(u, &lo, &hi));
    /* tip node (x = L, y = 0, z = 0): node i = cells, j = k = 0 of the last slab */
    const PetscInt dof = (bar.slabs - 1) * ndofslab + 3 * (bar.cells) + 2;
    (void)nx;
    if (dof >= lo && dof < hi) {
      const PetscScalar *a;
      PetscCall(VecGetArrayRead(u, &a));
      tip = PetscRealPart(a[dof - lo]);
      PetscCall(VecRestoreArrayRead(u, &a));
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &tip, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%d slabs of %d^3 cells: %d CG iterations, tip deflection %.6e m (Euler-Bernoulli: %.6e m)\n", (int)bar.slabs, (int)bar.cells, (int)its, (double)tip,
                          (double)(-bar.load * 4.0 * PetscPowReal((PetscReal)bar.slabs, 3) / (bar.E))));
  }
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&lambda));
  PetscCall(FETIDestroy(&feti));
  PetscCall(PetscFinalize());
  return reason > 0 ? 0 : 2;
}
