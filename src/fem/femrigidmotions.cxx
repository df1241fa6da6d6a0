/* The rigid motions of the bodies that nothing resists: FEMComputeFreeRigidMotions() and the frame its motion
   coordinates are given in, FEMComputeRigidMotionFrame().

   A rigid motion r of a body has K r = 0, so only a constraint can resist it. Gluing rows never do (they take the
   difference of two copies of a node, equal on a rigid motion of its body); a Dirichlet condition does, and so
   do the caller's rows (contact normal rows, tangential rows that carry a force). So the query works on the 6
   rigid motions per body (3 translations, 3 rotations about the body's centroid, scaled by its radius L so that
   each moves no node by more than 1) and those constraints directly: the Gram matrix A = C'C of the constraints
   C evaluated on the motions (36 flops per Dirichlet dof and row, no communication beyond gathering the
   Dirichlet dofs), exact on gluing (no roundoff), and the same whatever the decomposition and the number of
   ranks. Its null space, over all bodies at once, holds the free motions, also those of several bodies together
   (two bodies in contact floating together). */
#include <conefeti/private/femimpl.h>
#include <petscblaslapack.h>
#include <algorithm>
#include <cmath>

namespace {

/* Free when the eigenvalue of the body-scaled Gram matrix (each body's diagonal block scaled to a largest
   entry of 1) is below this: roundoff leaves ~1e-16 on a free motion, and the weakest real resistance (a
   rotation held by a row one cell off its axis on a body of 1e4 cells per edge among 1e4 rows) is ~1e-12 */
constexpr PetscReal kFreeTol = 1e-13;
/* entries below this (relative) are roundoff in a motion's coordinates */
constexpr PetscReal kClean = 1e-9;

struct Frame {
  PetscInt         nnodes = 0, offset = 0;
  const PetscReal *X    = nullptr;
  PetscReal        c[3] = {0, 0, 0}, L = 1;
};

PetscErrorCode GetFrame(FEM fem, PetscInt b, Frame &f)
{
  PetscFunctionBegin;
  PetscCall(FEMGetBodyNodes(fem, b, &f.nnodes, &f.X));
  PetscCall(FEMGetBodyNodeOffset(fem, b, &f.offset));
  for (int d = 0; d < 3; d++) f.c[d] = 0;
  for (PetscInt i = 0; i < f.nnodes; i++)
    for (int d = 0; d < 3; d++) f.c[d] += f.X[3 * i + d] / f.nnodes;
  f.L = 0;
  for (PetscInt i = 0; i < f.nnodes; i++) {
    const PetscReal y[3] = {f.X[3 * i] - f.c[0], f.X[3 * i + 1] - f.c[1], f.X[3 * i + 2] - f.c[2]};
    f.L                  = PetscMax(f.L, std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]));
  }
  if (!(f.L > 0)) f.L = 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* d . r_q(x) for the 6 motions q of a body: translations e_q, rotations (e_k x (x - c)) / L */
void RowCoefficients(const Frame &f, const PetscReal x[3], const PetscReal d[3], PetscReal w[6])
{
  const PetscReal y[3] = {x[0] - f.c[0], x[1] - f.c[1], x[2] - f.c[2]};
  for (int q = 0; q < 3; q++) w[q] = d[q];
  /* (e_k x y) . d = e_k . (y x d) */
  w[3] = (y[1] * d[2] - y[2] * d[1]) / f.L;
  w[4] = (y[2] * d[0] - y[0] * d[2]) / f.L;
  w[5] = (y[0] * d[1] - y[1] * d[0]) / f.L;
}

void AddRow(std::vector<PetscReal> &A, PetscInt n, const PetscInt idx[], const PetscReal w[], PetscInt m)
{
  for (PetscInt j = 0; j < m; j++)
    for (PetscInt i = 0; i < m; i++) A[idx[i] + n * idx[j]] += w[i] * w[j];
}

/* Reduced row echelon form of the k x n row-major M (rows: a basis of the free motions): each row gets a 1
   at its own coordinate (translations first) and 0 at the others' (slide along x, slide along y, ...); a
   basis that does not depend on LAPACK's choice inside the null space, and that keeps the motions of bodies
   that nothing couples apart */
void EchelonForm(std::vector<PetscReal> &M, PetscInt k, PetscInt n)
{
  PetscReal mmax = 0;
  for (PetscReal x : M) mmax = PetscMax(mmax, std::fabs(x));
  PetscInt r = 0;
  for (PetscInt col = 0; col < n && r < k; col++) {
    PetscInt p = r;
    for (PetscInt i = r + 1; i < k; i++)
      if (std::fabs(M[i * n + col]) > std::fabs(M[p * n + col])) p = i;
    if (std::fabs(M[p * n + col]) <= 1e-6 * mmax) continue;
    for (PetscInt j = 0; j < n; j++) std::swap(M[r * n + j], M[p * n + j]);
    const PetscReal piv = M[r * n + col];
    for (PetscInt j = 0; j < n; j++) M[r * n + j] /= piv;
    for (PetscInt i = 0; i < k; i++) {
      if (i == r) continue;
      const PetscReal f = M[i * n + col];
      for (PetscInt j = 0; j < n; j++) M[i * n + j] -= f * M[r * n + j];
    }
    r++;
  }
  for (PetscReal &x : M)
    if (std::fabs(x) < kClean) x = 0;
}

} // namespace

/*@C
  FEMComputeRigidMotionFrame - The frame of a body's rigid motion coordinates (`FEMComputeFreeRigidMotions()`):
  its centroid and radius.

  Not Collective

  Input Parameters:
+ fem  - the model, set up
- body - the body

  Output Parameters:
+ centroid - the mean of the body's node coordinates
- radius   - the largest distance of a node from the centroid (1 for a body of one point)

  Notes:
  A body's 6 motion coordinates v describe the rigid displacement u(x) = t + w x (x - c) with t = (v_0, v_1, v_2)
  and w = (v_3, v_4, v_5) / radius: the rotations turn about the centroid c and are scaled so that a unit
  coordinate moves no node by more than 1, like a unit translation.

  Level: intermediate

.seealso: `FEMComputeFreeRigidMotions()`, `FEMGetBodyNodes()`
@*/
PetscErrorCode FEMComputeRigidMotionFrame(FEM fem, PetscInt body, PetscReal centroid[3], PetscReal *radius)
{
  Frame f;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(GetFrame(fem, body, f));
  if (centroid)
    for (int d = 0; d < 3; d++) centroid[d] = f.c[d];
  if (radius) *radius = f.L;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMComputeFreeRigidMotions - The rigid motions of the bodies that neither the Dirichlet conditions nor the
  given rows resist.

  Collective

  Input Parameters:
+ fem   - the model, set up
. nrows - the number of further rows that can hold the bodies (0: the Dirichlet conditions alone)
- rows  - those rows (contact rows, `FEMHoldingRow`), the same on every rank; NULL when nrows is 0

  Output Parameters:
+ nfree   - the number of independent free rigid motions of all bodies together (6 for a body that nothing holds)
- motions - (optional) a basis of them: 6 coordinates per body for each motion, motion j of body b at
            (*motions)[6 * nbodies * j + 6 * b + q] (q = 0, 1, 2: translation along x, y, z; q = 3, 4, 5: rotation
            about x, y, z through the body's centroid, divided by its radius, `FEMComputeRigidMotionFrame()`);
            NULL when nfree is 0, else free it with `PetscFree()`

  Notes:
  A rigid motion of a body has K r = 0, so only a constraint resists it: a Dirichlet dof, whichever
  `FEMDirichletMode` holds it, or one of the rows (gluing never does). A motion that none of them resists is
  free: the stiffness matrix with these constraints is singular along it (`FEMAssembleGlobal()`'s K without
  contact when nrows is 0), and the FETI coarse problem is singular.

  The motions are the null space of the Gram matrix of the constraints evaluated on the 6 rigid motions of every
  body (LAPACK syev on 6 nbodies unknowns, each body's block scaled to a largest diagonal entry of 1, eigenvalues
  below 1e-13 of the largest are free). All bodies are taken together: a row between two bodies lets a motion of
  both together be free where neither is alone. The basis is in reduced row echelon form (each motion has a 1 at
  a coordinate where the others have 0, translations before rotations and body 0 before body 1), entries below
  1e-9 set to 0: a body on rollers under its bottom face gets "translation along x", "translation along y",
  "rotation about z" as its three motions, and bodies that no row couples get motions of one body each. The
  result does not depend on the decomposition or on the number of ranks.

  Level: intermediate

.seealso: `FEMHoldingRow`, `FEMComputeRigidMotionFrame()`, `FEMSetDirichlet()`, `FEMGetGlobalDirichletDofs()`
@*/
PetscErrorCode FEMComputeFreeRigidMotions(FEM fem, PetscInt nrows, const FEMHoldingRow rows[], PetscInt *nfree, PetscReal *motions[])
{
  MPI_Comm           comm = PetscObjectComm((PetscObject)fem);
  PetscInt           nb, ndir;
  IS                 is, all;
  const PetscInt    *idx;
  std::vector<Frame> frames;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscAssertPointer(nfree, 4);
  PetscCheck(nrows >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "nrows %" PetscInt_FMT " < 0", nrows);
  if (nrows) PetscAssertPointer(rows, 3);
  *nfree = 0;
  if (motions) *motions = NULL;
  PetscCall(FEMGetNumBodies(fem, &nb));
  if (!nb) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCallCXX(frames.resize(nb));
  for (PetscInt b = 0; b < nb; b++) PetscCall(GetFrame(fem, b, frames[b]));
  const auto inbody = [&](PetscInt b, PetscInt node) { return b >= 0 && b < nb && node >= 0 && node < frames[b].nnodes; };
  for (PetscInt r = 0; r < nrows; r++) {
    const FEMHoldingRow &h = rows[r];
    PetscCheck(inbody(h.body, h.node), comm, PETSC_ERR_ARG_OUTOFRANGE, "row %" PetscInt_FMT ": no node %" PetscInt_FMT " in body %" PetscInt_FMT, r, h.node, h.body);
    PetscCheck(h.other_body >= -1 && h.other_body < nb, comm, PETSC_ERR_ARG_OUTOFRANGE, "row %" PetscInt_FMT ": other body %" PetscInt_FMT " is neither -1 nor a body", r, h.other_body);
    PetscCheck(h.other_body < 0 || (h.nother >= 1 && h.nother <= 3), comm, PETSC_ERR_ARG_OUTOFRANGE, "row %" PetscInt_FMT ": %" PetscInt_FMT " nodes of the other body, not 1 to 3", r, h.nother);
    for (PetscInt v = 0; h.other_body >= 0 && v < h.nother; v++)
      PetscCheck(inbody(h.other_body, h.other_node[v]), comm, PETSC_ERR_ARG_OUTOFRANGE, "row %" PetscInt_FMT ": no node %" PetscInt_FMT " in body %" PetscInt_FMT, r, h.other_node[v], h.other_body);
  }
  const auto bodyofnode = [&](PetscInt g) {
    for (PetscInt b = 0; b < nb; b++)
      if (g >= frames[b].offset && g < frames[b].offset + frames[b].nnodes) return b;
    return (PetscInt)-1;
  };

  /* the Gram matrix of the constraints on the motions */
  const PetscInt         n = 6 * nb;
  std::vector<PetscReal> A((size_t)n * n, 0.0);
  PetscCall(FEMGetGlobalDirichletDofs(fem, &is));
  PetscCall(ISAllGather(is, &all));
  PetscCall(ISDestroy(&is));
  PetscCall(ISGetLocalSize(all, &ndir));
  PetscCall(ISGetIndices(all, &idx));
  for (PetscInt i = 0; i < ndir; i++) {
    const PetscInt g = idx[i], b = bodyofnode(g / 3);
    PetscCheck(b >= 0, comm, PETSC_ERR_PLIB, "Dirichlet dof %" PetscInt_FMT " belongs to no body", g);
    const Frame &f    = frames[b];
    PetscReal    d[3] = {0, 0, 0}, w[6];
    PetscInt     ix[6];
    d[g % 3] = 1;
    RowCoefficients(f, &f.X[3 * (g / 3 - f.offset)], d, w);
    for (int q = 0; q < 6; q++) ix[q] = 6 * b + q;
    AddRow(A, n, ix, w, 6);
  }
  PetscCall(ISRestoreIndices(all, &idx));
  PetscCall(ISDestroy(&all));
  for (PetscInt r = 0; r < nrows; r++) {
    const FEMHoldingRow &h = rows[r];
    PetscReal            w[12];
    PetscInt             ix[12], m = 6;
    RowCoefficients(frames[h.body], &frames[h.body].X[3 * h.node], h.dir, w);
    for (int q = 0; q < 6; q++) ix[q] = 6 * h.body + q;
    if (h.other_body >= 0) {
      /* the other body's point moves as the weighted sum of its nodes: the row is linear in the node positions */
      const PetscReal minus[3] = {-h.dir[0], -h.dir[1], -h.dir[2]};
      for (int q = 0; q < 6; q++) w[6 + q] = 0;
      for (PetscInt v = 0; v < h.nother; v++) {
        PetscReal wv[6];
        RowCoefficients(frames[h.other_body], &frames[h.other_body].X[3 * h.other_node[v]], minus, wv);
        for (int q = 0; q < 6; q++) w[6 + q] += h.other_weight[v] * wv[q];
      }
      for (int q = 0; q < 6; q++) ix[6 + q] = 6 * h.other_body + q;
      m = 12;
    }
    AddRow(A, n, ix, w, m);
  }

  /* each body's block scaled to a largest diagonal entry of 1: a body held by a million Dirichlet rows
     does not make another's few contact rows look like roundoff */
  std::vector<PetscReal> s(n, 1.0);
  for (PetscInt b = 0; b < nb; b++) {
    PetscReal dmax = 0;
    for (int q = 0; q < 6; q++) dmax = PetscMax(dmax, A[(6 * b + q) * (n + 1)]);
    if (dmax > 0)
      for (int q = 0; q < 6; q++) s[6 * b + q] = 1 / std::sqrt(dmax);
  }
  std::vector<PetscScalar> As((size_t)n * n);
  for (PetscInt j = 0; j < n; j++)
    for (PetscInt i = 0; i < n; i++) As[i + n * j] = s[i] * A[i + n * j] * s[j];
  std::vector<PetscReal> lambda(n);
  {
    PetscBLASInt             bn, lwork = -1, info;
    PetscScalar              wq;
    std::vector<PetscScalar> work;
    PetscCall(PetscBLASIntCast(n, &bn));
    PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "L", &bn, As.data(), &bn, lambda.data(), &wq, &lwork, &info));
    PetscCall(PetscBLASIntCast((PetscInt)PetscRealPart(wq), &lwork));
    PetscCallCXX(work.resize(lwork));
    PetscCallBLAS("LAPACKsyev", LAPACKsyev_("V", "L", &bn, As.data(), &bn, lambda.data(), work.data(), &lwork, &info));
    PetscCheck(info == 0, comm, PETSC_ERR_LIB, "LAPACK syev failed (info %d) on the %" PetscInt_FMT " x %" PetscInt_FMT " Gram matrix of the rigid motions", (int)info, n, n);
  }
  const PetscReal tol = kFreeTol * PetscMax(lambda[n - 1], 1.0);
  PetscInt        k   = 0;
  while (k < n && lambda[k] <= tol) k++; /* ascending */
  PetscCall(PetscInfo(fem, "%" PetscInt_FMT " of the %" PetscInt_FMT " rigid motions of the bodies are free (eigenvalues of the scaled Gram matrix from %g to %g)\n", k, n, (double)lambda[0],
                      (double)lambda[n - 1]));
  *nfree = k;
  if (!k || !motions) PetscFunctionReturn(PETSC_SUCCESS);

  /* the free motions in motion coordinates (unscaled), in echelon form */
  std::vector<PetscReal> M((size_t)k * n);
  for (PetscInt j = 0; j < k; j++)
    for (PetscInt i = 0; i < n; i++) M[j * n + i] = s[i] * PetscRealPart(As[i + n * j]);
  EchelonForm(M, k, n);
  PetscCall(PetscMalloc1((size_t)k * n, motions));
  std::copy(M.begin(), M.end(), *motions);
  PetscFunctionReturn(PETSC_SUCCESS);
}
