/* Layer fem: bodies as P1 tetrahedral meshes (generated for boxes, or given: FEMAddMesh(), FEMAddDMPlex()),
   linear elasticity, decomposition into subdomains (structured for boxes, or METIS), and the constraint rows
   (gluing, Dirichlet, and the caller's contact rows) that turn a scene into a FETI problem (see conefeti/feti.h).

   Numbering used throughout:
     body node     a given mesh: its own node numbers; a box: node (i,j,k), 0 <= i <= nx, ...; id = i + (nx+1)*(j + (ny+1)*k)
     global dof    3*(first node of body b + node) + component, bodies concatenated (FEMAssembleGlobal())
     subdomain     global id, bodies in order and subdomains of a body in order; subdomains are
                   spread over the ranks in contiguous ranges
     primal dof    the FETI primal vector: subdomains concatenated in subdomain order; inside a
                   subdomain nodes in increasing body-node order, 3 dofs per node */
#pragma once

#include <petscmat.h>
#include <petscdmplex.h>
#include <conefeti/feti.h>

/*S
  FEM - A finite-element model of linear elastic bodies (tetrahedral meshes, of boxes or given): materials,
  loads, Dirichlet boundaries, tagged boundary faces, and the decomposition into subdomains from
  which a `FETI` problem is built.

  Level: beginner

.seealso: `FEMCreate()`, `FEMAddBox()`, `FEMSetUp()`, `FEMCreateFETI()`
S*/
typedef struct _p_FEM *FEM;

/*E
  FEMDecompositionType - How a body is cut into subdomains.

$ FEM_DECOMPOSITION_STRUCTURED - px x py x pz boxes of hexahedra (-fem_decomposition structured -fem_subdomains px,py,pz)
$ FEM_DECOMPOSITION_METIS      - METIS on the element dual graph (face neighbours), any count (-fem_decomposition metis -fem_subdomains n)

  Level: beginner

.seealso: `FEMSetDecomposition()`
E*/
typedef enum {
  FEM_DECOMPOSITION_STRUCTURED,
  FEM_DECOMPOSITION_METIS
} FEMDecompositionType;
PETSC_EXTERN const char *const FEMDecompositionTypes[];

/*E
  FEMDirichletMode - How prescribed displacements (zero or given) on Dirichlet faces enter the FETI problem.

$ FEM_DIRICHLET_MULTIPLIERS - Total FETI: by rows of B (kind FETI_ROW_DIRICHLET, right-hand side the prescribed value); every subdomain floats
$ FEM_DIRICHLET_PRIMAL      - kept in the primal: the dofs are removed from the subdomain spaces (a nonzero value is lifted into the load); only floating subdomains contribute rigid modes

  Level: beginner

.seealso: `FEMSetDirichletMode()`
E*/
typedef enum {
  FEM_DIRICHLET_MULTIPLIERS,
  FEM_DIRICHLET_PRIMAL
} FEMDirichletMode;
PETSC_EXTERN const char *const FEMDirichletModes[];

/*S
  FEMFacePredicate - A user test on boundary triangles that defines a boundary tag (`FEMTagFaces()`).

  Calling Sequence:
$ PetscErrorCode predicate(const PetscReal centroid[3], const PetscReal normal[3], PetscBool *tagged, void *ctx)
+ centroid - the triangle's centroid
. normal   - its outward unit normal
. tagged   - set to PETSC_TRUE when the triangle belongs to the tag
- ctx      - the user context

  Level: intermediate

.seealso: `FEMTagFaces()`
S*/
typedef PetscErrorCode (*FEMFacePredicate)(const PetscReal centroid[3], const PetscReal normal[3], PetscBool *tagged, void *ctx);

/*S
  FEMVectorField - A vector field of position: a volume force density (`FEMSetBodyForce()`) or a surface traction (`FEMSetTractionField()`).

  Calling Sequence:
$ PetscErrorCode field(const PetscReal x[3], PetscReal value[3], void *ctx)
+ x     - the point
. value - the vector at x
- ctx   - the user context

  Level: intermediate

.seealso: `FEMSetBodyForce()`, `FEMSetTractionField()`
S*/
typedef PetscErrorCode (*FEMVectorField)(const PetscReal x[3], PetscReal value[3], void *ctx);

/*S
  FEMHoldingRow - A constraint row beyond the Dirichlet conditions that can hold rigid motions of the bodies
  (`FEMComputeFreeRigidMotions()`), such as a contact row: the displacement component along dir at node `node` of
  body `body`, minus the one at the point sum_v other_weight[v] X(other_node[v]) of body `other_body`.

$ body, node       - the row's node (body node numbering)
$ other_body       - the body on the other side, or -1 for a rigid foundation (then nother is 0)
$ nother           - the number of nodes of the other body that carry the point (1 to 3: a node, an edge, a triangle)
$ other_node       - those nodes
$ other_weight     - their weights (barycentric)
$ dir              - the direction of the row (a component of a row that a Dirichlet condition removes is 0)

  Level: intermediate

.seealso: `FEMComputeFreeRigidMotions()`, `FEMCreateFETIWithRows()`
S*/
typedef struct {
  PetscInt  body, node, other_body, nother, other_node[3];
  PetscReal other_weight[3];
  PetscReal dir[3];
} FEMHoldingRow;

PETSC_EXTERN PetscClassId  FEM_CLASSID;
PETSC_EXTERN PetscLogEvent FEM_SetUp, FEM_Assembly, FEM_Decompose;

PETSC_EXTERN PetscErrorCode FEMCreate(MPI_Comm, FEM *);
PETSC_EXTERN PetscErrorCode FEMDestroy(FEM *);
PETSC_EXTERN PetscErrorCode FEMAddBox(FEM, const PetscReal[3], const PetscReal[3], const PetscInt[3], PetscInt *);
PETSC_EXTERN PetscErrorCode FEMAddMesh(FEM, PetscInt, const PetscReal[], PetscInt, const PetscInt[], PetscInt *);
PETSC_EXTERN PetscErrorCode FEMAddFacetSet(FEM, PetscInt, const char[], PetscInt, const PetscInt[]);
PETSC_EXTERN PetscErrorCode FEMAddDMPlex(FEM, DM, PetscInt *);
PETSC_EXTERN PetscErrorCode FEMCreateDMPlexFromFile(MPI_Comm, const char[], DM *);
PETSC_EXTERN PetscErrorCode FEMDMPlexGetFacetSetNames(DM, PetscInt *, char ***);
PETSC_EXTERN PetscErrorCode FEMSetMaterial(FEM, PetscInt, PetscReal, PetscReal);
PETSC_EXTERN PetscErrorCode FEMGetMaterial(FEM, PetscInt, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode FEMTagFaces(FEM, PetscInt, const char[], FEMFacePredicate, void *);
PETSC_EXTERN PetscErrorCode FEMTagFacesWithin(FEM, PetscInt, const char[], const char[], FEMFacePredicate, void *);
PETSC_EXTERN PetscErrorCode FEMSetDirichlet(FEM, PetscInt, const char[], const PetscBool[3]);
PETSC_EXTERN PetscErrorCode FEMSetDisplacement(FEM, PetscInt, const char[], const PetscBool[3], const PetscReal[3]);
PETSC_EXTERN PetscErrorCode FEMGetNumDirichlet(FEM, PetscInt, PetscInt *);
PETSC_EXTERN PetscErrorCode FEMSetTraction(FEM, PetscInt, const char[], const PetscReal[3]);
PETSC_EXTERN PetscErrorCode FEMSetTractionField(FEM, PetscInt, const char[], FEMVectorField, void *);
PETSC_EXTERN PetscErrorCode FEMSetBodyForce(FEM, PetscInt, FEMVectorField, void *);
PETSC_EXTERN PetscErrorCode FEMSetDecomposition(FEM, PetscInt, FEMDecompositionType, const PetscInt[3]);
PETSC_EXTERN PetscErrorCode FEMSetDirichletMode(FEM, FEMDirichletMode);
PETSC_EXTERN PetscErrorCode FEMGetDirichletMode(FEM, FEMDirichletMode *);
PETSC_EXTERN PetscErrorCode FEMSetOptionsPrefix(FEM, const char[]);
PETSC_EXTERN PetscErrorCode FEMSetFromOptions(FEM);
PETSC_EXTERN PetscErrorCode FEMSetUp(FEM);
PETSC_EXTERN PetscErrorCode FEMView(FEM, PetscViewer);

PETSC_EXTERN PetscErrorCode FEMGetNumBodies(FEM, PetscInt *);
PETSC_EXTERN PetscErrorCode FEMGetBodyNodes(FEM, PetscInt, PetscInt *, const PetscReal **);
PETSC_EXTERN PetscErrorCode FEMGetBodyNodeOffset(FEM, PetscInt, PetscInt *);
PETSC_EXTERN PetscErrorCode FEMGetTaggedNodes(FEM, PetscInt, const char[], PetscInt *, const PetscInt **, const PetscReal **, const PetscReal **);
PETSC_EXTERN PetscErrorCode FEMGetTaggedTriangles(FEM, PetscInt, const char[], PetscInt *, const PetscInt **);
PETSC_EXTERN PetscErrorCode FEMGetNodeCopies(FEM, PetscInt, PetscInt, PetscInt *, const PetscInt **, const PetscInt **);
PETSC_EXTERN PetscErrorCode FEMGetNumSubdomains(FEM, PetscInt *, PetscInt *, PetscInt *);
PETSC_EXTERN PetscErrorCode FEMGetSubdomainMesh(FEM, PetscInt, PetscInt *, PetscInt *, const PetscInt **, PetscInt *, const PetscInt **);

PETSC_EXTERN PetscErrorCode FEMCreateFETI(FEM, FETI *);
PETSC_EXTERN PetscErrorCode FEMCreateFETIWithRows(FEM, PetscInt, const FETIRowKind[], const PetscInt[], const PetscInt[], const PetscInt[], const PetscInt[], const PetscScalar[], const PetscScalar[],
                                                  PetscInt[], FETI *);
PETSC_EXTERN PetscErrorCode FEMAssembleGlobal(FEM, Mat *, Vec *);
PETSC_EXTERN PetscErrorCode FEMComputeLoadResultant(FEM, PetscInt, const PetscReal[3], PetscReal[3], PetscReal[3], PetscReal *);
PETSC_EXTERN PetscErrorCode FEMComputeRigidMotionFrame(FEM, PetscInt, PetscReal[3], PetscReal *);
PETSC_EXTERN PetscErrorCode FEMComputeFreeRigidMotions(FEM, PetscInt, const FEMHoldingRow[], PetscInt *, PetscReal *[]);
PETSC_EXTERN PetscErrorCode FEMCreateGlobalCoordinates(FEM, Vec *);
PETSC_EXTERN PetscErrorCode FEMPrimalToGlobal(FEM, Vec, Vec);
PETSC_EXTERN PetscErrorCode FEMGlobalToPrimal(FEM, Vec, Vec);
PETSC_EXTERN PetscErrorCode FEMGetGlobalDirichletDofs(FEM, IS *);
PETSC_EXTERN PetscErrorCode FEMGetDirichletValues(FEM, IS, PetscReal[]);
PETSC_EXTERN PetscErrorCode FEMComputeReactions(FEM, FETI, Vec, Vec, PetscReal[]);
PETSC_EXTERN PetscErrorCode FEMElementStiffness(const PetscReal[12], PetscReal, PetscReal, PetscReal[144], PetscReal *);
