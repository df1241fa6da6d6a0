/* Private structures of the fem layer, shared between the files of src/fem. */
#pragma once

#include <petsc/private/petscimpl.h>
#include <conefeti/sys.h>
#include <conefeti/fem.h>
#include <conefeti/compat.h>

#include <array>
#include <map>
#include <string>
#include <vector>

/* The built-in tags x0, x1, y0, y1, z0, z1: the boundary triangles whose outward normal points mostly
   along -x, +x, -y, +y, -z, +z (on a box: exactly its six faces) */
PETSC_INTERN const char *const FEMBoxFaceNames[6];

/* A boundary triangle: one face of exactly one tetrahedron */
struct FEMBoundaryTriangle {
  std::array<PetscInt, 3>  v;       /* body node ids */
  PetscInt                 element; /* body element id of the tetrahedron it bounds */
  PetscInt                 face;    /* built-in tag 0..5 (x0, x1, y0, y1, z0, z1) of its outward normal */
  PetscReal                area;
  std::array<PetscReal, 3> normal; /* outward unit normal */
};

struct FEMTaggedNodes {
  std::vector<PetscInt>  nodes;     /* sorted body node ids */
  std::vector<PetscReal> areas;     /* lumped nodal area: sum over the tagged triangles of area/3 */
  std::vector<PetscReal> normals;   /* 3 per node: area-weighted average outward unit normal */
  std::vector<PetscInt>  triangles; /* 3 body node ids per tagged triangle (boundary order) */
};

struct FEMUserTag {
  std::string      name;
  std::string      within; /* empty: all boundary triangles; else only those of this tag */
  FEMFacePredicate predicate;
  void            *ctx;
};

struct FEMDirichletSpec {
  std::string              name;
  unsigned                 components; /* bit c set: component c is prescribed */
  std::array<PetscReal, 3> value;      /* the prescribed displacement of those components (0: clamped) */
};

struct FEMTractionSpec {
  std::string              name;
  FEMVectorField           field; /* NULL: constant */
  void                    *ctx;
  std::array<PetscReal, 3> value;
};

/* A body is a P1 tetrahedral mesh: generated from a box (FEMAddBox()) or given (FEMAddMesh()) */
struct FEMBody {
  PetscBool                                    isbox = PETSC_TRUE; /* box: lower, upper, cells define it and the mesh is generated in FEMSetUp() */
  std::array<PetscReal, 3>                     lower{}, upper{};
  std::array<PetscInt, 3>                      cells{};
  std::map<std::string, std::vector<PetscInt>> facetsets; /* FEMAddFacetSet(): 3 node ids per triangle */
  PetscReal                                    E = 0, nu = 0;
  PetscBool                                    materialset   = PETSC_FALSE;
  FEMDecompositionType                         decomposition = FEM_DECOMPOSITION_STRUCTURED;
  std::array<PetscInt, 3>                      parts{1, 1, 1};
  PetscBool                                    decompositionset = PETSC_FALSE;
  std::vector<FEMUserTag>                      usertags;
  std::vector<FEMDirichletSpec>                dirichlet;
  std::vector<FEMTractionSpec>                 tractions;
  FEMVectorField                               bodyforce    = nullptr;
  void                                        *bodyforcectx = nullptr;

  /* Given by FEMAddMesh() or built by FEMSetUp() for a box, on every rank */
  PetscInt               nnodes = 0, nelements = 0;
  std::vector<PetscReal> coords; /* 3 per node */
  std::vector<PetscInt>  conn;   /* 4 node ids per element, positively oriented */

  /* Built by FEMSetUp() on every rank */
  PetscInt                                     nodeoffset = 0;
  PetscInt                                     firstsub = 0, nsub = 0;
  std::vector<FEMBoundaryTriangle>             boundary;
  std::map<std::string, std::vector<PetscInt>> tags; /* tag -> indices into boundary */
  std::map<std::string, FEMTaggedNodes>        taggednodes;
  std::vector<PetscInt>                        part;           /* element -> subdomain index within the body */
  std::vector<unsigned char>                   dirichletmask;  /* node -> prescribed component bits */
  std::vector<PetscReal>                       dirichletvalue; /* 3 per node: the prescribed displacement; empty when every prescribed value is 0 */
  std::vector<unsigned char>                   onboundary;     /* node -> 1 when on the body's boundary */
  std::vector<unsigned char>                   oninterface;    /* node -> 1 when elements of two subdomains share it */
};

/* One subdomain owned by this rank */
struct FEMSubdomain {
  PetscInt              id = 0, body = 0;
  std::vector<PetscInt> elements; /* body element ids */
  std::vector<PetscInt> nodes;    /* sorted body node ids; local node l has primal dofs primaloffset + 3 l + c */
  std::vector<PetscInt> conn;     /* 4 local node indices per element */
  PetscInt              primaloffset = 0;
};

/* The copies of the nodes that lie on a body boundary or a subdomain interface, replicated on all ranks.
   Flat sorted arrays rather than a map of small vectors: a few words per node instead of ~150 bytes of
   tree nodes and heap blocks, which at H/h = 4 was about 50 bytes per primal unknown. Entry i is the node
   (body[i], node[i]), (body, node) increasing; its copies are [offset[i], offset[i+1]) in subdomains[]
   (increasing) and dofs[] (primal dof of the x component of each copy). */
struct FEMCopyTable {
  std::vector<PetscInt> body, node, offset, subdomains, dofs;

  /* index of the entry of (b, n), or -1 when the node has no entry */
  PetscInt Find(PetscInt b, PetscInt n) const
  {
    size_t lo = 0, hi = body.size();
    while (lo < hi) {
      const size_t mid = (lo + hi) / 2;
      if (body[mid] < b || (body[mid] == b && node[mid] < n)) lo = mid + 1;
      else hi = mid;
    }
    return lo < body.size() && body[lo] == b && node[lo] == n ? (PetscInt)lo : -1;
  }
  PetscInt        Count(PetscInt i) const { return offset[i + 1] - offset[i]; }
  const PetscInt *Subdomains(PetscInt i) const { return subdomains.data() + offset[i]; }
  const PetscInt *Dofs(PetscInt i) const { return dofs.data() + offset[i]; }
};

struct FEM_Impl {
  std::vector<FEMBody>      bodies;
  FEMDirichletMode          dirichletmode = FEM_DIRICHLET_MULTIPLIERS;
  PetscReal                 dirichlethold = 0.25;     /* -fem_dirichlet_min_hold: primal mode, subdomains held less firmly by Gamma_u get multipliers */
  std::vector<PetscInt>     dirichletrows;            /* per subdomain (all ranks), set by FEMCreateFETI(): 1 when its Dirichlet dofs are rows of B */
  PetscBool                 balancerows = PETSC_TRUE; /* -fem_balance_multipliers: B's rows (the multipliers) spread evenly over the ranks, see FEMCreateFETI() */
  PetscBool                 sbaij       = PETSC_TRUE; /* symmetric storage: half of AIJ (CHOLMOD factors a transient AIJ copy) */
  PetscBool                 setupcalled = PETSC_FALSE;
  PetscInt                  nsubdomains = 0, firstlocal = 0, nlocal = 0;
  std::vector<PetscInt>     subprimaloffset; /* nsubdomains + 1 */
  std::vector<FEMSubdomain> local;
  FEMCopyTable              copies;
  PetscInt                  nglobalnodes        = 0;
  VecScatter                primaltoglobal      = nullptr;
  Vec                       inversemultiplicity = nullptr;
};

struct _FEMOps {
  PetscErrorCode (*dummy)(void);
};

struct _p_FEM {
  PETSCHEADER(struct _FEMOps);
  FEM_Impl *impl;
};

/* The nodes of body element e */
static inline void FEMElementNodes(const FEMBody &b, PetscInt e, PetscInt v[4])
{
  for (PetscInt a = 0; a < 4; a++) v[a] = b.conn[4 * (size_t)e + a];
}

/* Mesh of a box (femmesh.cxx) */
PETSC_INTERN PetscErrorCode FEMBoxBuildMesh(FEMBody &);

/* A flat tetrahedron: 6 |volume| against the cube of its longest edge is 1 for a right-angled corner, 0.7 for a
   regular tetrahedron, and below 1e-10 only for a sliver no mesher produces on purpose */
static inline PetscBool FEMTetrahedronIsFlat(PetscReal det, PetscReal longest) { return PetscAbsReal(det) <= 1e-10 * longest * longest * longest ? PETSC_TRUE : PETSC_FALSE; }

/* Any tetrahedral mesh (femtopology.cxx): boundary triangles, tags, Dirichlet mask, interface nodes */
PETSC_INTERN void           FEMTetrahedronGeometry(const PetscReal *, const PetscInt[4], PetscReal *, PetscReal *);
PETSC_INTERN PetscErrorCode FEMCheckMesh(MPI_Comm, PetscInt, const FEMBody &);
PETSC_INTERN PetscErrorCode FEMBuildBoundary(FEMBody &);
PETSC_INTERN PetscErrorCode FEMBuildTags(PetscInt, FEMBody &);
PETSC_INTERN PetscErrorCode FEMMarkInterfaceNodes(FEMBody &);

/* Elasticity (femelasticity.cxx) */
PETSC_INTERN PetscErrorCode FEMElementLoad(const PetscReal[12], FEMVectorField, void *, PetscReal[12]);
PETSC_INTERN PetscErrorCode FEMTriangleLoad(const PetscReal[9], PetscReal, FEMVectorField, void *, const PetscReal[3], PetscReal[9]);

/* Decomposition (femdecompose.cxx) */
PETSC_INTERN PetscErrorCode FEMDecomposeBody(MPI_Comm, FEMBody &);
PETSC_INTERN PetscErrorCode FEMBuildLocalSubdomains(FEM);

/* The prescribed displacement of a body node's component (0 when it is clamped or free) */
static inline PetscReal FEMDirichletValue(const FEMBody &b, PetscInt n, PetscInt c) { return b.dirichletvalue.empty() ? 0.0 : b.dirichletvalue[3 * (size_t)n + c]; }

/* Subdomain assembly (femassemble.cxx) */
PETSC_INTERN PetscErrorCode FEMAssembleSubdomain(FEM, const FEMSubdomain &, Mat *, Vec *);
