/* The "user FEM code" of the hand-over error tests (feti_handoff_errors.cxx): the bar of tutorials/feti/ex1_handoff.cxx
   cut into slabs, with the user's own K_s, f_s, coordinates, B and row kinds, plus an independent check of the answer. */
#pragma once
#include <conefeti.h>
#include <vector>
#include <cstring>

struct Problem {
  PetscInt                 slabs = 2, cells = 2, first = 0, nlocal = 0, ndofslab = 0;
  PetscReal                E = 2.1e11, nu = 0.3, load = 1e6;
  std::vector<Mat>         K, Kref; /* Kref: a copy kept by the "user" to check the answer */
  std::vector<Vec>         f, fref, coords;
  Mat                      B = NULL;
  std::vector<FETIRowKind> kinds;
  PetscBool                allOnRank0 = PETSC_FALSE; /* every slab on rank 0, none elsewhere */
  PetscBool                unclamped  = PETSC_FALSE; /* no Dirichlet rows at x = 0: a bar that nothing holds */
};

static PetscErrorCode AssembleSlab(Problem &p, PetscInt s, MatType type, Mat *K, Vec *f, Vec *coords)
{
  const PetscInt  nc = p.cells, nx = nc + 1, nn = nx * nx * nx;
  const PetscReal h     = 1.0 / nc;
  auto            local = [&](PetscInt i, PetscInt j, PetscInt k) { return i + nx * (j + nx * k); };
  PetscScalar    *x, *fa;

  PetscFunctionBeginUser;
  PetscCall(MatCreate(PETSC_COMM_SELF, K));
  PetscCall(MatSetSizes(*K, 3 * nn, 3 * nn, 3 * nn, 3 * nn));
  PetscCall(MatSetBlockSize(*K, 3));
  PetscCall(MatSetType(*K, type));
  PetscCall(MatSeqAIJSetPreallocation(*K, 81, NULL));
  PetscCall(MatSeqSBAIJSetPreallocation(*K, 3, 27, NULL));
  PetscCall(MatSeqBAIJSetPreallocation(*K, 3, 27, NULL));
  if (!strcmp(type, MATSEQSBAIJ)) PetscCall(MatSetOption(*K, MAT_IGNORE_LOWER_TRIANGULAR, PETSC_TRUE));
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
          const PetscReal e1[3] = {X[3] - X[0], X[4] - X[1], X[5] - X[2]}, e2[3] = {X[6] - X[0], X[7] - X[1], X[8] - X[2]}, e3[3] = {X[9] - X[0], X[10] - X[1], X[11] - X[2]};
          const PetscReal det = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) - e1[1] * (e2[0] * e3[2] - e2[2] * e3[0]) + e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
          if (det < 0) {
            std::swap(v[1], v[2]);
            for (PetscInt d = 0; d < 3; d++) std::swap(X[3 + d], X[6 + d]);
          }
          PetscCall(FEMElementStiffness(X, p.E, p.nu, Ke, &V));
          PetscCall(MatSetValuesBlocked(*K, 4, v, 4, v, Ke, ADD_VALUES));
        }
  PetscCall(VecRestoreArray(*coords, &x));
  PetscCall(MatAssemblyBegin(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(VecGetArray(*f, &fa));
  if (s == p.slabs - 1)
    for (PetscInt k = 0; k < nx; k++)
      for (PetscInt j = 0; j < nx; j++) {
        const PetscReal w = (j == 0 || j == nc ? 0.5 : 1.0) * (k == 0 || k == nc ? 0.5 : 1.0);
        fa[3 * local(nc, j, k) + 2] -= p.load * w * h * h;
      }
  PetscCall(VecRestoreArray(*f, &fa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* K, f, coords of this rank's slabs and B (Total FETI: clamped at x = 0, Helmert gluing between slabs) */
static PetscErrorCode BuildBar(Problem &p, MatType type = MATSEQAIJ)
{
  PetscMPIInt size, rank;
  PetscInt    nlocalrows = 0, firstrow;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  p.first  = (p.slabs * rank) / size;
  p.nlocal = (p.slabs * (rank + 1)) / size - p.first;
  if (p.allOnRank0) {
    p.first  = rank ? p.slabs : 0;
    p.nlocal = rank ? 0 : p.slabs;
  }
  p.ndofslab = 3 * (p.cells + 1) * (p.cells + 1) * (p.cells + 1);
  p.K.resize(p.nlocal);
  p.Kref.resize(p.nlocal);
  p.f.resize(p.nlocal);
  p.fref.resize(p.nlocal);
  p.coords.resize(p.nlocal);
  for (PetscInt s = 0; s < p.nlocal; s++) {
    PetscCall(AssembleSlab(p, p.first + s, type, &p.K[s], &p.f[s], &p.coords[s]));
    PetscCall(MatDuplicate(p.K[s], MAT_COPY_VALUES, &p.Kref[s]));
    PetscCall(VecDuplicate(p.f[s], &p.fref[s]));
    PetscCall(VecCopy(p.f[s], p.fref[s]));
  }
  const PetscInt nface = (p.cells + 1) * (p.cells + 1);
  for (PetscInt s = p.first; s < p.first + p.nlocal; s++) {
    if (s == 0 && !p.unclamped) nlocalrows += 3 * nface;
    if (s < p.slabs - 1) nlocalrows += 3 * nface;
  }
  PetscCallMPI(MPI_Scan(&nlocalrows, &firstrow, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  firstrow -= nlocalrows;
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, nlocalrows, p.nlocal * p.ndofslab, PETSC_DETERMINE, p.slabs * p.ndofslab, 2, NULL, 1, NULL, &p.B));
  PetscInt row = firstrow;
  for (PetscInt s = p.first; s < p.first + p.nlocal; s++) {
    const PetscInt nx = p.cells + 1;
    for (PetscInt k = 0; k < nx; k++)
      for (PetscInt j = 0; j < nx; j++)
        for (PetscInt c = 0; c < 3; c++) {
          const PetscInt left = s * p.ndofslab + 3 * (0 + nx * (j + nx * k)) + c;
          if (s == 0 && !p.unclamped) {
            PetscCall(MatSetValue(p.B, row++, left, 1.0, INSERT_VALUES));
            p.kinds.push_back(FETI_ROW_DIRICHLET);
          }
          if (s < p.slabs - 1) {
            const PetscInt mine = s * p.ndofslab + 3 * (p.cells + nx * (j + nx * k)) + c, next = (s + 1) * p.ndofslab + 3 * (0 + nx * (j + nx * k)) + c;
            PetscCall(MatSetValue(p.B, row, mine, 1.0 / PetscSqrtReal(2.0), INSERT_VALUES));
            PetscCall(MatSetValue(p.B, row++, next, -1.0 / PetscSqrtReal(2.0), INSERT_VALUES));
            p.kinds.push_back(FETI_ROW_GLUING);
          }
        }
  }
  PetscCall(MatAssemblyBegin(p.B, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(p.B, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode DestroyBar(Problem &p)
{
  PetscFunctionBeginUser;
  for (auto &A : p.K) PetscCall(MatDestroy(&A));
  for (auto &A : p.Kref) PetscCall(MatDestroy(&A));
  for (auto &v : p.f) PetscCall(VecDestroy(&v));
  for (auto &v : p.fref) PetscCall(VecDestroy(&v));
  for (auto &v : p.coords) PetscCall(VecDestroy(&v));
  PetscCall(MatDestroy(&p.B));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Independent check with the user's own copies: ||B u|| / ||u||, equilibrium ||K u - f + B'l|| / ||f||, tip deflection */
static PetscErrorCode CheckAnswer(Problem &p, Mat B, Vec lambda, Vec u, const char *label)
{
  Vec                Bu, Btl;
  PetscReal          nBu, nu, req = 0, nf = 0, tip = 0;
  PetscInt           lo, hi;
  const PetscScalar *ua, *ba;

  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(B, &Btl, &Bu));
  PetscCall(MatMult(B, u, Bu));
  PetscCall(VecNorm(Bu, NORM_2, &nBu));
  PetscCall(VecNorm(u, NORM_2, &nu));
  PetscCall(MatMultTranspose(B, lambda, Btl));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(Btl, &ba));
  PetscInt off = 0;
  for (PetscInt s = 0; s < (PetscInt)p.Kref.size(); s++) {
    Vec      us, rs;
    PetscInt n;
    PetscCall(MatGetSize(p.Kref[s], &n, NULL));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &us));
    PetscCall(VecDuplicate(us, &rs));
    PetscScalar *a;
    PetscCall(VecGetArray(us, &a));
    for (PetscInt i = 0; i < n; i++) a[i] = ua[off + i];
    PetscCall(VecRestoreArray(us, &a));
    PetscCall(MatMult(p.Kref[s], us, rs));
    PetscCall(VecAXPY(rs, -1.0, p.fref[s]));
    PetscCall(VecGetArray(rs, &a));
    for (PetscInt i = 0; i < n; i++) a[i] += ba[off + i];
    PetscCall(VecRestoreArray(rs, &a));
    PetscReal r, fn;
    PetscCall(VecNorm(rs, NORM_2, &r));
    PetscCall(VecNorm(p.fref[s], NORM_2, &fn));
    req += r * r;
    nf += fn * fn;
    PetscCall(VecDestroy(&us));
    PetscCall(VecDestroy(&rs));
    off += n;
  }
  PetscCall(VecRestoreArrayRead(Btl, &ba));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &req, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nf, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscCall(VecGetOwnershipRange(u, &lo, &hi));
  const PetscInt dof = (p.slabs - 1) * p.ndofslab + 3 * p.cells + 2;
  if (dof >= lo && dof < hi) tip = PetscRealPart(ua[dof - lo]);
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &tip, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "[check %s] ||Bu||/||u|| = %.3e  ||K u - f + B'l||/||f|| = %.3e  tip = %.6e\n", label, (double)(nu > 0 ? nBu / nu : nBu),
                        (double)(nf > 0 ? PetscSqrtReal(req / nf) : PetscSqrtReal(req)), (double)tip));
  PetscCall(VecDestroy(&Bu));
  PetscCall(VecDestroy(&Btl));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* solve, print the KSP's verdict the way ex1 does, and check the answer independently */
static PetscErrorCode SolveAndReport(Problem &p, FETI feti, const char *label, KSPConvergedReason *reasonout = NULL)
{
  Vec                lambda, u;
  KSP                ksp;
  PetscInt           its;
  KSPConvergedReason reason;
  Mat                B;

  PetscFunctionBeginUser;
  PetscCall(FETICreateVecs(feti, &u, &lambda, NULL));
  PetscCall(FETISolveLinear(feti, lambda, u));
  PetscCall(FETIGetKSP(feti, &ksp));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "[%s] KSP reason %s (%d) after %d iterations\n", label, KSPConvergedReasons[reason], (int)reason, (int)its));
  PetscCall(FETIGetConstraints(feti, &B, NULL, NULL));
  PetscCall(CheckAnswer(p, B, lambda, u, label));
  if (reasonout) *reasonout = reason;
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&lambda));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* hand the problem over as ex1 does (coordinates for every subdomain), keeping the user's references if keep */
static PetscErrorCode HandOver(Problem &p, FETI *feti, PetscBool keep = PETSC_FALSE)
{
  PetscFunctionBeginUser;
  PetscCall(FETICreate(PETSC_COMM_WORLD, feti));
  PetscCall(FETISetSubdomains(*feti, p.nlocal, p.K.data(), p.f.data()));
  for (PetscInt s = 0; s < p.nlocal; s++) PetscCall(FETISetSubdomainCoordinates(*feti, s, p.coords[s]));
  PetscCall(FETISetConstraints(*feti, p.B, NULL, p.kinds.data()));
  if (!keep)
    for (PetscInt s = 0; s < p.nlocal; s++) PetscCall(MatDestroy(&p.K[s]));
  PetscCall(FETISetFromOptions(*feti));
  PetscFunctionReturn(PETSC_SUCCESS);
}
