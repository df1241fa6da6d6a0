/* The closest point of a triangle surface: what a contact zone between bodies pairs each slave node with.

   ContactTriangleClosestPoint() finds the closest point of one triangle by the Voronoi region of the point:
   one of the three vertices, the interior of one of the three edges, or the interior of the triangle, each
   recognized by the signs of a few dot products (no square roots, no division except by a positive
   denominator), and returns its barycentric weights, which are exactly (1, 0, 0) at a vertex and have an exact
   zero on an edge. ContactSurfaceSearch puts the triangles of a surface into a uniform grid of buckets (a
   triangle into every bucket its bounding box meets) so that a query only tests the triangles near the point,
   not all of them. Among triangles at the same distance the one with the smallest index wins: the answer does
   not depend on the order in which the buckets are visited, and every rank, which holds the same surface,
   finds the same pairing. */
#include <conefeti/private/contactmodelimpl.h>
#include <algorithm>
#include <cmath>

namespace {

inline PetscReal Dot(const PetscReal a[3], const PetscReal b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

} // namespace

void ContactTriangleClosestPoint(const PetscReal x[3], const PetscReal a[3], const PetscReal b[3], const PetscReal c[3], PetscReal chi[3], PetscReal w[3])
{
  PetscReal ab[3], ac[3], ax[3], bx[3], cx[3];
  for (int i = 0; i < 3; i++) {
    ab[i] = b[i] - a[i];
    ac[i] = c[i] - a[i];
    ax[i] = x[i] - a[i];
    bx[i] = x[i] - b[i];
    cx[i] = x[i] - c[i];
  }
  /* the projections of x - a, x - b, x - c on the two edge directions from a */
  const PetscReal d1 = Dot(ab, ax), d2 = Dot(ac, ax), d3 = Dot(ab, bx), d4 = Dot(ac, bx), d5 = Dot(ab, cx), d6 = Dot(ac, cx);
  /* signed areas (times 2|n|^2) of the sub-triangles x'bc, ax'c, abx' of the projection x' of x: the unnormalized
     barycentric weights when x' is inside */
  const PetscReal va = d3 * d6 - d5 * d4, vb = d5 * d2 - d1 * d6, vc = d1 * d4 - d3 * d2;
  PetscReal       wa, wb, wc;
  if (d1 <= 0 && d2 <= 0) wa = 1, wb = 0, wc = 0;       /* vertex a */
  else if (d3 >= 0 && d4 <= d3) wa = 0, wb = 1, wc = 0; /* vertex b */
  else if (vc <= 0 && d1 >= 0 && d3 <= 0) { /* edge ab */ wb = d1 / (d1 - d3);
    wa = 1 - wb, wc = 0;
  } else if (d6 >= 0 && d5 <= d6) wa = 0, wb = 0, wc = 1; /* vertex c */
  else if (vb <= 0 && d2 >= 0 && d6 <= 0) { /* edge ac */ wc = d2 / (d2 - d6);
    wa = 1 - wc, wb = 0;
  } else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) { /* edge bc */
    wc = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    wa = 0, wb = 1 - wc;
  } else if (va + vb + vc > 0) { /* interior */
    const PetscReal s = va + vb + vc;
    wb                = vb / s;
    wc                = vc / s;
    wa                = 1 - wb - wc;
  } else { /* a degenerate (flat) triangle: the nearest of its edges' points */
    const PetscReal *P[3] = {a, b, c};
    PetscReal        best = PETSC_MAX_REAL;
    wa = 1, wb = 0, wc = 0;
    for (int e = 0; e < 3; e++) {
      const PetscReal *p = P[e], *q = P[(e + 1) % 3];
      PetscReal        pq[3], px[3], t = 0, d2e = 0;
      for (int i = 0; i < 3; i++) pq[i] = q[i] - p[i], px[i] = x[i] - p[i];
      const PetscReal l2 = Dot(pq, pq);
      if (l2 > 0) t = PetscMin(PetscMax(Dot(pq, px) / l2, 0.0), 1.0);
      for (int i = 0; i < 3; i++) d2e += (px[i] - t * pq[i]) * (px[i] - t * pq[i]);
      if (d2e < best) {
        PetscReal ww[3] = {0, 0, 0};
        ww[e]           = 1 - t;
        ww[(e + 1) % 3] = t;
        wa = ww[0], wb = ww[1], wc = ww[2];
        best = d2e;
      }
    }
  }
  w[0] = wa;
  w[1] = wb;
  w[2] = wc;
  for (int i = 0; i < 3; i++) chi[i] = wa * a[i] + wb * b[i] + wc * c[i];
}

PetscErrorCode ContactSurfaceSearch::SetUp(PetscInt ntri, const PetscInt tri[], const PetscReal X[])
{
  PetscFunctionBegin;
  this->ntri   = ntri;
  this->tri    = tri;
  this->X      = X;
  longest_edge = 0;
  mean_edge    = 0;
  PetscCallCXX(box.assign(6 * (size_t)ntri, 0));
  PetscReal lo[3] = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}, hi[3] = {-PETSC_MAX_REAL, -PETSC_MAX_REAL, -PETSC_MAX_REAL};
  for (PetscInt t = 0; t < ntri; t++) {
    PetscReal *bx = &box[6 * t];
    for (int i = 0; i < 3; i++) bx[i] = PETSC_MAX_REAL, bx[3 + i] = -PETSC_MAX_REAL;
    for (int v = 0; v < 3; v++) {
      const PetscReal *p = &X[3 * tri[3 * t + v]], *q = &X[3 * tri[3 * t + (v + 1) % 3]];
      const PetscReal  e = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
      longest_edge       = PetscMax(longest_edge, e);
      mean_edge += e;
      for (int i = 0; i < 3; i++) bx[i] = PetscMin(bx[i], p[i]), bx[3 + i] = PetscMax(bx[3 + i], p[i]);
    }
    for (int i = 0; i < 3; i++) lo[i] = PetscMin(lo[i], bx[i]), hi[i] = PetscMax(hi[i], bx[3 + i]);
  }
  if (ntri) mean_edge /= 3 * ntri;
  PetscCallCXX(cells.clear());
  PetscCallCXX(start.assign(2, 0));
  for (int i = 0; i < 3; i++) n[i] = 1, origin[i] = 0;
  h = 1;
  if (!ntri) PetscFunctionReturn(PETSC_SUCCESS);
  /* buckets about the mean edge long, at most ~2 per triangle (a flat surface has one layer of them) */
  h = PetscMax(mean_edge, 1e-300);
  for (;;) {
    double total = 1;
    for (int i = 0; i < 3; i++) total *= std::floor((hi[i] - lo[i]) / h) + 1;
    if (total <= 2.0 * ntri + 8) break;
    h *= 1.5;
  }
  for (int i = 0; i < 3; i++) {
    origin[i] = lo[i];
    n[i]      = (PetscInt)std::floor((hi[i] - lo[i]) / h) + 1;
  }
  /* bucket lists in CSR form: count, then fill */
  const PetscInt ncell = n[0] * n[1] * n[2];
  PetscCallCXX(start.assign(ncell + 1, 0));
  for (int pass = 0; pass < 2; pass++) {
    std::vector<PetscInt> fill;
    if (pass) {
      for (PetscInt c = 0; c < ncell; c++) start[c + 1] += start[c];
      PetscCallCXX(cells.resize(start[ncell]));
      PetscCallCXX(fill.assign(start.begin(), start.end() - 1));
    }
    for (PetscInt t = 0; t < ntri; t++) {
      PetscInt r[6];
      Range(&box[6 * t], &box[6 * t + 3], r);
      for (PetscInt k = r[4]; k <= r[5]; k++)
        for (PetscInt j = r[2]; j <= r[3]; j++)
          for (PetscInt i = r[0]; i <= r[1]; i++) {
            const PetscInt c = i + n[0] * (j + n[1] * k);
            if (pass) cells[fill[c]++] = t;
            else start[c + 1]++;
          }
    }
  }
  PetscCallCXX(stamp.assign(ntri, 0));
  query = 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the buckets [r[0], r[1]] x [r[2], r[3]] x [r[4], r[5]] that the box [lo, hi] meets (clamped to the grid) */
void ContactSurfaceSearch::Range(const PetscReal lo[3], const PetscReal hi[3], PetscInt r[6]) const
{
  for (int i = 0; i < 3; i++) {
    const double a = std::floor((lo[i] - origin[i]) / h), b = std::floor((hi[i] - origin[i]) / h);
    r[2 * i]     = (PetscInt)std::min(std::max(a, 0.0), (double)(n[i] - 1));
    r[2 * i + 1] = (PetscInt)std::min(std::max(b, 0.0), (double)(n[i] - 1));
  }
}

PetscErrorCode ContactSurfaceSearch::Closest(const PetscReal x[3], PetscReal dmax, ContactSurfacePoint &p)
{
  PetscFunctionBegin;
  p.triangle = -1;
  p.dist     = PETSC_MAX_REAL;
  if (!ntri || !(dmax >= 0)) PetscFunctionReturn(PETSC_SUCCESS);
  PetscReal      lo[3], hi[3], best = dmax * dmax;
  PetscInt       r[6];
  const PetscInt q = ++query;
  for (int i = 0; i < 3; i++) lo[i] = x[i] - dmax, hi[i] = x[i] + dmax;
  Range(lo, hi, r);
  for (PetscInt k = r[4]; k <= r[5]; k++)
    for (PetscInt j = r[2]; j <= r[3]; j++)
      for (PetscInt i = r[0]; i <= r[1]; i++) {
        const PetscInt c = i + n[0] * (j + n[1] * k);
        for (PetscInt s = start[c]; s < start[c + 1]; s++) {
          const PetscInt t = cells[s];
          if (stamp[t] == q) continue;
          stamp[t] = q;
          /* the distance to the triangle's box first: most candidates end here */
          const PetscReal *bx = &box[6 * t];
          PetscReal        db = 0;
          for (int m = 0; m < 3; m++) {
            const PetscReal e = PetscMax(PetscMax(bx[m] - x[m], x[m] - bx[3 + m]), 0.0);
            db += e * e;
          }
          if (db > best) continue;
          PetscReal chi[3], w[3], d2 = 0;
          ContactTriangleClosestPoint(x, &X[3 * tri[3 * t]], &X[3 * tri[3 * t + 1]], &X[3 * tri[3 * t + 2]], chi, w);
          for (int m = 0; m < 3; m++) d2 += (chi[m] - x[m]) * (chi[m] - x[m]);
          /* the nearer triangle, and on a tie the one with the smaller index: independent of the visiting order */
          if (d2 < best || (d2 == best && (p.triangle < 0 || t < p.triangle))) {
            best       = d2;
            p.triangle = t;
            for (int m = 0; m < 3; m++) p.chi[m] = chi[m], p.w[m] = w[m];
          }
        }
      }
  if (p.triangle >= 0) p.dist = std::sqrt(best);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* every triangle, no buckets: the distance of a point that the bucketed search did not find within its distance
   (for the message that says how far the master surface is) */
PetscErrorCode ContactSurfaceSearch::Nearest(const PetscReal x[3], ContactSurfacePoint &p) const
{
  PetscReal best = PETSC_MAX_REAL;

  PetscFunctionBegin;
  p.triangle = -1;
  p.dist     = PETSC_MAX_REAL;
  for (PetscInt t = 0; t < ntri; t++) {
    PetscReal chi[3], w[3], d2 = 0;
    ContactTriangleClosestPoint(x, &X[3 * tri[3 * t]], &X[3 * tri[3 * t + 1]], &X[3 * tri[3 * t + 2]], chi, w);
    for (int m = 0; m < 3; m++) d2 += (chi[m] - x[m]) * (chi[m] - x[m]);
    if (d2 < best) {
      best       = d2;
      p.triangle = t;
      for (int m = 0; m < 3; m++) p.chi[m] = chi[m], p.w[m] = w[m];
    }
  }
  if (p.triangle >= 0) p.dist = std::sqrt(best);
  PetscFunctionReturn(PETSC_SUCCESS);
}
