/* The rigid obstacles of foundation zones: plane, sphere, cylinder. For each, the closest point chi(x)
   of the obstacle's surface to a node x, and from it the node's gap and contact normal as the seed paper
   defines them: n = (chi(x) - x)/|chi(x) - x| (into the obstacle), gap = (chi(x) - x).n. The body lies
   outside the obstacle; a node inside it (an initial overlap, which is how an indentation depth is set)
   gets a negative gap and keeps n = minus the obstacle's outward normal at chi(x), so that its contact
   row still pushes it out. The row N u = n.u <= gap linearizes the distance to the surface at x: exact
   for the plane, first order in u/R for the curved shapes (small displacements, as the whole model). */
#include <conefeti/private/contactmodelimpl.h>
#include <algorithm>
#include <cmath>

const char *const ContactObstacleShapes[] = {"plane", "sphere", "cylinder", "ContactObstacleShape", "CONTACT_OBSTACLE_", NULL};

namespace {

/* |v|, scaled by the largest entry first (no overflow or underflow for extreme entries) */
PetscReal Length(const PetscReal v[3])
{
  const PetscReal m = std::max({std::fabs(v[0]), std::fabs(v[1]), std::fabs(v[2])});
  if (!(m > 0)) return 0;
  const PetscReal a = v[0] / m, b = v[1] / m, c = v[2] / m;
  return m * std::sqrt(a * a + b * b + c * c);
}

PetscReal Dot(const PetscReal a[3], const PetscReal b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* a node closer than this fraction of the radius to the centre (sphere) or the axis (cylinder) has no
   well-defined outward direction: its normal would follow roundoff */
constexpr PetscReal kCentreTol = 1e-10;
/* a gap at most this many machine epsilons times the largest coordinate (or radius) it comes from is rounding */
constexpr PetscReal kGapRounding = 64;

} // namespace

/*@C
  ContactZoneCheckObstacle - Check a foundation zone's obstacle: a plane needs a nonzero normal, a sphere a
  finite radius > 0, a cylinder a finite radius > 0 and a nonzero axis (zones between bodies pass).

  Not Collective

  Input Parameter:
. zone - the zone

  Level: intermediate

.seealso: `ContactZone`, `ContactObstacleShape`, `ContactModelAddZone()`
@*/
PetscErrorCode ContactZoneCheckObstacle(const ContactZone *zone)
{
  PetscFunctionBegin;
  PetscAssertPointer(zone, 1);
  if (zone->type != CONTACT_ZONE_FOUNDATION) PetscFunctionReturn(PETSC_SUCCESS);
  /* a plane through z = -inf gave infinite gaps, which the rounding guard of the gap turned into 0: the body
     "touched" it and the solve converged. Only the vectors of the zone's shape count */
  {
    const bool       plane = zone->shape == CONTACT_OBSTACLE_PLANE, cylinder = zone->shape == CONTACT_OBSTACLE_CYLINDER;
    const PetscReal *v[2]    = {plane ? zone->point : zone->center, plane ? zone->normal : (cylinder ? zone->axis : NULL)};
    const char      *name[2] = {plane ? "point" : "center", plane ? "normal" : "axis"};
    for (int q = 0; q < 2; q++)
      if (v[q])
        for (int c = 0; c < 3; c++)
          PetscCheck(!PetscIsInfOrNanReal(v[q][c]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "contact zone: the %s obstacle's %s (%g, %g, %g) is not finite", ContactObstacleShapes[zone->shape],
                     name[q], (double)v[q][0], (double)v[q][1], (double)v[q][2]);
  }
  switch (zone->shape) {
  case CONTACT_OBSTACLE_PLANE: PetscCheck(Length(zone->normal) > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "contact zone: the foundation plane needs a nonzero normal"); break;
  case CONTACT_OBSTACLE_SPHERE:
  case CONTACT_OBSTACLE_CYLINDER:
    PetscCheck(zone->radius > 0 && zone->radius < PETSC_MAX_REAL, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "contact zone: the %s obstacle needs a finite radius > 0, got %g",
               ContactObstacleShapes[zone->shape], (double)zone->radius);
    if (zone->shape == CONTACT_OBSTACLE_CYLINDER) PetscCheck(Length(zone->axis) > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "contact zone: the cylinder obstacle needs a nonzero axis");
    break;
  default: SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "contact zone: unknown obstacle shape %d", (int)zone->shape);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  ContactZoneComputeGap - The closest point of a foundation zone's obstacle surface to a point, the gap and
  the contact normal there.

  Not Collective

  Input Parameters:
+ zone - a foundation zone (checked by `ContactZoneCheckObstacle()`)
- x    - the point (a node of the body)

  Output Parameters:
+ chi - the closest point of the obstacle's surface (or NULL)
. gap - the distance to the surface, (chi - x).n: negative when x lies inside the obstacle (or NULL)
- n   - the unit contact normal, pointing into the obstacle: (chi - x)/|chi - x| when x is outside, minus
        the obstacle's outward normal at chi always (or NULL)

  Notes:
  Plane (point p, normal m toward the body, unit after scaling): gap = (x - p).m, n = -m, chi = x - gap m.
  Sphere (center c, radius R): gap = |x - c| - R, n = -(x - c)/|x - c|, chi = c - R n.
  Cylinder (axis through c along a, radius R): with y the part of x - c normal to a, gap = |y| - R,
  n = -y/|y|, chi = x + gap n.
  A point on the sphere's centre or the cylinder's axis (closer than 1e-10 R) has no defined normal: error.
  A gap within the rounding of its computation, |gap| <= 64 eps max(|x|, |p| or |c|, R) (max norms, eps the
  machine epsilon), is returned as 0: the point lies on the surface as far as its coordinates can say.

  Level: intermediate

.seealso: `ContactZone`, `ContactObstacleShape`, `ContactModelGetNodeGeometry()`
@*/
PetscErrorCode ContactZoneComputeGap(const ContactZone *zone, const PetscReal x[], PetscReal chi[], PetscReal *gap, PetscReal n[])
{
  PetscReal nn[3], g = 0;

  PetscFunctionBegin;
  PetscAssertPointer(zone, 1);
  PetscAssertPointer(x, 2);
  PetscCheck(zone->type == CONTACT_ZONE_FOUNDATION, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "ContactZoneComputeGap: only foundation zones have an obstacle");
  PetscCall(ContactZoneCheckObstacle(zone));
  switch (zone->shape) {
  case CONTACT_OBSTACLE_PLANE: {
    const PetscReal len  = Length(zone->normal);
    const PetscReal m[3] = {zone->normal[0] / len, zone->normal[1] / len, zone->normal[2] / len};
    const PetscReal y[3] = {x[0] - zone->point[0], x[1] - zone->point[1], x[2] - zone->point[2]};
    g                    = Dot(y, m);
    for (int c = 0; c < 3; c++) nn[c] = -m[c];
  } break;
  case CONTACT_OBSTACLE_SPHERE:
  case CONTACT_OBSTACLE_CYLINDER: {
    PetscReal y[3] = {x[0] - zone->center[0], x[1] - zone->center[1], x[2] - zone->center[2]};
    if (zone->shape == CONTACT_OBSTACLE_CYLINDER) {
      const PetscReal len  = Length(zone->axis);
      const PetscReal a[3] = {zone->axis[0] / len, zone->axis[1] / len, zone->axis[2] / len};
      const PetscReal s    = Dot(y, a);
      for (int c = 0; c < 3; c++) y[c] -= s * a[c];
    }
    const PetscReal dist = Length(y);
    PetscCheck(dist > kCentreTol * zone->radius, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
               "contact zone: the point (%g, %g, %g) lies on the %s obstacle's %s, where the contact normal is undefined; move the obstacle (its center%s)", (double)x[0], (double)x[1], (double)x[2],
               ContactObstacleShapes[zone->shape], zone->shape == CONTACT_OBSTACLE_SPHERE ? "centre" : "axis", zone->shape == CONTACT_OBSTACLE_CYLINDER ? " or axis" : "");
    g = dist - zone->radius;
    for (int c = 0; c < 3; c++) nn[c] = -y[c] / dist;
  } break;
  default: SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "contact zone: unknown obstacle shape %d", (int)zone->shape);
  }
  { /* a gap within the rounding of the differences of coordinates it comes from is zero: a node placed on the
       surface (a sphere touching a scaled mesh's corner) would otherwise get a gap of +-1e-17 and, in a scene with
       no other load, a solve of rounding that no residual can judge */
    const PetscReal *o   = zone->shape == CONTACT_OBSTACLE_PLANE ? zone->point : zone->center;
    PetscReal        mag = zone->shape == CONTACT_OBSTACLE_PLANE ? 0 : zone->radius;
    for (int c = 0; c < 3; c++) mag = PetscMax(mag, PetscMax(PetscAbsReal(x[c]), PetscAbsReal(o[c])));
    if (PetscAbsReal(g) <= kGapRounding * PETSC_MACHINE_EPSILON * mag) g = 0;
  }
  if (chi)
    for (int c = 0; c < 3; c++) chi[c] = x[c] + g * nn[c];
  if (gap) *gap = g;
  if (n)
    for (int c = 0; c < 3; c++) n[c] = nn[c];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the gap and normal of a foundation zone's node, with an error that names the zone, the body and the node */
PetscErrorCode ContactObstacleNodeGeometry_Private(ContactModel cm, PetscInt z, ContactNodeInfo &info)
{
  const ContactZone &zone = cm->data->zones[z];
  PetscReal          y[3] = {info.x[0] - zone.center[0], info.x[1] - zone.center[1], info.x[2] - zone.center[2]};

  PetscFunctionBegin;
  if (zone.shape != CONTACT_OBSTACLE_PLANE) { /* the one failure of ContactZoneComputeGap() a checked zone can meet, named for the model */
    if (zone.shape == CONTACT_OBSTACLE_CYLINDER) {
      const PetscReal len = Length(zone.axis), s = Dot(y, zone.axis) / (len * len);
      for (int c = 0; c < 3; c++) y[c] -= s * zone.axis[c];
    }
    PetscCheck(Length(y) > kCentreTol * zone.radius, PetscObjectComm((PetscObject)cm), PETSC_ERR_ARG_WRONG,
               "contact zone %" PetscInt_FMT ": node %" PetscInt_FMT " of body %" PetscInt_FMT " at (%g, %g, %g) lies on the %s obstacle's %s, where the contact normal is undefined; move the "
               "obstacle (-scene_zone%" PetscInt_FMT "_center%s)",
               z, info.node, info.body, (double)info.x[0], (double)info.x[1], (double)info.x[2], ContactObstacleShapes[zone.shape], zone.shape == CONTACT_OBSTACLE_SPHERE ? "centre" : "axis", z,
               zone.shape == CONTACT_OBSTACLE_CYLINDER ? ", _axis" : "");
  }
  PetscCall(ContactZoneComputeGap(&zone, info.x, NULL, &info.gap, info.n));
  PetscFunctionReturn(PETSC_SUCCESS);
}
