/* Structured tetrahedral mesh of a box: nx x ny x nz hexahedra, each split into the 6 tetrahedra
   of the Kuhn (Freudenthal) split along its main diagonal. Every hexahedron is split with the same
   orientation, so the face diagonals of neighbours coincide and the mesh is conforming; each face
   diagonal joins the face's lowest and highest corner. */
#include <conefeti/private/femimpl.h>

#include <algorithm>
#include <cmath>

const char *const FEMBoxFaceNames[6] = {"x0", "x1", "y0", "y1", "z0", "z1"};

/* The six axis permutations (a,b,c); tetrahedron t has vertices 0, e_a, e_a+e_b, e_a+e_b+e_c of its hexahedron */
static const PetscInt  KuhnPermutation[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
static const PetscBool KuhnOdd[6]            = {PETSC_FALSE, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE};

static inline PetscInt BoxNodeId(const FEMBody &b, PetscInt i, PetscInt j, PetscInt k) { return i + (b.cells[0] + 1) * (j + (b.cells[1] + 1) * k); }

void FEMBoxNodeIJK(const FEMBody &b, PetscInt node, PetscInt ijk[3])
{
  ijk[0] = node % (b.cells[0] + 1);
  ijk[1] = (node / (b.cells[0] + 1)) % (b.cells[1] + 1);
  ijk[2] = node / ((b.cells[0] + 1) * (b.cells[1] + 1));
}

/* Node ids of body element e, positively oriented */
void FEMBoxElementNodes(const FEMBody &b, PetscInt e, PetscInt v[4])
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

/* Coordinates and boundary triangles. Each boundary quad (corners p00, p10, p01, p11 in the face's two
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

/* Tags (built-in faces and user predicates), lumped nodal areas and normals, and the Dirichlet mask */
PetscErrorCode FEMBoxBuildTags(FEMBody &b)
{
  PetscFunctionBegin;
  b.tags.clear();
  b.taggednodes.clear();
  for (PetscInt f = 0; f < 6; f++) PetscCallCXX(b.tags[FEMBoxFaceNames[f]]);
  for (size_t t = 0; t < b.boundary.size(); t++) PetscCallCXX(b.tags[FEMBoxFaceNames[b.boundary[t].face]].push_back((PetscInt)t));
  for (const FEMUserTag &ut : b.usertags) {
    std::vector<PetscInt> &list = b.tags[ut.name];
    list.clear();
    for (size_t t = 0; t < b.boundary.size(); t++) {
      const FEMBoundaryTriangle &tri = b.boundary[t];
      PetscReal                  centroid[3];
      PetscBool                  tagged = PETSC_FALSE;
      for (PetscInt d = 0; d < 3; d++) centroid[d] = (b.coords[3 * tri.v[0] + d] + b.coords[3 * tri.v[1] + d] + b.coords[3 * tri.v[2] + d]) / 3.0;
      PetscCall(ut.predicate(centroid, tri.normal.data(), &tagged, ut.ctx));
      if (tagged) PetscCallCXX(list.push_back((PetscInt)t));
    }
  }
  for (const auto &entry : b.tags) {
    std::map<PetscInt, std::array<PetscReal, 4>> acc; /* node -> area, area-weighted normal */
    for (PetscInt t : entry.second) {
      const FEMBoundaryTriangle &tri = b.boundary[t];
      for (PetscInt n : tri.v) {
        std::array<PetscReal, 4> &a = acc[n];
        a[0] += tri.area / 3.0;
        for (PetscInt d = 0; d < 3; d++) a[1 + d] += tri.area * tri.normal[d];
      }
    }
    FEMTaggedNodes &tn = b.taggednodes[entry.first];
    for (const auto &na : acc) {
      const PetscReal len = std::sqrt(na.second[1] * na.second[1] + na.second[2] * na.second[2] + na.second[3] * na.second[3]);
      PetscCallCXX(tn.nodes.push_back(na.first));
      PetscCallCXX(tn.areas.push_back(na.second[0]));
      for (PetscInt d = 0; d < 3; d++) PetscCallCXX(tn.normals.push_back(len > 0 ? na.second[1 + d] / len : 0.0));
    }
  }
  PetscCallCXX(b.dirichletmask.assign(b.nnodes, 0));
  for (const FEMDirichletSpec &ds : b.dirichlet) {
    auto it = b.tags.find(ds.name);
    PetscCheck(it != b.tags.end(), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "FEMSetDirichlet(): no boundary tag \"%s\" (built-in tags are x0 x1 y0 y1 z0 z1; others come from FEMTagFaces())",
               ds.name.c_str());
    for (PetscInt t : it->second)
      for (PetscInt n : b.boundary[t].v) b.dirichletmask[n] |= (unsigned char)ds.components;
  }
  for (const FEMTractionSpec &ts : b.tractions)
    PetscCheck(b.tags.count(ts.name), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "FEMSetTraction(): no boundary tag \"%s\" (built-in tags are x0 x1 y0 y1 z0 z1; others come from FEMTagFaces())",
               ts.name.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The subdomains (body-local indices, increasing) whose elements contain the node */
PetscErrorCode FEMBoxNodeSubdomains(const FEMBody &b, PetscInt node, std::vector<PetscInt> &subs)
{
  PetscInt ijk[3];

  PetscFunctionBegin;
  subs.clear();
  FEMBoxNodeIJK(b, node, ijk);
  for (PetscInt dk = -1; dk <= 0; dk++)
    for (PetscInt dj = -1; dj <= 0; dj++)
      for (PetscInt di = -1; di <= 0; di++) {
        const PetscInt ci = ijk[0] + di, cj = ijk[1] + dj, ck = ijk[2] + dk;
        if (ci < 0 || cj < 0 || ck < 0 || ci >= b.cells[0] || cj >= b.cells[1] || ck >= b.cells[2]) continue;
        const PetscInt hex = ci + b.cells[0] * (cj + b.cells[1] * ck);
        for (PetscInt t = 0; t < 6; t++) {
          PetscInt v[4];
          FEMBoxElementNodes(b, 6 * hex + t, v);
          if (v[0] == node || v[1] == node || v[2] == node || v[3] == node) PetscCallCXX(subs.push_back(b.part[6 * hex + t]));
        }
      }
  std::sort(subs.begin(), subs.end());
  subs.erase(std::unique(subs.begin(), subs.end()), subs.end());
  PetscFunctionReturn(PETSC_SUCCESS);
}
