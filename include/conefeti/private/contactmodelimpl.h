/* ContactModel internals shared by the files of the contact layer that build, solve and judge a model. */
#pragma once

#include <conefeti/private/contactimpl.h>
#include <vector>

/* one contact node: where it is, its rows' directions and gap, its law. Between bodies it is a node of the slave
   face (body, node) paired with the point chi = sum_i weight[i] X(master[i]) of the master face (other_body): its rows
   act on u(body, node) - sum_i weight[i] u(other_body, master[i]). A weight below 1e-12 is dropped (the others
   renormalized), so that a slave node on a master node has one master node of weight 1: node to node. */
struct ContactNodeInfo {
  PetscInt   zone, body, node, other_body = -1;
  PetscInt   nmaster = 0, master[3] = {-1, -1, -1};
  PetscReal  weight[3] = {0, 0, 0}, chi[3] = {0, 0, 0};
  unsigned   master_fixed[3] = {0, 0, 0}; /* the master nodes' Dirichlet components: their terms are left out (zero there) */
  PetscReal  x[3], area, n[3], t1[3], t2[3], gap;
  ContactLaw law;
  PetscReal  coef; /* Tresca: bound as a nodal force; Coulomb: F */
  PetscInt   first_row;
  unsigned   fixed = 0; /* the node's Dirichlet components: their terms are left out of its rows (a friction node's t2 = e_c then gives a zero row: FrictionOnRollers()) */
};

/* The displacement the data impose on a row of B with value c: a Dirichlet row's value, the overlap part min(c, 0) of a
   contact gap; 0 on gluing and tangential rows (their values are 0). A model whose rows impose none and whose f is 0
   has no load (WithoutLoad()); the forces of these displacements scale the equilibrium residual (contactresiduals.cxx) */
static inline PetscReal ContactImposedValue_Private(FETIRowKind kind, PetscReal c) { return kind == FETI_ROW_CONTACT_NORMAL ? PetscMin(c, 0) : c; }

struct ContactModelData {
  FEM                          fem = nullptr;
  std::vector<ContactZone>     zones;
  std::vector<ContactNodeInfo> nodes;               /* all contact nodes, the same on every rank */
  std::vector<PetscInt>        rows;                /* multiplier index of each contact row (node k's rows start at nodes[k].first_row) */
  std::vector<PetscInt>        unmatched;           /* per zone between bodies: slave nodes without a master point within the search distance */
  std::vector<PetscInt>        leftout_friction;    /* per zone: friction nodes left out for fixed components their normal does not lie beside */
  std::vector<PetscReal>       leftout_normal;      /* per zone: the largest component of those nodes' normals along a fixed direction */
  std::vector<PetscInt>        leftout_overlapping; /* per zone: nodes left out for their Dirichlet conditions that overlap initially (gap < 0) */
  std::vector<PetscReal>       leftout_overlap;     /* per zone: the largest initial overlap -gap among those */
  std::vector<PetscInt>        slave;               /* per zone between bodies: the slave body (the zone's body or other body); -1 for foundation zones */
  std::vector<PetscReal>       search;              /* per zone between bodies: the search distance used */
  FETI                         feti   = nullptr;
  ContactProblem               cp     = nullptr;
  Vec                          lambda = nullptr, u = nullptr, alpha = nullptr;
  ContactPipeline              pipeline = CONTACT_PIPELINE_LINEAR;
  ContactStatistics            stats    = {}; /* of the last ContactModelSolve(): all its solves, and the verdict */

  /* the residuals of the last ContactModelComputeResiduals(), valid while u and lambda keep these states
     (ContactModelSolve() computes them for its verdict; the summary asks again) */
  ContactResiduals residuals          = {};
  PetscObjectState residuals_state[2] = {-1, -1};

  /* acceptance of a solution by its mechanical residuals (ContactModelSolve()) */
  PetscReal acceptance_factor = 10;          /* every residual <= factor * the solver's relative tolerance */
  PetscBool acceptance_given  = PETSC_FALSE; /* -contact_acceptance_factor was given: no cap (ContactAcceptance_Private()) */
  PetscInt  refine_max        = 3;           /* tighter solves, warm started, when the solver's own test passed but the residuals did not */

  /* contact nodes whose multipliers this rank owns, in the contact problem's order (law by law) */
  std::vector<PetscInt>  local;       /* indices into nodes */
  PetscInt               polygon = 0; /* -contact_friction_polygon: k tangential rows per friction node (0: t1, t2 and a disk) */
  PetscInt               stride  = 3; /* entries of mult per local node: 1 + 2 (disks) or 1 + polygon */
  std::vector<PetscInt>  mult;        /* stride per local node: normal, then the tangential multiplier indices (-1 when frictionless) */
  std::vector<PetscInt>  lbody, lnode;
  std::vector<PetscReal> lcoords, larea;
  PetscBool              setup = PETSC_FALSE, solved = PETSC_FALSE;
  ConeFETIProgress       progress; /* ContactModelSetProgress(); passed on to the FETI problem and the contact problem */
};

struct _ContactModelOps {
  PetscErrorCode (*unused)(void);
};
struct _p_ContactModel {
  PETSCHEADER(struct _ContactModelOps);
  ContactModelData *data;
};

/* a foundation zone's node: its gap and normal from the obstacle (contactobstacle.cxx) */
PETSC_INTERN PetscErrorCode ContactObstacleNodeGeometry_Private(ContactModel, PetscInt, ContactNodeInfo &);

/* t1, t2 with (n, t1, t2) orthonormal, as every contact node gets them (contactmodel.cxx) */
PETSC_INTERN void ContactTangents_Private(const PetscReal[3], PetscReal[3], PetscReal[3]);

/* one contact node for the copies of a node that zones give the same row (contactsharednodes.cxx); merged: the copies dropped */
PETSC_INTERN PetscErrorCode ContactMergeSharedNodes_Private(ContactModel, PetscInt *);

/* "<check> of body b is <value> (<what it means>)" for the check c of r */
PETSC_INTERN PetscErrorCode ContactResidualsDescribe_Private(const ContactResiduals *, ContactCheck, char[], size_t);

/* The closest point of a triangle surface (contactsearch.cxx) */
struct ContactSurfacePoint {
  PetscInt  triangle = -1;                                  /* index of the closest triangle; -1: none within the search distance */
  PetscReal chi[3] = {0, 0, 0}, w[3] = {0, 0, 0}, dist = 0; /* the point, its barycentric weights on the triangle's vertices, its distance */
};

/* closest point chi of x on the triangle (a, b, c), chi = w[0] a + w[1] b + w[2] c: a vertex (one weight exactly 1), an
   edge (one weight exactly 0) or the interior (a degenerate triangle: the nearest point of its edges) */
PETSC_INTERN void ContactTriangleClosestPoint(const PetscReal[3], const PetscReal[3], const PetscReal[3], const PetscReal[3], PetscReal[3], PetscReal[3]);

/* a surface of triangles (vertex ids into coordinates X, both borrowed) in a uniform grid of buckets */
class ContactSurfaceSearch {
public:
  PetscReal longest_edge = 0, mean_edge = 0; /* of the surface's triangles */

  PetscErrorCode SetUp(PetscInt ntri, const PetscInt tri[], const PetscReal X[]);
  /* the closest point of the surface within dmax of x (p.triangle = -1 if none); ties: the smaller triangle index */
  PetscErrorCode Closest(const PetscReal x[3], PetscReal dmax, ContactSurfacePoint &p);
  /* the closest point at any distance, by testing every triangle */
  PetscErrorCode Nearest(const PetscReal x[3], ContactSurfacePoint &p) const;

private:
  PetscInt               ntri = 0;
  const PetscInt        *tri  = nullptr;
  const PetscReal       *X    = nullptr;
  std::vector<PetscReal> box; /* 6 per triangle: lower and upper corner of its bounding box */
  PetscReal              origin[3] = {0, 0, 0}, h = 1;
  PetscInt               n[3] = {1, 1, 1};
  std::vector<PetscInt>  start, cells; /* CSR: the triangles of bucket c are cells[start[c] .. start[c+1]) */
  std::vector<PetscInt>  stamp;        /* the last query that tested each triangle */
  PetscInt               query = 0;

  void Range(const PetscReal lo[3], const PetscReal hi[3], PetscInt r[6]) const;
};
