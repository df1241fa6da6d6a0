/* The FEM object: bodies (boxes), materials, loads, boundary tags, decomposition; setup and queries. */
#include <conefeti/private/femimpl.h>

#include <algorithm>
#include <cstring>

const char *const FEMDecompositionTypes[] = {"structured", "metis", "FEMDecompositionType", "FEM_DECOMPOSITION_", NULL};
const char *const FEMDirichletModes[]     = {"multipliers", "primal", "FEMDirichletMode", "FEM_DIRICHLET_", NULL};

static PetscErrorCode FEMDestroy_Private(FEM fem)
{
  PetscFunctionBegin;
  if (fem->impl) {
    PetscCall(VecScatterDestroy(&fem->impl->primaltoglobal));
    PetscCall(VecDestroy(&fem->impl->inversemultiplicity));
  }
  PetscCallCXX(delete fem->impl);
  fem->impl = nullptr;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMCreate - Create an empty finite-element model.

  Collective

  Input Parameter:
. comm - MPI communicator; subdomains are spread over its ranks

  Output Parameter:
. fem - the model

  Level: beginner

.seealso: `FEMAddBox()`, `FEMSetUp()`, `FEMCreateFETI()`, `FEMDestroy()`
@*/
PetscErrorCode FEMCreate(MPI_Comm comm, FEM *fem)
{
  FEM f;

  PetscFunctionBegin;
  PetscAssertPointer(fem, 2);
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscHeaderCreate(f, FEM_CLASSID, "FEM", "Finite-element model of elastic bodies", "FEM", comm, FEMDestroy, FEMView));
  PetscCallCXX(f->impl = new FEM_Impl());
  *fem = f;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMDestroy - Destroy a model.

  Collective

  Input Parameter:
. fem - the model

  Level: beginner

.seealso: `FEMCreate()`
@*/
PetscErrorCode FEMDestroy(FEM *fem)
{
  PetscFunctionBegin;
  if (!fem || !*fem) PetscFunctionReturn(PETSC_SUCCESS);
  PetscValidHeaderSpecific(*fem, FEM_CLASSID, 1);
  if (--((PetscObject)(*fem))->refct > 0) {
    *fem = NULL;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(FEMDestroy_Private(*fem));
  PetscCall(PetscHeaderDestroy(fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The nodes of a body, before FEMSetUp() generates the boxes */
static double BodyNodeCount(const FEMBody &b) { return b.isbox ? ((double)b.cells[0] + 1) * ((double)b.cells[1] + 1) * ((double)b.cells[2] + 1) : (double)b.nnodes; }

static PetscErrorCode CheckBody(FEM fem, PetscInt body)
{
  PetscFunctionBegin;
  PetscCheck(body >= 0 && body < (PetscInt)fem->impl->bodies.size(), PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE, "Body %" PetscInt_FMT " does not exist (the model has %d bodies)",
             body, (int)fem->impl->bodies.size());
  PetscCheck(!fem->impl->setupcalled, PetscObjectComm((PetscObject)fem), PETSC_ERR_ORDER, "The model is set up already; change bodies before FEMSetUp()");
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMAddBox - Add a body: the box [lower, upper] meshed by cells[0] x cells[1] x cells[2] hexahedra, each split into 6 tetrahedra.

  Logically Collective

  Input Parameters:
+ fem   - the model
. lower - lower corner
. upper - upper corner (upper[d] > lower[d])
- cells - number of hexahedra along x, y, z (>= 1)

  Output Parameter:
. body - the index of the new body (may be NULL)

  Notes:
  The six faces carry the tags x0, x1, y0, y1, z0, z1 (x = lower[0], x = upper[0], ...).
  The default material is steel (E = 2.12e11, nu = 0.277) and the default decomposition one subdomain.
  The mesh is numbered by `PetscInt`: its 6 nx ny nz tetrahedra and 3 (nx+1)(ny+1)(nz+1) unknowns (summed over
  all bodies) must not exceed `PETSC_MAX_INT`, else this is an error.

  Level: beginner

.seealso: `FEMSetMaterial()`, `FEMTagFaces()`, `FEMSetDirichlet()`, `FEMSetDecomposition()`
@*/
PetscErrorCode FEMAddBox(FEM fem, const PetscReal lower[3], const PetscReal upper[3], const PetscInt cells[3], PetscInt *body)
{
  FEMBody b;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCheck(!fem->impl->setupcalled, PetscObjectComm((PetscObject)fem), PETSC_ERR_ORDER, "Add bodies before FEMSetUp()");
  for (PetscInt d = 0; d < 3; d++) {
    PetscCheck(!PetscIsInfOrNanReal(lower[d]) && !PetscIsInfOrNanReal(upper[d]), PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE,
               "Box side %" PetscInt_FMT ": lower %g and upper %g must be finite numbers", d, (double)lower[d], (double)upper[d]);
    PetscCheck(upper[d] > lower[d], PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE, "Box side %" PetscInt_FMT ": upper %g must exceed lower %g", d, (double)upper[d], (double)lower[d]);
    PetscCheck(cells[d] >= 1, PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE, "Box needs at least one cell along axis %" PetscInt_FMT ", got %" PetscInt_FMT, d, cells[d]);
    b.lower[d] = lower[d];
    b.upper[d] = upper[d];
    b.cells[d] = cells[d];
  }
  {
    /* Node, element and dof numbers are PetscInt: count them in floating point (exact up to 2^53, and an
       overflowing product stays far above the limit), so a box too large fails here, not in the mesher */
    const double nodes = ((double)cells[0] + 1) * ((double)cells[1] + 1) * ((double)cells[2] + 1), tets = 6.0 * cells[0] * cells[1] * cells[2];
    double       total = 3 * nodes; /* the undecomposed dofs of all bodies, numbered together */
    for (const FEMBody &o : fem->impl->bodies) total += 3.0 * BodyNodeCount(o);
    PetscCheck(3 * nodes <= PETSC_MAX_INT && tets <= PETSC_MAX_INT, PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE,
               "The box of %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT
               " cells has %.4g unknowns (3 per node) and %.4g tetrahedra: its mesh does not fit %d-bit PetscInt indices (at most %" PetscInt_FMT "); use fewer cells",
               cells[0], cells[1], cells[2], 3 * nodes, tets, (int)(8 * sizeof(PetscInt)), (PetscInt)PETSC_MAX_INT);
    PetscCheck(total <= PETSC_MAX_INT, PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE,
               "With the box of %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT
               " cells the model's %d bodies have %.4g unknowns (3 per node): they do not fit %d-bit PetscInt indices (at most %" PetscInt_FMT "); use fewer cells",
               cells[0], cells[1], cells[2], (int)fem->impl->bodies.size() + 1, total, (int)(8 * sizeof(PetscInt)), (PetscInt)PETSC_MAX_INT);
  }
  b.E  = 2.12e11;
  b.nu = 0.277;
  PetscCallCXX(fem->impl->bodies.push_back(b));
  if (body) *body = (PetscInt)fem->impl->bodies.size() - 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMAddMesh - Add a body given as a mesh of linear (P1) tetrahedra.

  Collective

  Input Parameters:
+ fem    - the model
. nnodes - number of nodes (used on rank 0 only)
. coords - 3 nnodes coordinates, node-major (rank 0 only; NULL elsewhere)
. ntets  - number of tetrahedra (rank 0 only)
- tets   - 4 ntets node ids, 0-based, each tetrahedron positively oriented: the fourth node lies on the side of
           the counter-clockwise normal of the first three (rank 0 only; NULL elsewhere)

  Output Parameter:
. body - the index of the new body (may be NULL)

  Notes:
  Only rank 0's arrays are read; they are broadcast and copied, so the caller may free them on return. The mesh is
  checked here: a node index out of range, a coordinate that is not finite, an inverted or degenerate (flat)
  tetrahedron, and a node that no tetrahedron uses are errors naming the element or node.

  Like a box, the body has the built-in boundary tags x0, x1, y0, y1, z0, z1: the boundary triangles whose outward
  normal points mostly along -x, +x, -y, +y, -z, +z. Name other parts of the boundary with `FEMAddFacetSet()` (the
  physical surfaces of a Gmsh model) or `FEMTagFaces()`. Several bodies may come from meshes and boxes together.

  A mesh body is decomposed by METIS (`FEM_DECOMPOSITION_METIS`, one subdomain unless `FEMSetDecomposition()` or
  -fem_subdomains asks for more; structured counts px,py,pz ask for px py pz parts). Pieces of the mesh that share
  no face become subdomains of their own. Every rank keeps a copy of the whole mesh (about 100 bytes per node
  with the boundary data), which bounds the size of a mesh to the memory of one rank.

  Level: beginner

.seealso: `FEMAddFacetSet()`, `FEMAddBox()`, `FEMSetDecomposition()`
@*/
PetscErrorCode FEMAddMesh(FEM fem, PetscInt nnodes, const PetscReal coords[], PetscInt ntets, const PetscInt tets[], PetscInt *body)
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)fem);
  PetscMPIInt rank;
  PetscInt    sizes[2] = {nnodes, ntets};
  FEMBody     b;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCheck(!fem->impl->setupcalled, comm, PETSC_ERR_ORDER, "Add bodies before FEMSetUp()");
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Bcast(sizes, 2, MPIU_INT, 0, comm));
  PetscCheck(sizes[0] >= 4 && sizes[1] >= 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "FEMAddMesh(): a mesh needs at least 4 nodes and one tetrahedron, got %" PetscInt_FMT " nodes and %" PetscInt_FMT " tetrahedra", sizes[0], sizes[1]);
  {
    double total = 3.0 * sizes[0];
    for (const FEMBody &o : fem->impl->bodies) total += 3.0 * BodyNodeCount(o);
    PetscCheck(4.0 * sizes[1] <= PETSC_MAX_INT && total <= PETSC_MAX_INT, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "FEMAddMesh(): with this mesh (%" PetscInt_FMT " nodes, %" PetscInt_FMT " tetrahedra) the model has %.4g unknowns: they do not fit %d-bit PetscInt indices (at most %" PetscInt_FMT ")",
               sizes[0], sizes[1], total, (int)(8 * sizeof(PetscInt)), (PetscInt)PETSC_MAX_INT);
  }
  if (rank == 0) {
    PetscAssertPointer(coords, 3);
    PetscAssertPointer(tets, 5);
  }
  b.isbox     = PETSC_FALSE;
  b.nnodes    = sizes[0];
  b.nelements = sizes[1];
  PetscCallCXX(b.coords.resize(3 * (size_t)b.nnodes));
  PetscCallCXX(b.conn.resize(4 * (size_t)b.nelements));
  if (rank == 0) {
    std::copy(coords, coords + 3 * (size_t)b.nnodes, b.coords.begin());
    std::copy(tets, tets + 4 * (size_t)b.nelements, b.conn.begin());
  }
  PetscCallMPI(MPI_Bcast(b.coords.data(), (PetscMPIInt)(3 * b.nnodes), MPIU_REAL, 0, comm));
  PetscCallMPI(MPI_Bcast(b.conn.data(), (PetscMPIInt)(4 * b.nelements), MPIU_INT, 0, comm));
  PetscCall(FEMCheckMesh(comm, (PetscInt)fem->impl->bodies.size(), b));
  b.E             = 2.12e11;
  b.nu            = 0.277;
  b.decomposition = FEM_DECOMPOSITION_METIS;
  PetscCallCXX(fem->impl->bodies.push_back(std::move(b)));
  if (body) *body = (PetscInt)fem->impl->bodies.size() - 1;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMAddFacetSet - Name a set of boundary triangles of a mesh body: a boundary tag, like a Gmsh physical surface.

  Collective

  Input Parameters:
+ fem        - the model
. body       - a body from `FEMAddMesh()`
. name       - the tag name (a built-in name x0 ... z1 is replaced)
. ntriangles - number of triangles (rank 0 only)
- triangles  - 3 ntriangles body node ids, in any order within a triangle (rank 0 only; NULL elsewhere)

  Notes:
  Only rank 0's arrays are read. Each triangle must be a face of exactly one tetrahedron of the body; `FEMSetUp()`
  reports one that is not. The name is then accepted wherever a tag is (`FEMSetDirichlet()`, `FEMSetTraction()`,
  `FEMGetTaggedNodes()`, `FEMTagFacesWithin()`, contact zones).

  Level: beginner

.seealso: `FEMAddMesh()`, `FEMTagFaces()`
@*/
PetscErrorCode FEMAddFacetSet(FEM fem, PetscInt body, const char name[], PetscInt ntriangles, const PetscInt triangles[])
{
  MPI_Comm              comm = PetscObjectComm((PetscObject)fem);
  PetscMPIInt           rank;
  PetscInt              n = ntriangles;
  std::vector<PetscInt> tri;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckBody(fem, body));
  PetscValidCharPointer(name, 3);
  PetscCheck(!fem->impl->bodies[body].isbox, comm, PETSC_ERR_ARG_WRONG, "FEMAddFacetSet(): body %" PetscInt_FMT " is a box; name parts of a box's boundary with FEMTagFaces()", body);
  PetscCheck(name[0], comm, PETSC_ERR_ARG_WRONG, "FEMAddFacetSet(): body %" PetscInt_FMT ": the set needs a name", body);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm));
  PetscCheck(n >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "FEMAddFacetSet(): facet set \"%s\" of body %" PetscInt_FMT ": %" PetscInt_FMT " triangles", name, body, n);
  PetscCallCXX(tri.resize(3 * (size_t)n));
  if (rank == 0 && n) {
    PetscAssertPointer(triangles, 5);
    std::copy(triangles, triangles + 3 * (size_t)n, tri.begin());
  }
  PetscCallMPI(MPI_Bcast(tri.data(), (PetscMPIInt)(3 * n), MPIU_INT, 0, comm));
  for (PetscInt i = 0; i < 3 * n; i++)
    PetscCheck(tri[i] >= 0 && tri[i] < fem->impl->bodies[body].nnodes, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "FEMAddFacetSet(): facet set \"%s\" of body %" PetscInt_FMT ": triangle %" PetscInt_FMT " has node %" PetscInt_FMT ", outside 0..%" PetscInt_FMT, name, body, i / 3, tri[i],
               fem->impl->bodies[body].nnodes - 1);
  fem->impl->bodies[body].facetsets[name] = std::move(tri);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMSetMaterial - Set the isotropic material of a body.

  Logically Collective

  Input Parameters:
+ fem  - the model
. body - the body
. E    - Young's modulus (> 0)
- nu   - Poisson's ratio (-1 < nu < 1/2)

  Options Database Keys:
+ -fem_E <E>   - Young's modulus of all bodies
- -fem_nu <nu> - Poisson's ratio of all bodies

  Level: beginner

.seealso: `FEMAddBox()`
@*/
PetscErrorCode FEMSetMaterial(FEM fem, PetscInt body, PetscReal E, PetscReal nu)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckBody(fem, body));
  PetscCheck(E > 0 && !PetscIsInfOrNanReal(E), PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE, "Young's modulus E = %g must be a finite positive number", (double)E);
  PetscCheck(nu > -1 && nu < 0.5, PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE, "Poisson's ratio nu = %g must lie in (-1, 0.5)", (double)nu);
  fem->impl->bodies[body].E           = E;
  fem->impl->bodies[body].nu          = nu;
  fem->impl->bodies[body].materialset = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMTagFaces - Define a boundary tag of a body by a predicate on its boundary triangles.

  Logically Collective

  Input Parameters:
+ fem       - the model
. body      - the body
. tag       - the tag name (a built-in name x0 ... z1 is replaced)
. predicate - called with the centroid and the outward unit normal of each boundary triangle; sets tagged
- ctx       - context for the predicate

  Notes:
  The predicate is evaluated in `FEMSetUp()` on every rank and must give the same answer everywhere.

  Level: intermediate

.seealso: `FEMSetDirichlet()`, `FEMSetTraction()`, `FEMGetTaggedNodes()`
@*/
PetscErrorCode FEMTagFaces(FEM fem, PetscInt body, const char tag[], FEMFacePredicate predicate, void *ctx)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckBody(fem, body));
  PetscValidCharPointer(tag, 3);
  PetscCheck(predicate, PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_NULL, "FEMTagFaces(): tag \"%s\" needs a predicate", tag);
  PetscCallCXX(fem->impl->bodies[body].usertags.push_back({tag, "", predicate, ctx}));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMTagFacesWithin - Define a boundary tag of a body as the triangles of another tag that satisfy a predicate.

  Logically Collective

  Input Parameters:
+ fem       - the model
. body      - the body
. tag       - the new tag's name
. within    - an existing tag: built-in, a facet set (`FEMAddFacetSet()`), or a tag defined before this one
. predicate - called with the centroid and the outward unit normal of each triangle of within; sets tagged
- ctx       - context for the predicate

  Notes:
  `FEMSetUp()` evaluates the tags in the order they were defined; it reports a within tag that does not exist.

  Level: intermediate

.seealso: `FEMTagFaces()`, `FEMAddFacetSet()`
@*/
PetscErrorCode FEMTagFacesWithin(FEM fem, PetscInt body, const char tag[], const char within[], FEMFacePredicate predicate, void *ctx)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckBody(fem, body));
  PetscValidCharPointer(tag, 3);
  PetscValidCharPointer(within, 4);
  PetscCheck(predicate, PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_NULL, "FEMTagFacesWithin(): tag \"%s\" needs a predicate", tag);
  PetscCallCXX(fem->impl->bodies[body].usertags.push_back({tag, within, predicate, ctx}));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMSetDirichlet - Fix displacement components (u = 0) on the tagged faces of a body (`FEMSetDisplacement()` with value 0).

  Logically Collective

  Input Parameters:
+ fem        - the model
. body       - the body
. tag        - a boundary tag (x0, x1, y0, y1, z0, z1, or one from `FEMTagFaces()`)
- components - which components are fixed (NULL: all three); e.g. {PETSC_TRUE, PETSC_FALSE, PETSC_FALSE} is a symmetry plane x = const

  Level: beginner

.seealso: `FEMSetDirichletMode()`, `FEMSetDisplacement()`, `FEMTagFaces()`
@*/
PetscErrorCode FEMSetDirichlet(FEM fem, PetscInt body, const char tag[], const PetscBool components[3])
{
  unsigned mask = 7;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckBody(fem, body));
  PetscValidCharPointer(tag, 3);
  if (components) mask = (components[0] ? 1u : 0u) | (components[1] ? 2u : 0u) | (components[2] ? 4u : 0u);
  PetscCallCXX(fem->impl->bodies[body].dirichlet.push_back({tag, mask, {0, 0, 0}}));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMSetDisplacement - Prescribe displacement components on the tagged faces of a body: a grip or a punch moved by a given vector.

  Logically Collective

  Input Parameters:
+ fem        - the model
. body       - the body
. tag        - a boundary tag (x0, x1, y0, y1, z0, z1, a facet set, or one from `FEMTagFaces()`)
. components - which components are prescribed (NULL: all three); the others stay free
- value      - the displacement ux, uy, uz (the entries of components not prescribed are ignored)

  Notes:
  `FEMSetDirichlet()` is this with value 0. Every prescribed component is a Dirichlet dof, handled as
  `FEMSetDirichletMode()` says: in Total FETI its row of B gets the right-hand side c = value (B u = c); in the
  primal mode the value is lifted into the load (f - K u_D, `FETISetSubdomainDirichletValues()`) and u takes it after
  the primal recovery. Contact leaves out nodes with a prescribed nonzero component.

  Conditions may overlap (a node on the edge of two faces): a node component prescribed by two of them must get the
  same value from both, otherwise `FEMSetUp()` stops with an error naming both tags and the node. The conditions are
  numbered per body in the order set (`FEMSetDirichlet()` and `FEMSetDisplacement()` together); `FEMComputeReactions()`
  reports one resultant per condition in that order.

  Level: beginner

.seealso: `FEMSetDirichlet()`, `FEMSetDirichletMode()`, `FEMComputeReactions()`, `FEMTagFaces()`
@*/
PetscErrorCode FEMSetDisplacement(FEM fem, PetscInt body, const char tag[], const PetscBool components[3], const PetscReal value[3])
{
  unsigned                 mask = 7;
  std::array<PetscReal, 3> v{};

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckBody(fem, body));
  PetscValidCharPointer(tag, 3);
  PetscAssertPointer(value, 5);
  if (components) mask = (components[0] ? 1u : 0u) | (components[1] ? 2u : 0u) | (components[2] ? 4u : 0u);
  for (PetscInt c = 0; c < 3; c++) {
    if (!(mask & (1u << c))) continue;
    PetscCheck(!PetscIsInfOrNanReal(value[c]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "FEMSetDisplacement(): body %" PetscInt_FMT ", tag \"%s\": the %c displacement %g is not finite", body, tag,
               (char)('x' + c), (double)value[c]);
    v[c] = value[c];
  }
  PetscCallCXX(fem->impl->bodies[body].dirichlet.push_back({tag, mask, v}));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetNumDirichlet - The number of Dirichlet conditions of a body (`FEMSetDirichlet()` and `FEMSetDisplacement()` calls).

  Not Collective

  Input Parameters:
+ fem  - the model
- body - the body

  Output Parameter:
. n - the number of conditions; `FEMComputeReactions()` numbers them in the order they were set

  Level: intermediate

.seealso: `FEMComputeReactions()`, `FEMSetDisplacement()`
@*/
PetscErrorCode FEMGetNumDirichlet(FEM fem, PetscInt body, PetscInt *n)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCheck(body >= 0 && body < (PetscInt)fem->impl->bodies.size(), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "FEMGetNumDirichlet(): body %" PetscInt_FMT " does not exist (%zu bodies)", body,
             fem->impl->bodies.size());
  PetscAssertPointer(n, 3);
  *n = (PetscInt)fem->impl->bodies[body].dirichlet.size();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMSetTraction - Apply a constant surface traction (force per unit area) on the tagged faces of a body.

  Logically Collective

  Input Parameters:
+ fem   - the model
. body  - the body
. tag   - a boundary tag
- value - the traction vector

  Level: beginner

.seealso: `FEMSetTractionField()`, `FEMSetBodyForce()`
@*/
PetscErrorCode FEMSetTraction(FEM fem, PetscInt body, const char tag[], const PetscReal value[3])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckBody(fem, body));
  PetscCallCXX(fem->impl->bodies[body].tractions.push_back({tag, nullptr, nullptr, {value[0], value[1], value[2]}}));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMSetTractionField - Apply a surface traction given as a function of position on the tagged faces of a body.

  Logically Collective

  Input Parameters:
+ fem   - the model
. body  - the body
. tag   - a boundary tag
. field - the traction (force per unit area) at a point
- ctx   - its context

  Notes:
  Integrated by the edge-midpoint rule, exact for tractions linear in position.

  Level: intermediate

.seealso: `FEMSetTraction()`
@*/
PetscErrorCode FEMSetTractionField(FEM fem, PetscInt body, const char tag[], FEMVectorField field, void *ctx)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckBody(fem, body));
  PetscCallCXX(fem->impl->bodies[body].tractions.push_back({tag, field, ctx, {0, 0, 0}}));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMSetBodyForce - Apply a volume force density on a body.

  Logically Collective

  Input Parameters:
+ fem   - the model
. body  - the body
. field - force per unit volume at a point
- ctx   - its context

  Notes:
  Integrated by the 4-point rule (exact for quadratic integrands). Without this call the body carries no volume force.

  Level: beginner

.seealso: `FEMSetTraction()`
@*/
PetscErrorCode FEMSetBodyForce(FEM fem, PetscInt body, FEMVectorField field, void *ctx)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckBody(fem, body));
  fem->impl->bodies[body].bodyforce    = field;
  fem->impl->bodies[body].bodyforcectx = ctx;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMSetDecomposition - Choose how a body is cut into subdomains.

  Logically Collective

  Input Parameters:
+ fem   - the model
. body  - the body
. type  - `FEM_DECOMPOSITION_STRUCTURED` or `FEM_DECOMPOSITION_METIS`
- parts - structured: subdomains along x, y, z; METIS: parts[0] is the number of subdomains

  Options Database Keys:
+ -fem_decomposition <structured,metis> - the type, for every body without an explicit call
- -fem_subdomains <px,py,pz or n>         - the counts, idem

  Notes:
  METIS asks for contiguous parts; a part that is still not face-connected becomes several subdomains.
  The structured decomposition needs a box (`FEMAddBox()`); for a mesh body (`FEMAddMesh()`) structured counts
  px,py,pz ask METIS for px py pz parts.

  Level: beginner

.seealso: `FEMSetUp()`, `FEMGetNumSubdomains()`
@*/
PetscErrorCode FEMSetDecomposition(FEM fem, PetscInt body, FEMDecompositionType type, const PetscInt parts[3])
{
  FEMBody *b;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckBody(fem, body));
  b                = &fem->impl->bodies[body];
  b->decomposition = type;
  b->parts         = {parts[0], type == FEM_DECOMPOSITION_METIS ? 1 : parts[1], type == FEM_DECOMPOSITION_METIS ? 1 : parts[2]};
          for (PetscInt d = 0; d < 3; d++) PetscCheck(b->parts[d] >= 1, PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE, "Subdomain count %" PetscInt_FMT " must be positive", b->parts[d]);
  b->decompositionset = PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMSetDirichletMode - Choose how Dirichlet conditions enter the FETI problem.

  Logically Collective

  Input Parameters:
+ fem  - the model
- mode - `FEM_DIRICHLET_MULTIPLIERS` (Total FETI, the default) or `FEM_DIRICHLET_PRIMAL`

  Options Database Key:
. -fem_dirichlet <multipliers,primal> - the mode

  Level: beginner

.seealso: `FEMCreateFETI()`, `FEMDirichletMode`
@*/
PetscErrorCode FEMSetDirichletMode(FEM fem, FEMDirichletMode mode)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  fem->impl->dirichletmode = mode;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetDirichletMode - How Dirichlet conditions enter the FETI problem.

  Not Collective

  Input Parameter:
. fem - the model

  Output Parameter:
. mode - the mode

  Level: beginner

.seealso: `FEMSetDirichletMode()`
@*/
PetscErrorCode FEMGetDirichletMode(FEM fem, FEMDirichletMode *mode)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  *mode = fem->impl->dirichletmode;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMSetOptionsPrefix - Set the prefix of the model's options (-<prefix>fem_...).

  Logically Collective

  Input Parameters:
+ fem    - the model
- prefix - the prefix

  Level: intermediate

.seealso: `FEMSetFromOptions()`
@*/
PetscErrorCode FEMSetOptionsPrefix(FEM fem, const char prefix[])
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)fem, prefix));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMSetFromOptions - Read the model's options.

  Collective

  Input Parameter:
. fem - the model

  Options Database Keys:
+ -fem_decomposition <structured,metis> - decomposition of every body without `FEMSetDecomposition()`
. -fem_subdomains <px,py,pz or n>         - subdomain counts (structured: per axis; METIS: total per body)
. -fem_dirichlet <multipliers,primal>     - Total FETI (Dirichlet by multipliers) or Dirichlet kept in the primal
. -fem_dirichlet_min_hold <0.25>          - primal mode: a subdomain whose Dirichlet dofs hold its rigid motions less firmly than this (see `FEMCreateFETI()`) gets them as multipliers (0: never)
. -fem_balance_multipliers <true>         - spread B's rows (the multipliers) evenly over the ranks instead of keeping them with the rank of their lowest subdomain (see `FEMCreateFETI()`)
. -fem_matrix_type <sbaij,aij>            - storage of the subdomain stiffness matrices (SBAIJ, the default, is half of AIJ; CHOLMOD factors a transient AIJ copy)
. -fem_E <E>                              - Young's modulus of every body without `FEMSetMaterial()`
. -fem_nu <nu>                            - Poisson's ratio of every body without `FEMSetMaterial()`
- -fem_view                               - view the model after `FEMSetUp()`

  Level: beginner

.seealso: `FEMSetDecomposition()`, `FEMSetDirichletMode()`
@*/
PetscErrorCode FEMSetFromOptions(FEM fem)
{
  FEM_Impl            &impl     = *fem->impl;
  FEMDecompositionType type     = FEM_DECOMPOSITION_STRUCTURED;
  PetscInt             parts[3] = {1, 1, 1}, nparts = 3;
  PetscBool            settype, setparts, setE, setnu;
  PetscReal            E = 2.12e11, nu = 0.277;
  char                 mattype[16];
  const char          *prefix; /* the options the errors name are the user's, with the FEM's prefix */

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)fem, &prefix));
  if (!prefix) prefix = "";
  PetscCall(PetscStrncpy(mattype, impl.sbaij ? "sbaij" : "aij", sizeof(mattype)));
  PetscObjectOptionsBegin((PetscObject)fem);
  PetscCall(PetscOptionsEnum("-fem_decomposition", "Decomposition of the bodies into subdomains", "FEMSetDecomposition", FEMDecompositionTypes, (PetscEnum)type, (PetscEnum *)&type, &settype));
  PetscCall(PetscOptionsIntArray("-fem_subdomains", "Subdomains per body: px,py,pz (structured) or n (metis)", "FEMSetDecomposition", parts, &nparts, &setparts));
  PetscCall(PetscOptionsEnum("-fem_dirichlet", "Dirichlet conditions by multipliers (Total FETI) or kept in the primal", "FEMSetDirichletMode", FEMDirichletModes, (PetscEnum)impl.dirichletmode,
                             (PetscEnum *)&impl.dirichletmode, NULL));
  PetscCall(PetscOptionsReal("-fem_dirichlet_min_hold", "Primal mode: a subdomain whose Dirichlet dofs hold its rigid motions less firmly than this gets them as multipliers (0: never)",
                             "FEMCreateFETI", impl.dirichlethold, &impl.dirichlethold, NULL));
  PetscCall(PetscOptionsBool("-fem_balance_multipliers", "Spread B's rows (the multipliers) evenly over the ranks instead of keeping them on the rank of their lowest subdomain", "FEMCreateFETI",
                             impl.balancerows, &impl.balancerows, NULL));
  PetscCall(PetscOptionsString("-fem_matrix_type", "Subdomain stiffness storage: sbaij or aij", "FEMCreateFETI", mattype, mattype, sizeof(mattype), NULL));
  PetscCall(PetscOptionsReal("-fem_E", "Young's modulus of bodies without FEMSetMaterial()", "FEMSetMaterial", E, &E, &setE));
  PetscCall(PetscOptionsReal("-fem_nu", "Poisson's ratio of bodies without FEMSetMaterial()", "FEMSetMaterial", nu, &nu, &setnu));
  PetscCall(PetscOptionsName("-fem_view", "View the model after setup", "FEMView", NULL));
  PetscOptionsEnd();
  /* checked where read, also when every body has its own material: inf passes "E > 0" and fails much later (FETI's K+ check) */
  PetscCheck(!setE || (E > 0 && !PetscIsInfOrNanReal(E)), PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE, "-%sfem_E %g: Young's modulus must be a finite positive number", prefix,
             (double)E);
  PetscCheck(!setnu || (nu > -1 && nu < 0.5), PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE, "-%sfem_nu %g: Poisson's ratio must lie in (-1, 0.5)", prefix, (double)nu);
  PetscCheck(impl.dirichlethold >= 0 && !PetscIsInfOrNanReal(impl.dirichlethold), PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE,
             "-%sfem_dirichlet_min_hold %g: must be a finite number >= 0 (0: keep every Dirichlet dof in the primal)", prefix, (double)impl.dirichlethold);
  PetscCheck(!strcmp(mattype, "sbaij") || !strcmp(mattype, "aij"), PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_WRONG, "-%sfem_matrix_type %s: use sbaij or aij", prefix, mattype);
  impl.sbaij = strcmp(mattype, "sbaij") ? PETSC_FALSE : PETSC_TRUE;
  if (setparts && type == FEM_DECOMPOSITION_STRUCTURED)
    PetscCheck(nparts == 3, PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_WRONG, "-%sfem_subdomains needs px,py,pz for the structured decomposition, got %" PetscInt_FMT " values", prefix, nparts);
  if (setparts && type == FEM_DECOMPOSITION_METIS)
    PetscCheck(nparts == 1, PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_WRONG, "-%sfem_subdomains needs one count n for the METIS decomposition, got %" PetscInt_FMT " values", prefix, nparts);
  for (FEMBody &b : impl.bodies) {
    if (!b.decompositionset && (settype || setparts)) {
      b.decomposition = type;
      b.parts         = {parts[0], type == FEM_DECOMPOSITION_METIS ? 1 : parts[1], type == FEM_DECOMPOSITION_METIS ? 1 : parts[2]};
              for (PetscInt d = 0; d < 3; d++)
        PetscCheck(b.parts[d] >= 1, PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_OUTOFRANGE, "-%sfem_subdomains: count %" PetscInt_FMT " must be positive", prefix, b.parts[d]);
    }
    if (!b.materialset) {
      if (setE) b.E = E;
      if (setnu) b.nu = nu;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMSetUp - Mesh the bodies, evaluate tags, decompose into subdomains and spread them over the ranks.

  Collective

  Input Parameter:
. fem - the model

  Notes:
  Every rank holds the node coordinates, the connectivity, the boundary triangles and the element-to-subdomain map
  of every body (about 20 bytes per element and 30 per node). Each rank builds the nodes and elements of its own
  subdomains only. There must be at least as many subdomains as ranks.

  Level: beginner

.seealso: `FEMCreateFETI()`, `FEMAssembleGlobal()`
@*/
PetscErrorCode FEMSetUp(FEM fem)
{
  FEM_Impl &impl = *fem->impl;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  if (impl.setupcalled) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCheck(!impl.bodies.empty(), PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_WRONGSTATE, "The model has no body: call FEMAddBox() before FEMSetUp()");
  PetscCall(PetscLogEventBegin(FEM_SetUp, fem, 0, 0, 0));
  impl.nglobalnodes = 0;
  for (size_t i = 0; i < impl.bodies.size(); i++) {
    FEMBody &b   = impl.bodies[i];
    b.nodeoffset = impl.nglobalnodes;
    if (b.isbox) PetscCall(FEMBoxBuildMesh(b));
    else PetscCall(FEMBuildBoundary(b));
    PetscCall(FEMBuildTags((PetscInt)i, b));
    impl.nglobalnodes += b.nnodes;
  }
  PetscCall(PetscLogEventBegin(FEM_Decompose, fem, 0, 0, 0));
  for (FEMBody &b : impl.bodies) PetscCall(FEMDecomposeBody(PetscObjectComm((PetscObject)fem), b));
  PetscCall(FEMBuildLocalSubdomains(fem));
  PetscCall(PetscLogEventEnd(FEM_Decompose, fem, 0, 0, 0));
  impl.setupcalled = PETSC_TRUE;
  PetscCall(PetscLogEventEnd(FEM_SetUp, fem, 0, 0, 0));
  PetscCall(PetscObjectViewFromOptions((PetscObject)fem, NULL, "-fem_view"));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMView - Print the bodies, their decomposition and the subdomain sizes.

  Collective

  Input Parameters:
+ fem    - the model
- viewer - an ASCII viewer (NULL: stdout)

  Options Database Key:
. -fem_view - view after `FEMSetUp()`

  Level: beginner

.seealso: `FEMSetUp()`
@*/
PetscErrorCode FEMView(FEM fem, PetscViewer viewer)
{
  FEM_Impl &impl = *fem->impl;
  PetscBool ascii;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(PetscObjectComm((PetscObject)fem), &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(PETSC_SUCCESS);
  {
    PetscMPIInt size;
    const char *prefix;
    PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)fem), &size));
    PetscCall(PetscObjectGetOptionsPrefix((PetscObject)fem, &prefix));
    PetscCall(PetscViewerASCIIPrintf(viewer, "FEM Object: %s%s%s%d MPI process%s\n", prefix ? "(" : "", prefix ? prefix : "", prefix ? ") " : "", size, size > 1 ? "es" : ""));
  }
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "%d bodies, Dirichlet conditions %s\n", (int)impl.bodies.size(),
                                   impl.dirichletmode == FEM_DIRICHLET_PRIMAL ? "kept in the primal" : "by multipliers (Total FETI)"));
  for (size_t i = 0; i < impl.bodies.size(); i++) {
    const FEMBody &b = impl.bodies[i];
    if (!b.isbox)
      PetscCall(PetscViewerASCIIPrintf(viewer, "body %d: mesh of %" PetscInt_FMT " nodes and %" PetscInt_FMT " tetrahedra, E %g, nu %g, metis decomposition %" PetscInt_FMT, (int)i, b.nnodes,
                                       b.nelements, (double)b.E, (double)b.nu, b.decomposition == FEM_DECOMPOSITION_METIS ? b.parts[0] : b.parts[0] * b.parts[1] * b.parts[2]));
    else
      PetscCall(PetscViewerASCIIPrintf(
          viewer, "body %d: box [%g,%g]x[%g,%g]x[%g,%g], %" PetscInt_FMT "x%" PetscInt_FMT "x%" PetscInt_FMT " cells, E %g, nu %g, %s decomposition %" PetscInt_FMT "x%" PetscInt_FMT "x%" PetscInt_FMT,
          (int)i, (double)b.lower[0], (double)b.upper[0], (double)b.lower[1], (double)b.upper[1], (double)b.lower[2], (double)b.upper[2], b.cells[0], b.cells[1], b.cells[2], (double)b.E, (double)b.nu,
          FEMDecompositionTypes[b.decomposition], b.parts[0], b.parts[1], b.parts[2]));
    if (impl.setupcalled) PetscCall(PetscViewerASCIIPrintf(viewer, " -> %" PetscInt_FMT " subdomains, %" PetscInt_FMT " nodes, %" PetscInt_FMT " tetrahedra", b.nsub, b.nnodes, b.nelements));
    PetscCall(PetscViewerASCIIPrintf(viewer, "\n"));
  }
  if (impl.setupcalled)
    PetscCall(PetscViewerASCIIPrintf(viewer, "%" PetscInt_FMT " subdomains, %" PetscInt_FMT " primal dofs (%" PetscInt_FMT " undecomposed)\n", impl.nsubdomains, impl.subprimaloffset.back(),
                                     3 * impl.nglobalnodes));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetNumBodies - Number of bodies.

  Not Collective

  Input Parameter:
. fem - the model

  Output Parameter:
. n - the number of bodies

  Level: beginner

.seealso: `FEMAddBox()`
@*/
PetscErrorCode FEMGetNumBodies(FEM fem, PetscInt *n)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  *n = (PetscInt)fem->impl->bodies.size();
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CheckSetUpBody(FEM fem, PetscInt body)
{
  PetscFunctionBegin;
  PetscCheck(fem->impl->setupcalled, PetscObjectComm((PetscObject)fem), PETSC_ERR_ORDER, "Call FEMSetUp() first");
  PetscCheck(body >= 0 && body < (PetscInt)fem->impl->bodies.size(), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Body %" PetscInt_FMT " does not exist (the model has %d bodies)", body,
             (int)fem->impl->bodies.size());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetBodyNodes - The node coordinates of a body (the same on every rank).

  Not Collective

  Input Parameters:
+ fem  - the model, set up
- body - the body

  Output Parameters:
+ n      - number of nodes
- coords - 3 n coordinates, node-major (do not free)

  Level: intermediate

.seealso: `FEMGetTaggedNodes()`, `FEMGetBodyNodeOffset()`
@*/
PetscErrorCode FEMGetBodyNodes(FEM fem, PetscInt body, PetscInt *n, const PetscReal **coords)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckSetUpBody(fem, body));
  if (n) *n = fem->impl->bodies[body].nnodes;
  if (coords) *coords = fem->impl->bodies[body].coords.data();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetBodyNodeOffset - The global index of a body's first node in the undecomposed numbering of `FEMAssembleGlobal()`.

  Not Collective

  Input Parameters:
+ fem  - the model, set up
- body - the body

  Output Parameter:
. offset - global node index of body node 0 (its dofs start at 3 offset)

  Level: intermediate

.seealso: `FEMAssembleGlobal()`
@*/
PetscErrorCode FEMGetBodyNodeOffset(FEM fem, PetscInt body, PetscInt *offset)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckSetUpBody(fem, body));
  *offset = fem->impl->bodies[body].nodeoffset;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetTaggedNodes - The nodes of a boundary tag with their lumped areas and outward normals (the same on every rank).

  Not Collective

  Input Parameters:
+ fem  - the model, set up
. body - the body
- tag  - the tag (x0 ... z1 or one from `FEMTagFaces()`)

  Output Parameters:
+ n       - number of nodes
. nodes   - sorted body node ids (do not free)
. areas   - lumped nodal areas: each tagged triangle gives a third of its area to each vertex (do not free)
- normals - 3 per node: the area-weighted mean outward unit normal of the tagged triangles at the node (do not free)

  Notes:
  A multiplier is a nodal force; the contact stress at a node is the multiplier divided by its area.
  At a node on the rim of the tag only the tagged triangles count.

  Level: intermediate

.seealso: `FEMTagFaces()`, `FEMGetNodeCopies()`, `FEMCreateFETIWithRows()`
@*/
PetscErrorCode FEMGetTaggedNodes(FEM fem, PetscInt body, const char tag[], PetscInt *n, const PetscInt **nodes, const PetscReal **areas, const PetscReal **normals)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckSetUpBody(fem, body));
  auto it = fem->impl->bodies[body].taggednodes.find(tag);
  PetscCheck(it != fem->impl->bodies[body].taggednodes.end(), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Body %" PetscInt_FMT " has no boundary tag \"%s\"", body, tag);
  if (n) *n = (PetscInt)it->second.nodes.size();
  if (nodes) *nodes = it->second.nodes.data();
  if (areas) *areas = it->second.areas.data();
  if (normals) *normals = it->second.normals.data();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetTaggedTriangles - The boundary triangles of a tag (the same on every rank).

  Not Collective

  Input Parameters:
+ fem  - the model, set up
. body - the body
- tag  - the tag (x0 ... z1 or one from `FEMTagFaces()`)

  Output Parameters:
+ n         - number of triangles
- triangles - 3 body node ids per triangle (do not free); every id is among the tag's nodes (`FEMGetTaggedNodes()`)

  Notes:
  The surface a contact zone between bodies searches for the closest point of each slave node.

  Level: intermediate

.seealso: `FEMGetTaggedNodes()`, `FEMTagFaces()`
@*/
PetscErrorCode FEMGetTaggedTriangles(FEM fem, PetscInt body, const char tag[], PetscInt *n, const PetscInt **triangles)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckSetUpBody(fem, body));
  auto it = fem->impl->bodies[body].taggednodes.find(tag);
  PetscCheck(it != fem->impl->bodies[body].taggednodes.end(), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "Body %" PetscInt_FMT " has no boundary tag \"%s\"", body, tag);
  if (n) *n = (PetscInt)(it->second.triangles.size() / 3);
  if (triangles) *triangles = it->second.triangles.data();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetNodeCopies - The copies of a body node in the subdomains: which subdomains hold it and where its dofs are in the FETI primal vector.

  Not Collective

  Input Parameters:
+ fem  - the model, set up
. body - the body
- node - a body node on the body's boundary or on a subdomain interface

  Output Parameters:
+ ncopies    - number of subdomains holding the node
. subdomains - their global ids, increasing (do not free)
- dofs       - for each copy, the primal index of its x dof (y, z follow); minus the subdomain's offset (`FETIGetSubdomainOffset()`) it is the local dof in K_s (do not free)

  Notes:
  Available on every rank for boundary and interface nodes (the places where contact rows live).

  Level: intermediate

.seealso: `FEMCreateFETIWithRows()`, `FEMGetTaggedNodes()`
@*/
PetscErrorCode FEMGetNodeCopies(FEM fem, PetscInt body, PetscInt node, PetscInt *ncopies, const PetscInt **subdomains, const PetscInt **dofs)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCall(CheckSetUpBody(fem, body));
  const FEMCopyTable &t = fem->impl->copies;
  const PetscInt      i = t.Find(body, node);
  PetscCheck(i >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Node %" PetscInt_FMT " of body %" PetscInt_FMT " is neither on the body's boundary nor on a subdomain interface", node, body);
  if (ncopies) *ncopies = t.Count(i);
  if (subdomains) *subdomains = t.Subdomains(i);
  if (dofs) *dofs = t.Dofs(i);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetNumSubdomains - Subdomain counts.

  Not Collective

  Input Parameter:
. fem - the model, set up

  Output Parameters:
+ nglobal - total number of subdomains
. nlocal  - number on this rank
- first   - global id of this rank's first subdomain (they are contiguous)

  Level: intermediate

.seealso: `FEMGetSubdomainMesh()`
@*/
PetscErrorCode FEMGetNumSubdomains(FEM fem, PetscInt *nglobal, PetscInt *nlocal, PetscInt *first)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCheck(fem->impl->setupcalled, PetscObjectComm((PetscObject)fem), PETSC_ERR_ORDER, "Call FEMSetUp() first");
  if (nglobal) *nglobal = fem->impl->nsubdomains;
  if (nlocal) *nlocal = fem->impl->nlocal;
  if (first) *first = fem->impl->firstlocal;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetSubdomainMesh - The mesh of one of this rank's subdomains, for output.

  Not Collective

  Input Parameters:
+ fem - the model, set up
- s   - local subdomain index, 0 <= s < nlocal

  Output Parameters:
+ body      - the body it belongs to
. nnodes    - number of nodes; local node l has primal dofs offset + 3 l + c
. nodes     - body node ids of the local nodes, increasing (do not free)
. nelements - number of tetrahedra
- conn      - 4 local node indices per tetrahedron, positively oriented (do not free)

  Level: intermediate

.seealso: `FEMGetNumSubdomains()`, `FEMGetBodyNodes()`
@*/
PetscErrorCode FEMGetSubdomainMesh(FEM fem, PetscInt s, PetscInt *body, PetscInt *nnodes, const PetscInt **nodes, PetscInt *nelements, const PetscInt **conn)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCheck(fem->impl->setupcalled, PetscObjectComm((PetscObject)fem), PETSC_ERR_ORDER, "Call FEMSetUp() first");
  PetscCheck(s >= 0 && s < fem->impl->nlocal, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "Local subdomain %" PetscInt_FMT " does not exist (this rank has %" PetscInt_FMT ")", s, fem->impl->nlocal);
  const FEMSubdomain &sd = fem->impl->local[s];
  if (body) *body = sd.body;
  if (nnodes) *nnodes = (PetscInt)sd.nodes.size();
  if (nodes) *nodes = sd.nodes.data();
  if (nelements) *nelements = (PetscInt)sd.elements.size();
  if (conn) *conn = sd.conn.data();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The scatter from primal copies to global dofs and the inverse multiplicity, built on first use */
static PetscErrorCode PrimalGlobalScatter(FEM fem, Vec uprimal, Vec uglobal)
{
  FEM_Impl &impl = *fem->impl;

  PetscFunctionBegin;
  if (impl.primaltoglobal) PetscFunctionReturn(PETSC_SUCCESS);
  std::vector<PetscInt> from, to;
  IS                    isfrom, isto;
  Vec                   ones;
  for (const FEMSubdomain &sd : impl.local) {
    const PetscInt offset = impl.bodies[sd.body].nodeoffset;
    for (size_t l = 0; l < sd.nodes.size(); l++)
      for (PetscInt c = 0; c < 3; c++) {
        PetscCallCXX(from.push_back(sd.primaloffset + 3 * (PetscInt)l + c));
        PetscCallCXX(to.push_back(3 * (offset + sd.nodes[l]) + c));
      }
  }
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)from.size(), from.data(), PETSC_COPY_VALUES, &isfrom));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)to.size(), to.data(), PETSC_COPY_VALUES, &isto));
  PetscCall(VecScatterCreate(uprimal, isfrom, uglobal, isto, &impl.primaltoglobal));
  PetscCall(ISDestroy(&isfrom));
  PetscCall(ISDestroy(&isto));
  PetscCall(VecDuplicate(uglobal, &impl.inversemultiplicity));
  PetscCall(VecDuplicate(uprimal, &ones));
  PetscCall(VecSet(ones, 1.0));
  PetscCall(VecSet(impl.inversemultiplicity, 0.0));
  PetscCall(VecScatterBegin(impl.primaltoglobal, ones, impl.inversemultiplicity, ADD_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(impl.primaltoglobal, ones, impl.inversemultiplicity, ADD_VALUES, SCATTER_FORWARD));
  PetscCall(VecReciprocal(impl.inversemultiplicity));
  PetscCall(VecDestroy(&ones));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMPrimalToGlobal - Map a FETI primal vector (subdomain copies) to the undecomposed global vector, averaging the copies of each node.

  Collective

  Input Parameters:
+ fem     - the model, set up
- uprimal - primal vector (layout of the FETI's primal vectors)

  Output Parameter:
. uglobal - vector in the layout of `FEMAssembleGlobal()`

  Level: intermediate

.seealso: `FEMGlobalToPrimal()`, `FEMAssembleGlobal()`, `FETIRecoverPrimal()`
@*/
PetscErrorCode FEMPrimalToGlobal(FEM fem, Vec uprimal, Vec uglobal)
{
  FEM_Impl &impl = *fem->impl;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscValidHeaderSpecific(uprimal, VEC_CLASSID, 2);
  PetscValidHeaderSpecific(uglobal, VEC_CLASSID, 3);
  PetscCheck(impl.setupcalled, PetscObjectComm((PetscObject)fem), PETSC_ERR_ORDER, "Call FEMSetUp() first");
  PetscCall(PrimalGlobalScatter(fem, uprimal, uglobal));
  PetscCall(VecSet(uglobal, 0.0));
  PetscCall(VecScatterBegin(impl.primaltoglobal, uprimal, uglobal, ADD_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(impl.primaltoglobal, uprimal, uglobal, ADD_VALUES, SCATTER_FORWARD));
  PetscCall(VecPointwiseMult(uglobal, uglobal, impl.inversemultiplicity));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGlobalToPrimal - Copy an undecomposed global vector to every subdomain copy of each node (a continuous field in FETI primal form).

  Collective

  Input Parameters:
+ fem     - the model, set up
- uglobal - vector in the layout of `FEMAssembleGlobal()`

  Output Parameter:
. uprimal - primal vector (layout of the FETI's primal vectors)

  Level: intermediate

.seealso: `FEMPrimalToGlobal()`
@*/
PetscErrorCode FEMGlobalToPrimal(FEM fem, Vec uglobal, Vec uprimal)
{
  FEM_Impl &impl = *fem->impl;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscValidHeaderSpecific(uglobal, VEC_CLASSID, 2);
  PetscValidHeaderSpecific(uprimal, VEC_CLASSID, 3);
  PetscCheck(impl.setupcalled, PetscObjectComm((PetscObject)fem), PETSC_ERR_ORDER, "Call FEMSetUp() first");
  PetscCall(PrimalGlobalScatter(fem, uprimal, uglobal));
  PetscCall(VecScatterBegin(impl.primaltoglobal, uglobal, uprimal, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(impl.primaltoglobal, uglobal, uprimal, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetGlobalDirichletDofs - The Dirichlet dofs in the undecomposed numbering of `FEMAssembleGlobal()`, owned by this rank.

  Collective

  Input Parameter:
. fem - the model, set up

  Output Parameter:
. is - global dof indices (destroy it)

  Level: intermediate

.seealso: `FEMAssembleGlobal()`, `FEMSetDirichlet()`
@*/
PetscErrorCode FEMGetGlobalDirichletDofs(FEM fem, IS *is)
{
  FEM_Impl             &impl        = *fem->impl;
  PetscInt              nlocalnodes = PETSC_DECIDE, nglobal = impl.nglobalnodes, last;
  std::vector<PetscInt> dofs;
  MPI_Comm              comm = PetscObjectComm((PetscObject)fem);

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCheck(impl.setupcalled, comm, PETSC_ERR_ORDER, "Call FEMSetUp() first");
  PetscCall(PetscSplitOwnership(comm, &nlocalnodes, &nglobal));
  PetscCallMPI(MPI_Scan(&nlocalnodes, &last, 1, MPIU_INT, MPI_SUM, comm));
  const PetscInt first = last - nlocalnodes;
  for (const FEMBody &b : impl.bodies) {
    const PetscInt lo = std::max(first, b.nodeoffset), hi = std::min(last, b.nodeoffset + b.nnodes);
    for (PetscInt g = lo; g < hi; g++)
      for (PetscInt c = 0; c < 3; c++)
        if (b.dirichletmask[g - b.nodeoffset] & (1u << c)) PetscCallCXX(dofs.push_back(3 * g + c));
  }
  PetscCall(ISCreateGeneral(comm, (PetscInt)dofs.size(), dofs.data(), PETSC_COPY_VALUES, is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetDirichletValues - The prescribed displacements of Dirichlet dofs given in the undecomposed numbering.

  Not Collective

  Input Parameters:
+ fem  - the model, set up
- dofs - global dof indices, each a Dirichlet dof (e.g. from `FEMGetGlobalDirichletDofs()`, or all of them gathered)

  Output Parameter:
. values - the prescribed displacement of each (0 on clamped dofs), in the order of dofs

  Level: intermediate

.seealso: `FEMGetGlobalDirichletDofs()`, `FEMSetDisplacement()`
@*/
PetscErrorCode FEMGetDirichletValues(FEM fem, IS dofs, PetscReal values[])
{
  FEM_Impl       &impl = *fem->impl;
  PetscInt        n;
  const PetscInt *idx;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscValidHeaderSpecific(dofs, IS_CLASSID, 2);
  PetscCheck(impl.setupcalled, PETSC_COMM_SELF, PETSC_ERR_ORDER, "Call FEMSetUp() first");
  PetscCall(ISGetLocalSize(dofs, &n));
  PetscCall(ISGetIndices(dofs, &idx));
  for (PetscInt i = 0; i < n; i++) {
    const PetscInt g = idx[i] / 3, c = idx[i] % 3;
    PetscInt       b = 0;
    while (b + 1 < (PetscInt)impl.bodies.size() && impl.bodies[b + 1].nodeoffset <= g) b++;
    const FEMBody &body = impl.bodies[b];
    PetscCheck(idx[i] >= 0 && g - body.nodeoffset < body.nnodes && (body.dirichletmask[g - body.nodeoffset] & (1u << c)), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "FEMGetDirichletValues(): dof %" PetscInt_FMT " is not a Dirichlet dof", idx[i]);
    values[i] = FEMDirichletValue(body, g - body.nodeoffset, c);
  }
  PetscCall(ISRestoreIndices(dofs, &idx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMGetMaterial - The elastic constants of a body.

  Not Collective

  Input Parameters:
+ fem  - the model
- body - the body

  Output Parameters:
+ E  - Young's modulus (or NULL)
- nu - Poisson's ratio (or NULL)

  Level: intermediate

.seealso: `FEMSetMaterial()`
@*/
PetscErrorCode FEMGetMaterial(FEM fem, PetscInt body, PetscReal *E, PetscReal *nu)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCheck(body >= 0 && body < (PetscInt)fem->impl->bodies.size(), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "FEMGetMaterial: body %" PetscInt_FMT " does not exist (%zu bodies)", body,
             fem->impl->bodies.size());
  PetscCheck(fem->impl->bodies[body].materialset, PetscObjectComm((PetscObject)fem), PETSC_ERR_ARG_WRONGSTATE, "FEMGetMaterial: body %" PetscInt_FMT " has no material (FEMSetMaterial())", body);
  if (E) *E = fem->impl->bodies[body].E;
  if (nu) *nu = fem->impl->bodies[body].nu;
  PetscFunctionReturn(PETSC_SUCCESS);
}
