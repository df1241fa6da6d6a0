/* Layer io: scenes from the options database, the summary of a solve (human table and one JSON
   line), and HDF5 + XDMF output that ParaView opens.

   A scene is a set of -scene_* options (usually a commented options file in petsc-options/, see
   docs/scenes.md): boxes with material, mesh and decomposition, supports, tractions, volume
   forces, and contact zones with their laws. ContactSceneSetUp() turns it into a set-up FEM and a set-up
   ContactModel; ContactSceneSolve() runs the pipeline the scene calls for; ContactSceneGetSummary() collects the
   counts of the seed paper's tables and the mechanical residuals; ContactSceneWriteOutput() writes
   <basename>.h5 and <basename>.xmf (docs/output.md). */
#pragma once

#include <conefeti/contact.h>

/*S
  ContactScene - A contact (or linear elasticity) problem read from options: a FEM model, its contact
  zones, and the ContactModel that solves it.

  Level: beginner

.seealso: `ContactSceneCreateFromOptions()`, `ContactSceneSetUp()`, `ContactSceneSolve()`, `ContactSceneGetSummary()`, `ContactSceneWriteOutput()`
S*/
typedef struct _p_ContactScene *ContactScene;

PETSC_EXTERN PetscClassId  CONTACTSCENE_CLASSID;
PETSC_EXTERN PetscLogEvent CONTACTSCENE_SetUp, CONTACTSCENE_Solve, CONTACTSCENE_Summary, CONTACTSCENE_Output;

/*S
  ContactSceneSupportForce - The reaction of one Dirichlet condition of a scene (a clamped or a displaced face): the force
  the support exerts on the body (`FEMComputeReactions()`).

  Fields:
+ body   - the body
. option - the option stem that set it: fix, fix_x, fix_y, fix_z, or displace<k>
. face   - the face selector as given (one longer than 63 characters: its start, `#` and a hash of the whole, as a contact zone names it)
- force  - the resultant force (fx, fy, fz)

  Level: intermediate

.seealso: `ContactSceneSummary`, `FEMComputeReactions()`
S*/
#define CONTACTSCENE_MAX_SUPPORTS 32
typedef struct {
  PetscInt  body;
  char      option[16];
  char      face[64];
  PetscReal force[3];
} ContactSceneSupportForce;

/*S
  ContactSceneSummary - What a solve of a scene cost and how good it is: the counts of the seed paper's
  tables, times, the mechanical residuals and the contact node states.

  Fields:
+ scene         - the scene name (-scene_name)
. ranks         - MPI processes
. pipeline      - linear, frictionless, tresca or coulomb
. algorithm     - the Coulomb algorithm (meaningful for the Coulomb pipeline)
. description   - one line: the pipeline and the solvers it runs
. n             - primal unknowns of the undecomposed mesh without Dirichlet dofs (the seed paper's n)
. n_primal      - FETI primal dimension (subdomain dofs, interface nodes counted in every subdomain)
. m             - multipliers (rows of B); m = m_gluing + m_dirichlet + m_normal + m_tangential
. m_gluing, m_dirichlet, m_normal, m_tangential - the rows by kind
. subdomains    - number of subdomains
. rigid_modes   - coarse dimension (rows of G)
. contact_nodes - contact nodes (separated + stick + slip)
. iter          - Iter of the seed paper (outer iterations, or successive approximations for MSA; CG iterations for the linear pipeline)
. al_iter       - all augmented Lagrangian outer iterations
. n_A           - n_A^QPP + n_A^QPQ + n_A^other: Hessian (F) products of the solve
. n_A_qpp, n_A_qpq, n_A_other - products in the bound-constrained (mprgp) solves, the disk-constrained (mpgp) solves, and elsewhere
. n_A_estimate  - products spent estimating ||F|| (not in n_A)
. coarse_solves - solves with G G' since the FETI setup (`FETIGetCoarseSolveCount()`: every product with P or Q takes one)
. norm_F        - the ||F|| estimate the solver used (0 for the linear pipeline)
. time_setup    - seconds: mesh, FETI operators and factorizations, contact problem
. time_solve    - seconds: the solve with primal recovery
. time_phases   - seconds per `ConeFETIPhase` (rank 0's): the setup broken down (mesh, contact rows, kernels, memory, coarse,
                  factorization, explicit_kplus, operators, contact_problem; they sum to at most time_setup) and the solve;
                  0 for a phase that did not run
. fixed_point   - Coulomb: relative fixed-point residual |g - F l_n| / |F l_n| at the end
. feasibility   - |G l - e| at the end
. rtol          - the contact solver's relative tolerance (-contact_rtol; 0 for the linear pipeline)
. friction_polygon - tangential multipliers per friction node when the disks are replaced by polygons (-contact_friction_polygon; 0: disks)
. acceptance    - the largest mechanical residual a converged solve may have (`ContactModelSolve()`)
. refinements   - tighter solves after the first, run because the solver's test passed before the residuals did
. failed_check  - why the solve did not converge: a `ContactChecks` name, "solver", or "" when it converged
. kplus_explicit - whether F products used explicit dense blocks of K+ (in at least one subdomain)
. kplus_fallback - whether those blocks were asked for but dropped because they would not fit in memory (`FETIGetKplusExplicit()`)
. kplus_type    - how they were asked for (`FETIGetKplusType()`: the contact layer's default is auto, per subdomain by memory)
. kplus_blocks  - the subdomains whose F products used a dense block (`FETIGetKplusType()`)
. kplus_precision - the storage of the block Cholesky factors asked for (`FETIGetKplusPrecision()`)
. kplus_single  - the subdomains whose factor is stored in float
. kplus_factor_bytes, kplus_factor_double_bytes - the block Cholesky factors as kept, and the same in double (all ranks)
. unmatched_nodes - slave nodes of zones between bodies without a master point within the search distance (`ContactModelGetUnmatchedNodes()`)
. left_out_friction, left_out_overlapping, left_out_overlap - nodes of the contact faces that their Dirichlet conditions keep out of contact (`ContactModelGetLeftOutNodes()`)
. max_nu        - the largest Poisson's ratio of the scene's bodies (above 0.45 the table notes that linear tetrahedra lock)
. linear_option - with contact: the first option of the linear FETI solve given (-feti_ksp_*, -feti_pc_*), which such a scene does not run ("" when none)
. zone_inside, zone_inside_overlap - the first foundation zone whose every contact node starts inside its obstacle (-1: none), and the smallest overlap there (`ContactModelGetZoneInside()`)
. contact_force - the resultant of the contact forces on the zones' first bodies (`ContactModelGetContactForce()`, all zones)
. bodies_zones  - the contact zones between bodies (their forces on the zones' other bodies are the opposite of those in contact_force)
. normal_force  - the sum of the normal contact forces l_n over all contact nodes
. nsupports     - the Dirichlet conditions (clamped and displaced faces) of all bodies; the first CONTACTSCENE_MAX_SUPPORTS are in supports
. supports      - their reactions, body by body in the order of the options (_fix, _fix_x, _fix_y, _fix_z, then _displace0, _displace1, ...)
. reaction      - the sum of all reactions (over every condition, also those beyond supports)
. applied_load  - the resultant of all applied loads (tractions and volume forces, `FEMComputeLoadResultant()`, summed over the bodies)
. residuals     - the mechanical residuals (each relative) and the node counts
. fingerprint   - `ConeFETIVecFingerprint()` of the multipliers: the same on any number of ranks (on one machine)
. finite        - whether every residual is a finite number
. converged     - whether the solve met its tolerances (and the residuals are finite)
- reason        - a sentence saying how the solve ended

  Level: beginner

.seealso: `ContactSceneGetSummary()`, `ContactSceneSummaryView()`, `ContactSceneSummaryViewJSON()`
S*/
typedef struct {
  char                     scene[256];
  PetscMPIInt              ranks;
  ContactPipeline          pipeline;
  ContactCoulombAlgorithm  algorithm;
  char                     description[256];
  PetscInt                 n, n_primal, m, m_gluing, m_dirichlet, m_normal, m_tangential, subdomains, rigid_modes, contact_nodes;
  PetscInt                 iter, al_iter, n_A, n_A_qpp, n_A_qpq, n_A_other, n_A_estimate, coarse_solves;
  PetscReal                norm_F, time_setup, time_solve, fixed_point, feasibility, rtol, acceptance;
  PetscReal                time_phases[CONEFETI_PHASE_COUNT];
  PetscInt                 refinements;
  char                     failed_check[32];
  PetscBool                kplus_explicit, kplus_fallback;
  FETIKplusType            kplus_type;
  PetscInt                 kplus_blocks;
  FETIKplusPrecision       kplus_precision;
  PetscInt                 kplus_single;
  PetscReal                kplus_factor_bytes, kplus_factor_double_bytes;
  PetscInt                 unmatched_nodes;
  PetscInt                 left_out_friction, left_out_overlapping;
  PetscReal                left_out_overlap;
  PetscReal                max_nu;
  PetscReal                contact_force[3], normal_force;
  PetscInt                 bodies_zones;
  PetscInt                 nsupports;
  ContactSceneSupportForce supports[CONTACTSCENE_MAX_SUPPORTS];
  PetscReal                reaction[3], applied_load[3];
  PetscInt                 friction_polygon;
  ContactResiduals         residuals;
  char                     fingerprint[17];
  PetscBool                finite, converged;
  char                     reason[512];
  char                     linear_option[64];
  PetscInt                 zone_inside;
  PetscReal                zone_inside_overlap;
} ContactSceneSummary;

PETSC_EXTERN PetscErrorCode ContactSceneCreate(MPI_Comm, ContactScene *);
PETSC_EXTERN PetscErrorCode ContactSceneCreateFromOptions(MPI_Comm, const char[], ContactScene *);
PETSC_EXTERN PetscErrorCode ContactSceneDestroy(ContactScene *);
PETSC_EXTERN PetscErrorCode ContactSceneSetOptionsPrefix(ContactScene, const char[]);
PETSC_EXTERN PetscErrorCode ContactSceneSetFromOptions(ContactScene);
PETSC_EXTERN PetscErrorCode ContactSceneSetUp(ContactScene);
PETSC_EXTERN PetscErrorCode ContactSceneSetUpFEM(ContactScene);
PETSC_EXTERN PetscErrorCode ContactSceneSolve(ContactScene);
PETSC_EXTERN PetscErrorCode ContactSceneView(ContactScene, PetscViewer);
PETSC_EXTERN PetscErrorCode ContactSceneGetName(ContactScene, const char **);
PETSC_EXTERN PetscErrorCode ContactSceneGetFEM(ContactScene, FEM *);
PETSC_EXTERN PetscErrorCode ContactSceneGetContactModel(ContactScene, ContactModel *);
PETSC_EXTERN PetscErrorCode ContactSceneGetBodyMaterial(ContactScene, PetscInt, PetscReal *, PetscReal *);
PETSC_EXTERN PetscErrorCode ContactSceneGetPipelineDescription(ContactScene, ContactPipeline *, ContactCoulombAlgorithm *, char[], size_t);
PETSC_EXTERN PetscErrorCode ContactSceneGetSummary(ContactScene, ContactSceneSummary *);
PETSC_EXTERN PetscErrorCode ContactSceneSetProgress(ContactScene, ConeFETIProgressFn, void *);
PETSC_EXTERN PetscErrorCode ContactSceneSummaryView(const ContactSceneSummary *, PetscViewer);
PETSC_EXTERN PetscErrorCode ContactSceneSummaryViewJSON(const ContactSceneSummary *, PetscViewer);
PETSC_EXTERN PetscErrorCode ContactSceneSummaryToJSON(const ContactSceneSummary *, char[], size_t);
PETSC_EXTERN PetscErrorCode ContactSceneWriteOutput(ContactScene, const char[]);
