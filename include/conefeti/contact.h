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

#include <conefeti/qp.h>

/*E
  ContactLaw - The law of a group of contact nodes.

$ CONTACT_FRICTIONLESS - normal multiplier only; no tangential multipliers exist for the node
$ CONTACT_TRESCA       - given slip bound g_k (a force, in multiplier units)
$ CONTACT_COULOMB      - friction coefficient F_k: slip bound F_k l_n,k

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
. products_other   - products outside the inner solvers (block linear terms, gradients after a sweep, setup)
. products_estimate- products spent estimating ||F|| (reported apart)
. fixed_point      - relative Coulomb fixed-point residual |g - F l_n| / |F l_n| at the end (0 if not Coulomb)
- feasibility      - |G l - e| at the end

  Level: beginner

.seealso: `ContactProblemGetStatistics()`
S*/
typedef struct {
  ContactPipeline         pipeline;
  ContactCoulombAlgorithm algorithm;
  PetscBool               converged;
  char                    reason[256];
  PetscInt                outer_iterations;
  PetscInt                al_iterations;
  PetscInt                products_qpp;
  PetscInt                products_qpq;
  PetscInt                products_other;
  PetscInt                products_estimate;
  PetscReal               fixed_point;
  PetscReal               feasibility;
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
PETSC_EXTERN PetscErrorCode ContactProblemSetOptionsPrefix(ContactProblem, const char[]);
PETSC_EXTERN PetscErrorCode ContactProblemSetFromOptions(ContactProblem);
PETSC_EXTERN PetscErrorCode ContactProblemSetUp(ContactProblem);
PETSC_EXTERN PetscErrorCode ContactProblemSolve(ContactProblem, Vec);
PETSC_EXTERN PetscErrorCode ContactProblemView(ContactProblem, PetscViewer);
PETSC_EXTERN PetscErrorCode ContactProblemGetPipeline(ContactProblem, ContactPipeline *);
PETSC_EXTERN PetscErrorCode ContactProblemGetStatistics(ContactProblem, ContactStatistics *);
PETSC_EXTERN PetscErrorCode ContactProblemGetEqualityMultiplier(ContactProblem, Vec);
PETSC_EXTERN PetscErrorCode ContactProblemGetNodes(ContactProblem, PetscInt *, const PetscInt **, const PetscInt **, const PetscInt **, const ContactLaw **, const PetscReal **);
PETSC_EXTERN PetscErrorCode ContactProblemGetSlipBounds(ContactProblem, Vec, PetscReal[]);
PETSC_EXTERN PetscErrorCode ContactProblemGetTao(ContactProblem, Tao *);
