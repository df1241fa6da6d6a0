/* What the fem layer derives from any tetrahedral mesh, whether a box generated it or the user gave it:
   the checks of a given mesh, its boundary triangles, the boundary tags with their nodes, areas and
   normals, the Dirichlet mask, and the nodes that subdomains share. */
#include <conefeti/private/femimpl.h>

#include <algorithm>
#include <cmath>

/* 6 x the signed volume of tetrahedron v (det[x1-x0, x2-x0, x3-x0]) and its longest edge */
void FEMTetrahedronGeometry(const PetscReal *X, const PetscInt v[4], PetscReal *det, PetscReal *longest)
{
  PetscReal e[3][3];
  for (PetscInt a = 0; a < 3; a++)
    for (PetscInt d = 0; d < 3; d++) e[a][d] = X[3 * v[a + 1] + d] - X[3 * v[0] + d];
  *det     = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) + e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  *longest = 0;
  for (PetscInt a = 0; a < 4; a++)
    for (PetscInt c = a + 1; c < 4; c++) {
      PetscReal l2 = 0;
      for (PetscInt d = 0; d < 3; d++) l2 += (X[3 * v[a] + d] - X[3 * v[c] + d]) * (X[3 * v[a] + d] - X[3 * v[c] + d]);
      *longest = PetscMax(*longest, PetscSqrtReal(l2));
    }
}

/* The checks of a mesh given by FEMAddMesh(): indices in range, finite coordinates, every tetrahedron
   positively oriented and not flat, every node used. A flat tetrahedron has a singular element
   stiffness, an inverted one a negative-definite one: either would make a subdomain indefinite and
   show up much later as a failed factorization, far from its cause. */
PetscErrorCode FEMCheckMesh(MPI_Comm comm, PetscInt body, const FEMBody &b)
{
  std::vector<unsigned char> used(b.nnodes, 0);

  PetscFunctionBegin;
  for (PetscInt i = 0; i < 3 * b.nnodes; i++)
    PetscCheck(std::isfinite(b.coords[i]), comm, PETSC_ERR_ARG_WRONG, "FEMAddMesh(): body %" PetscInt_FMT ": coordinate %" PetscInt_FMT " of node %" PetscInt_FMT " is %g, not a finite number", body,
               i % 3, i / 3, (double)b.coords[i]);
  for (PetscInt e = 0; e < b.nelements; e++) {
    PetscInt  v[4];
    PetscReal det, longest;
    FEMElementNodes(b, e, v);
    for (PetscInt a = 0; a < 4; a++) {
      PetscCheck(v[a] >= 0 && v[a] < b.nnodes, comm, PETSC_ERR_ARG_OUTOFRANGE,
                 "FEMAddMesh(): body %" PetscInt_FMT ": tetrahedron %" PetscInt_FMT " has node %" PetscInt_FMT ", outside 0..%" PetscInt_FMT, body, e, v[a], b.nnodes - 1);
      used[v[a]] = 1;
    }
    FEMTetrahedronGeometry(b.coords.data(), v, &det, &longest);
    PetscCheck(!FEMTetrahedronIsFlat(det, longest), comm, PETSC_ERR_ARG_WRONG,
               "FEMAddMesh(): body %" PetscInt_FMT ": tetrahedron %" PetscInt_FMT " (nodes %" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT
               ") is degenerate (volume %g, longest edge %g)",
               body, e, v[0], v[1], v[2], v[3], (double)(det / 6), (double)longest);
    PetscCheck(det > 0, comm, PETSC_ERR_ARG_WRONG,
               "FEMAddMesh(): body %" PetscInt_FMT ": tetrahedron %" PetscInt_FMT " (nodes %" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT
               ") is inverted (volume %g < 0): list the nodes of every tetrahedron so that the fourth lies on the side of the first three's counter-clockwise normal",
               body, e, v[0], v[1], v[2], v[3], (double)(det / 6));
  }
  for (PetscInt n = 0; n < b.nnodes; n++)
    PetscCheck(used[n], comm, PETSC_ERR_ARG_WRONG, "FEMAddMesh(): body %" PetscInt_FMT ": node %" PetscInt_FMT " belongs to no tetrahedron (it would have no stiffness); leave it out", body, n);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The built-in tag of an outward normal: its dominant axis and sign */
static PetscInt DominantFace(const std::array<PetscReal, 3> &n)
{
  PetscInt axis = 0;
  for (PetscInt d = 1; d < 3; d++)
    if (std::fabs(n[d]) > std::fabs(n[axis])) axis = d;
  return 2 * axis + (n[axis] > 0 ? 1 : 0);
}

/* The boundary triangles of a given mesh: the tetrahedron faces that belong to one tetrahedron only, each
   with its outward normal (away from the tetrahedron's fourth vertex). Faces are matched by sorting. */
PetscErrorCode FEMBuildBoundary(FEMBody &b)
{
  struct Face {
    std::array<PetscInt, 3> key; /* sorted nodes */
    PetscInt                element, opposite;
  };
  std::vector<Face> faces;

  PetscFunctionBegin;
  PetscCallCXX(faces.resize(4 * (size_t)b.nelements));
  for (PetscInt e = 0; e < b.nelements; e++) {
    PetscInt v[4];
    FEMElementNodes(b, e, v);
    for (PetscInt k = 0; k < 4; k++) {
      Face    &f = faces[4 * (size_t)e + k];
      PetscInt m = 0;
      for (PetscInt a = 0; a < 4; a++)
        if (a != k) f.key[m++] = v[a];
      std::sort(f.key.begin(), f.key.end());
      f.element  = e;
      f.opposite = v[k];
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face &x, const Face &y) { return x.key != y.key ? x.key < y.key : x.element < y.element; });
  b.boundary.clear();
  PetscCallCXX(b.onboundary.assign(b.nnodes, 0));
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) j++;
    PetscCheck(j - i <= 2, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
               "The mesh is not a manifold: the triangle (%" PetscInt_FMT ", %" PetscInt_FMT ", %" PetscInt_FMT ") is a face of %d tetrahedra (at most 2 may share a face)", faces[i].key[0],
               faces[i].key[1], faces[i].key[2], (int)(j - i));
    if (j - i == 1) {
      const Face         &f = faces[i];
      FEMBoundaryTriangle t;
      const PetscReal    *x0 = &b.coords[3 * f.key[0]], *x1 = &b.coords[3 * f.key[1]], *x2 = &b.coords[3 * f.key[2]], *xo = &b.coords[3 * f.opposite];
      PetscReal           a[3], c[3], n[3], len;
      for (PetscInt d = 0; d < 3; d++) {
        a[d] = x1[d] - x0[d];
        c[d] = x2[d] - x0[d];
      }
      n[0] = a[1] * c[2] - a[2] * c[1];
      n[1] = a[2] * c[0] - a[0] * c[2];
      n[2] = a[0] * c[1] - a[1] * c[0];
      len  = PetscSqrtReal(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      t.v  = f.key;
      if (n[0] * (xo[0] - x0[0]) + n[1] * (xo[1] - x0[1]) + n[2] * (xo[2] - x0[2]) > 0) { /* points inward: turn the triangle over */
        std::swap(t.v[1], t.v[2]);
        for (PetscInt d = 0; d < 3; d++) n[d] = -n[d];
      }
      t.element = f.element;
      t.area    = 0.5 * len;
      for (PetscInt d = 0; d < 3; d++) t.normal[d] = n[d] / len;
      t.face = DominantFace(t.normal);
      for (PetscInt v : t.v) b.onboundary[v] = 1;
      PetscCallCXX(b.boundary.push_back(t));
    }
    i = j;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static std::string TagList(const FEMBody &b)
{
  std::string s;
  for (const auto &t : b.tags) s += (s.empty() ? "" : " ") + t.first;
  return s;
}

/* Tags (built-in faces, facet sets, user predicates), lumped nodal areas and normals, and the Dirichlet mask */
PetscErrorCode FEMBuildTags(PetscInt body, FEMBody &b)
{
  PetscFunctionBegin;
  b.tags.clear();
  b.taggednodes.clear();
  for (PetscInt f = 0; f < 6; f++) PetscCallCXX(b.tags[FEMBoxFaceNames[f]]);
  for (size_t t = 0; t < b.boundary.size(); t++) PetscCallCXX(b.tags[FEMBoxFaceNames[b.boundary[t].face]].push_back((PetscInt)t));
  if (!b.facetsets.empty()) {
    std::map<std::array<PetscInt, 3>, PetscInt> which; /* sorted nodes -> boundary triangle */
    for (size_t t = 0; t < b.boundary.size(); t++) {
      std::array<PetscInt, 3> key = b.boundary[t].v;
      std::sort(key.begin(), key.end());
      PetscCallCXX(which[key] = (PetscInt)t);
    }
    for (const auto &set : b.facetsets) {
      std::vector<PetscInt> &list = b.tags[set.first];
      list.clear();
      for (size_t i = 0; i < set.second.size() / 3; i++) {
        std::array<PetscInt, 3> key = {set.second[3 * i], set.second[3 * i + 1], set.second[3 * i + 2]};
        std::sort(key.begin(), key.end());
        auto it = which.find(key);
        PetscCheck(it != which.end(), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
                   "Facet set \"%s\" of body %" PetscInt_FMT ": its triangle %zu (nodes %" PetscInt_FMT " %" PetscInt_FMT " %" PetscInt_FMT ") is not a boundary face of the body's tetrahedra",
                   set.first.c_str(), body, i, set.second[3 * i], set.second[3 * i + 1], set.second[3 * i + 2]);
        PetscCallCXX(list.push_back(it->second));
      }
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
    }
  }
  for (const FEMUserTag &ut : b.usertags) {
    std::vector<PetscInt> candidates, list;
    if (ut.within.empty()) {
      PetscCallCXX(candidates.resize(b.boundary.size()));
      for (size_t t = 0; t < b.boundary.size(); t++) candidates[t] = (PetscInt)t;
    } else {
      auto it = b.tags.find(ut.within);
      PetscCheck(it != b.tags.end(), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Tag \"%s\" of body %" PetscInt_FMT " is to be taken within tag \"%s\", which does not exist (the body has: %s)",
                 ut.name.c_str(), body, ut.within.c_str(), TagList(b).c_str());
      candidates = it->second;
    }
    for (PetscInt t : candidates) {
      const FEMBoundaryTriangle &tri = b.boundary[t];
      PetscReal                  centroid[3];
      PetscBool                  tagged = PETSC_FALSE;
      for (PetscInt d = 0; d < 3; d++) centroid[d] = (b.coords[3 * tri.v[0] + d] + b.coords[3 * tri.v[1] + d] + b.coords[3 * tri.v[2] + d]) / 3.0;
      PetscCall(ut.predicate(centroid, tri.normal.data(), &tagged, ut.ctx));
      if (tagged) PetscCallCXX(list.push_back(t));
    }
    b.tags[ut.name] = std::move(list);
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
    for (PetscInt t : entry.second) PetscCallCXX(tn.triangles.insert(tn.triangles.end(), b.boundary[t].v.begin(), b.boundary[t].v.end()));
    for (const auto &na : acc) {
      const PetscReal len = std::sqrt(na.second[1] * na.second[1] + na.second[2] * na.second[2] + na.second[3] * na.second[3]);
      PetscCallCXX(tn.nodes.push_back(na.first));
      PetscCallCXX(tn.areas.push_back(na.second[0]));
      for (PetscInt d = 0; d < 3; d++) PetscCallCXX(tn.normals.push_back(len > 0 ? na.second[1 + d] / len : 0.0));
    }
  }
  /* The Dirichlet mask and values. A node component prescribed by two conditions (a node on the edge between two
     supports) must get the same value from both: a clamped face next to a displaced one shares its edge nodes,
     and which value would win is not the user's choice to leave open. */
  PetscCallCXX(b.dirichletmask.assign(b.nnodes, 0));
  PetscCallCXX(b.dirichletvalue.clear());
  for (const FEMDirichletSpec &ds : b.dirichlet)
    for (PetscInt c = 0; c < 3; c++)
      if ((ds.components & (1u << c)) && ds.value[c] != 0.0 && b.dirichletvalue.empty()) PetscCallCXX(b.dirichletvalue.assign(3 * (size_t)b.nnodes, 0.0));
  {
    std::vector<int> owner; /* 3 per node: the condition that prescribed it first, for the message */
    if (b.dirichlet.size() > 1) PetscCallCXX(owner.assign(3 * (size_t)b.nnodes, -1));
    for (size_t k = 0; k < b.dirichlet.size(); k++) {
      const FEMDirichletSpec &ds = b.dirichlet[k];
      auto                    it = b.tags.find(ds.name);
      PetscCheck(it != b.tags.end(), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "FEMSetDirichlet(): body %" PetscInt_FMT " has no boundary tag \"%s\" (it has: %s)", body, ds.name.c_str(),
                 TagList(b).c_str());
      for (PetscInt t : it->second)
        for (PetscInt n : b.boundary[t].v)
          for (PetscInt c = 0; c < 3; c++) {
            if (!(ds.components & (1u << c))) continue;
            const PetscReal old = FEMDirichletValue(b, n, c);
            if (b.dirichletmask[n] & (1u << c)) {
              const FEMDirichletSpec &first = b.dirichlet[owner.empty() || owner[3 * (size_t)n + c] < 0 ? k : owner[3 * (size_t)n + c]];
              PetscCheck(old == ds.value[c], PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
                         "FEMSetDisplacement(): body %" PetscInt_FMT ", node %" PetscInt_FMT " at (%g, %g, %g): its %c displacement is prescribed as %g by \"%s\" and as %g by \"%s\" (a node "
                         "component prescribed twice must get one value)",
                         body, n, (double)b.coords[3 * n], (double)b.coords[3 * n + 1], (double)b.coords[3 * n + 2], (char)('x' + c), (double)old, first.name.c_str(), (double)ds.value[c],
                         ds.name.c_str());
              continue;
            }
            b.dirichletmask[n] |= (unsigned char)(1u << c);
            if (!b.dirichletvalue.empty()) b.dirichletvalue[3 * (size_t)n + c] = ds.value[c];
            if (!owner.empty()) owner[3 * (size_t)n + c] = (int)k;
          }
    }
  }
  for (const FEMTractionSpec &ts : b.tractions)
    PetscCheck(b.tags.count(ts.name), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "FEMSetTraction(): body %" PetscInt_FMT " has no boundary tag \"%s\" (it has: %s)", body, ts.name.c_str(),
               TagList(b).c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The nodes that elements of two or more subdomains share (after the decomposition): with the boundary
   nodes, the ones whose copies the replicated copy table lists */
PetscErrorCode FEMMarkInterfaceNodes(FEMBody &b)
{
  std::vector<PetscInt> first;

  PetscFunctionBegin;
  PetscCallCXX(first.assign(b.nnodes, -1));
  PetscCallCXX(b.oninterface.assign(b.nnodes, 0));
  for (PetscInt e = 0; e < b.nelements; e++)
    for (PetscInt a = 0; a < 4; a++) {
      const PetscInt n = b.conn[4 * (size_t)e + a];
      if (first[n] < 0) first[n] = b.part[e];
      else if (first[n] != b.part[e]) b.oninterface[n] = 1;
    }
  PetscFunctionReturn(PETSC_SUCCESS);
}
