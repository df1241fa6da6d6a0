/* Layer contact: the frictional contact solve on a dual contact problem.

   A dual contact problem is
     min 1/2 l'Fl - l'h   s.t.  G l = e (optional),  l_n >= 0 (normal multipliers),
                                |(l_t1, l_t2)_k| <= g_k (tangential pairs), the rest free,
   with g_k given (Tresca) or g_k = F_k l_n,k (Coulomb), per contact node k. FETI produces one
   (F = B K+ B', G = R'B', with the projector form), but nothing here needs FETI: any operator F
   (e.g. a Delassus operator) works. The pipeline is chosen from what the problem contains:
   no contact nodes: a linear solve; frictionless nodes only: smalxe + mprgp; Tresca: one smalxe +
   mpgp solve; Coulomb: the friction loop (Algorithm 1, 2 of the seed paper, or monolithic). */
#pragma once

#include <conefeti/sys.h>
#include <conefeti/qp.h>

/*E
  ContactLaw - The law of a group of contact nodes.

$ CONTACT_FRICTIONLESS - normal multiplier only; no tangential multipliers exist for the node
$ CONTACT_TRESCA       - given slip bound g_k (a force, in multiplier units)
$ CONTACT_COULOMB      - friction coefficient F_k: slip bound F_k l_n,k

  References:
+ * - R. Kucera, A new algorithm for solving 3D contact problems with Coulomb friction (the seed paper of conefeti: the dual formulation with Tresca and Coulomb friction)
- * - J. Haslinger, Approximation of the Signorini problem with friction, obeying Coulomb law, Math. Methods Appl. Sci. 5, 422-437 (1983)

  Level: beginner

.seealso: `ContactProblemAddNodes()`
E*/
typedef enum {
  CONTACT_FRICTIONLESS,
  CONTACT_TRESCA,
  CONTACT_COULOMB
} ContactLaw;
PETSC_EXTERN const char *const ContactLaws[];

/*E
  ContactPipeline - What the solve does, chosen from the problem (only the effects it contains).

$ CONTACT_PIPELINE_LINEAR       - no contact node: equality-constrained (or free) quadratic, smalxe with CG inside
$ CONTACT_PIPELINE_FRICTIONLESS - normal multipliers >= 0: smalxe + mprgp
$ CONTACT_PIPELINE_TRESCA       - given slip bounds: one smalxe + mpgp solve
$ CONTACT_PIPELINE_COULOMB      - the friction loop (`ContactCoulombAlgorithm`)

  References:
+ * - Z. Dostal, Optimal Quadratic Programming Algorithms, with Applications to Variational Inequalities, Springer (2009) (smalxe + mprgp)
- * - R. Kucera, A new algorithm for solving 3D contact problems with Coulomb friction (the seed paper of conefeti: Tresca by smalxe + mpgp)

  Level: beginner
E*/
typedef enum {
  CONTACT_PIPELINE_LINEAR,
  CONTACT_PIPELINE_FRICTIONLESS,
  CONTACT_PIPELINE_TRESCA,
  CONTACT_PIPELINE_COULOMB
} ContactPipeline;
PETSC_EXTERN const char *const ContactPipelines[];

/*E
  ContactCoulombAlgorithm - How the Coulomb fixed point g = F l_n is found.

$ CONTACT_COULOMB_MSA        - Algorithm 1: successive approximations outside, a full smalxe Tresca solve inside
$ CONTACT_COULOMB_MERGED     - Algorithm 2 (the seed paper's): one augmented Lagrangian loop; per outer step a block
$                              Gauss-Seidel sweep (normal and gluing multipliers by mprgp, tangential by mpgp on
$                              disks of radius F l_n taken from the new normal multipliers)
$ CONTACT_COULOMB_MONOLITHIC - one loop, one mpgp over all multipliers, radii F l_n updated before every inner solve

  References:
+ * - R. Kucera, A new algorithm for solving 3D contact problems with Coulomb friction (the seed paper of conefeti: Algorithms 1 and 2)
- * - J. Haslinger, R. Kucera, Z. Dostal, An algorithm for the numerical realization of 3D contact problems with Coulomb friction, J. Comput. Appl. Math. 164-165, 387-408 (2004) (the method of
successive approximations)

  Level: beginner
E*/
typedef enum {
  CONTACT_COULOMB_MSA,
  CONTACT_COULOMB_MERGED,
  CONTACT_COULOMB_MONOLITHIC
} ContactCoulombAlgorithm;
PETSC_EXTERN const char *const ContactCoulombAlgorithms[];

/*S
  ContactStatistics - What a contact solve cost and how it ended.

  Fields:
+ pipeline         - the pipeline that ran
. algorithm        - the Coulomb algorithm (meaningful for the Coulomb pipeline)
. converged        - whether the solve met its tolerances
. reason           - a sentence saying how the solve ended
. outer_iterations - Iter of the seed paper: augmented Lagrangian outer iterations (merged, monolithic) or
                     successive approximations (MSA)
. al_iterations    - all augmented Lagrangian outer iterations (differs from outer_iterations for MSA only)
. products_qpp     - n_A^QPP: Hessian products in the bound-constrained (mprgp) inner solves
. products_qpq     - n_A^QPQ: Hessian products in the disk-constrained (mpgp) inner solves
. products_other   - products outside the inner solvers (block linear terms, gradients after a sweep, setup; after a solve that did not
                     converge, the two of the test of F's symmetry, `ContactProblemSolve()`)
. products_estimate- products spent estimating ||F|| (reported apart)
. fixed_point      - relative Coulomb fixed-point residual |g - F l_n| / |F l_n| at the end (0 if not Coulomb)
. feasibility      - |G l - e| at the end
. acceptance       - the largest residual a converged solution may have (`ContactModelSolve()`: the acceptance factor times
                     the solver's relative tolerance; 0 when the solve was not judged by its residuals)
. refinements      - tighter solves run after the first because the solver's own test passed but the residuals did not
- failed_check     - why a solve did not converge: a `ContactChecks` name, "solver" (the solver's own test failed), "dual_kkt" or
                     "dual_equality" (-contact_kkt_check: the KKT residual recomputed from the multipliers), or "" when it converged

  Level: beginner

.seealso: `ContactProblemGetStatistics()`
S*/
typedef struct {
  ContactPipeline         pipeline;
  ContactCoulombAlgorithm algorithm;
  PetscBool               converged;
  char                    reason[512];
  PetscInt                outer_iterations;
  PetscInt                al_iterations;
  PetscInt                products_qpp;
  PetscInt                products_qpq;
  PetscInt                products_other;
  PetscInt                products_estimate;
  PetscReal               fixed_point;
  PetscReal               feasibility;
  PetscReal               acceptance;
  PetscInt                refinements;
  char                    failed_check[32];
} ContactStatistics;

/*S
  ContactProblem - A dual contact problem and its solver.

  Level: beginner

.seealso: `ContactProblemCreate()`, `ContactProblemAddNodes()`, `ContactProblemSolve()`
S*/
typedef struct _p_ContactProblem *ContactProblem;
PETSC_EXTERN PetscClassId         CONTACTPROBLEM_CLASSID;

PETSC_EXTERN PetscErrorCode ContactProblemCreate(MPI_Comm, ContactProblem *);
PETSC_EXTERN PetscErrorCode ContactProblemDestroy(ContactProblem *);
PETSC_EXTERN PetscErrorCode ContactProblemSetOperator(ContactProblem, Mat, Vec);
PETSC_EXTERN PetscErrorCode ContactProblemSetEquality(ContactProblem, Mat, Vec);
PETSC_EXTERN PetscErrorCode ContactProblemSetProjector(ContactProblem, Mat, Vec);
PETSC_EXTERN PetscErrorCode ContactProblemAddNodes(ContactProblem, ContactLaw, PetscInt, const PetscInt[], const PetscInt[], const PetscInt[], const PetscReal[]);
PETSC_EXTERN PetscErrorCode ContactProblemAddPolygonNodes(ContactProblem, ContactLaw, PetscInt, PetscInt, const PetscInt[], const PetscInt[], const PetscReal[]);
PETSC_EXTERN PetscErrorCode ContactProblemGetFrictionPolygon(ContactProblem, PetscInt *, const PetscInt **);
PETSC_EXTERN PetscErrorCode ContactProblemSetOptionsPrefix(ContactProblem, const char[]);
PETSC_EXTERN PetscErrorCode ContactProblemSetFromOptions(ContactProblem);
PETSC_EXTERN PetscErrorCode ContactProblemSetUp(ContactProblem);
PETSC_EXTERN PetscErrorCode ContactProblemSolve(ContactProblem, Vec);
PETSC_EXTERN PetscErrorCode ContactProblemView(ContactProblem, PetscViewer);
PETSC_EXTERN PetscErrorCode ContactProblemGetPipeline(ContactProblem, ContactPipeline *);
PETSC_EXTERN PetscErrorCode ContactProblemGetCoulombAlgorithm(ContactProblem, ContactCoulombAlgorithm *);
PETSC_EXTERN PetscErrorCode ContactProblemGetStatistics(ContactProblem, ContactStatistics *);
PETSC_EXTERN PetscErrorCode ContactProblemGetEqualityMultiplier(ContactProblem, Vec);
PETSC_EXTERN PetscErrorCode ContactProblemGetNodes(ContactProblem, PetscInt *, const PetscInt **, const PetscInt **, const PetscInt **, const ContactLaw **, const PetscReal **);
PETSC_EXTERN PetscErrorCode ContactProblemGetSlipBounds(ContactProblem, Vec, PetscReal[]);
PETSC_EXTERN PetscErrorCode ContactProblemGetTao(ContactProblem, Tao *);
PETSC_EXTERN PetscErrorCode ContactProblemGetPC(ContactProblem, PC *);
PETSC_EXTERN PetscErrorCode ContactProblemSetProgress(ContactProblem, ConeFETIProgressFn, void *);
PETSC_EXTERN PetscErrorCode ContactProblemComputeKKTResidual(ContactProblem, Vec, PetscReal *, PetscReal *);

/* ---------------------------------------------------------------------------------------------
   Contact on a finite element model: zones, the FETI dual problem, primal recovery, residuals
   --------------------------------------------------------------------------------------------- */

#include <conefeti/fem.h>
#include <conefeti/feti.h>

/* The FETI interchange file with the contact pairing of a ContactProblem (docs/feti-interchange.md) */
PETSC_EXTERN PetscErrorCode FETIWriteContact(FETI, ContactProblem, PetscViewer);
PETSC_EXTERN PetscErrorCode FETILoadContact(FETI, ContactProblem, PetscViewer);

/*E
  ContactZoneType - Where a contact zone's nodes may touch.

$ CONTACT_ZONE_FOUNDATION - a rigid obstacle: a plane, a sphere or a cylinder (`ContactObstacleShape`)
$ CONTACT_ZONE_BODIES     - another body, node to surface: each node of the slave face is paired with the closest point of
                            the master face (any meshes; on conforming meshes this is node to node)

  Level: beginner
E*/
typedef enum {
  CONTACT_ZONE_FOUNDATION,
  CONTACT_ZONE_BODIES
} ContactZoneType;
PETSC_EXTERN const char *const ContactZoneTypes[];

/*E
  ContactZoneSlave - Which face of a zone between bodies is the slave (its nodes carry the contact rows; the other face,
  the master, is the surface their closest points lie on).

$ CONTACT_SLAVE_FINER - the face with the smaller mean triangle edge length (on a tie, within a relative 1e-6: the zone's body);
                        the default of a zero-initialized zone
$ CONTACT_SLAVE_BODY  - the face of the zone's body
$ CONTACT_SLAVE_OTHER - the face of the zone's other body

  Notes:
  The finer face as slave keeps the coarser surface from passing between the slave nodes (docs/contact.md, "Contact
  between bodies").

  Level: beginner

.seealso: `ContactZone`
E*/
typedef enum {
  CONTACT_SLAVE_FINER,
  CONTACT_SLAVE_BODY,
  CONTACT_SLAVE_OTHER
} ContactZoneSlave;
PETSC_EXTERN const char *const ContactZoneSlaves[];

/*E
  ContactObstacleShape - The shape of a foundation zone's rigid obstacle; the body lies outside it.

$ CONTACT_OBSTACLE_PLANE    - the half-space below a plane (`ContactZone` point, normal); the default of a zero-initialized zone
$ CONTACT_OBSTACLE_SPHERE   - a ball (center, radius)
$ CONTACT_OBSTACLE_CYLINDER - an infinite circular cylinder (center: a point of its axis, axis, radius)

  Notes:
  The gap and the contact normal of a node x come from the closest point chi(x) of the obstacle's surface
  (`ContactZoneComputeGap()`): n = (chi(x) - x)/|chi(x) - x| points into the obstacle and the gap is
  (chi(x) - x).n, the distance to the surface, negative when x lies inside the obstacle (an initial overlap,
  e.g. an indentation depth); n is then still minus the obstacle's outward normal at chi(x).

  Level: beginner

.seealso: `ContactZone`, `ContactZoneComputeGap()`
E*/
typedef enum {
  CONTACT_OBSTACLE_PLANE,
  CONTACT_OBSTACLE_SPHERE,
  CONTACT_OBSTACLE_CYLINDER
} ContactObstacleShape;
PETSC_EXTERN const char *const ContactObstacleShapes[];

/*S
  ContactZone - A contact zone: the tagged face of a body that may touch a rigid obstacle or another
  body's tagged face, and the law on it.

  Fields:
+ type       - foundation or bodies
. body, face - the body and the tag of the face that may touch (a node with a Dirichlet component is left out,
               except a frictionless node whose contact normal has a nonzero component that is not fixed: its row
               then acts on the free components only, e.g. on a symmetry plane)
. other_body, other_face - bodies: the other body and its face (any mesh: node to surface, see `ContactZoneSlave`)
. point, normal - foundation, plane: a point of the plane and its normal pointing toward the body;
                  the gap of a node x is (x - point).normal/|normal|
. law        - frictionless, Tresca or Coulomb
. coef       - Tresca: slip bound as a stress (force per area, turned into nodal forces with the nodal
               areas); Coulomb: the friction coefficient F
. shape      - foundation: the obstacle's shape (plane when zero-initialized)
. center     - sphere: its center; cylinder: a point of its axis
. axis       - cylinder: the axis direction (any length but zero)
. radius     - sphere, cylinder: the radius (> 0)
. slave      - bodies: which face is the slave (`ContactZoneSlave`; finer when zero-initialized)
- search_distance - bodies: a slave node is a contact node when the master face has a point within this distance
                    (0, the default: the master face's longest triangle edge); larger than any initial gap meant to close

  Notes:
  Between bodies, each slave node x is paired with the closest point chi(x) of the master face: the contact normal is
  n = (chi(x) - x)/|chi(x) - x|, turned to the slave's outward side (against it when x has passed into the master), or
  the slave's outward normal where chi(x) and x (nearly) coincide; the gap is (chi(x) - x).n. The rows act on
  u_slave(x) - u_master(chi(x)), interpolated with the barycentric weights of chi(x) on its master triangle.
  `ContactModelGetUnmatchedNodes()` counts the slave nodes without a master point within the search distance.

  Level: beginner

.seealso: `ContactModelAddZone()`, `ContactObstacleShape`, `ContactZoneComputeGap()`
S*/
typedef struct {
  ContactZoneType      type;
  PetscInt             body;
  char                 face[64];
  PetscInt             other_body;
  char                 other_face[64];
  PetscReal            point[3], normal[3];
  ContactLaw           law;
  PetscReal            coef;
  ContactObstacleShape shape;
  PetscReal            center[3], axis[3], radius;
  ContactZoneSlave     slave;
  PetscReal            search_distance;
} ContactZone;

PETSC_EXTERN PetscErrorCode ContactZoneCheckObstacle(const ContactZone *);
PETSC_EXTERN PetscErrorCode ContactZoneComputeGap(const ContactZone *, const PetscReal[], PetscReal[], PetscReal *, PetscReal[]);

/*E
  ContactNodeStatus - State of a contact node in a solution.

$ CONTACT_NODE_SEPARATED - no pressure (the gap may be open)
$ CONTACT_NODE_STICK     - in contact, no tangential motion
$ CONTACT_NODE_SLIP      - in contact, tangential motion with the tangential force on its bound

  Level: beginner
E*/
typedef enum {
  CONTACT_NODE_SEPARATED,
  CONTACT_NODE_STICK,
  CONTACT_NODE_SLIP
} ContactNodeStatus;
PETSC_EXTERN const char *const ContactNodeStatuses[];

/*E
  ContactCheck - One of the mechanical checks of a solution (`ContactResiduals`).

$ CONTACT_CHECK_EQUILIBRIUM     - K u = f - B'l (per body)
$ CONTACT_CHECK_GLUING          - B u = c on gluing and Dirichlet rows: subdomain copies agree, supports hold (per body)
$ CONTACT_CHECK_PENETRATION     - N u <= d: no node passes the obstacle (per zone)
$ CONTACT_CHECK_NORMAL_SIGN     - l_n >= 0: contact pushes, never pulls (per zone)
$ CONTACT_CHECK_COMPLEMENTARITY - l_n (d - N u) = 0: no contact force across an open gap (per zone)
$ CONTACT_CHECK_FRICTION_CONE   - |l_t| <= g: friction within its bound (per zone)
$ CONTACT_CHECK_SLIP_RULE       - stick nodes do not move, slipping nodes move against their friction force (per zone)

  Level: beginner

.seealso: `ContactResiduals`, `ContactModelComputeResiduals()`
E*/
typedef enum {
  CONTACT_CHECK_EQUILIBRIUM,
  CONTACT_CHECK_GLUING,
  CONTACT_CHECK_PENETRATION,
  CONTACT_CHECK_NORMAL_SIGN,
  CONTACT_CHECK_COMPLEMENTARITY,
  CONTACT_CHECK_FRICTION_CONE,
  CONTACT_CHECK_SLIP_RULE,
  CONTACT_NUM_CHECKS
} ContactCheck;
PETSC_EXTERN const char *const ContactChecks[];

/*S
  ContactResiduals - The mechanical quality of a solution, computed from u and lambda, each relative
  (dimensionless) to a scale of the body or zone where it is measured:

  Fields:
+ equilibrium     - max over bodies b of |(K u - f + B'l)_b| / max(|f_b|, |(B'l)_b|, |(K u)_b|)
. gluing          - max over bodies of max |(B u - c)_i| over the body's gluing and Dirichlet rows / max |u_b|
. penetration     - max over zones of max (N u - d)_+ / U_z (U_z: the largest displacement of the zone's bodies)
. normal_sign     - max over zones of max (-l_n)_+ / L_z (L_z: the zone's largest contact multiplier)
. complementarity - max over zones of max |l_n (d - N u)| / (L_z U_z)
. friction_cone   - max over zones of max (|l_t| - g)_+ / L_z (g: Tresca bound or F l_n)
. slip_rule       - max over zones of max |l_t - P_g(l_t + k T u)| / L_z with k = L_z / U_z: zero exactly when stick nodes do not
                    move and slipping nodes move along l_t with |l_t| = g (the friction force -T'l_t opposes the slip)
. max             - the largest of the above
. approximation   - with a friction polygon (-contact_friction_polygon): the friction cone and slip rule of the disk law
                    (|l_t| <= g), which the polygon only approximates, judged like friction_cone and slip_rule (those then
                    judge the polygon law the solver solved); not in max: the error of the model, not of the solve. 0 with disks
. worst           - the check of max
. where           - per check, the body (equilibrium, gluing) or zone (the others) where it is largest (-1: not measured)
- counts[3]       - number of separated, stick and slip nodes

  Notes:
  A scale below 1e-6 times the largest scale of its kind in the scene is raised to that (double precision cannot
  resolve smaller forces in one solve of the scene); without any load all scales vanish, and the exact solution
  u = 0, l = 0 has residuals 0.

  Level: beginner

.seealso: `ContactModelComputeResiduals()`, `ContactCheck`
S*/
typedef struct {
  PetscReal    equilibrium, gluing, penetration, normal_sign, complementarity, friction_cone, slip_rule, max;
  ContactCheck worst;
  PetscInt     where[CONTACT_NUM_CHECKS];
  PetscInt     counts[3];
  PetscReal    approximation;
} ContactResiduals;

/*S
  ContactModel - A finite element model with contact zones, solved by FETI and the contact solver.

  Level: beginner

.seealso: `ContactModelCreate()`, `ContactModelAddZone()`, `ContactModelSolve()`
S*/
typedef struct _p_ContactModel *ContactModel;
PETSC_EXTERN PetscClassId       CONTACTMODEL_CLASSID;

PETSC_EXTERN PetscErrorCode ContactModelCreate(FEM, ContactModel *);
PETSC_EXTERN PetscErrorCode ContactModelDestroy(ContactModel *);
PETSC_EXTERN PetscErrorCode ContactModelAddZone(ContactModel, const ContactZone *);
PETSC_EXTERN PetscErrorCode ContactModelSetFromOptions(ContactModel);
PETSC_EXTERN PetscErrorCode ContactModelSetUp(ContactModel);
PETSC_EXTERN PetscErrorCode ContactModelSolve(ContactModel);
PETSC_EXTERN PetscErrorCode ContactModelView(ContactModel, PetscViewer);
PETSC_EXTERN PetscErrorCode ContactModelGetFETI(ContactModel, FETI *);
PETSC_EXTERN PetscErrorCode ContactModelGetContactProblem(ContactModel, ContactProblem *);
PETSC_EXTERN PetscErrorCode ContactModelGetPipeline(ContactModel, ContactPipeline *);
PETSC_EXTERN PetscErrorCode ContactModelGetSolution(ContactModel, Vec *, Vec *);
PETSC_EXTERN PetscErrorCode ContactModelGetStatistics(ContactModel, ContactStatistics *);
PETSC_EXTERN PetscErrorCode ContactModelSetProgress(ContactModel, ConeFETIProgressFn, void *);
PETSC_EXTERN PetscErrorCode ContactModelComputeResiduals(ContactModel, ContactResiduals *);
PETSC_EXTERN PetscErrorCode ContactModelGetNodes(ContactModel, PetscInt *, const PetscInt **, const PetscInt **, const PetscReal **, const PetscReal **);
PETSC_EXTERN PetscErrorCode ContactModelGetUnmatchedNodes(ContactModel, PetscInt *);
PETSC_EXTERN PetscErrorCode ContactModelGetLeftOutNodes(ContactModel, PetscInt *, PetscInt *, PetscReal *);
PETSC_EXTERN PetscErrorCode ContactModelGetZoneInside(ContactModel, PetscInt *, PetscReal *);
PETSC_EXTERN PetscErrorCode ContactModelGetNodeStates(ContactModel, PetscReal[], PetscReal[], PetscReal[], ContactNodeStatus[]);
PETSC_EXTERN PetscErrorCode ContactModelGetNodeGeometry(ContactModel, PetscReal[], PetscReal[]);
PETSC_EXTERN PetscErrorCode ContactModelGetNodePartners(ContactModel, PetscInt[], PetscInt[], PetscReal[], PetscReal[]);
PETSC_EXTERN PetscErrorCode ContactModelGetContactForce(ContactModel, PetscInt, PetscReal[], PetscReal *);
