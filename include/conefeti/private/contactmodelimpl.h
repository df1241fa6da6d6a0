/* ContactModel internals shared by the files of the contact layer that build, solve and judge a model. */
#pragma once

#include <conefeti/private/contactimpl.h>
#include <vector>

/* one contact node: where it is, its rows' directions and gap, its law */
struct ContactNodeInfo {
  PetscInt   zone, body, node, other_body = -1, other_node = -1;
  PetscReal  x[3], area, n[3], t1[3], t2[3], gap;
  ContactLaw law;
  PetscReal  coef; /* Tresca: bound as a nodal force; Coulomb: F */
  PetscInt   first_row;
  unsigned   fixed = 0; /* the first body's Dirichlet components at the node (frictionless nodes only): left out of its row */
};

struct ContactModelData {
  FEM                          fem = nullptr;
  std::vector<ContactZone>     zones;
  std::vector<ContactNodeInfo> nodes;     /* all contact nodes, the same on every rank */
  std::vector<PetscInt>        rows;      /* multiplier index of each contact row (node k's rows start at nodes[k].first_row) */
  std::vector<PetscInt>        unmatched; /* per zone: nodes of a node-to-node zone's first face without a partner */
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
  PetscReal acceptance_factor = 10; /* every residual <= factor * the solver's relative tolerance */
  PetscInt  refine_max        = 3;  /* tighter solves, warm started, when the solver's own test passed but the residuals did not */

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

/* "<check> of body b is <value> (<what it means>)" for the check c of r */
PETSC_INTERN PetscErrorCode ContactResidualsDescribe_Private(const ContactResiduals *, ContactCheck, char[], size_t);
