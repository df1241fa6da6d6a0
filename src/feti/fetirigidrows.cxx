/* G = R'B' and G' = B R through the rigid-body structure of R instead of its stored rows.

   Why: G and G' run three or four times per Hessian product, and what they read is mostly R's rows at the dofs B
   touches: k <= 6 doubles per dof, 18 per node (docs/scale.md, "The projector's cost": at 10^6 unknowns G and G'
   took a quarter of the solve). A subdomain's kernel built from node coordinates spans the six rigid-body modes,
   R_s = Rhat_s T_s: Rhat_s holds per node (1,0,0), (0,1,0), (0,0,1), (-Y,X,0), (0,-Z,Y), (Z,0,-X) of the centred
   and scaled coordinates X, Y, Z (FETIRigidBodyModes()), T_s is 6 x k (the orthonormalization and the restriction
   to the modes that vanish on the Dirichlet dofs). Then

     (R_s' w)   = T_s' sum_nodes Rhat_i' w_i   (six sums over the nodes, four products each),
     (R_s a)_i  = Rhat_i (T_s a)               (beta = T_s a once per subdomain, then three short sums per node),

   which read three coordinates per node instead of 18 numbers. T_s is fitted by least squares and kept only when
   Rhat_s T_s reproduces the stored R_s to 1e-12 of its largest entry at every dof (kernels given by the user
   through FETISetSubdomainKernel(), or without coordinates, keep the stored rows: then every subdomain does, the
   choice is the same on any number of ranks). Every subdomain lives on one rank and is summed in its node order,
   so the results are the same on any number of ranks; they differ from the stored rows' in the last bits (R is
   Rhat T up to rounding). -feti_rigid_rows 0 restores the stored rows.

   In redundant coarse mode G' forms R a at B's ghost dofs (other ranks' subdomains) itself (fetioperators.cxx,
   FETISetUpGhostCoarseRows()); here the ghost dofs get their node's coordinates and component and their
   subdomain's T once at setup, so that they are computed by the same expression as on their owner. */
#include <conefeti/private/fetiimpl.h>
#include <conefeti/private/allgather.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace {

/* beta = T a: the six rigid-mode amplitudes of a subdomain's coarse values a (k of them), summed in column order */
inline void RigidAmplitudes(const PetscScalar *T, PetscInt k, const PetscScalar *a, PetscScalar beta[6])
{
  for (PetscInt m = 0; m < 6; m++) {
    PetscScalar s = 0;
    for (PetscInt j = 0; j < k; j++) s += T[6 * j + m] * a[j];
    beta[m] = s;
  }
}

/* component c of Rhat_i beta at a node with coordinates X, Y, Z: the one expression owners and ghosts share */
inline PetscScalar RigidComponent(PetscInt c, PetscScalar X, PetscScalar Y, PetscScalar Z, const PetscScalar beta[6])
{
  switch (c) {
  case 0: return (beta[0] - Y * beta[3]) + Z * beta[5];
  case 1: return (beta[1] + X * beta[3]) - Z * beta[4];
  default: return (beta[2] + Y * beta[4]) - X * beta[5];
  }
}

/* T (6 x k, column-major) minimizing |Rhat T - R| by the normal equations (Rhat'Rhat is 6 x 6, well conditioned for
   centred and scaled coordinates); *ok when the fit reproduces R to 1e-12 of its largest entry */
PetscErrorCode FitTransform(PetscInt n, PetscInt k, const std::vector<PetscScalar> &Rhat, const std::vector<PetscScalar> &R, std::vector<PetscScalar> &T, PetscBool *ok)
{
  PetscScalar A[36] = {0}, L[36] = {0};
  PetscReal   rmax = 0, res = 0;

  PetscFunctionBegin;
  *ok = PETSC_TRUE;
  PetscCallCXX(T.assign(6 * (size_t)k, 0.0));
  for (PetscInt p = 0; p < 6; p++)
    for (PetscInt q = 0; q <= p; q++) {
      PetscScalar s = 0;
      for (PetscInt i = 0; i < n; i++) s += Rhat[(size_t)p * n + i] * Rhat[(size_t)q * n + i];
      A[6 * p + q] = A[6 * q + p] = s;
    }
  for (PetscInt j = 0; j < 6; j++) { /* Cholesky A = L L' */
    PetscScalar d = A[6 * j + j];
    for (PetscInt t = 0; t < j; t++) d -= L[6 * j + t] * L[6 * j + t];
    if (!(PetscRealPart(d) > 0)) {
      *ok = PETSC_FALSE;
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    L[6 * j + j] = PetscSqrtScalar(d);
    for (PetscInt i = j + 1; i < 6; i++) {
      PetscScalar s = A[6 * i + j];
      for (PetscInt t = 0; t < j; t++) s -= L[6 * i + t] * L[6 * j + t];
      L[6 * i + j] = s / L[6 * j + j];
    }
  }
  for (PetscInt c = 0; c < k; c++) {
    PetscScalar b[6];
    for (PetscInt p = 0; p < 6; p++) {
      PetscScalar s = 0;
      for (PetscInt i = 0; i < n; i++) s += Rhat[(size_t)p * n + i] * R[(size_t)c * n + i];
      b[p] = s;
    }
    for (PetscInt i = 0; i < 6; i++) { /* L y = b */
      for (PetscInt t = 0; t < i; t++) b[i] -= L[6 * i + t] * b[t];
      b[i] /= L[6 * i + i];
    }
    for (PetscInt i = 5; i >= 0; i--) { /* L' t = y */
      for (PetscInt t = i + 1; t < 6; t++) b[i] -= L[6 * t + i] * b[t];
      b[i] /= L[6 * i + i];
    }
    for (PetscInt p = 0; p < 6; p++) T[6 * (size_t)c + p] = b[p];
  }
  for (PetscInt c = 0; c < k; c++)
    for (PetscInt i = 0; i < n; i++) {
      PetscScalar s = 0;
      for (PetscInt p = 0; p < 6; p++) s += Rhat[(size_t)p * n + i] * T[6 * (size_t)c + p];
      rmax = std::max(rmax, (PetscReal)PetscAbsScalar(R[(size_t)c * n + i]));
      res  = std::max(res, (PetscReal)PetscAbsScalar(s - R[(size_t)c * n + i]));
    }
  if (!(res <= 1e-12 * rmax)) *ok = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/* Sets up impl.rigid from the touched dofs impl.grows (increasing local primal indices) and R's diagonal block Rd
   (local coarse columns from cstart; NULL: R is not block diagonal, no rigid rows here). Collective: the rigid rows
   are used on every rank or on none. */
PetscErrorCode FETISetUpRigidRows(FETI feti, Mat Rd, PetscInt cstart)
{
  FETI_Impl     &impl = *feti->impl;
  FETIRigidRows &rr   = impl.rigid;
  MPI_Comm       comm = PetscObjectComm((PetscObject)feti);
  PetscMPIInt    mine = impl.rigidrows && Rd ? 1 : 0, all;

  PetscFunctionBegin;
  rr                    = FETIRigidRows();
  const PetscInt   *ria = nullptr, *rja = nullptr;
  PetscScalar      *rv = nullptr;
  std::vector<char> touchednode;
  if (mine) PetscCall(MatSeqAIJGetCSRAndMemType(Rd, &ria, &rja, &rv, NULL));
  for (size_t s = 0; s < impl.sub.size() && mine; s++) {
    const FETISubdomain &sd = impl.sub[s];
    if (!sd.coords || sd.n % 3) {
      mine = 0;
      break;
    }
    const PetscInt           k = sd.nkernel, c0 = sd.coarseoffset - cstart;
    std::vector<PetscScalar> Rhat, R((size_t)sd.n * k, 0.0), T;
    PetscBool                ok = PETSC_TRUE;
    for (PetscInt i = 0; i < sd.n; i++) /* the stored rows of this subdomain */
      for (PetscInt t = ria[sd.localoffset + i]; t < ria[sd.localoffset + i + 1]; t++) {
        const PetscInt j = rja[t] - c0;
        if (j < 0 || j >= k) ok = PETSC_FALSE;
        else R[(size_t)j * sd.n + i] = rv[t];
      }
    if (k > 0 && ok) {
      PetscCall(FETIRigidBodyModes(sd.coords, sd.n, Rhat));
      PetscCall(FitTransform(sd.n, k, Rhat, R, T, &ok));
    }
    if (!ok) {
      mine = 0;
      break;
    }
    /* the nodes B touches (grows is increasing, so they come in order) */
    const PetscInt nn = sd.n / 3, lo = sd.localoffset, hi = sd.localoffset + sd.n;
    PetscCallCXX(rr.subnode.push_back((PetscInt)rr.nodebase.size()));
    PetscCallCXX(rr.subcoarse.push_back(c0));
    PetscCallCXX(rr.subk.push_back(k));
    PetscCallCXX(T.resize(36, 0.0)); /* padded: 6 x 6 */
    PetscCallCXX(rr.T.insert(rr.T.end(), T.begin(), T.end()));
    PetscCallCXX(touchednode.assign(nn, 0));
    for (auto it = std::lower_bound(impl.grows.begin(), impl.grows.end(), lo); it != impl.grows.end() && *it < hi; ++it) touchednode[(*it - lo) / 3] = 1;
    for (PetscInt i = 0; i < nn; i++)
      if (touchednode[i]) {
        PetscCallCXX(rr.nodebase.push_back(lo + 3 * i));
        for (PetscInt d = 0; d < 3; d++) PetscCallCXX(rr.rows.push_back(lo + 3 * i + d));
        if (k > 0) { /* X = column 3's y entry, Y = column 4's z entry, Z = column 5's x entry (FETIRigidBodyModes()) */
          PetscCallCXX(rr.xyz.push_back(Rhat[3 * (size_t)sd.n + 3 * i + 1]));
          PetscCallCXX(rr.xyz.push_back(Rhat[4 * (size_t)sd.n + 3 * i + 2]));
          PetscCallCXX(rr.xyz.push_back(Rhat[5 * (size_t)sd.n + 3 * i + 0]));
        } else
          for (PetscInt d = 0; d < 3; d++) PetscCallCXX(rr.xyz.push_back(0.0));
      }
  }
  PetscCallMPI(MPIU_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, comm));
  if (!all) {
    rr = FETIRigidRows();
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCallCXX(rr.subnode.push_back((PetscInt)rr.nodebase.size()));
  rr.use = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y (local coarse) = R' w, w read at the dofs of the touched nodes (B' x there: the other dofs of those nodes are
   rows of B' without entries, which hold 0) */
PetscErrorCode FETIRigidRowsApplyRt(FETI feti, const PetscScalar *w, PetscScalar *y)
{
  const FETIRigidRows &rr = feti->impl->rigid;
  const PetscInt       ns = (PetscInt)rr.subk.size();

  PetscFunctionBegin;
  for (PetscInt s = 0; s < ns; s++) {
    const PetscInt k = rr.subk[s];
    if (!k) continue;
    PetscScalar acc[6] = {0, 0, 0, 0, 0, 0};
    for (PetscInt t = rr.subnode[s]; t < rr.subnode[s + 1]; t++) {
      const PetscScalar *wi = w + rr.nodebase[t], *c = rr.xyz.data() + 3 * t;
      const PetscScalar  X = c[0], Y = c[1], Z = c[2], wx = wi[0], wy = wi[1], wz = wi[2];
      acc[0] += wx;
      acc[1] += wy;
      acc[2] += wz;
      acc[3] += X * wy - Y * wx;
      acc[4] += Y * wz - Z * wy;
      acc[5] += Z * wx - X * wz;
    }
    const PetscScalar *T  = rr.T.data() + 36 * s;
    PetscScalar       *ys = y + rr.subcoarse[s];
    for (PetscInt j = 0; j < k; j++) {
      PetscScalar v = 0;
      for (PetscInt m = 0; m < 6; m++) v += T[6 * j + m] * acc[m];
      ys[j] = v;
    }
  }
  PetscCall(PetscLogFlops(13.0 * rr.nodebase.size() + 12.0 * rr.T.size() / 6));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* w = R a at the dofs of the touched nodes (a: local coarse values); the other dofs of w keep what they held.
   compact: w holds only those dofs, three per touched node in the order of rr.rows (rr.wc) */
PetscErrorCode FETIRigidRowsApplyR(FETI feti, const PetscScalar *a, PetscBool compact, PetscScalar *w)
{
  const FETIRigidRows &rr = feti->impl->rigid;
  const PetscInt       ns = (PetscInt)rr.subk.size();

  PetscFunctionBegin;
  for (PetscInt s = 0; s < ns; s++) {
    const PetscInt k    = rr.subk[s];
    PetscScalar    b[6] = {0, 0, 0, 0, 0, 0};
    if (!k) { /* no kernel: R is empty there, and B reads zeros */
      for (PetscInt t = rr.subnode[s]; t < rr.subnode[s + 1]; t++)
        for (PetscInt d = 0; d < 3; d++) w[(compact ? 3 * t : rr.nodebase[t]) + d] = 0;
      continue;
    }
    RigidAmplitudes(rr.T.data() + 36 * s, k, a + rr.subcoarse[s], b);
    for (PetscInt t = rr.subnode[s]; t < rr.subnode[s + 1]; t++) {
      const PetscScalar *c  = rr.xyz.data() + 3 * t;
      PetscScalar       *wi = w + (compact ? 3 * t : rr.nodebase[t]);
      for (PetscInt d = 0; d < 3; d++) wi[d] = RigidComponent(d, c[0], c[1], c[2], b);
    }
  }
  PetscCall(PetscLogFlops(12.0 * rr.nodebase.size() + 12.0 * rr.T.size() / 6));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* B's local columns in the numbering of rr.rows, for G' through the compact array rr.wc (FETIApplyGt()). Why: B
   gathers R x from wherever its columns point; in the primal vector the touched dofs are 55% of it at H/h = 6, spread
   over all of it (12.6 MB at 10^6 unknowns, more than stays in cache between products), and there G' cost twice G.
   Not collective: each rank decides for its own B. */
PetscErrorCode FETISetUpRigidCompactColumns(FETI feti)
{
  FETI_Impl            &impl = *feti->impl;
  FETIRigidRows        &rr   = impl.rigid;
  const PetscInt       *ia, *ja;
  PetscScalar          *va;
  PetscInt              m, n;
  std::vector<PetscInt> pos;

  PetscFunctionBegin;
  if (rr.compact) PetscFunctionReturn(PETSC_SUCCESS);
  rr.compact = -1;
  if (!rr.use || !impl.Bsum.Ad) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(MatGetLocalSize(impl.Bsum.Ad, &m, &n));
  PetscCall(MatSeqAIJGetCSRAndMemType(impl.Bsum.Ad, &ia, &ja, &va, NULL));
  PetscCallCXX(pos.assign(n, -1));
  for (size_t q = 0; q < rr.rows.size(); q++) {
    if (rr.rows[q] < 0 || rr.rows[q] >= n) PetscFunctionReturn(PETSC_SUCCESS);
    pos[rr.rows[q]] = (PetscInt)q;
  }
  PetscCallCXX(rr.bcols.resize(ia[m]));
  for (PetscInt k = 0; k < ia[m]; k++) {
    if (pos[ja[k]] < 0) { /* an entry outside the touched nodes (B with an explicit zero where R x is not formed) */
      PetscCallCXX(std::vector<PetscInt>().swap(rr.bcols));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    rr.bcols[k] = pos[ja[k]];
  }
  PetscCallCXX(rr.wc.assign(rr.rows.size(), 0.0));
  rr.compact = 1;
  PetscCall(PetscInfo(feti, "G' gathers R x from a compact array of the %zu dofs of the touched nodes (of %" PetscInt_FMT " local primal dofs)\n", rr.rows.size(), n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* For the ghost dofs of B (impl.Bsum.garray): their node's coordinates and component, their subdomain's T, k and
   global coarse offset, from their owners (one scatter per number with B's own ghost scatter, and one gather of
   the transforms of all subdomains: redundant mode keeps the coarse problem small). Collective. *ok: every ghost
   dof got its data on every rank. */
PetscErrorCode FETISetUpRigidGhostRows(FETI feti, PetscBool *ok)
{
  FETI_Impl                            &impl = *feti->impl;
  FETIRigidRows                        &rr   = impl.rigid;
  MPI_Comm                              comm = PetscObjectComm((PetscObject)feti);
  PetscInt                              nghost;
  PetscMPIInt                           mine = 1, all;
  Vec                                   v;
  const PetscInt                        nfields = 5; /* X, Y, Z, component, global subdomain + 1 (0: no touched node there) */
  std::vector<std::vector<PetscScalar>> got(nfields);

  PetscFunctionBegin;
  *ok = PETSC_FALSE;
  if (!rr.use || !impl.Bsum.scatter) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecGetLocalSize(impl.Bsum.ghosts, &nghost));
  PetscCall(VecDuplicate(impl.wp3, &v));
  for (PetscInt f = 0; f < nfields; f++) {
    PetscScalar       *va;
    const PetscScalar *ga;
    PetscCall(VecSet(v, 0.0));
    PetscCall(VecGetArray(v, &va));
    for (size_t s = 0; s + 1 < rr.subnode.size(); s++)
      for (PetscInt t = rr.subnode[s]; t < rr.subnode[s + 1]; t++)
        for (PetscInt d = 0; d < 3; d++) va[rr.nodebase[t] + d] = f < 3 ? rr.xyz[3 * t + f] : (f == 3 ? (PetscScalar)d : (PetscScalar)(impl.firstsub + (PetscInt)s + 1));
    PetscCall(VecRestoreArray(v, &va));
    PetscCall(VecScatterBegin(impl.Bsum.scatter, v, impl.Bsum.ghosts, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(impl.Bsum.scatter, v, impl.Bsum.ghosts, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(impl.Bsum.ghosts, &ga));
    PetscCallCXX(got[f].assign(ga, ga + nghost));
    PetscCall(VecRestoreArrayRead(impl.Bsum.ghosts, &ga));
  }
  PetscCall(VecDestroy(&v));
  /* every subdomain's global index, k, global coarse offset and T (39 numbers) on every rank */
  const PetscInt           rec = 39, nsub = (PetscInt)rr.subk.size();
  std::vector<PetscScalar> minerec((size_t)rec * nsub), allrec;
  for (PetscInt s = 0; s < nsub; s++) {
    PetscScalar *r = minerec.data() + (size_t)rec * s;
    r[0]           = (PetscScalar)(impl.firstsub + s);
    r[1]           = (PetscScalar)rr.subk[s];
    r[2]           = (PetscScalar)impl.sub[s].coarseoffset;
    std::copy(rr.T.begin() + 36 * s, rr.T.begin() + 36 * (s + 1), r + 3);
  }
  PetscCall(ConeFETIAllgather(comm, minerec, allrec));
  std::map<PetscInt, PetscInt> where; /* global subdomain -> its record */
  for (PetscInt r = 0; r < (PetscInt)allrec.size() / rec; r++) where[(PetscInt)PetscRealPart(allrec[(size_t)rec * r])] = r;
  /* the ghost subdomains' table, and each ghost dof's entry in it */
  std::map<PetscInt, PetscInt> table;
  PetscCallCXX(rr.gxyz.assign(3 * (size_t)nghost, 0.0));
  PetscCallCXX(rr.gcomp.assign(nghost, 0));
  PetscCallCXX(rr.gsub.assign(nghost, -1));
  for (PetscInt t = 0; t < nghost && mine; t++) {
    const PetscInt gid = (PetscInt)PetscRealPart(got[4][t]) - 1;
    auto           w   = where.find(gid);
    if (gid < 0 || w == where.end()) {
      mine = 0;
      break;
    }
    auto e = table.find(gid);
    if (e == table.end()) {
      const PetscScalar *r = allrec.data() + (size_t)rec * w->second;
      e                    = table.emplace(gid, (PetscInt)rr.gsubk.size()).first;
      PetscCallCXX(rr.gsubk.push_back((PetscInt)PetscRealPart(r[1])));
      PetscCallCXX(rr.gsubcoarse.push_back((PetscInt)PetscRealPart(r[2])));
      PetscCallCXX(rr.gT.insert(rr.gT.end(), r + 3, r + 3 + 36));
    }
    rr.gsub[t] = e->second;
    for (PetscInt d = 0; d < 3; d++) rr.gxyz[3 * t + d] = got[d][t];
    rr.gcomp[t] = (PetscInt)PetscRealPart(got[3][t]);
  }
  PetscCallCXX(rr.gbeta.assign(6 * rr.gsubk.size(), 0.0));
  PetscCallMPI(MPIU_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, comm));
  *ok = all ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* ghost values R a at impl.Bsum.garray from the whole coarse vector a (global indices), as their owners form them */
PetscErrorCode FETIRigidRowsApplyGhosts(FETI feti, const PetscScalar *a, PetscScalar *ghost)
{
  FETIRigidRows &rr = feti->impl->rigid;
  const size_t   ng = rr.gsub.size();

  PetscFunctionBegin;
  for (size_t g = 0; g < rr.gsubk.size(); g++)
    if (rr.gsubk[g]) RigidAmplitudes(rr.gT.data() + 36 * g, rr.gsubk[g], a + rr.gsubcoarse[g], rr.gbeta.data() + 6 * g);
  for (size_t t = 0; t < ng; t++) {
    const PetscInt g = rr.gsub[t];
    ghost[t]         = rr.gsubk[g] ? RigidComponent(rr.gcomp[t], rr.gxyz[3 * t], rr.gxyz[3 * t + 1], rr.gxyz[3 * t + 2], rr.gbeta.data() + 6 * g) : 0.0;
  }
  PetscCall(PetscLogFlops(4.0 * ng + 12.0 * rr.gT.size() / 6));
  PetscFunctionReturn(PETSC_SUCCESS);
}
