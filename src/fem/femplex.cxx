/* Bodies from DMPlex meshes: a 3D DMPlex of tetrahedra, read by PETSc from a mesh file or built by the user's
   own code, becomes one FEMAddMesh() call and one FEMAddFacetSet() per labelled boundary surface.

   Everything is read on rank 0: PETSc's file readers (Gmsh among them) read on rank 0 anyway, and
   FEMAddMesh() takes rank 0's arrays and broadcasts them. Errors found while converting are raised on every
   rank with the same message (rank 0 finds them, the message is broadcast), so an error in the mesh never
   leaves the other ranks waiting in a collective call. */
#include <conefeti/private/femimpl.h>
#include <petscdmplex.h>
#include <conefeti/compat.h>
#include <conefeti/private/format.h>
#include <conefeti/private/errortext.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace {

/* Labels PETSc keeps for itself (topology, cell types, output) or that are not about faces; "Face Sets" is
   read by value, every other label that holds triangles becomes one facet set named after it. */
bool ReservedLabel(const char *name)
{
  static const char *const reserved[] = {"depth", "celltype", "Face Sets", "Cell Sets", "Vertex Sets", "Edge Sets", "ghost", "vtk", "dim"};
  for (const char *r : reserved)
    if (!strcmp(name, r)) return true;
  return false;
}

bool BuiltinTag(const std::string &name)
{
  static const char *const builtin[] = {"x0", "x1", "y0", "y1", "z0", "z1"};
  for (const char *b : builtin)
    if (name == b) return true;
  return false;
}

/* One facet set: a name and its triangles (node triples of the body) */
struct FacetSet {
  std::string           name;
  std::vector<PetscInt> triangles;
};

/* The body as rank 0 sees it after the conversion */
struct PlexBody {
  std::vector<PetscReal> coords;
  std::vector<PetscInt>  tets;
  std::vector<FacetSet>  sets;
  std::string            error; /* a message for the user (bad mesh), raised on every rank */
};

/* The names, in the order FEMAddDMPlex() adds them, of the facet sets of dm (sequential use) */
PetscErrorCode FacetSetLabels(DM dm, std::vector<std::pair<std::string, DMLabel>> &labels, std::vector<PetscInt> &facevalues, DMLabel *facesets)
{
  PetscInt nlabels, depth;

  PetscFunctionBegin;
  labels.clear();
  facevalues.clear();
  *facesets = NULL;
  PetscCall(DMPlexGetDepth(dm, &depth));
  if (depth < 3) PetscFunctionReturn(PETSC_SUCCESS); /* not interpolated: no triangles to label */
  PetscCall(DMGetLabel(dm, "Face Sets", facesets));
  if (*facesets) {
    IS              values;
    PetscInt        n;
    const PetscInt *v;
    PetscCall(DMLabelGetValueIS(*facesets, &values));
    PetscCall(ISGetLocalSize(values, &n));
    PetscCall(ISGetIndices(values, &v));
    for (PetscInt i = 0; i < n; i++) PetscCallCXX(facevalues.push_back(v[i]));
    PetscCall(ISRestoreIndices(values, &v));
    PetscCall(ISDestroy(&values));
    std::sort(facevalues.begin(), facevalues.end());
  }
  PetscCall(DMGetNumLabels(dm, &nlabels));
  for (PetscInt l = 0; l < nlabels; l++) {
    const char *name;
    DMLabel     label;
    PetscInt    fStart, fEnd, nfaces = 0;
    PetscCall(DMGetLabelName(dm, l, &name));
    if (ReservedLabel(name)) continue;
    PetscCall(DMGetLabelByNum(dm, l, &label));
    PetscCall(DMPlexGetDepthStratum(dm, 2, &fStart, &fEnd));
    {
      IS              values;
      PetscInt        n;
      const PetscInt *v;
      PetscCall(DMLabelGetValueIS(label, &values));
      PetscCall(ISGetLocalSize(values, &n));
      PetscCall(ISGetIndices(values, &v));
      for (PetscInt i = 0; i < n && !nfaces; i++) {
        IS              points;
        PetscInt        np;
        const PetscInt *p;
        PetscCall(DMLabelGetStratumIS(label, v[i], &points));
        if (!points) continue;
        PetscCall(ISGetLocalSize(points, &np));
        PetscCall(ISGetIndices(points, &p));
        for (PetscInt k = 0; k < np; k++)
          if (p[k] >= fStart && p[k] < fEnd) nfaces++;
        PetscCall(ISRestoreIndices(points, &p));
        PetscCall(ISDestroy(&points));
      }
      PetscCall(ISRestoreIndices(values, &v));
      PetscCall(ISDestroy(&values));
    }
    if (nfaces) PetscCallCXX(labels.emplace_back(name, label));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The boundary triangles among the points of one stratum of label, as node triples of the body (node[v - vStart]) */
PetscErrorCode StratumTriangles(DM dm, DMLabel label, PetscInt value, const std::vector<PetscInt> &node, PetscInt vStart, std::vector<PetscInt> &faces, PetscInt *interior)
{
  IS              points;
  PetscInt        np, fStart, fEnd;
  const PetscInt *p;

  PetscFunctionBegin;
  PetscCall(DMPlexGetDepthStratum(dm, 2, &fStart, &fEnd));
  PetscCall(DMLabelGetStratumIS(label, value, &points));
  if (!points) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(ISGetLocalSize(points, &np));
  PetscCall(ISGetIndices(points, &p));
  for (PetscInt k = 0; k < np; k++) {
    PetscInt  f = p[k], nsupp, nclosure, *closure = NULL, tri[3], nv = 0;
    PetscBool ok = PETSC_TRUE;
    if (f < fStart || f >= fEnd) continue; /* an edge or a vertex of the surface, or a cell */
    PetscCall(DMPlexGetSupportSize(dm, f, &nsupp));
    if (nsupp != 1) { /* between two cells: not on the boundary */
      (*interior)++;
      continue;
    }
    PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &nclosure, &closure));
    for (PetscInt c = 0; c < nclosure; c++) {
      const PetscInt q = closure[2 * c];
      if (q < vStart || q >= vStart + (PetscInt)node.size()) continue;
      if (nv < 3) tri[nv] = node[q - vStart];
      nv++;
    }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &nclosure, &closure));
    for (PetscInt c = 0; c < 3 && nv == 3; c++)
      if (tri[c] < 0) ok = PETSC_FALSE;
    if (nv != 3 || !ok) continue; /* not a triangle of the body */
    for (PetscInt c = 0; c < 3; c++) PetscCallCXX(faces.push_back(tri[c]));
  }
  PetscCall(ISRestoreIndices(points, &p));
  PetscCall(ISDestroy(&points));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Rank 0: dm (sequential view) -> arrays. User errors go to body.error, not raised here. */
PetscErrorCode Convert(DM dm, PlexBody &body)
{
  const char           *name;
  PetscInt              dim, cdim, cStart, cEnd, vStart, vEnd, depth;
  Vec                   X;
  PetscSection          cs;
  const PetscScalar    *x;
  std::map<int, long>   others; /* cells that are not tetrahedra, by polytope type */
  std::vector<PetscInt> node;
  std::vector<PetscInt> cellvertices; /* 4 per tetrahedron, DMPlex points */
  DM                    cdm;

  PetscFunctionBegin;
  PetscCall(PetscObjectGetName((PetscObject)dm, &name));
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMGetCoordinateDim(dm, &cdim));
  if (dim != 3 || cdim != 3) {
    /* the usual cause: a .geo file with Physical Surfaces but no Physical Volume, whose mesh file Gmsh writes with
       the elements of the physical groups only, so the tetrahedra are left out */
    body.error = ConeFETIFormat("%s: a %dD mesh in %dD space; a body needs a 3D mesh of tetrahedra%s", name, (int)dim, (int)cdim,
                                dim < 3 ? " (Gmsh writes only the elements of physical groups when there are any: give the volume a Physical Volume, or set Mesh.SaveAll = 1)" : "");
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(DMGetCellCoordinateDM(dm, &cdm));
  if (cdm) {
    body.error = ConeFETIFormat("%s: the mesh has cellwise (periodic) coordinates; a body needs a mesh with one position per vertex", name);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(DMPlexGetDepth(dm, &depth));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCallCXX(node.assign(vEnd - vStart, -1));
  for (PetscInt c = cStart; c < cEnd; c++) {
    DMPolytopeType ct;
    PetscInt       n, *closure = NULL, nv = 0, v4[4];
    PetscCall(DMPlexGetCellType(dm, c, &ct));
    if (ct != DM_POLYTOPE_TETRAHEDRON) {
      others[(int)ct]++;
      continue;
    }
    PetscCall(DMPlexGetTransitiveClosure(dm, c, PETSC_TRUE, &n, &closure));
    for (PetscInt k = 0; k < n; k++) {
      const PetscInt q = closure[2 * k];
      if (q >= vStart && q < vEnd) {
        if (nv < 4) v4[nv] = q;
        nv++;
      }
    }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, c, PETSC_TRUE, &n, &closure));
    PetscCheck(nv == 4, PETSC_COMM_SELF, PETSC_ERR_PLIB, "%s: tetrahedron %" PetscInt_FMT " has %" PetscInt_FMT " vertices in its closure", name, c, nv);
    for (PetscInt k = 0; k < 4; k++) PetscCallCXX(cellvertices.push_back(v4[k]));
  }
  if (!others.empty()) {
    std::string list;
    for (const auto &o : others) list += ConeFETIFormat("%s%ld of type %s", list.empty() ? "" : ", ", o.second, DMPolytopeTypes[o.first]);
    body.error = ConeFETIFormat("%s: %ld tetrahedra and cells %s; a body is a mesh of linear tetrahedra only (in Gmsh: Mesh.SubdivisionAlgorithm 0, no Recombine)", name,
                                (long)(cellvertices.size() / 4), list.c_str());
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (cellvertices.empty()) {
    body.error = ConeFETIFormat("%s: the mesh has no cells (a body needs 3D tetrahedra; a Gmsh file meshed in 2D only?)", name);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  /* nodes: the vertices the tetrahedra use, in DMPlex vertex order */
  for (PetscInt q : cellvertices) node[q - vStart] = 0;
  {
    PetscInt n = 0;
    for (PetscInt &id : node)
      if (id == 0) id = n++;
    PetscCallCXX(body.coords.resize(3 * n));
  }
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  {
    /* a curved (second-order) mesh keeps coordinates on edges too, and none on some vertices */
    PetscInt pStart, pEnd, curved = 0;
    PetscCall(PetscSectionGetChart(cs, &pStart, &pEnd));
    for (PetscInt q = pStart; q < pEnd; q++) {
      PetscInt dof;
      PetscCall(PetscSectionGetDof(cs, q, &dof));
      if ((q < vStart || q >= vEnd) ? dof > 0 : dof != 3) curved++;
    }
    if (curved) {
      body.error = ConeFETIFormat("%s: the mesh has second-order (curved) elements: %" PetscInt_FMT " of its points carry coordinates other than one x,y,z per vertex; a body is a mesh of "
                                  "linear tetrahedra (in Gmsh: Mesh.ElementOrder 1, or gmsh -3 -order 1)",
                                  name, curved);
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt dof, off;
    if (node[v - vStart] < 0) continue;
    PetscCall(PetscSectionGetDof(cs, v, &dof));
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    PetscCheck(dof == 3, PETSC_COMM_SELF, PETSC_ERR_SUP, "%s: vertex %" PetscInt_FMT " has %" PetscInt_FMT " coordinates, expected 3", name, v, dof);
    for (PetscInt d = 0; d < 3; d++) body.coords[3 * node[v - vStart] + d] = PetscRealPart(x[off + d]);
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  /* orientation: DMPlex's convention (PETSc's |J| > 0) is checked by PETSc's own cell geometry, so an element that
     is inverted in the input stays an error; a good cell is then turned positive (det[x1-x0,x2-x0,x3-x0] > 0),
     the orientation FEMAddMesh() takes. In DMPlex's convention that determinant is negative, so a good cell
     gets two vertices swapped. */
  PetscCallCXX(body.tets.resize(cellvertices.size()));
  for (size_t t = 0; t < cellvertices.size() / 4; t++) {
    const PetscInt c = cStart + (PetscInt)t;
    PetscInt       id[4];
    PetscReal      det, detJ, J[9], v0[3], lmax;
    for (PetscInt k = 0; k < 4; k++) id[k] = node[cellvertices[4 * t + k] - vStart];
    FEMTetrahedronGeometry(body.coords.data(), id, &det, &lmax);
    const std::string which = ConeFETIFormat("%s: tetrahedron %ld (DMPlex cell %" PetscInt_FMT ", vertices at (%g,%g,%g), (%g,%g,%g), (%g,%g,%g), (%g,%g,%g))", name, (long)t, c,
                                             (double)body.coords[3 * id[0]], (double)body.coords[3 * id[0] + 1], (double)body.coords[3 * id[0] + 2], (double)body.coords[3 * id[1]],
                                             (double)body.coords[3 * id[1] + 1], (double)body.coords[3 * id[1] + 2], (double)body.coords[3 * id[2]], (double)body.coords[3 * id[2] + 1],
                                             (double)body.coords[3 * id[2] + 2], (double)body.coords[3 * id[3]], (double)body.coords[3 * id[3] + 1], (double)body.coords[3 * id[3] + 2]);
    if (!std::isfinite(det)) {
      body.error = which + " has a coordinate that is not a finite number";
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    if (FEMTetrahedronIsFlat(det, lmax)) {
      body.error = ConeFETIFormat("%s is degenerate: volume %g for edges up to %g long", which.c_str(), (double)(std::fabs(det) / 6), (double)lmax);
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    PetscCall(DMPlexComputeCellGeometryAffineFEM(dm, c, v0, J, NULL, &detJ));
    if (detJ < 0) {
      body.error =
          ConeFETIFormat("%s is inverted (negative volume %g in DMPlex's orientation convention, which is the reverse of Gmsh's and Exodus's): its vertices are listed in the wrong order in the mesh",
                         which.c_str(), (double)(-std::fabs(det) / 6));
      PetscFunctionReturn(PETSC_SUCCESS);
    }
    if (det < 0) std::swap(id[1], id[2]);
    for (PetscInt k = 0; k < 4; k++) body.tets[4 * t + k] = id[k];
  }
  {
    /* one body is one connected piece: a second piece would float apart from the first in the same subdomains,
       with rigid motions that no kernel of the body's subdomains describes (and METIS cannot split it) */
    std::vector<PetscInt> root(body.coords.size() / 3);
    for (size_t i = 0; i < root.size(); i++) root[i] = (PetscInt)i;
    auto find = [&root](PetscInt i) {
      while (root[i] != i) i = root[i] = root[root[i]];
      return i;
    };
    for (size_t t = 0; t < body.tets.size() / 4; t++)
      for (int k = 1; k < 4; k++) {
        const PetscInt a = find(body.tets[4 * t]), b = find(body.tets[4 * t + k]);
        if (a != b) root[std::max(a, b)] = std::min(a, b);
      }
    std::map<PetscInt, long> pieces; /* tetrahedra per piece, by its first node */
    for (size_t t = 0; t < body.tets.size() / 4; t++) pieces[find(body.tets[4 * t])]++;
    if (pieces.size() > 1) {
      std::string list;
      for (const auto &q : pieces) {
        if (list.size() > 200) {
          list += ", ...";
          break;
        }
        list += ConeFETIFormat("%s%ld tetrahedra at (%g, %g, %g)", list.empty() ? "" : ", ", q.second, (double)body.coords[3 * q.first], (double)body.coords[3 * q.first + 1],
                               (double)body.coords[3 * q.first + 2]);
      }
      body.error = ConeFETIFormat("%s: the mesh has %d disconnected pieces (%s); a body is one connected piece: give each piece a body of its own (with -scene_body<b>_volume when the file "
                                  "has a physical volume per piece)",
                                  name, (int)pieces.size(), list.c_str());
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  /* facet sets: "Face Sets" by value (named by the number), every other label that holds triangles by its name */
  {
    std::vector<std::pair<std::string, DMLabel>> labels;
    std::vector<PetscInt>                        values;
    DMLabel                                      facesets;
    PetscInt                                     interior = 0;
    PetscCall(FacetSetLabels(dm, labels, values, &facesets));
    for (PetscInt v : values) {
      FacetSet s;
      s.name = ConeFETIFormat("%" PetscInt_FMT, v);
      PetscCall(StratumTriangles(dm, facesets, v, node, vStart, s.triangles, &interior));
      PetscCallCXX(body.sets.push_back(s));
    }
    for (const auto &l : labels) {
      FacetSet        s;
      IS              vis;
      PetscInt        n;
      const PetscInt *vv;
      if (BuiltinTag(l.first)) {
        body.error = ConeFETIFormat("%s: the label '%s' has the name of a built-in face tag (x0 x1 y0 y1 z0 z1): rename it", name, l.first.c_str());
        PetscFunctionReturn(PETSC_SUCCESS);
      }
      s.name = l.first;
      PetscCall(DMLabelGetValueIS(l.second, &vis));
      PetscCall(ISGetLocalSize(vis, &n));
      PetscCall(ISGetIndices(vis, &vv));
      for (PetscInt i = 0; i < n; i++) PetscCall(StratumTriangles(dm, l.second, vv[i], node, vStart, s.triangles, &interior));
      PetscCall(ISRestoreIndices(vis, &vv));
      PetscCall(ISDestroy(&vis));
      PetscCallCXX(body.sets.push_back(s));
    }
    if (interior) PetscCall(PetscInfo(dm, "%s: %" PetscInt_FMT " labelled triangles lie between two cells and are left out of the facet sets\n", name, interior));
  }
  (void)depth;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* dm as rank 0 holds it, or NULL: a sequential DM on rank 0, or all cells of a parallel one on rank 0 */
PetscErrorCode CheckPlacement(MPI_Comm comm, DM dm, std::string &error)
{
  PetscMPIInt rank, size, dmsize = 1;
  PetscInt    cells = 0, others = 0;
  PetscBool   plex = PETSC_TRUE, given = dm ? PETSC_TRUE : PETSC_FALSE;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (dm) {
    PetscInt cStart, cEnd;
    PetscCall(PetscObjectTypeCompare((PetscObject)dm, DMPLEX, &plex));
    PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)dm), &dmsize));
    if (plex) {
      PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
      cells = cEnd - cStart;
    }
  }
  if (rank) others = cells;
  {
    PetscInt buf[3] = {others, plex ? 0 : 1, (rank == 0 && !given) ? 1 : 0};
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, buf, 3, MPIU_INT, MPI_MAX, comm));
    if (buf[2]) error = "FEMAddDMPlex(): rank 0 must pass the mesh (a DMPlex; NULL only on the other ranks)";
    else if (buf[1]) error = "FEMAddDMPlex(): the DM is not a DMPlex";
    else if (buf[0] && dmsize > 1) error = "FEMAddDMPlex(): the DMPlex is distributed (cells on ranks other than 0); pass it before DMPlexDistribute(): the FEM decomposes the body itself";
  }
  (void)size;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode BcastString(MPI_Comm comm, std::string &s)
{
  PetscMPIInt rank;
  long        len = (long)s.size();

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_LONG, 0, comm));
  if (rank) PetscCallCXX(s.assign((size_t)len, ' '));
  if (len) PetscCallMPI(MPI_Bcast(&s[0], (PetscMPIInt)len, MPI_CHAR, 0, comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/*@C
  FEMAddDMPlex - Add a body meshed by a 3D `DMPLEX` of linear tetrahedra, with a boundary tag for each labelled
  boundary surface.

  Collective

  Input Parameters:
+ fem - the model
- dm  - the mesh on rank 0 of the model's communicator (see Notes); may be NULL on the other ranks

  Output Parameter:
. body - the new body's index

  Notes:
  The mesh is what PETSc's readers produce (`DMPlexCreateFromFile()`, `DMPlexCreateGmshFromFile()`,
  `FEMCreateDMPlexFromFile()`) or the user's own code builds: a 3D `DMPLEX`, interpolated when it carries
  boundary labels, whose cells are all `DM_POLYTOPE_TETRAHEDRON`, with one coordinate triple per vertex. Its
  cells must all be on rank 0: either a sequential `DM` on rank 0 (the other ranks pass NULL or their own,
  ignored, copy), or a `DM` on the model's communicator that has not been distributed (`DMPlexDistribute()`);
  the model decomposes the body itself (METIS, -fem_subdomains). Rank 0 holds the `DM` and the converted
  arrays; `FEMAddMesh()` broadcasts a copy (coordinates and connectivity) to
  every rank.

  Cells keep DMPlex's orientation convention: a cell that PETSc's geometry finds inverted (|J| < 0, for a Gmsh
  file: an element whose nodes are listed in the wrong order) is an error, as is a degenerate cell (volume below
  1e-10 times its longest edge cubed), a cell that is not a tetrahedron and a mesh without cells; every message
  starts with the `DM`'s name (`PetscObjectSetName()`; the file name for `FEMCreateDMPlexFromFile()`). The
  vertices the tetrahedra use become the body's nodes, in DMPlex vertex order.

  Besides the built-in tags x0 x1 y0 y1 z0 z1 (the boundary triangles by the dominant direction of their outward
  normal), the body gets one facet set (`FEMAddFacetSet()`) per value v of the label "Face Sets", named by the
  number ("7"; Gmsh physical surfaces by number), and one per other label that holds triangles, named after the
  label with all its values (Gmsh physical names read by `FEMCreateDMPlexFromFile()` or
  -dm_plex_gmsh_use_regions, or labels of the user's own). PETSc's own labels (depth, celltype, Cell Sets, Vertex
  Sets, ...) are not facet sets. Only boundary triangles enter a set: labelled triangles between two cells are
  left out (-info says how many).

  Level: intermediate

.seealso: `FEMCreateDMPlexFromFile()`, `FEMDMPlexGetFacetSetNames()`, `FEMAddMesh()`, `FEMAddFacetSet()`, `FEMAddBox()`
@*/
PetscErrorCode FEMAddDMPlex(FEM fem, DM dm, PetscInt *body)
{
  MPI_Comm    comm;
  PetscMPIInt rank;
  PlexBody    pb;
  PetscInt    nsets = 0, id;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscAssertPointer(body, 3);
  comm = PetscObjectComm((PetscObject)fem);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(CheckPlacement(comm, dm, pb.error));
  PetscCheck(pb.error.empty(), comm, PETSC_ERR_ARG_WRONG, "%s", pb.error.c_str());
  if (!rank) PetscCall(Convert(dm, pb));
  PetscCall(BcastString(comm, pb.error));
  PetscCheck(pb.error.empty(), comm, PETSC_ERR_ARG_WRONG, "%s", pb.error.c_str());
  PetscCall(FEMAddMesh(fem, (PetscInt)pb.coords.size() / 3, pb.coords.data(), (PetscInt)pb.tets.size() / 4, pb.tets.data(), &id));
  nsets = (PetscInt)pb.sets.size();
  PetscCallMPI(MPI_Bcast(&nsets, 1, MPIU_INT, 0, comm));
  for (PetscInt s = 0; s < nsets; s++) {
    std::string name = rank ? std::string() : pb.sets[s].name;
    PetscCall(BcastString(comm, name));
    PetscCall(FEMAddFacetSet(fem, id, name.c_str(), rank ? 0 : (PetscInt)pb.sets[s].triangles.size() / 3, rank ? NULL : pb.sets[s].triangles.data()));
  }
  *body = id;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMDMPlexGetFacetSetNames - The names of the facet sets `FEMAddDMPlex()` makes of a `DMPLEX`.

  Not Collective

  Input Parameter:
. dm - the mesh (on the rank that holds it)

  Output Parameters:
+ n     - the number of names
- names - the names, in the order `FEMAddDMPlex()` adds the sets (free with `PetscStrArrayDestroy()`)

  Notes:
  A name is listed when the label holds triangles at all, whether or not they lie on the boundary.

  Level: intermediate

.seealso: `FEMAddDMPlex()`, `FEMCreateDMPlexFromFile()`
@*/
PetscErrorCode FEMDMPlexGetFacetSetNames(DM dm, PetscInt *n, char ***names)
{
  std::vector<std::pair<std::string, DMLabel>> labels;
  std::vector<PetscInt>                        values;
  DMLabel                                      facesets;
  std::vector<std::string>                     all;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(dm, DM_CLASSID, 1);
  PetscCall(FacetSetLabels(dm, labels, values, &facesets));
  for (PetscInt v : values) PetscCallCXX(all.push_back(ConeFETIFormat("%" PetscInt_FMT, v)));
  for (const auto &l : labels) PetscCallCXX(all.push_back(l.first));
  *n = (PetscInt)all.size();
  PetscCall(PetscMalloc1(all.size() + 1, names));
  for (size_t i = 0; i < all.size(); i++) PetscCall(PetscStrallocpy(all[i].c_str(), &(*names)[i]));
  (*names)[all.size()] = NULL;
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {

/* A Gmsh file's $PhysicalNames: (dimension, tag, name). The section is text in ASCII and binary files alike and
   comes right after $MeshFormat (MSH 2.2 and 4.x). */
struct PhysicalName {
  int         dim, tag;
  std::string name;
};

PetscErrorCode ReadPhysicalNames(const char filename[], double *version, std::vector<PhysicalName> &names, std::string &error)
{
  FILE *fp;
  char  line[4096];
  bool  insection = false, informat = false;
  long  expected = -1;

  PetscFunctionBegin;
  names.clear();
  *version = 0;
  fp       = fopen(filename, "rb");
  if (!fp) PetscFunctionReturn(PETSC_SUCCESS); /* the reader says why */
  while (fgets(line, sizeof(line), fp)) {
    std::string s(line);
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    if (informat) { /* "version file-type data-size" */
      *version = std::atof(s.c_str());
      informat = false;
      continue;
    }
    if (s == "$MeshFormat") informat = true;
    if (!insection) {
      if (s == "$PhysicalNames") insection = true;
      else if (s == "$Entities" || s == "$Nodes" || s == "$NodeData" || s == "$Elements") break; /* none */
      continue;
    }
    if (s == "$EndPhysicalNames") break;
    if (expected < 0) {
      expected = std::atol(s.c_str());
      continue;
    }
    PhysicalName pn;
    const size_t q0 = s.find('"'), q1 = s.rfind('"');
    if (sscanf(s.c_str(), "%d %d", &pn.dim, &pn.tag) != 2 || q0 == std::string::npos || q1 <= q0) {
      error = ConeFETIFormat("%s: the $PhysicalNames line '%s' is not 'dimension tag \"name\"'", filename, s.c_str());
      break;
    }
    pn.name = s.substr(q0 + 1, q1 - q0 - 1);
    PetscCallCXX(names.push_back(pn));
  }
  fclose(fp);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* a label `name` on the points of label `from` with value tag (the physical group's triangles or cells) */
PetscErrorCode NameStratum(DM dm, const char from[], PetscInt tag, const char name[])
{
  DMLabel         src, dst;
  IS              points;
  PetscInt        n;
  const PetscInt *p;

  PetscFunctionBegin;
  PetscCall(DMGetLabel(dm, from, &src));
  if (!src) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DMLabelGetStratumIS(src, tag, &points));
  if (!points) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(DMCreateLabel(dm, name));
  PetscCall(DMGetLabel(dm, name, &dst));
  PetscCall(ISGetLocalSize(points, &n));
  PetscCall(ISGetIndices(points, &p));
  for (PetscInt i = 0; i < n; i++) PetscCall(DMLabelSetValue(dst, p[i], tag));
  PetscCall(ISRestoreIndices(points, &p));
  PetscCall(ISDestroy(&points));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Rank 0: read the file on PETSC_COMM_SELF; a failure becomes a message naming the file */
PetscErrorCode ReadOnRankZero(const char filename[], DM *dm, std::string &error)
{
  PetscBool                 exists, multiset, multiple, isgmsh = PETSC_FALSE;
  double                    version = 0;
  std::vector<PhysicalName> names;
  PetscErrorCode            ierr;
  size_t                    len;

  PetscFunctionBegin;
  *dm = NULL;
  PetscCall(PetscTestFile(filename, 'r', &exists));
  if (!exists) {
    error = ConeFETIFormat("%s: no such file, or not readable", filename);
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscStrlen(filename, &len));
  for (const char *ext : {".msh", ".msh2", ".msh4"}) {
    const size_t l = strlen(ext);
    if (len >= l && !strcmp(filename + len - l, ext)) isgmsh = PETSC_TRUE;
  }
  if (isgmsh) PetscCall(ReadPhysicalNames(filename, &version, names, error));
  if (!error.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  /* MSH 4: every physical group of an element, not only its first (a triangle in two physical surfaces). MSH 2
     lists an element once per physical group, and its second tag is the elementary entity, not a group. */
  PetscCall(PetscOptionsHasName(NULL, NULL, "-dm_plex_gmsh_multiple_tags", &multiset));
  multiple = isgmsh && version >= 4 && !multiset ? PETSC_TRUE : PETSC_FALSE;
  if (multiple) PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_multiple_tags", "1"));
  /* PETSc's reader raises its errors on this rank only: catch them, to raise one collective error naming the file */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  ierr = DMPlexCreateFromFile(PETSC_COMM_SELF, filename, "", PETSC_TRUE, dm);
  PetscCall(PetscPopErrorHandler());
  if (multiple) PetscCall(PetscOptionsClearValue(NULL, "-dm_plex_gmsh_multiple_tags"));
  if (ierr) {
    error = ConeFETIFormat("%s: the mesh could not be read (a truncated file, or not a format PETSc reads?): %s", filename, ConeFETIErrorText(ierr).c_str());
    *dm   = NULL; /* left as the failed reader left it: a leak, not a crash */
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(PetscObjectSetName((PetscObject)*dm, filename));
  for (const PhysicalName &pn : names) {
    if (pn.dim == 2) PetscCall(NameStratum(*dm, "Face Sets", pn.tag, pn.name.c_str()));
    if (pn.dim == 3) PetscCall(NameStratum(*dm, "Cell Sets", pn.tag, pn.name.c_str()));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

} // namespace

/*@C
  FEMCreateDMPlexFromFile - Read a mesh file into a `DMPLEX` on rank 0, ready for `FEMAddDMPlex()`, with Gmsh's
  physical names as labels.

  Collective

  Input Parameters:
+ comm     - the communicator of the model the mesh is for
- filename - any file `DMPlexCreateFromFile()` reads: Gmsh .msh (MSH 2.2 and 4.x, ASCII and binary), and the
             formats of PETSc's configuration (Exodus, CGNS, Fluent, PETSc's HDF5, ...)

  Output Parameter:
. dm - on rank 0 the interpolated mesh on `PETSC_COMM_SELF`, named after the file; NULL on the other ranks

  Notes:
  The whole file is read on rank 0 (as PETSc's Gmsh reader does anyway): an interpolated DMPlex takes some
  hundreds of bytes per tetrahedron there (docs/scenes.md gives a measurement). A missing, unreadable or
  truncated file is an error on every rank, naming the file and what the reader said.

  For a Gmsh file the labels are PETSc's "Cell Sets" and "Face Sets" (values: the physical group numbers; an
  element in several physical groups gets every one: MSH 4 is read with -dm_plex_gmsh_multiple_tags, MSH 2 lists
  such an element once per group) and, for each named physical surface or volume of $PhysicalNames, a label of
  that name holding its triangles or cells (value: the number), as -dm_plex_gmsh_use_regions makes them but
  without losing the unnamed groups. `FEMAddDMPlex()` thus makes a facet set of every physical surface by number
  and of every named one also by name.

  Level: intermediate

.seealso: `FEMAddDMPlex()`, `DMPlexCreateFromFile()`
@*/
PetscErrorCode FEMCreateDMPlexFromFile(MPI_Comm comm, const char filename[], DM *dm)
{
  PetscMPIInt rank;
  std::string error;

  PetscFunctionBegin;
  PetscAssertPointer(dm, 3);
  PetscCheck(filename && filename[0], comm, PETSC_ERR_ARG_WRONG, "FEMCreateDMPlexFromFile(): no file name");
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  *dm = NULL;
  if (!rank) PetscCall(ReadOnRankZero(filename, dm, error));
  PetscCall(BcastString(comm, error));
  if (!error.empty()) PetscCall(DMDestroy(dm));
  PetscCheck(error.empty(), comm, PETSC_ERR_FILE_READ, "%s", error.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}
