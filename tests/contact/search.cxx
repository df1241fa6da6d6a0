/* The closest-point search of contact zones between bodies (src/contact/contactsearch.cxx, compiled into this program:
   its functions are internal to the library).

   -case triangle: the closest point of one triangle, in each of its seven Voronoi regions, against the answer known
                   by construction (the weights of a vertex exactly (1, 0, 0), an edge with an exact 0), and for random
                   points and triangles: chi lies in the triangle and no point of the triangle (vertices, edge points,
                   a dense sample) is nearer
   -case surface:  a triangulated, tilted, bumpy surface: the bucketed search returns the triangle testing every
                   triangle returns (the same distance, the same triangle on a tie), within and beyond the search
                   distance; a point on a vertex that six triangles share gets the smallest of their indices */
#include <conefeti/private/contactmodelimpl.h>
#include <cmath>
#include <random>

static PetscReal Dist(const PetscReal a[3], const PetscReal b[3]) { return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])); }

static PetscErrorCode Triangle()
{
  const PetscReal a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
  struct Case {
    PetscReal   x[3], w[3];
    const char *region;
  } cases[] = {
      {{0.2, 0.3, 0.5}, {0.5, 0.2, 0.3}, "interior"}, {{-1, -1, 1}, {1, 0, 0}, "vertex a"},        {{2, -0.5, 0}, {0, 1, 0}, "vertex b"},   {{-0.5, 2, 0.3}, {0, 0, 1}, "vertex c"},
      {{0.5, -1, 0.2}, {0.5, 0.5, 0}, "edge ab"},     {{-1, 0.25, 0}, {0.75, 0, 0.25}, "edge ac"}, {{1, 1, 0.5}, {0, 0.5, 0.5}, "edge bc"}, {{0.25, 0.25, -3}, {0.5, 0.25, 0.25}, "interior, below"},
  };
  std::mt19937                           gen(7);
  std::uniform_real_distribution<double> U(-1, 1);
  PetscReal                              worst = 0;

  PetscFunctionBegin;
  for (const Case &k : cases) {
    PetscReal chi[3], w[3];
    ContactTriangleClosestPoint(k.x, a, b, c, chi, w);
    for (int i = 0; i < 3; i++) {
      PetscCheck(std::fabs(w[i] - k.w[i]) <= 1e-15, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%s: weight %d is %.17g, expected %g", k.region, i, (double)w[i], (double)k.w[i]);
      PetscCheck(k.w[i] != 0 || w[i] == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%s: weight %d is %g, not exactly 0", k.region, i, (double)w[i]);
      PetscCheck(k.w[i] != 1 || w[i] == 1, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%s: weight %d is %.17g, not exactly 1", k.region, i, (double)w[i]);
    }
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "%-16s x = (%g, %g, %g): chi = (%g, %g, %g), weights (%g, %g, %g)\n", k.region, (double)k.x[0], (double)k.x[1], (double)k.x[2], (double)chi[0],
                          (double)chi[1], (double)chi[2], (double)w[0], (double)w[1], (double)w[2]));
  }
  /* random triangles and points: chi in the triangle, and nearer than every sampled point of it */
  for (int trial = 0; trial < 2000; trial++) {
    PetscReal P[3][3], x[3], chi[3], w[3];
    for (auto &p : P)
      for (PetscReal &v : p) v = U(gen);
    for (PetscReal &v : x) v = 2 * U(gen);
    ContactTriangleClosestPoint(x, P[0], P[1], P[2], chi, w);
    PetscCheck(w[0] >= 0 && w[1] >= 0 && w[2] >= 0 && std::fabs(w[0] + w[1] + w[2] - 1) < 1e-13, PETSC_COMM_SELF, PETSC_ERR_PLIB, "trial %d: weights (%g, %g, %g) are not barycentric", trial,
               (double)w[0], (double)w[1], (double)w[2]);
    const PetscReal d = Dist(x, chi);
    for (int i = 0; i <= 40; i++)
      for (int j = 0; i + j <= 40; j++) {
        const PetscReal s = i / 40.0, t = j / 40.0,
                        q[3] = {(1 - s - t) * P[0][0] + s * P[1][0] + t * P[2][0], (1 - s - t) * P[0][1] + s * P[1][1] + t * P[2][1], (1 - s - t) * P[0][2] + s * P[1][2] + t * P[2][2]};
        worst                = PetscMax(worst, d - Dist(x, q));
      }
  }
  PetscCheck(worst <= 1e-14, PETSC_COMM_SELF, PETSC_ERR_PLIB, "a sampled point of a triangle is nearer than its closest point by %g", (double)worst);
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "2000 random triangles: closest points barycentric and nearest of every sampled point (by at most %g)\n", (double)worst));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Surface()
{
  const PetscInt                         nx = 7, ny = 5; /* squares, each cut into two triangles along its diagonal */
  std::vector<PetscReal>                 X;
  std::vector<PetscInt>                  tri;
  ContactSurfaceSearch                   search;
  std::mt19937                           gen(11);
  std::uniform_real_distribution<double> U(-0.5, 1.5);
  PetscInt                               within = 0, beyond = 0;

  PetscFunctionBegin;
  /* the grid over [0,1]^2, tilted and bumped so that no triangle is axis-aligned */
  for (PetscInt j = 0; j <= ny; j++)
    for (PetscInt i = 0; i <= nx; i++) {
      const PetscReal u = (PetscReal)i / nx, v = (PetscReal)j / ny, z = 0.1 * std::sin(3 * u) * std::cos(2 * v);
      X.insert(X.end(), {0.8 * u - 0.6 * z, v, 0.6 * u + 0.8 * z});
    }
  for (PetscInt j = 0; j < ny; j++)
    for (PetscInt i = 0; i < nx; i++) {
      const PetscInt p = i + (nx + 1) * j, q = p + 1, r = p + nx + 1, s = r + 1;
      tri.insert(tri.end(), {p, q, s, p, s, r});
    }
  const PetscInt ntri = (PetscInt)tri.size() / 3;
  PetscCall(search.SetUp(ntri, tri.data(), X.data()));
  for (int trial = 0; trial < 3000; trial++) {
    PetscReal           x[3] = {U(gen), U(gen), U(gen) - 0.5};
    const PetscReal     dmax = trial % 2 ? 0.3 : 10;
    ContactSurfacePoint p, all;
    PetscCall(search.Closest(x, dmax, p));
    PetscCall(search.Nearest(x, all));
    if (all.dist <= dmax) {
      PetscCheck(p.triangle >= 0 && p.dist == all.dist, PETSC_COMM_SELF, PETSC_ERR_PLIB,
                 "point %d: the search finds triangle %" PetscInt_FMT " at %.17g, every triangle gives %" PetscInt_FMT " at %.17g", trial, p.triangle, (double)p.dist, all.triangle, (double)all.dist);
      within++;
    } else {
      PetscCheck(p.triangle < 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "point %d: the search finds triangle %" PetscInt_FMT " at %g beyond the search distance %g", trial, p.triangle, (double)p.dist,
                 (double)dmax);
      beyond++;
    }
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF,
                        "surface of %" PetscInt_FMT " triangles: %" PetscInt_FMT " points found as by testing every triangle, %" PetscInt_FMT " beyond the search distance found none\n", ntri, within,
                        beyond));
  /* an inner vertex shared by six triangles: the smallest index among them, weight exactly 1 on the vertex */
  {
    const PetscInt      v = 3 + (nx + 1) * 2;
    ContactSurfacePoint p;
    PetscInt            first = -1;
    PetscCall(search.Closest(&X[3 * v], 0.1, p));
    for (PetscInt t = 0; t < ntri && first < 0; t++)
      for (int k = 0; k < 3; k++)
        if (tri[3 * t + k] == v) first = t;
    PetscCheck(p.triangle == first, PETSC_COMM_SELF, PETSC_ERR_PLIB, "vertex %" PetscInt_FMT ": triangle %" PetscInt_FMT ", expected the first that holds it, %" PetscInt_FMT, v, p.triangle, first);
    PetscBool one = PETSC_FALSE;
    for (int k = 0; k < 3; k++)
      if (tri[3 * p.triangle + k] == v && p.w[k] == 1 && p.dist == 0) one = PETSC_TRUE;
    PetscCheck(one, PETSC_COMM_SELF, PETSC_ERR_PLIB, "vertex %" PetscInt_FMT ": weights (%g, %g, %g), distance %g", v, (double)p.w[0], (double)p.w[1], (double)p.w[2], (double)p.dist);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "a shared vertex: the first triangle holding it (%" PetscInt_FMT "), weight 1 on the vertex, distance 0\n", p.triangle));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char      which[32] = "triangle";
  PetscBool flg;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", which, sizeof(which), &flg));
  PetscCall(PetscStrcmp(which, "surface", &flg));
  if (flg) PetscCall(Surface());
  else PetscCall(Triangle());
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "search test passed\n"));
  PetscCall(PetscFinalize());
  return 0;
}
