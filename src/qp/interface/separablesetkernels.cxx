/* SeparableSet kernels: projection, free/chopped/projected gradients, feasible step length.
   Math: docs/algorithms.md, 'Separable sets'. Every kernel is one pass over the local entries and
   blocks; reductions are combined into one MPI call per kernel. */
#include <conefeti/private/separablesetimpl.h>
#include <conefeti/private/reproduciblesum.h>
#include <cmath>

PetscLogEvent QP_Project, QP_Split;

namespace {

constexpr PetscReal kInf = PETSC_INFINITY;

/* ---------- per-block geometry ---------- */

/* Projection of a point y (relative coordinates z = y - center) onto the disk of radius r. */
inline void ProjectDisk(PetscReal &z0, PetscReal &z1, PetscReal r)
{
  const PetscReal nz = std::hypot(z0, z1);
  if (nz <= r) return;
  if (r == 0 || nz == 0) {
    z0 = z1 = 0;
    return;
  }
  const PetscReal s = r / nz;
  z0 *= s;
  z1 *= s;
}

/* Projection onto K = {|y_t| <= mu y_n} (apex at the origin). */
inline void ProjectCone(PetscReal &yn, PetscReal &y1, PetscReal &y2, PetscReal mu)
{
  const PetscReal st = std::hypot(y1, y2);
  if (yn >= 0 && st <= mu * yn) return; /* inside (includes the apex) */
  if (mu * st <= -yn) {                 /* inside the polar cone: projects to the apex */
    yn = y1 = y2 = 0;
    return;
  }
  /* onto the boundary ray through (1, mu t^), t^ = y_t/|y_t| (st > 0 here unless mu = 0) */
  const PetscReal a = (yn + mu * st) / (1 + mu * mu);
  if (st > 0) {
    y1 = a * mu * y1 / st;
    y2 = a * mu * y2 / st;
  } else {
    y1 = y2 = 0;
  }
  yn = a;
}

/* Largest alpha >= 0 with q(alpha) = a alpha^2 - 2 b alpha + c >= 0 on [0, alpha], given c >= 0.
   Both curved blocks reduce to this: the stable root formula avoids cancellation. */
inline PetscReal QuadraticStep(PetscReal a, PetscReal b, PetscReal c)
{
  c = PetscMax(c, 0);
  if (b > 0) {
    const PetscReal D = b * b - a * c;
    return D < 0 ? kInf : c / (b + std::sqrt(D));
  }
  if (a < 0) return (b - std::sqrt(b * b - a * c)) / a;
  return kInf;
}

/* Projected gradient on a block whose point lies on a smooth boundary with outward unit normal nu:
   -gP is the projection of -g on the half-space {d : nu.d <= 0}. */
template <int D> inline void BoundaryProjectedGradient(const PetscReal g[D], const PetscReal nu[D], PetscReal gp[D])
{
  PetscReal dot = 0;
  for (int k = 0; k < D; k++) dot += nu[k] * g[k];
  for (int k = 0; k < D; k++) gp[k] = dot >= 0 ? g[k] : g[k] - dot * nu[k];
}

} // namespace

/*@C
  SeparableSetProject - Project a vector onto the set, in place.

  Collective

  Input Parameters:
+ set - the set
- x   - the vector, overwritten by its projection

  Level: beginner

.seealso: `SeparableSetProjectedGradient()`, `SeparableSetDistance()`
@*/
PetscErrorCode SeparableSetProject(SeparableSet set, Vec x)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  PetscValidHeaderSpecific(x, VEC_CLASSID, 2);
  PetscCall(SeparableSetCheckCompatible_Private(set, x));
  PetscCall(SeparableSetProjectedStep_Private(set, x, 0.0, NULL, x));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y = P(x - alpha d); d may be NULL (pure projection); y may alias x. */
PetscErrorCode SeparableSetProjectedStep_Private(SeparableSet set, Vec x, PetscReal alpha, Vec d_, Vec y)
{
  SeparableSetData  *d;
  const PetscScalar *xa, *da = NULL;
  PetscScalar       *ya;

  PetscFunctionBegin;
  PetscCall(SeparableSetSetUp_Private(set));
  PetscCall(PetscLogEventBegin(QP_Project, 0, 0, 0, 0));
  d = set->data;
  if (d_) PetscCall(VecGetArrayRead(d_, &da));
  if (x == y) {
    PetscCall(VecGetArray(y, &ya));
    xa = ya;
  } else {
    PetscCall(VecGetArrayRead(x, &xa));
    PetscCall(VecGetArray(y, &ya));
  }
  const PetscReal *lo = d->lo.data(), *hi = d->hi.data();
  for (PetscInt i = 0; i < d->n; i++) {
    PetscReal v = PetscRealPart(xa[i]) - (da ? alpha * PetscRealPart(da[i]) : 0.0);
    if (d->kind[i] == SEPARABLE_SCALAR) v = PetscMin(PetscMax(v, lo[i]), hi[i]);
    ya[i] = v;
  }
  for (size_t k = 0; k < d->disk_radius.size(); k++) {
    const PetscInt i = d->disk_idx[2 * k], j = d->disk_idx[2 * k + 1];
    PetscReal      z0 = PetscRealPart(ya[i]) - d->eff_center[2 * k], z1 = PetscRealPart(ya[j]) - d->eff_center[2 * k + 1];
    ProjectDisk(z0, z1, d->disk_radius[k]);
    ya[i] = d->eff_center[2 * k] + z0;
    ya[j] = d->eff_center[2 * k + 1] + z1;
  }
  for (size_t k = 0; k < d->cone_mu.size(); k++) {
    const PetscInt  *id = &d->cone_idx[3 * k];
    const PetscReal *v  = &d->cone_apex[3 * k];
    PetscReal        yn = PetscRealPart(ya[id[0]]) - v[0], y1 = PetscRealPart(ya[id[1]]) - v[1], y2 = PetscRealPart(ya[id[2]]) - v[2];
    ProjectCone(yn, y1, y2, d->cone_mu[k]);
    ya[id[0]] = v[0] + yn;
    ya[id[1]] = v[1] + y1;
    ya[id[2]] = v[2] + y2;
  }
  if (x == y) PetscCall(VecRestoreArray(y, &ya));
  else {
    PetscCall(VecRestoreArrayRead(x, &xa));
    PetscCall(VecRestoreArray(y, &ya));
  }
  if (d_) PetscCall(VecRestoreArrayRead(d_, &da));
  PetscCall(PetscLogEventEnd(QP_Project, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {
/* The arrays and sums of one split (sum: gp2, beta2, phitphi, phiAp, xg, xb). */
struct SplitData {
  const SeparableSetData *d;
  const PetscScalar      *xa, *ga, *apa, *ba;
  PetscScalar            *pa, *ba_;
  PetscReal              *ta;   /* scalar entries' terms of phi~ (zero elsewhere), summed against g in the second pass */
  unsigned char          *fr;   /* 1 where the block is free (interior or arc), for SeparableSetMaskFree_Private() */
  unsigned char          *arc;  /* per disk: 1 for an arc block */
  PetscReal              *curv; /* per disk: the curvature term of an arc block */
  PetscReal               alpha;
  PetscReal               arcmax; /* > 0: disk blocks on their circle may move along it while alpha -g.nu/r <= arcmax */
  bool                    keep;   /* keep the arc blocks of the last split (during a CG run: the face stays fixed) */
  PetscInt                narc;
  DoubleDouble            sum[6];
};

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
/* Two passes: the first classifies the entries and blocks and writes phi and beta (branches, no
   sums but the curved blocks' phi~ terms), the second, branch-free, accumulates all six sums in
   SIMD lanes (DoubleDouble4). */
template <bool Fused> CONEFETI_INLINE_KERNEL void SplitKernel(SplitData &sd)
{
  const SeparableSetData *d  = sd.d;
  const PetscScalar      *xa = sd.xa, *ga = sd.ga, *apa = sd.apa, *ba = sd.ba;
  PetscScalar            *pa = sd.pa, *ba_ = sd.ba_;
  PetscReal              *ta    = sd.ta;
  unsigned char          *fr    = sd.fr;
  const PetscReal         alpha = sd.alpha, ialpha = 1 / alpha;
  DoubleDouble            curved; /* phi~.phi of the disk and cone blocks */
  const PetscReal        *lo = d->lo.data(), *hi = d->hi.data();
  const PetscReal         tol = SEPARABLE_BOUNDARY_RTOL;
  const PetscInt          n   = d->n;

  /* scalars */
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal xi = PetscRealPart(xa[i]), gi = PetscRealPart(ga[i]);
    PetscReal       f = 0, c = 0, t = 0;
    if (d->kind[i] != SEPARABLE_SCALAR) {
      ta[i] = 0;
      continue;
    }
    fr[i] = 0;
    if (lo[i] == hi[i]) { /* pinned */
    } else if (xi <= lo[i]) c = PetscMin(gi, 0);
    else if (xi >= hi[i]) c = PetscMax(gi, 0);
    else {
      fr[i] = 1;
      /* min(g, (x - l)/alpha) for g > 0, max(g, (x - u)/alpha) otherwise, without a branch on the sign
         of g (a coin toss for the branch predictor): the first bound is >= 0, the second <= 0 */
      f = gi;
      t = PetscMax(PetscMin(gi, (xi - lo[i]) * ialpha), (xi - hi[i]) * ialpha);
    }
    pa[i]  = f;
    ba_[i] = c;
    ta[i]  = t;
  }

  /* disks: interior unless within the relative tolerance of the circle. On the circle with the gradient
     pushing outward (g.nu < 0), the block may instead count as free along the circle (an arc block: phi is
     the tangential part of g, beta = 0), so that CG steps move it along the arc (curvature term -g.nu/r,
     see SeparableSetArcTangent_Private()); only while alpha -g.nu/r <= arcmax: a block held more firmly
     is left to the projected steps, which already scale its tangential move by 1/(1 + alpha |g.nu|/r) */
  sd.narc = 0;
  for (size_t k = 0; k < d->disk_radius.size(); k++) {
    const PetscInt  i = d->disk_idx[2 * k], j = d->disk_idx[2 * k + 1];
    const PetscReal r     = d->disk_radius[k];
    const PetscReal z[2]  = {PetscRealPart(xa[i]) - d->eff_center[2 * k], PetscRealPart(xa[j]) - d->eff_center[2 * k + 1]};
    const PetscReal gg[2] = {PetscRealPart(ga[i]), PetscRealPart(ga[j])};
    PetscReal       f[2] = {0, 0}, c[2] = {0, 0};
    const PetscReal nz = std::hypot(z[0], z[1]);
    fr[i] = fr[j]      = 0;
    const bool was_arc = sd.arc[k];
    sd.arc[k]          = 0;
    sd.curv[k]         = 0;
    if (r == 0) { /* pinned at the center */
    } else if (nz < r * (1 - tol)) {
      fr[i] = fr[j] = 1;
      f[0]          = gg[0];
      f[1]          = gg[1];
      PetscReal w0 = z[0] - alpha * gg[0], w1 = z[1] - alpha * gg[1];
      ProjectDisk(w0, w1, r);
      curved.add(((z[0] - w0) * gg[0] + (z[1] - w1) * gg[1]) / alpha);
    } else {
      const PetscReal nu[2] = {z[0] / nz, z[1] / nz};
      const PetscReal gnu   = nu[0] * gg[0] + nu[1] * gg[1];
      if (sd.keep ? was_arc : (sd.arcmax > 0 && gnu < 0 && -gnu * alpha <= sd.arcmax * r)) { /* an arc block: the tangential part of g is free */
        fr[i] = fr[j] = 1;
        f[0]          = gg[0] - gnu * nu[0];
        f[1]          = gg[1] - gnu * nu[1];
        if (gnu > 0) { /* (kept arc block) the gradient now pulls it inward: that part is chopped */
          c[0] = gnu * nu[0];
          c[1] = gnu * nu[1];
        }
        PetscReal w0 = z[0] - alpha * f[0], w1 = z[1] - alpha * f[1];
        ProjectDisk(w0, w1, r);
        curved.add(((z[0] - w0) * f[0] + (z[1] - w1) * f[1]) / alpha);
        sd.arc[k]  = 1;
        sd.curv[k] = PetscMax(-gnu, 0) / r;
        sd.narc++;
      } else BoundaryProjectedGradient<2>(gg, nu, c);
    }
    pa[i]  = f[0];
    pa[j]  = f[1];
    ba_[i] = c[0];
    ba_[j] = c[1];
  }

  /* cones: apex, interior, or smooth boundary; mu = 0 is a half-line (tangential entries pinned) */
  for (size_t k = 0; k < d->cone_mu.size(); k++) {
    const PetscInt  *id    = &d->cone_idx[3 * k];
    const PetscReal *v     = &d->cone_apex[3 * k];
    const PetscReal  mu    = d->cone_mu[k];
    const PetscReal  y[3]  = {PetscRealPart(xa[id[0]]) - v[0], PetscRealPart(xa[id[1]]) - v[1], PetscRealPart(xa[id[2]]) - v[2]};
    const PetscReal  gg[3] = {PetscRealPart(ga[id[0]]), PetscRealPart(ga[id[1]]), PetscRealPart(ga[id[2]])};
    PetscReal        f[3] = {0, 0, 0}, c[3] = {0, 0, 0};
    const PetscReal  st   = std::hypot(y[1], y[2]);
    bool             free = false;
    if (mu == 0) { /* {y_t = 0, y_n >= 0}: y_n is a scalar with lower bound */
      if (y[0] > 0) {
        free              = true; /* y_n only: the tangential entries are pinned */
        f[0]              = gg[0];
        const PetscReal t = gg[0] > 0 ? PetscMin(gg[0], y[0] / alpha) : gg[0];
        curved.addProductT<Fused>(t, gg[0]);
      } else c[0] = PetscMin(gg[0], 0);
    } else if (y[0] <= 0) { /* apex: the tangent cone is K itself, -gP = P_K(-g) */
      PetscReal m[3] = {-gg[0], -gg[1], -gg[2]};
      ProjectCone(m[0], m[1], m[2], mu);
      for (int q = 0; q < 3; q++) c[q] = -m[q];
    } else if (st < mu * y[0] * (1 - tol)) {
      free = true;
      for (int q = 0; q < 3; q++) f[q] = gg[q];
      PetscReal w[3] = {y[0] - alpha * gg[0], y[1] - alpha * gg[1], y[2] - alpha * gg[2]};
      ProjectCone(w[0], w[1], w[2], mu);
      curved.add(((y[0] - w[0]) * gg[0] + (y[1] - w[1]) * gg[1] + (y[2] - w[2]) * gg[2]) / alpha);
    } else {
      const PetscReal s     = 1 / std::sqrt(1 + mu * mu);
      const PetscReal nu[3] = {-mu * s, s * y[1] / st, s * y[2] / st};
      BoundaryProjectedGradient<3>(gg, nu, c);
    }
    for (int q = 0; q < 3; q++) {
      pa[id[q]]  = f[q];
      ba_[id[q]] = c[q];
      fr[id[q]]  = free && (mu > 0 || q == 0);
    }
  }

  DoubleDouble4 sum[6]; /* locals, so that the accumulators stay in registers */
  for (PetscInt i = 0; i < n; i += 4) {
    const DoubleDoubleLanes f = LoadLanes(pa, i, n), c = LoadLanes(ba_, i, n), x = LoadLanes(xa, i, n), g = LoadLanes(ga, i, n);
    sum[0].addProductT<Fused>(f, f);
    sum[0].addProductT<Fused>(c, c);
    sum[1].addProductT<Fused>(c, c);
    sum[2].addProductT<Fused>(LoadLanes(ta, i, n), g);
    if (apa) sum[3].addProductT<Fused>(f, LoadLanes(apa, i, n));
    sum[4].addProductT<Fused>(x, g);
    if (ba) sum[5].addProductT<Fused>(x, LoadLanes(ba, i, n));
  }
  for (int q = 0; q < 6; q++) sd.sum[q] = sum[q].total();
  sd.sum[2].add(curved);
}
#pragma GCC diagnostic pop

#if CONEFETI_FMA_DISPATCH
CONEFETI_TARGET_FMA void SplitKernelFMA(SplitData &sd) { SplitKernel<true>(sd); }
#endif
} // namespace

/* One pass: free gradient phi, chopped gradient beta, and the sums of SeparableSplit.
   The reduced free gradient phi~ = (x - P(x - alpha phi))/alpha enters only through phi~.phi.
   arcmax > 0 lets disk blocks on their circle count as free along it (arc blocks, see SplitKernel()),
   0 keeps Kucera's split. Ap (may be NULL) gives phi.Ap for the CG update; b (may be NULL) gives x.b for
   the objective. */
PetscErrorCode SeparableSetSplitGradient_Private(SeparableSet set, Vec x, Vec g, PetscReal alpha, PetscReal arcmax, PetscBool keep, Vec phi, Vec beta, Vec Ap, Vec b, SeparableSplit *out)
{
  SeparableSetData  *d;
  const PetscScalar *xa, *ga, *apa = NULL, *ba = NULL;
  PetscScalar       *pa, *ba_;

  PetscFunctionBegin;
  PetscCall(SeparableSetSetUp_Private(set));
  PetscCall(PetscLogEventBegin(QP_Split, 0, 0, 0, 0));
  d = set->data;
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArrayRead(g, &ga));
  if (Ap) PetscCall(VecGetArrayRead(Ap, &apa));
  if (b) PetscCall(VecGetArrayRead(b, &ba));
  PetscCall(VecGetArrayWrite(phi, &pa));
  PetscCall(VecGetArrayWrite(beta, &ba_));
  SplitData sd{d, xa, ga, apa, ba, pa, ba_, d->split_work.data(), d->split_free.data(), d->disk_arc.data(), d->disk_curv.data(), alpha, arcmax, keep && arcmax > 0 ? true : false, 0, {}};
#if CONEFETI_FMA_DISPATCH
  if (ReproducibleSumUseFMA()) SplitKernelFMA(sd);
  else
#endif
    SplitKernel<CONEFETI_FMA_BASELINE>(sd);
  DoubleDouble *sum = sd.sum;
  PetscCall(VecRestoreArrayWrite(phi, &pa));
  PetscCall(VecRestoreArrayWrite(beta, &ba_));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecRestoreArrayRead(g, &ga));
  if (Ap) PetscCall(VecRestoreArrayRead(Ap, &apa));
  if (b) PetscCall(VecRestoreArrayRead(b, &ba));
  PetscCall(ReproducibleAllreduce(sum, 6, PetscObjectComm((PetscObject)set)));
  if (arcmax > 0) PetscCall(MPIU_Allreduce(&sd.narc, &out->narc, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)set)));
  else out->narc = 0;
  out->gp2     = sum[0].value();
  out->beta2   = sum[1].value();
  out->phitphi = sum[2].value();
  out->phiAp   = sum[3].value();
  out->xg      = sum[4].value();
  out->xb      = sum[5].value();
  PetscCall(PetscLogEventEnd(QP_Split, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* z_i = 0 where the last split found the entry's block not free (on the boundary, pinned): a
   preconditioned free gradient restricted to the face, M^-1 phi -> [M^-1]_FF phi_F. */
PetscErrorCode SeparableSetMaskFree_Private(SeparableSet set, Vec z)
{
  SeparableSetData *d = set->data;
  PetscScalar      *za;

  PetscFunctionBegin;
  PetscCall(VecGetArray(z, &za));
  for (PetscInt i = 0; i < d->n; i++)
    if (!d->split_free[i]) za[i] = 0;
  PetscCall(VecRestoreArray(z, &za));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* On the arc blocks of the last split (at x): p becomes its tangential part, Wp = curv p there (0 elsewhere),
   and pWp = p'Wp. Moving an arc block along its circle by the retracted step P(x - a p) has the second
   derivative p'Ap + p'Wp in a (the circle's curvature times the outward push -g.nu), which the CG step
   length and the conjugacy then use. */
PetscErrorCode SeparableSetArcTangent_Private(SeparableSet set, Vec x, Vec p, Vec Wp, PetscReal *pWp)
{
  SeparableSetData  *d = set->data;
  const PetscScalar *xa;
  PetscScalar       *pa, *wa;
  DoubleDouble       sum;

  PetscFunctionBegin;
  PetscCall(VecSet(Wp, 0.0));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArray(p, &pa));
  PetscCall(VecGetArray(Wp, &wa));
  for (size_t k = 0; k < d->disk_arc.size(); k++) {
    if (!d->disk_arc[k]) continue;
    const PetscInt  i = d->disk_idx[2 * k], j = d->disk_idx[2 * k + 1];
    const PetscReal z0 = PetscRealPart(xa[i]) - d->eff_center[2 * k], z1 = PetscRealPart(xa[j]) - d->eff_center[2 * k + 1];
    const PetscReal nz = std::hypot(z0, z1), n0 = z0 / nz, n1 = z1 / nz;
    const PetscReal pn = n0 * PetscRealPart(pa[i]) + n1 * PetscRealPart(pa[j]);
    const PetscReal t0 = PetscRealPart(pa[i]) - pn * n0, t1 = PetscRealPart(pa[j]) - pn * n1;
    pa[i] = t0;
    pa[j] = t1;
    wa[i] = d->disk_curv[k] * t0;
    wa[j] = d->disk_curv[k] * t1;
    sum.addProduct(d->disk_curv[k] * t0, t0);
    sum.addProduct(d->disk_curv[k] * t1, t1);
  }
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecRestoreArray(p, &pa));
  PetscCall(VecRestoreArray(Wp, &wa));
  PetscCall(ReproducibleAllreduce(&sum, 1, PetscObjectComm((PetscObject)set)));
  *pWp = sum.value();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* For the step x - a p of a CG step along arcs: the retraction d = P(x - a p) - (x - a p), nonzero only on
   arc blocks (it puts them back on their circles). Returns d.(g - a Ap) and |d|^2, with which
   q(P(x - a p)) - q(x) <= -a g.p + a^2/2 p'Ap + d.(g - a Ap) + ||A||/2 |d|^2 exactly. */
PetscErrorCode SeparableSetArcRetraction_Private(SeparableSet set, Vec x, PetscReal a, Vec p, Vec g, Vec Ap, PetscReal *dg, PetscReal *dd)
{
  SeparableSetData  *d = set->data;
  const PetscScalar *xa, *pa, *ga, *apa;
  DoubleDouble       sum[2];

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArrayRead(p, &pa));
  PetscCall(VecGetArrayRead(g, &ga));
  PetscCall(VecGetArrayRead(Ap, &apa));
  for (size_t k = 0; k < d->disk_arc.size(); k++) {
    if (!d->disk_arc[k]) continue;
    const PetscInt  i = d->disk_idx[2 * k], j = d->disk_idx[2 * k + 1];
    const PetscReal y0 = PetscRealPart(xa[i]) - a * PetscRealPart(pa[i]) - d->eff_center[2 * k], y1 = PetscRealPart(xa[j]) - a * PetscRealPart(pa[j]) - d->eff_center[2 * k + 1];
    PetscReal       w0 = y0, w1 = y1;
    ProjectDisk(w0, w1, d->disk_radius[k]);
    const PetscReal d0 = w0 - y0, d1 = w1 - y1;
    sum[0].addProduct(d0, PetscRealPart(ga[i]) - a * PetscRealPart(apa[i]));
    sum[0].addProduct(d1, PetscRealPart(ga[j]) - a * PetscRealPart(apa[j]));
    sum[1].addProduct(d0, d0);
    sum[1].addProduct(d1, d1);
  }
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecRestoreArrayRead(p, &pa));
  PetscCall(VecRestoreArrayRead(g, &ga));
  PetscCall(VecRestoreArrayRead(Ap, &apa));
  PetscCall(ReproducibleAllreduce(sum, 2, PetscObjectComm((PetscObject)set)));
  *dg = sum[0].value();
  *dd = sum[1].value();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Largest alpha >= 0 such that x - alpha p stays in the set (infinity if unbounded). Arc blocks of the
   last split (at x) do not limit it: their move along the circle is retracted by the projection. */
PetscErrorCode SeparableSetFeasibleStep_Private(SeparableSet set, Vec x, Vec p, PetscReal *alpha_f)
{
  SeparableSetData  *d;
  const PetscScalar *xa, *pa;
  PetscReal          amin = kInf;

  PetscFunctionBegin;
  PetscCall(SeparableSetSetUp_Private(set));
  d = set->data;
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArrayRead(p, &pa));
  const PetscReal *lo = d->lo.data(), *hi = d->hi.data();
  /* branch-free (the sign of p is a coin toss for the branch predictor): absent bounds are infinite,
     so their ratio is too; p = 0 and the entries of other blocks are masked */
  const unsigned char *kind = d->kind.data();
  for (PetscInt i = 0; i < d->n; i++) {
    const PetscReal pi = PetscRealPart(pa[i]), xi = PetscRealPart(xa[i]);
    const PetscReal r    = pi > 0 ? PetscMax(xi - lo[i], 0) : PetscMin(xi - hi[i], 0);
    const bool      open = pi > 0 ? lo[i] <= -kInf : hi[i] >= kInf; /* no bound that way: r / pi is finite when |pi| > 1 */
    const PetscReal a    = (pi != 0 && kind[i] == SEPARABLE_SCALAR && !open) ? r / pi : kInf;
    amin                 = PetscMin(amin, a);
  }
  for (size_t k = 0; k < d->disk_radius.size(); k++) {
    const PetscInt  i = d->disk_idx[2 * k], j = d->disk_idx[2 * k + 1];
    const PetscReal p0 = PetscRealPart(pa[i]), p1 = PetscRealPart(pa[j]);
    if ((p0 == 0 && p1 == 0) || d->disk_arc[k]) continue; /* an arc block moves along its circle: the projection after the step retracts it */
    const PetscReal z0 = PetscRealPart(xa[i]) - d->eff_center[2 * k], z1 = PetscRealPart(xa[j]) - d->eff_center[2 * k + 1], r = d->disk_radius[k];
    /* |z - alpha p|^2 <= r^2 */
    amin = PetscMin(amin, QuadraticStep(-(p0 * p0 + p1 * p1), -(z0 * p0 + z1 * p1), r * r - (z0 * z0 + z1 * z1)));
  }
  for (size_t k = 0; k < d->cone_mu.size(); k++) {
    const PetscInt  *id = &d->cone_idx[3 * k];
    const PetscReal *v  = &d->cone_apex[3 * k];
    const PetscReal  mu = d->cone_mu[k];
    const PetscReal  pn = PetscRealPart(pa[id[0]]), p1 = PetscRealPart(pa[id[1]]), p2 = PetscRealPart(pa[id[2]]);
    if (pn == 0 && p1 == 0 && p2 == 0) continue;
    const PetscReal yn = PetscRealPart(xa[id[0]]) - v[0], y1 = PetscRealPart(xa[id[1]]) - v[1], y2 = PetscRealPart(xa[id[2]]) - v[2];
    if (mu == 0) { /* only y_n moves freely above 0; moving a pinned tangential entry is infeasible */
      if (p1 != 0 || p2 != 0) amin = 0;
      else if (pn > 0) amin = PetscMin(amin, PetscMax(yn, 0) / pn);
      continue;
    }
    if (yn <= 0) { /* at the apex: feasible iff -p lies in the cone */
      if (std::hypot(p1, p2) > -mu * pn) amin = 0;
      continue;
    }
    /* mu^2 (y_n - a p_n)^2 - |y_t - a p_t|^2 >= 0, staying on the upper nappe (it cannot jump nappes without q < 0 or the apex) */
    amin = PetscMin(amin, QuadraticStep(mu * mu * pn * pn - p1 * p1 - p2 * p2, mu * mu * yn * pn - y1 * p1 - y2 * p2, mu * mu * yn * yn - y1 * y1 - y2 * y2));
  }
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecRestoreArrayRead(p, &pa));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &amin, 1, MPIU_REAL, MPIU_MIN, PetscObjectComm((PetscObject)set)));
  *alpha_f = amin;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetProjectedGradient - The projected gradient gP of a function with gradient g at a feasible x:
  -gP is the projection of -g on the tangent cone of the set at x. Its norm is the KKT residual.

  Collective

  Input Parameters:
+ set - the set
. x   - a feasible point
- g   - the gradient at x

  Output Parameter:
. gp - the projected gradient (may not alias x or g)

  Level: intermediate

.seealso: `SeparableSetProject()`
@*/
PetscErrorCode SeparableSetProjectedGradient(SeparableSet set, Vec x, Vec g, Vec gp)
{
  Vec            beta;
  SeparableSplit s;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  PetscCall(SeparableSetCheckCompatible_Private(set, x));
  PetscCall(VecDuplicate(gp, &beta));
  PetscCall(SeparableSetSplitGradient_Private(set, x, g, 1.0, 0.0, PETSC_FALSE, gp, beta, NULL, NULL, &s));
  PetscCall(VecAXPY(gp, 1.0, beta));
  PetscCall(VecDestroy(&beta));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetDistance - Euclidean distance of a vector from the set.

  Collective

  Input Parameters:
+ set - the set
- x   - the vector

  Output Parameter:
. dist - |x - P(x)|

  Level: intermediate

.seealso: `SeparableSetProject()`
@*/
PetscErrorCode SeparableSetDistance(SeparableSet set, Vec x, PetscReal *dist)
{
  Vec px;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  PetscCall(SeparableSetCheckCompatible_Private(set, x));
  PetscCall(VecDuplicate(x, &px));
  PetscCall(SeparableSetProjectedStep_Private(set, x, 0.0, NULL, px));
  PetscCall(VecAXPY(px, -1.0, x));
  PetscCall(VecNorm(px, NORM_2, dist));
  PetscCall(VecDestroy(&px));
  PetscFunctionReturn(PETSC_SUCCESS);
}
