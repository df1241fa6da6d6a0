/* The box generator: a structured tetrahedral mesh of nx x ny x nz hexahedra, each split into the 6
   tetrahedra of the Kuhn (Freudenthal) split along its main diagonal. After generation a box is a mesh
   like any other (femtopology.cxx); the generator also lists its boundary triangles, face by face, so
   that boxes keep the triangle order (and the load sums) they always had. Every hexahedron is split with the same
   orientation, so the face diagonals of neighbours coincide and the mesh is conforming; each face
   diagonal joins the face's lowest and highest corner. */
#include <conefeti/private/femimpl.h>

#include <algorithm>

const char *const FEMBoxFaceNames[6] = {"x0", "x1", "y0", "y1", "z0", "z1"};

/* The six axis permutations (a,b,c); tetrahedron t has vertices 0, e_a, e_a+e_b, e_a+e_b+e_c of its hexahedron */
static const PetscInt  KuhnPermutation[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
static const PetscBool KuhnOdd[6]            = {PETSC_FALSE, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE};

static inline PetscInt BoxNodeId(const FEMBody &b, PetscInt i, PetscInt j, PetscInt k) { return i + (b.cells[0] + 1) * (j + (b.cells[1] + 1) * k); }

/* Node ids of box element e, positively oriented */
static void BoxElementNodes(const FEMBody &b, PetscInt e, PetscInt v[4])
{
  const PetscInt hex = e / 6, t = e % 6;
  PetscInt       c[3]   = {hex % b.cells[0], (hex / b.cells[0]) % b.cells[1], hex / (b.cells[0] * b.cells[1])};
  PetscInt       off[3] = {0, 0, 0};

  v[0] = BoxNodeId(b, c[0], c[1], c[2]);
  for (PetscInt s = 0; s < 3; s++) {
    off[KuhnPermutation[t][s]] = 1;
    v[s + 1]                   = BoxNodeId(b, c[0] + off[0], c[1] + off[1], c[2] + off[2]);
  }
  if (KuhnOdd[t]) std::swap(v[1], v[2]);
}

static PetscInt KuhnIndex(PetscInt a, PetscInt b)
{
  for (PetscInt t = 0; t < 6; t++)
    if (KuhnPermutation[t][0] == a && KuhnPermutation[t][1] == b) return t;
  return -1;
}

/* Coordinates, connectivity and boundary triangles. Each boundary quad (corners p00, p10, p01, p11 in the face's two
   axes u < v) is cut along p00-p11 into the triangles that are faces of the Kuhn tetrahedra. */
PetscErrorCode FEMBoxBuildMesh(FEMBody &b)
{
  const PetscInt nx = b.cells[0], ny = b.cells[1], nz = b.cells[2];
  PetscReal      h[3];

  PetscFunctionBegin;
  b.nnodes    = (nx + 1) * (ny + 1) * (nz + 1);
  b.nelements = 6 * nx * ny * nz;
  for (PetscInt d = 0; d < 3; d++) h[d] = (b.upper[d] - b.lower[d]) / b.cells[d];
  PetscCallCXX(b.coords.resize(3 * b.nnodes));
  PetscCallCXX(b.onboundary.assign(b.nnodes, 0));
  PetscCallCXX(b.conn.resize(4 * (size_t)b.nelements));
  for (PetscInt e = 0; e < b.nelements; e++) BoxElementNodes(b, e, &b.conn[4 * (size_t)e]);
  for (PetscInt k = 0; k <= nz; k++)
    for (PetscInt j = 0; j <= ny; j++)
      for (PetscInt i = 0; i <= nx; i++) {
        const PetscInt n = BoxNodeId(b, i, j, k);
        /* the upper face coordinates are set exactly, not accumulated */
        b.coords[3 * n + 0] = i == nx ? b.upper[0] : b.lower[0] + i * h[0];
        b.coords[3 * n + 1] = j == ny ? b.upper[1] : b.lower[1] + j * h[1];
        b.coords[3 * n + 2] = k == nz ? b.upper[2] : b.lower[2] + k * h[2];
        if (i == 0 || i == nx || j == 0 || j == ny || k == 0 || k == nz) b.onboundary[n] = 1;
      }

  b.boundary.clear();
  for (PetscInt face = 0; face < 6; face++) {
    const PetscInt d = face / 2, side = face % 2;
    const PetscInt u = d == 0 ? 1 : 0, w = d == 2 ? 1 : 2; /* in-face axes, u < w */
    for (PetscInt q = 0; q < b.cells[w]; q++)
      for (PetscInt p = 0; p < b.cells[u]; p++) {
        PetscInt cell[3], node[2][2];
        cell[d] = side ? b.cells[d] - 1 : 0;
        cell[u] = p;
        cell[w] = q;
        for (PetscInt a = 0; a < 2; a++)
          for (PetscInt c = 0; c < 2; c++) {
            PetscInt ijk[3];
            ijk[d]     = side ? b.cells[d] : 0;
            ijk[u]     = p + a;
            ijk[w]     = q + c;
            node[a][c] = BoxNodeId(b, ijk[0], ijk[1], ijk[2]);
          }
        const PetscInt hex = cell[0] + nx * (cell[1] + ny * cell[2]);
        /* lower face: tetrahedra (u,w,d) and (w,u,d); upper face: (d,u,w) and (d,w,u) */
        const PetscInt tets[2]   = {side ? KuhnIndex(d, u) : KuhnIndex(u, w), side ? KuhnIndex(d, w) : KuhnIndex(w, u)};
        const PetscInt tri[2][3] = {{node[0][0], node[1][0], node[1][1]}, {node[0][0], node[0][1], node[1][1]}};
        for (PetscInt s = 0; s < 2; s++) {
          FEMBoundaryTriangle t;
          t.v         = {tri[s][0], tri[s][1], tri[s][2]};
          t.element   = 6 * hex + tets[s];
          t.face      = face;
          t.area      = 0.5 * h[u] * h[w];
          t.normal    = {0, 0, 0};
          t.normal[d] = side ? 1.0 : -1.0;
          PetscCallCXX(b.boundary.push_back(t));
        }
      }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
