/* The rigid obstacles of foundation zones (src/contact/contactobstacle.cxx): the gap and the normal of a node
   come from the closest point chi(x) of the obstacle's surface. -case selects one property:

   closest_point  ContactZoneComputeGap() on points around a sphere, a cylinder and a plane, inside and
                  outside: chi lies on the surface (|chi - c| = R, its distance to the axis is R, on the plane),
                  n is a unit vector, chi - x = gap n, the gap is the signed distance (|x - c| - R, ...), and n
                  points into the obstacle: minus the outward normal at chi, also for a point inside
   box_nodes      a box (0,1)x(0,1)x(0,1) under a sphere (or a cylinder along y) above its top face, set as a
                  ContactModel: every contact node has the gap |x - c| - R and the normal (c - x)/|c - x|
                  (cylinder: of the part normal to the axis); the node right below the centre has the gap
                  (distance - R) and the normal +z; -overlap d moves the obstacle down by d, and the nodes
                  inside get negative gaps (accepted)
   on_centre      a node on the sphere's centre: the setup fails with a message naming the zone and the node
   bad_zone       ContactModelAddZone() rejects a sphere of radius 0, a cylinder with a zero axis, a plane through an
                  infinite point and a law that is no ContactLaw (-what radius|axis|point_inf|law) */
#include <conefeti.h>
#include <conefeti/compat.h>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

static PetscReal Dist(const PetscReal a[3], const PetscReal b[3]) { return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])); }

/* distance from x to the line through c along the unit vector a */
static PetscReal AxisDist(const PetscReal x[3], const PetscReal c[3], const PetscReal a[3])
{
  PetscReal y[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
  PetscReal s    = y[0] * a[0] + y[1] * a[1] + y[2] * a[2];
  for (int i = 0; i < 3; i++) y[i] -= s * a[i];
  return std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
}

static PetscErrorCode CaseClosestPoint(void)
{
  ContactZone     sphere = {}, cyl = {}, plane = {};
  PetscReal       worst  = 0;
  PetscInt        inside = 0, count = 0;
  PetscRandom     rnd;
  const PetscReal axis[3] = {0.6, 0, 0.8}; /* unit */

  PetscFunctionBeginUser;
  sphere.type      = CONTACT_ZONE_FOUNDATION;
  sphere.shape     = CONTACT_OBSTACLE_SPHERE;
  sphere.radius    = 0.7;
  sphere.center[0] = 0.1, sphere.center[1] = -0.2, sphere.center[2] = 0.3;
  cyl         = sphere;
  cyl.shape   = CONTACT_OBSTACLE_CYLINDER;
  cyl.axis[0] = 3, cyl.axis[1] = 0, cyl.axis[2] = 4; /* not unit: only the direction matters */
  plane.type      = CONTACT_ZONE_FOUNDATION;
  plane.point[2]  = 0.25;
  plane.normal[0] = 0, plane.normal[1] = 0, plane.normal[2] = 2;
  PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -2, 2));
  for (PetscInt k = 0; k < 200; k++) {
    PetscReal x[3], chi[3], n[3], gap, expect, e = 0;
    for (int i = 0; i < 3; i++) PetscCall(PetscRandomGetValueReal(rnd, &x[i]));
    for (const ContactZone *z : {&sphere, &cyl, &plane}) {
      PetscCall(ContactZoneComputeGap(z, x, chi, &gap, n));
      const PetscReal nlen = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      e                    = PetscMax(e, std::fabs(nlen - 1));
      for (int i = 0; i < 3; i++) e = PetscMax(e, std::fabs(chi[i] - x[i] - gap * n[i])); /* chi - x = gap n */
      PetscReal out[3];                                                                   /* outward normal of the obstacle at chi */
      if (z->shape == CONTACT_OBSTACLE_SPHERE) {
        expect = Dist(x, z->center) - z->radius;
        e      = PetscMax(e, std::fabs(Dist(chi, z->center) - z->radius));
        for (int i = 0; i < 3; i++) out[i] = (chi[i] - z->center[i]) / z->radius;
      } else if (z->shape == CONTACT_OBSTACLE_CYLINDER) {
        expect         = AxisDist(x, z->center, axis) - z->radius;
        e              = PetscMax(e, std::fabs(AxisDist(chi, z->center, axis) - z->radius));
        PetscReal y[3] = {chi[0] - z->center[0], chi[1] - z->center[1], chi[2] - z->center[2]}, s = y[0] * axis[0] + y[1] * axis[1] + y[2] * axis[2];
        for (int i = 0; i < 3; i++) out[i] = (y[i] - s * axis[i]) / z->radius;
      } else {
        expect = x[2] - 0.25;
        e      = PetscMax(e, std::fabs(chi[2] - 0.25));
        out[0] = out[1] = 0, out[2] = 1;
      }
      e = PetscMax(e, std::fabs(gap - expect));
      for (int i = 0; i < 3; i++) e = PetscMax(e, std::fabs(n[i] + out[i])); /* n = -outward normal, inside or outside */
      if (gap < 0) inside++;
      count++;
    }
    worst = PetscMax(worst, e);
  }
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%" PetscInt_FMT " points (%" PetscInt_FMT " inside an obstacle): largest error %.2e\n", count, inside, (double)worst));
  PetscCheck(worst < 1e-13 && inside > 10 && inside < count - 10, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "closest point, gap or normal wrong (error %g) or the points do not cover both sides",
             (double)worst);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* a box (0,1)^3 clamped at its bottom, 4x4x4 cells, its top face z1 under the obstacle */
static PetscErrorCode BoxModel(const ContactZone &zone, FEM *fem, ContactModel *cm)
{
  PetscReal   lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  PetscInt    cells[3] = {4, 4, 4}, sub[3] = {2, 1, 1}, body;
  ContactZone z = zone;

  PetscFunctionBeginUser;
  PetscCall(FEMCreate(PETSC_COMM_WORLD, fem));
  PetscCall(FEMAddBox(*fem, lo, hi, cells, &body));
  PetscCall(FEMSetMaterial(*fem, body, 1e9, 0.3));
  PetscCall(FEMSetDirichlet(*fem, body, "z0", NULL));
  PetscCall(FEMSetDecomposition(*fem, body, FEM_DECOMPOSITION_STRUCTURED, sub));
  PetscCall(FEMSetUp(*fem));
  PetscCall(ContactModelCreate(*fem, cm));
  z.type = CONTACT_ZONE_FOUNDATION;
  z.body = body;
  PetscCall(PetscStrcpy(z.face, "z1"));
  /* z.law as the caller left it: frictionless from ContactZone z = {} */
  PetscCall(ContactModelAddZone(*cm, &z));
  PetscCall(ContactModelSetUp(*cm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CaseBoxNodes(const char *shape, PetscReal overlap)
{
  ContactZone      z = {};
  FEM              fem;
  ContactModel     cm;
  PetscInt         n, below = 0, negative = 0, total;
  const PetscReal *X, *area;
  PetscReal        e        = 0;
  const PetscBool  cylinder = std::string(shape) == "cylinder" ? PETSC_TRUE : PETSC_FALSE;

  PetscFunctionBeginUser;
  z.shape  = cylinder ? CONTACT_OBSTACLE_CYLINDER : CONTACT_OBSTACLE_SPHERE;
  z.radius = 0.8;
  /* the obstacle touches the top face at (0.5, 0.5, 1), then moves down by the overlap */
  z.center[0] = 0.5, z.center[1] = 0.5, z.center[2] = 1 + z.radius - overlap;
  if (cylinder) z.axis[1] = 2;
  PetscCall(BoxModel(z, &fem, &cm));
  PetscCall(ContactModelGetNodes(cm, &n, NULL, NULL, &X, &area));
  std::vector<PetscReal> normal(3 * n), gap(n);
  PetscCall(ContactModelGetNodeGeometry(cm, normal.data(), gap.data()));
  for (PetscInt j = 0; j < n; j++) {
    const PetscReal *x    = &X[3 * j];
    PetscReal        y[3] = {z.center[0] - x[0], z.center[1] - x[1], z.center[2] - x[2]}, d;
    if (cylinder) y[1] = 0; /* the part normal to the axis y */
    d = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
    e = PetscMax(e, std::fabs(gap[j] - (d - z.radius)));
    for (int i = 0; i < 3; i++) e = PetscMax(e, std::fabs(normal[3 * j + i] - y[i] / d));
    if (gap[j] < 0) negative++;
    if (std::fabs(x[0] - 0.5) < 1e-12 && (cylinder || std::fabs(x[1] - 0.5) < 1e-12)) { /* right below the centre (the axis) */
      below++;
      e = PetscMax(e, std::fabs(gap[j] + overlap));
      e = PetscMax(e, std::fabs(normal[3 * j + 2] - 1));
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &e, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &below, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &negative, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(&n, &total, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s, overlap %g: %" PetscInt_FMT " contact nodes, %" PetscInt_FMT " below the %s, %" PetscInt_FMT " with a negative gap; largest error %.2e\n", shape,
                        (double)overlap, total, below, cylinder ? "axis" : "centre", negative, (double)e));
  PetscCheck(total == 25 && below == (cylinder ? 5 : 1) && e < 1e-13, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "wrong contact nodes, gaps or normals");
  PetscCheck(overlap > 0 ? negative > 0 : negative == 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the overlap does not give negative gaps (or a gap is negative without overlap)");
  PetscCall(ContactModelDestroy(&cm));
  PetscCall(FEMDestroy(&fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CaseOnCentre(void)
{
  ContactZone  z = {};
  FEM          fem;
  ContactModel cm;

  PetscFunctionBeginUser;
  z.shape     = CONTACT_OBSTACLE_SPHERE;
  z.radius    = 0.3;
  z.center[0] = 0.5, z.center[1] = 0.5, z.center[2] = 1; /* a node of the top face */
  PetscCall(BoxModel(z, &fem, &cm));
  PetscCall(ContactModelDestroy(&cm));
  PetscCall(FEMDestroy(&fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CaseBadZone(const char *what)
{
  ContactZone  z = {};
  FEM          fem;
  ContactModel cm;

  PetscFunctionBeginUser;
  const std::string w(what);
  z.shape     = w == "radius" || w == "law" ? CONTACT_OBSTACLE_SPHERE : (w == "point_inf" ? CONTACT_OBSTACLE_PLANE : CONTACT_OBSTACLE_CYLINDER);
  z.radius    = w == "radius" ? 0 : 1; /* with -what law a valid sphere */
  z.center[2] = 3;
  if (w == "point_inf") { /* a plane at z = -inf: the gaps were infinite, rounded to 0, and the body "touched" it */
    z.point[2]  = -std::numeric_limits<PetscReal>::infinity();
    z.normal[2] = 1;
  }
  if (w == "law") z.law = (ContactLaw)7; /* was accepted, and the run ended with a misleading friction-cone failure */
  PetscCall(BoxModel(z, &fem, &cm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char      c[64] = "closest_point", shape[32] = "sphere", what[32] = "radius";
  PetscReal overlap = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Rigid obstacles: closest point, gap and normal"));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", c, sizeof(c), NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-shape", shape, sizeof(shape), NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-what", what, sizeof(what), NULL));
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-overlap", &overlap, NULL));
  std::string s(c);
  if (s == "closest_point") PetscCall(CaseClosestPoint());
  else if (s == "box_nodes") PetscCall(CaseBoxNodes(shape, overlap));
  else if (s == "on_centre") PetscCall(CaseOnCentre());
  else if (s == "bad_zone") PetscCall(CaseBadZone(what));
  else SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "unknown -case %s", c);
  PetscCall(PetscFinalize());
  return 0;
}
