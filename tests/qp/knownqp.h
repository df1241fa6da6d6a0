/* Quadratic programs with known solutions, for tests.

   A = Q D Q' with Q a product of Householder reflections and D log-spaced in [scale/cond, scale];
   a solution x*, its active set and the multipliers are chosen block by block, and b is built so
   that the KKT conditions hold exactly: A x* - b = -n with n in the normal cone of the set at x*
   (plus C'mu* when there is an equality C x = d). The generator is deterministic and independent
   of the number of MPI ranks, so runs on 1, 2, 3 ranks solve the same problem, and by default A is
   a shell whose products are bitwise the same on any number of ranks. */
#pragma once

#include <conefeti.h>
#include <conefeti/compat.h>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

/* splitmix64: small, deterministic, the same on every rank */
struct TestRandom {
  uint64_t state;
  explicit TestRandom(uint64_t seed) : state(seed) {}
  double uniform()
  {
    uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z          = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z          = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return (double)(z >> 11) / 9007199254740992.0;
  }
  double range(double a, double b) { return a + (b - a) * uniform(); }
};

/* Block states; each kind of problem cycles through a list of them. */
enum class BlockState {
  FREE,
  LOWER_ACTIVE,
  UPPER_ACTIVE,
  BOX_INTERIOR,
  LOWER_DEGENERATE, /* on the bound with zero multiplier */
  PINNED,           /* l = u */
  DISK_INTERIOR,
  DISK_ACTIVE,
  DISK_DEGENERATE, /* on the circle with zero multiplier */
  DISK_RADIUS0,
  CONE_INTERIOR,
  CONE_ACTIVE,
  CONE_DEGENERATE,
  CONE_APEX,
  CONE_MU0 /* half-line: tangential pinned, normal at its bound */
};

/* The matrix as a shell whose product sums every row in the same order on any number of ranks
   (a dense BLAS product changes its summation order with the local size), so that runs on 1, 2, 3
   ranks see bitwise the same products and the solver's rank independence can be tested exactly. */
struct RowOrderedDense {
  std::vector<double> rows; /* local rows, row-major */
  PetscInt            nlocal = 0, N = 0;
  VecScatter          toall = nullptr;
  Vec                 xall  = nullptr;
};

static inline PetscErrorCode RowOrderedMult(Mat M, Vec x, Vec y)
{
  RowOrderedDense   *d;
  const PetscScalar *xa;
  PetscScalar       *ya;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(M, &d));
  PetscCall(VecScatterBegin(d->toall, x, d->xall, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(d->toall, x, d->xall, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(d->xall, &xa));
  PetscCall(VecGetArrayWrite(y, &ya));
  for (PetscInt i = 0; i < d->nlocal; i++) {
    double s = 0;
    for (PetscInt j = 0; j < d->N; j++) s += d->rows[i * d->N + j] * PetscRealPart(xa[j]);
    ya[i] = s;
  }
  PetscCall(VecRestoreArrayRead(d->xall, &xa));
  PetscCall(VecRestoreArrayWrite(y, &ya));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the diagonal, for PCJACOBI (preconditioning in face) */
static inline PetscErrorCode RowOrderedGetDiagonal(Mat M, Vec v)
{
  RowOrderedDense *d;
  PetscScalar     *va;
  PetscInt         rstart;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(M, &d));
  PetscCall(MatGetOwnershipRange(M, &rstart, NULL));
  PetscCall(VecGetArrayWrite(v, &va));
  for (PetscInt i = 0; i < d->nlocal; i++) va[i] = d->rows[i * d->N + rstart + i];
  PetscCall(VecRestoreArrayWrite(v, &va));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode RowOrderedDestroy(Mat M)
{
  RowOrderedDense *d;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(M, &d));
  PetscCall(VecScatterDestroy(&d->toall));
  PetscCall(VecDestroy(&d->xall));
  delete d;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* C x = d with C stored whole on every rank, products in a fixed order (see RowOrderedDense) */
struct OrderedRows {
  std::vector<double> C; /* m x N, row-major, all rows */
  PetscInt            m = 0, N = 0, mstart = 0, mlocal = 0, nstart = 0, nlocal = 0;
  VecScatter          xall = nullptr, yall = nullptr;
  Vec                 xa = nullptr, ya = nullptr;
};

static inline PetscErrorCode OrderedRowsMult(Mat M, Vec x, Vec y)
{
  OrderedRows       *d;
  const PetscScalar *xa;
  PetscScalar       *ya;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(M, &d));
  PetscCall(VecScatterBegin(d->xall, x, d->xa, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(d->xall, x, d->xa, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(d->xa, &xa));
  PetscCall(VecGetArrayWrite(y, &ya));
  for (PetscInt r = 0; r < d->mlocal; r++) {
    double s = 0;
    for (PetscInt j = 0; j < d->N; j++) s += d->C[(d->mstart + r) * d->N + j] * PetscRealPart(xa[j]);
    ya[r] = s;
  }
  PetscCall(VecRestoreArrayRead(d->xa, &xa));
  PetscCall(VecRestoreArrayWrite(y, &ya));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode OrderedRowsMultTranspose(Mat M, Vec y, Vec x)
{
  OrderedRows       *d;
  const PetscScalar *ya;
  PetscScalar       *xa;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(M, &d));
  PetscCall(VecScatterBegin(d->yall, y, d->ya, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(d->yall, y, d->ya, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(d->ya, &ya));
  PetscCall(VecGetArrayWrite(x, &xa));
  for (PetscInt i = 0; i < d->nlocal; i++) {
    double s = 0;
    for (PetscInt r = 0; r < d->m; r++) s += d->C[r * d->N + d->nstart + i] * PetscRealPart(ya[r]);
    xa[i] = s;
  }
  PetscCall(VecRestoreArrayRead(d->ya, &ya));
  PetscCall(VecRestoreArrayWrite(x, &xa));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode OrderedRowsDestroy(Mat M)
{
  OrderedRows *d;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(M, &d));
  PetscCall(VecScatterDestroy(&d->xall));
  PetscCall(VecScatterDestroy(&d->yall));
  PetscCall(VecDestroy(&d->xa));
  PetscCall(VecDestroy(&d->ya));
  delete d;
  PetscFunctionReturn(PETSC_SUCCESS);
}

struct KnownQP {
  Mat          A = nullptr, C = nullptr;
  Vec          b = nullptr, xstar = nullptr, lb = nullptr, ub = nullptr, d = nullptr;
  SeparableSet set        = nullptr;
  PetscReal    lambda_min = 0, lambda_max = 0;
  PetscBool    has_curved = PETSC_FALSE;
};

/* Unit layouts (6 entries each, so no block straddles ranks) per problem kind. */
struct UnitLayout {
  std::vector<int>                     sizes;  /* block sizes in the unit: 1 scalar, 2 disk, 3 cone */
  std::vector<std::vector<BlockState>> cycles; /* per block position, the states cycled over units */
};

static inline PetscErrorCode KnownQPLayout(const std::string &kind, UnitLayout *L)
{
  using S = BlockState;
  PetscFunctionBegin;
  if (kind == "bounds") {
    L->sizes  = {1, 1, 1, 1, 1, 1};
    L->cycles = {{S::FREE, S::BOX_INTERIOR}, {S::LOWER_ACTIVE}, {S::UPPER_ACTIVE}, {S::BOX_INTERIOR, S::LOWER_ACTIVE}, {S::LOWER_DEGENERATE, S::FREE}, {S::PINNED, S::UPPER_ACTIVE}};
  } else if (kind == "box") { /* bounds without pinned entries (interior-point methods need l < u) */
    L->sizes  = {1, 1, 1, 1, 1, 1};
    L->cycles = {{S::FREE, S::BOX_INTERIOR}, {S::LOWER_ACTIVE}, {S::UPPER_ACTIVE}, {S::BOX_INTERIOR, S::LOWER_ACTIVE}, {S::LOWER_DEGENERATE, S::FREE}, {S::UPPER_ACTIVE, S::FREE}};
  } else if (kind == "disks") {
    L->sizes  = {2, 2, 2};
    L->cycles = {{S::DISK_INTERIOR, S::DISK_ACTIVE}, {S::DISK_ACTIVE}, {S::DISK_ACTIVE, S::DISK_DEGENERATE, S::DISK_RADIUS0, S::DISK_INTERIOR}};
  } else if (kind == "cones") {
    L->sizes  = {3, 3};
    L->cycles = {{S::CONE_ACTIVE, S::CONE_INTERIOR}, {S::CONE_ACTIVE, S::CONE_APEX, S::CONE_DEGENERATE, S::CONE_MU0}};
  } else if (kind == "mixed") {
    L->sizes  = {2, 3, 1};
    L->cycles = {{S::DISK_ACTIVE, S::DISK_INTERIOR, S::DISK_RADIUS0}, {S::CONE_ACTIVE, S::CONE_INTERIOR, S::CONE_APEX}, {S::LOWER_ACTIVE, S::FREE, S::UPPER_ACTIVE}};
  } else if (kind == "disk_radius0") {
    L->sizes  = {2, 2, 2};
    L->cycles = {{S::DISK_RADIUS0}, {S::DISK_ACTIVE}, {S::DISK_RADIUS0}};
  } else if (kind == "boundary_zero_multiplier") {
    L->sizes  = {2, 3, 1};
    L->cycles = {{S::DISK_DEGENERATE}, {S::CONE_DEGENERATE}, {S::LOWER_DEGENERATE}};
  } else if (kind == "cone_apex") {
    L->sizes  = {3, 3};
    L->cycles = {{S::CONE_APEX}, {S::CONE_APEX, S::CONE_ACTIVE}};
  } else SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "unknown problem kind %s", kind.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Dense random orthogonal matrix (row-major n x n) as a product of k Householder reflections. */
static inline std::vector<double> RandomOrthogonal(PetscInt n, PetscInt k, TestRandom &rnd)
{
  std::vector<double> Q(n * n, 0.0), v(n);
  for (PetscInt i = 0; i < n; i++) Q[i * n + i] = 1.0;
  for (PetscInt r = 0; r < k; r++) {
    double nv = 0;
    for (PetscInt i = 0; i < n; i++) nv += (v[i] = rnd.range(-1, 1)) * v[i];
    nv = std::sqrt(nv);
    for (auto &vi : v) vi /= nv;
    for (PetscInt row = 0; row < n; row++) { /* Q <- Q (I - 2 v v') */
      double dot = 0;
      for (PetscInt j = 0; j < n; j++) dot += Q[row * n + j] * v[j];
      for (PetscInt j = 0; j < n; j++) Q[row * n + j] -= 2 * dot * v[j];
    }
  }
  return Q;
}

/* units: number of 6-entry units; A and b are scaled by `scale` (the solution is not); m: number of
   equality rows (0: none), rows of C orthonormal. */
static inline PetscErrorCode KnownQPCreate(MPI_Comm comm, const std::string &kind, PetscInt units, PetscReal cond, PetscReal scale, PetscInt m, KnownQP *qp, PetscReal bound_cap = PETSC_INFINITY,
                                           PetscBool shell = PETSC_TRUE, uint64_t seed = 12345)
{
  UnitLayout            L;
  PetscInt              N = 6 * units, nlocal, rstart, ulocal = PETSC_DECIDE, mlocal = PETSC_DECIDE;
  TestRandom            rnd(seed);
  std::vector<double>   x(N), nvec(N), lo(N, PETSC_NINFINITY), hi(N, PETSC_INFINITY);
  std::vector<PetscInt> disks, cones;
  std::vector<double>   centers, radii, mus;

  PetscFunctionBegin;
  PetscCall(KnownQPLayout(kind, &L));
  PetscCall(PetscSplitOwnership(comm, &ulocal, &units));
  nlocal = 6 * ulocal;
  PetscCallMPI(MPI_Scan(&nlocal, &rstart, 1, MPIU_INT, MPI_SUM, comm));
  rstart -= nlocal;

  /* blocks, solution and normal-cone vector, for all entries (same on every rank) */
  for (PetscInt u = 0, i = 0; u < units; u++) {
    for (size_t pos = 0; pos < L.sizes.size(); pos++) {
      const auto &cyc = L.cycles[pos];
      BlockState  st  = cyc[u % cyc.size()];
      double      kap = rnd.range(0.5, 1.5);
      switch (L.sizes[pos]) {
      case 1: {
        double v = rnd.range(-1, 1);
        x[i]     = v;
        nvec[i]  = 0;
        if (st == BlockState::LOWER_ACTIVE || st == BlockState::LOWER_DEGENERATE) {
          lo[i]   = v;
          hi[i]   = (u % 2) ? v + 1 : PETSC_INFINITY;
          nvec[i] = st == BlockState::LOWER_ACTIVE ? -kap : 0;
        } else if (st == BlockState::UPPER_ACTIVE) {
          hi[i]   = v;
          lo[i]   = (u % 2) ? PETSC_NINFINITY : v - 1;
          nvec[i] = kap;
        } else if (st == BlockState::BOX_INTERIOR) {
          lo[i] = v - 0.5;
          hi[i] = v + 0.5;
        } else if (st == BlockState::PINNED) {
          lo[i] = hi[i] = v;
          nvec[i]       = rnd.range(-1, 1);
        }
        i += 1;
      } break;
      case 2: {
        double c0 = rnd.range(-1, 1), c1 = rnd.range(-1, 1), r = rnd.range(0.5, 1.5), th = rnd.range(0, 2 * M_PI);
        double rho = st == BlockState::DISK_INTERIOR ? 0.5 : 1.0;
        if (st == BlockState::DISK_RADIUS0) r = 0;
        x[i]     = c0 + rho * r * std::cos(th);
        x[i + 1] = c1 + rho * r * std::sin(th);
        if (st == BlockState::DISK_ACTIVE) {
          nvec[i]     = kap * std::cos(th);
          nvec[i + 1] = kap * std::sin(th);
        } else if (st == BlockState::DISK_RADIUS0) {
          nvec[i]     = rnd.range(-1, 1);
          nvec[i + 1] = rnd.range(-1, 1);
        }
        disks.insert(disks.end(), {i, i + 1});
        centers.insert(centers.end(), {c0, c1});
        radii.push_back(r);
        i += 2;
      } break;
      case 3: {
        double mu = rnd.range(0.2, 1.0), yn = rnd.range(0.5, 1.5), th = rnd.range(0, 2 * M_PI), t0 = std::cos(th), t1 = std::sin(th);
        if (st == BlockState::CONE_MU0) mu = 0;
        double ratio = st == BlockState::CONE_INTERIOR ? 0.5 : 1.0;
        if (st == BlockState::CONE_APEX) {
          x[i] = x[i + 1] = x[i + 2] = 0;
          double a                   = rnd.range(0.1, 1.0); /* strictly inside the polar cone: mu |n_t| < -n_n */
          nvec[i + 1]                = a * t0;
          nvec[i + 2]                = a * t1;
          nvec[i]                    = -mu * a - rnd.range(0.2, 1.0);
        } else if (st == BlockState::CONE_MU0) {
          x[i]        = 0;
          x[i + 1]    = 0;
          x[i + 2]    = 0;
          nvec[i]     = -kap;
          nvec[i + 1] = rnd.range(-1, 1);
          nvec[i + 2] = rnd.range(-1, 1);
        } else {
          x[i]     = yn;
          x[i + 1] = ratio * mu * yn * t0;
          x[i + 2] = ratio * mu * yn * t1;
          if (st == BlockState::CONE_ACTIVE) { /* outward normal (-mu, t)/sqrt(1 + mu^2) */
            double s    = kap / std::sqrt(1 + mu * mu);
            nvec[i]     = -mu * s;
            nvec[i + 1] = s * t0;
            nvec[i + 2] = s * t1;
          }
        }
        cones.insert(cones.end(), {i, i + 1, i + 2});
        mus.push_back(mu);
        i += 3;
      } break;
      }
    }
  }

  /* A = Q D Q' (owned rows) */
  std::vector<double> Q = RandomOrthogonal(N, 8, rnd), D(N);
  for (PetscInt k = 0; k < N; k++) D[k] = scale * std::pow(cond, -(double)k / (double)PetscMax(N - 1, 1));
  qp->lambda_max = scale;
  qp->lambda_min = scale / cond;
  if (shell) {
    RowOrderedDense *d = new RowOrderedDense;
    Vec              tmp;
    d->nlocal = nlocal;
    d->N      = N;
    d->rows.resize(nlocal * N);
    for (PetscInt r = rstart; r < rstart + nlocal; r++)
      for (PetscInt c = 0; c < N; c++) {
        double s = 0;
        for (PetscInt k = 0; k < N; k++) s += Q[r * N + k] * D[k] * Q[c * N + k];
        d->rows[(r - rstart) * N + c] = s;
      }
    PetscCall(MatCreateShell(comm, nlocal, nlocal, N, N, d, &qp->A));
    PetscCall(MatShellSetOperation(qp->A, MATOP_MULT, (void (*)(void))RowOrderedMult));
    PetscCall(MatShellSetOperation(qp->A, MATOP_DESTROY, (void (*)(void))RowOrderedDestroy));
    PetscCall(MatShellSetOperation(qp->A, MATOP_GET_DIAGONAL, (void (*)(void))RowOrderedGetDiagonal));
    PetscCall(VecCreateMPI(comm, nlocal, N, &tmp));
    PetscCall(VecScatterCreateToAll(tmp, &d->toall, &d->xall));
    PetscCall(VecDestroy(&tmp));
  } else {
    PetscCall(MatCreateDense(comm, nlocal, nlocal, N, N, NULL, &qp->A));
    for (PetscInt r = rstart; r < rstart + nlocal; r++) {
      std::vector<PetscScalar> row(N);
      std::vector<PetscInt>    cols(N);
      for (PetscInt c = 0; c < N; c++) {
        double s = 0;
        for (PetscInt k = 0; k < N; k++) s += Q[r * N + k] * D[k] * Q[c * N + k];
        row[c]  = s;
        cols[c] = c;
      }
      PetscCall(MatSetValues(qp->A, 1, &r, N, cols.data(), row.data(), INSERT_VALUES));
    }
    PetscCall(MatAssemblyBegin(qp->A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(qp->A, MAT_FINAL_ASSEMBLY));
  }
  PetscCall(MatSetOption(qp->A, MAT_SYMMETRIC, PETSC_TRUE));

  /* vectors */
  PetscCall(MatCreateVecs(qp->A, &qp->xstar, &qp->b));
  PetscCall(VecDuplicate(qp->xstar, &qp->lb));
  PetscCall(VecDuplicate(qp->xstar, &qp->ub));
  for (PetscInt r = rstart; r < rstart + nlocal; r++) {
    PetscCall(VecSetValue(qp->xstar, r, x[r], INSERT_VALUES));
    PetscCall(VecSetValue(qp->lb, r, PetscMax(lo[r], -bound_cap), INSERT_VALUES)); /* bound_cap: for solvers that need finite bounds */
    PetscCall(VecSetValue(qp->ub, r, PetscMin(hi[r], bound_cap), INSERT_VALUES));
  }
  for (Vec v : {qp->xstar, qp->lb, qp->ub}) {
    PetscCall(VecAssemblyBegin(v));
    PetscCall(VecAssemblyEnd(v));
  }
  /* b = A x* + scale n (+ scale C' mu*): A and b both carry the scale, the solution does not */
  PetscCall(MatMult(qp->A, qp->xstar, qp->b));
  for (PetscInt r = rstart; r < rstart + nlocal; r++) PetscCall(VecSetValue(qp->b, r, scale * nvec[r], ADD_VALUES));
  PetscCall(VecAssemblyBegin(qp->b));
  PetscCall(VecAssemblyEnd(qp->b));
  if (m > 0) {
    std::vector<double> Q2 = RandomOrthogonal(N, 6, rnd), mustar(m);
    PetscInt            cstart;
    for (auto &v : mustar) v = scale * rnd.range(-1, 1);
    {
      OrderedRows *d = new OrderedRows;
      Vec          tx, ty;
      d->m = m;
      d->N = N;
      d->C.assign(Q2.begin(), Q2.begin() + m * N);
      PetscCall(PetscSplitOwnership(comm, &mlocal, &m));
      PetscCallMPI(MPI_Scan(&mlocal, &cstart, 1, MPIU_INT, MPI_SUM, comm));
      cstart -= mlocal;
      d->mstart = cstart;
      d->mlocal = mlocal;
      d->nstart = rstart;
      d->nlocal = nlocal;
      PetscCall(MatCreateShell(comm, mlocal, nlocal, m, N, d, &qp->C));
      PetscCall(MatShellSetOperation(qp->C, MATOP_MULT, (void (*)(void))OrderedRowsMult));
      PetscCall(MatShellSetOperation(qp->C, MATOP_MULT_TRANSPOSE, (void (*)(void))OrderedRowsMultTranspose));
      PetscCall(MatShellSetOperation(qp->C, MATOP_DESTROY, (void (*)(void))OrderedRowsDestroy));
      PetscCall(VecCreateMPI(comm, nlocal, N, &tx));
      PetscCall(VecCreateMPI(comm, mlocal, m, &ty));
      PetscCall(VecScatterCreateToAll(tx, &d->xall, &d->xa));
      PetscCall(VecScatterCreateToAll(ty, &d->yall, &d->ya));
      PetscCall(VecDestroy(&tx));
      PetscCall(VecDestroy(&ty));
    }
    PetscCall(MatCreateVecs(qp->C, NULL, &qp->d));
    PetscCall(MatMult(qp->C, qp->xstar, qp->d));
    Vec mu, ctmu;
    PetscCall(VecDuplicate(qp->d, &mu));
    PetscCall(VecDuplicate(qp->b, &ctmu));
    for (PetscInt r = cstart; r < cstart + mlocal; r++) PetscCall(VecSetValue(mu, r, mustar[r], INSERT_VALUES));
    PetscCall(VecAssemblyBegin(mu));
    PetscCall(VecAssemblyEnd(mu));
    PetscCall(MatMultTranspose(qp->C, mu, ctmu));
    PetscCall(VecAXPY(qp->b, 1.0, ctmu));
    PetscCall(VecDestroy(&mu));
    PetscCall(VecDestroy(&ctmu));
  }

  /* the set: local blocks only */
  PetscCall(SeparableSetCreate(comm, nlocal, N, &qp->set));
  {
    std::vector<PetscInt> li;
    std::vector<double>   lc, lr;
    for (size_t k = 0; k < radii.size(); k++)
      if (disks[2 * k] >= rstart && disks[2 * k] < rstart + nlocal) {
        li.insert(li.end(), {disks[2 * k], disks[2 * k + 1]});
        lc.insert(lc.end(), {centers[2 * k], centers[2 * k + 1]});
        lr.push_back(radii[k]);
      }
    PetscCall(SeparableSetAddDisks(qp->set, (PetscInt)lr.size(), li.data(), lc.data(), lr.data()));
    li.clear();
    lr.clear();
    for (size_t k = 0; k < mus.size(); k++)
      if (cones[3 * k] >= rstart && cones[3 * k] < rstart + nlocal) {
        li.insert(li.end(), {cones[3 * k], cones[3 * k + 1], cones[3 * k + 2]});
        lr.push_back(mus[k]);
      }
    PetscCall(SeparableSetAddCones(qp->set, (PetscInt)lr.size(), li.data(), lr.data()));
  }
  PetscCall(SeparableSetSetBounds(qp->set, qp->lb, qp->ub));
  qp->has_curved = (!radii.empty() || !mus.empty()) ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

static inline PetscErrorCode KnownQPDestroy(KnownQP *qp)
{
  PetscFunctionBegin;
  PetscCall(MatDestroy(&qp->A));
  PetscCall(MatDestroy(&qp->C));
  for (Vec *v : {&qp->b, &qp->xstar, &qp->lb, &qp->ub, &qp->d}) PetscCall(VecDestroy(v));
  PetscCall(SeparableSetDestroy(&qp->set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ||x - x*|| / ||x*|| */
static inline PetscErrorCode KnownQPError(KnownQP *qp, Vec x, PetscReal *err)
{
  Vec       e;
  PetscReal ne, ns;

  PetscFunctionBegin;
  PetscCall(VecDuplicate(x, &e));
  PetscCall(VecWAXPY(e, -1.0, qp->xstar, x));
  PetscCall(VecNorm(e, NORM_2, &ne));
  PetscCall(VecNorm(qp->xstar, NORM_2, &ns));
  *err = ne / ns;
  PetscCall(VecDestroy(&e));
  PetscFunctionReturn(PETSC_SUCCESS);
}
