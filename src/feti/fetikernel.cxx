/* Kernel of a subdomain stiffness matrix and the choice of fixing dofs for its generalized inverse.

   Kernel: the rigid-body modes (from node coordinates) or a user basis, restricted to the modes that
   vanish on the dofs kept at zero in the primal (a subdomain touching the Dirichlet boundary along an
   edge keeps the rotation about that edge), orthonormalized.

   Fixing dofs: K+ = [K_NN^-1 0; 0 0] is a generalized inverse of K whenever the removed set F makes
   R_F (the kernel basis restricted to F) nonsingular, since then K_NN is nonsingular and
   rank K_NN = rank K. How well K_NN is conditioned depends on how well R_F is: the dofs are picked
   by pivoting on R among the dofs of a few nodes chosen far apart (farthest-point sampling). */
#include <conefeti/private/fetiimpl.h>

#include <algorithm>
#include <cmath>

/* The six rigid-body modes of the nodes in coords (3 per node), centred and scaled by the extent so
   that translations and rotations have comparable size. Column-major n x 6. */
PetscErrorCode FETIRigidBodyModes(Vec coords, PetscInt n, std::vector<PetscScalar> &R)
{
  const PetscScalar *x;
  PetscReal          centre[3] = {0, 0, 0}, extent = 0;
  const PetscInt     nn = n / 3;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(coords, &x));
  for (PetscInt i = 0; i < nn; i++)
    for (PetscInt d = 0; d < 3; d++) centre[d] += PetscRealPart(x[3 * i + d]) / nn;
  for (PetscInt i = 0; i < nn; i++)
    for (PetscInt d = 0; d < 3; d++) extent = std::max(extent, std::abs(PetscRealPart(x[3 * i + d]) - centre[d]));
  if (extent == 0) extent = 1;
  PetscCallCXX(R.assign(6 * (size_t)n, 0.0));
  for (PetscInt i = 0; i < nn; i++) {
    const PetscReal X = (PetscRealPart(x[3 * i]) - centre[0]) / extent, Y = (PetscRealPart(x[3 * i + 1]) - centre[1]) / extent, Z = (PetscRealPart(x[3 * i + 2]) - centre[2]) / extent;
    for (PetscInt d = 0; d < 3; d++) R[(size_t)d * n + 3 * i + d] = 1.0;
    /* rotations about z, x, y */
    R[3 * (size_t)n + 3 * i + 0] = -Y;
    R[3 * (size_t)n + 3 * i + 1] = X;
    R[4 * (size_t)n + 3 * i + 1] = -Z;
    R[4 * (size_t)n + 3 * i + 2] = Y;
    R[5 * (size_t)n + 3 * i + 0] = Z;
    R[5 * (size_t)n + 3 * i + 2] = -X;
  }
  PetscCall(VecRestoreArrayRead(coords, &x));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Modified Gram-Schmidt, twice; a column that loses all but droptol of its norm is dependent and dropped */
PetscErrorCode FETIOrthonormalizeColumns(PetscInt n, PetscInt *k, std::vector<PetscScalar> &R, PetscReal droptol)
{
  PetscInt kept = 0;

  PetscFunctionBegin;
  for (PetscInt j = 0; j < *k; j++) {
    PetscScalar *col   = &R[(size_t)j * n];
    PetscReal    norm0 = 0, norm = 0;
    for (PetscInt i = 0; i < n; i++) norm0 += PetscRealPart(col[i] * PetscConj(col[i]));
    norm0 = std::sqrt(norm0);
    for (PetscInt pass = 0; pass < 2; pass++)
      for (PetscInt q = 0; q < kept; q++) {
        const PetscScalar *cq  = &R[(size_t)q * n];
        PetscScalar        dot = 0;
        for (PetscInt i = 0; i < n; i++) dot += col[i] * PetscConj(cq[i]);
        for (PetscInt i = 0; i < n; i++) col[i] -= dot * cq[i];
      }
    for (PetscInt i = 0; i < n; i++) norm += PetscRealPart(col[i] * PetscConj(col[i]));
    norm = std::sqrt(norm);
    if (norm0 == 0 || norm <= droptol * norm0) continue;
    PetscScalar *dst = &R[(size_t)kept * n];
    for (PetscInt i = 0; i < n; i++) dst[i] = col[i] / norm;
    kept++;
  }
  *k = kept;
  PetscCallCXX(R.resize((size_t)kept * n));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One-sided (Hestenes) Jacobi SVD of A (rows x m, column-major): on return the columns of A are
   orthogonal with norms sigma_j, and A_in V = A_out. Works on A itself, not on A'A, so a singular
   value at roundoff level stays at roundoff level (a Gram matrix would square it into 1e-8 noise). */
static void OneSidedJacobi(PetscInt rows, PetscInt m, std::vector<PetscReal> &A, std::vector<PetscReal> &sigma, std::vector<PetscReal> &V)
{
  V.assign((size_t)m * m, 0.0);
  for (PetscInt i = 0; i < m; i++) V[(size_t)i * m + i] = 1.0;
  for (PetscInt sweep = 0; sweep < 60; sweep++) {
    PetscBool rotated = PETSC_FALSE;
    for (PetscInt p = 0; p < m; p++)
      for (PetscInt q = p + 1; q < m; q++) {
        PetscReal  alpha = 0, beta = 0, gamma = 0;
        PetscReal *ap = &A[(size_t)p * rows], *aq = &A[(size_t)q * rows];
        for (PetscInt i = 0; i < rows; i++) {
          alpha += ap[i] * ap[i];
          beta += aq[i] * aq[i];
          gamma += ap[i] * aq[i];
        }
        if (gamma == 0 || std::abs(gamma) <= 1e-15 * std::sqrt(alpha * beta)) continue;
        rotated              = PETSC_TRUE;
        const PetscReal zeta = (beta - alpha) / (2 * gamma);
        const PetscReal t    = (zeta >= 0 ? 1.0 : -1.0) / (std::abs(zeta) + std::sqrt(1 + zeta * zeta));
        const PetscReal c = 1 / std::sqrt(1 + t * t), s = c * t;
        for (PetscInt i = 0; i < rows; i++) {
          const PetscReal x = ap[i], y = aq[i];
          ap[i] = c * x - s * y;
          aq[i] = s * x + c * y;
        }
        for (PetscInt i = 0; i < m; i++) {
          const PetscReal x = V[(size_t)p * m + i], y = V[(size_t)q * m + i];
          V[(size_t)p * m + i] = c * x - s * y;
          V[(size_t)q * m + i] = s * x + c * y;
        }
      }
    if (!rotated) break;
  }
  sigma.assign(m, 0.0);
  for (PetscInt j = 0; j < m; j++) {
    PetscReal norm = 0;
    for (PetscInt i = 0; i < rows; i++) norm += A[(size_t)j * rows + i] * A[(size_t)j * rows + i];
    sigma[j] = std::sqrt(norm);
  }
}

/* Replace the orthonormal basis R (n x k) by an orthonormal basis of its vectors that vanish on the dofs D.
   A combination v counts as vanishing when its RMS value on D is below tol times its RMS value overall. */
PetscErrorCode FETIKernelVanishingOn(PetscInt n, PetscInt *k, std::vector<PetscScalar> &R, const std::vector<PetscInt> &D, PetscReal tol)
{
  const PetscInt           m = *k, nd = (PetscInt)D.size();
  std::vector<PetscReal>   RD((size_t)nd * m), sigma, V;
  std::vector<PetscScalar> Rnew;
  PetscInt                 knew = 0;

  PetscFunctionBegin;
  if (D.empty() || m == 0) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt j = 0; j < m; j++)
    for (PetscInt i = 0; i < nd; i++) RD[(size_t)j * nd + i] = PetscRealPart(R[(size_t)j * n + D[i]]);
  OneSidedJacobi(nd, m, RD, sigma, V);
  /* for unit v: RMS on D = sigma / sqrt(|D|), RMS overall = 1 / sqrt(n) */
  const PetscReal scale = std::sqrt((PetscReal)n / (PetscReal)nd);
  PetscCallCXX(Rnew.assign((size_t)m * n, 0.0));
  for (PetscInt j = 0; j < m; j++) {
    PetscCall(PetscInfo(NULL, "kernel candidate %" PetscInt_FMT ": RMS on the %" PetscInt_FMT " Dirichlet dofs / RMS overall = %g\n", j, nd, (double)(sigma[j] * scale)));
    if (sigma[j] * scale > tol) continue;
    PetscScalar *col = &Rnew[(size_t)knew * n];
    for (PetscInt a = 0; a < m; a++)
      for (PetscInt i = 0; i < n; i++) col[i] += V[(size_t)j * m + a] * R[(size_t)a * n + i];
    for (PetscInt d : D) col[d] = 0; /* exactly zero where u = 0 is imposed */
    knew++;
  }
  Rnew.resize((size_t)knew * n);
  R  = std::move(Rnew);
  *k = knew;
  PetscCall(FETIOrthonormalizeColumns(n, k, R, 1e-8));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* How firmly the dofs D (kept at zero in the primal) hold a body with the node coordinates coords: the
   smallest RMS value on D relative to the RMS value overall of a unit combination of its rigid-body modes.
   It is the conditioning of the rigid modes restricted to D, as for the fixing dofs: a body clamped on a
   whole face has about 0.4; one held at a patch of size a has about a over its own size, and its K_NN
   then has low-energy modes (the body swinging about the patch) that make K+ and F large; one held at a
   node or along a line has 0 (rigid modes vanish on D: rotations about the node or the line). 0 when D
   is empty. */
PetscErrorCode FETIDirichletHold(Vec coords, PetscInt n, const std::vector<PetscInt> &D, PetscReal *hold)
{
  std::vector<PetscScalar> R;
  std::vector<PetscReal>   RD, sigma, V;
  PetscInt                 k  = 6;
  const PetscInt           nd = (PetscInt)D.size();

  PetscFunctionBegin;
  *hold = 0;
  if (D.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(FETIRigidBodyModes(coords, n, R));
  PetscCall(FETIOrthonormalizeColumns(n, &k, R, 1e-8));
  PetscCallCXX(RD.resize((size_t)nd * k));
  for (PetscInt j = 0; j < k; j++)
    for (PetscInt i = 0; i < nd; i++) RD[(size_t)j * nd + i] = PetscRealPart(R[(size_t)j * n + D[i]]);
  OneSidedJacobi(nd, k, RD, sigma, V);
  *hold = PETSC_MAX_REAL;
  for (PetscInt j = 0; j < k; j++) *hold = std::min(*hold, sigma[j] * std::sqrt((PetscReal)n / (PetscReal)nd));
  if (k < 6) *hold = 0; /* a body of fewer than three non-collinear nodes: nothing to measure */
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Greedy row pivoting: choose k of the candidate rows of R that span its row space as well as possible.
   Returns the smallest pivot relative to the largest (0 when the candidates cannot complement the kernel). */
static PetscReal PivotRows(PetscInt n, PetscInt k, const std::vector<PetscScalar> &R, const std::vector<PetscInt> &cand, std::vector<PetscInt> &chosen)
{
  const PetscInt           m = (PetscInt)cand.size();
  std::vector<PetscScalar> M((size_t)m * k);
  PetscReal                first = 0, last = 0;

  chosen.clear();
  for (PetscInt r = 0; r < m; r++)
    for (PetscInt j = 0; j < k; j++) M[(size_t)r * k + j] = R[(size_t)j * n + cand[r]];
  for (PetscInt s = 0; s < k; s++) {
    PetscInt  best     = -1;
    PetscReal bestnorm = 0;
    for (PetscInt r = 0; r < m; r++) {
      PetscReal norm = 0;
      for (PetscInt j = 0; j < k; j++) norm += PetscRealPart(M[(size_t)r * k + j] * PetscConj(M[(size_t)r * k + j]));
      if (norm > bestnorm) {
        bestnorm = norm;
        best     = r;
      }
    }
    if (best < 0) return 0;
    bestnorm = std::sqrt(bestnorm);
    if (s == 0) first = bestnorm;
    last = bestnorm;
    chosen.push_back(cand[best]);
    std::vector<PetscScalar> q(k);
    for (PetscInt j = 0; j < k; j++) q[j] = M[(size_t)best * k + j] / bestnorm;
    for (PetscInt r = 0; r < m; r++) {
      PetscScalar dot = 0;
      for (PetscInt j = 0; j < k; j++) dot += M[(size_t)r * k + j] * PetscConj(q[j]);
      for (PetscInt j = 0; j < k; j++) M[(size_t)r * k + j] -= dot * q[j];
    }
  }
  return first > 0 ? last / first : 0;
}

/* Fixing dofs: k dofs of up to ncand well-separated nodes, chosen by pivoting on R (see the file comment).
   Without coordinates, or when the candidates cannot complement the kernel, all free dofs are candidates. */
PetscErrorCode FETIChooseFixingDofs(PetscInt n, PetscInt k, const std::vector<PetscScalar> &R, Vec coords, const std::vector<PetscInt> &D, PetscInt ncand, std::vector<PetscInt> &fixing)
{
  std::vector<char>     isD(n, 0);
  std::vector<PetscInt> cand;
  PetscReal             quality = 0;

  PetscFunctionBegin;
  fixing.clear();
  if (k == 0) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt d : D) isD[d] = 1;
  if (coords && ncand > 0) {
    const PetscScalar     *x;
    const PetscInt         nn        = n / 3;
    PetscReal              centre[3] = {0, 0, 0};
    std::vector<PetscReal> mindist(nn, PETSC_MAX_REAL);
    std::vector<PetscInt>  nodes;
    PetscCall(VecGetArrayRead(coords, &x));
    for (PetscInt i = 0; i < nn; i++)
      for (PetscInt d = 0; d < 3; d++) centre[d] += PetscRealPart(x[3 * i + d]) / nn;
    auto dist2 = [&](PetscInt i, const PetscReal *p) {
      PetscReal s = 0;
      for (PetscInt d = 0; d < 3; d++) s += (PetscRealPart(x[3 * i + d]) - p[d]) * (PetscRealPart(x[3 * i + d]) - p[d]);
      return s;
    };
    auto isfree = [&](PetscInt i) { return !(isD[3 * i] && isD[3 * i + 1] && isD[3 * i + 2]); };
    /* farthest-point sampling, starting from the free node farthest from the centre */
    for (PetscInt i = 0; i < nn; i++) mindist[i] = isfree(i) ? dist2(i, centre) : -1;
    for (PetscInt c = 0; c < std::min(ncand, nn); c++) {
      const PetscInt best = (PetscInt)(std::max_element(mindist.begin(), mindist.end()) - mindist.begin());
      if (mindist[best] < 0) break;
      nodes.push_back(best);
      PetscReal p[3] = {PetscRealPart(x[3 * best]), PetscRealPart(x[3 * best + 1]), PetscRealPart(x[3 * best + 2])};
      for (PetscInt i = 0; i < nn; i++)
        if (mindist[i] >= 0) mindist[i] = std::min(mindist[i], dist2(i, p));
      mindist[best] = -1;
    }
    PetscCall(VecRestoreArrayRead(coords, &x));
    for (PetscInt node : nodes)
      for (PetscInt d = 0; d < 3; d++)
        if (!isD[3 * node + d]) cand.push_back(3 * node + d);
    quality = PivotRows(n, k, R, cand, fixing);
  }
  if (quality < 1e-3) {
    cand.clear();
    for (PetscInt i = 0; i < n; i++)
      if (!isD[i]) cand.push_back(i);
    quality = PivotRows(n, k, R, cand, fixing);
    PetscCheck(quality > 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Cannot choose fixing dofs complementary to the kernel (dimension %" PetscInt_FMT ")", k);
  }
  std::sort(fixing.begin(), fixing.end());
  PetscFunctionReturn(PETSC_SUCCESS);
}
