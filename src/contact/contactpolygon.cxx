/* The friction polygon: the approximation of the friction disk |l_t| <= g by simple bounds (the approximate method
   of Haslinger, Kucera and Dostal, J. Comput. Appl. Math. 164-165 (2004), with which the seed paper compares its
   disk-constrained method in Table 3).

   A friction node gets k tangential rows d_j.(u_A - u_B) instead of two, along the directions
   d_j = cos(j pi/k) t1 + sin(j pi/k) t2, j = 0..k-1, and k multipliers m_j with the box constraints |m_j| <= c g.
   The friction force is -sum_j m_j d_j: the set of admissible tangential forces is the zonotope
   {sum_j m_j d_j : |m_j| <= c g}, a regular 2k-gon (a square for k = 2, an octagon for k = 4). In the primal
   this replaces the Euclidean norm of the slip in the friction term g |u_t| by the polyhedral norm
   c g sum_j |d_j.u_t|; the dual of that term is the box. The dual contact problem then has bounds only, and the
   bound-constrained MPRGP solves it.

   The polygon is inscribed in the disk, c = sin(pi/(2k)) (its vertices lie on the circle of radius g): every
   polygon solution has |l_t| <= g, an admissible friction force of the disk law, and the error of the
   approximation is one-sided (less friction than the law allows, by at most 1 - cos(pi/(2k)) of g: 29% for
   k = 2, 7.6% for k = 4, in the directions of the edge midpoints). The edges of a zonotope are parallel to its
   generators, so the edge normals are the d_j turned by pi/2 and the inradius is
   c g sum_i |sin(i pi/k)| = c g cot(pi/(2k)) = g cos(pi/(2k)). */
#include <conefeti/private/contactimpl.h>
#include <cmath>
#include <limits>

/* c: each multiplier's bound over g, so that the polygon's vertices lie on the circle of radius g */
PetscReal ContactPolygonBoundFactor(PetscInt k) { return std::sin(PETSC_PI / (2.0 * (PetscReal)k)); }

/* d_j in the node's (t1, t2) frame */
void ContactPolygonDirection(PetscInt k, PetscInt j, PetscReal d[2])
{
  const PetscReal a = PETSC_PI * (PetscReal)j / (PetscReal)k;
  d[0]              = j == 0 ? 1.0 : std::cos(a);
  d[1]              = j == 0 ? 0.0 : std::sin(a);
  if (2 * j == k) d[0] = 0.0, d[1] = 1.0; /* exactly t2, so that k = 2 gives the rows of the disk method */
}

/* the tangential force sum_j m_j d_j of the multipliers m (k of them) in the (t1, t2) frame */
void ContactPolygonTraction(PetscInt k, const PetscReal m[], PetscReal lt[2])
{
  lt[0] = lt[1] = 0;
  for (PetscInt j = 0; j < k; j++) {
    PetscReal d[2];
    ContactPolygonDirection(k, j, d);
    lt[0] += m[j] * d[0];
    lt[1] += m[j] * d[1];
  }
}

/* the tangential motion (t1.u, t2.u) from the k rows' values du_j = d_j.u: the first two directions are
   independent (d_0 = t1) */
void ContactPolygonTangentialMotion(PetscInt k, const PetscReal du[], PetscReal tu[2])
{
  PetscReal d[2];
  ContactPolygonDirection(k, 1, d);
  tu[0] = du[0];
  tu[1] = (du[1] - d[0] * du[0]) / d[1];
}

/* the polygon's gauge of lt for the slip bound g: <= 1 inside the polygon, 1 on its boundary */
PetscReal ContactPolygonGauge(PetscInt k, const PetscReal lt[2], PetscReal g)
{
  const PetscReal inradius = g * std::cos(PETSC_PI / (2.0 * (PetscReal)k));
  PetscReal       s        = 0;
  for (PetscInt j = 0; j < k; j++) {
    PetscReal d[2];
    ContactPolygonDirection(k, j, d);
    s = PetscMax(s, PetscAbsReal(-d[1] * lt[0] + d[0] * lt[1])); /* along the normal of the edges parallel to d_j */
  }
  if (!(inradius > 0)) return s > 0 ? std::numeric_limits<PetscReal>::infinity() : 0.0;
  return s / inradius;
}
