/* ContactProblem internals shared by the files of the contact layer. */
#pragma once

#include <conefeti/contact.h>
#include <conefeti/compat.h>
#include <conefeti/private/progress.h>
#include <petsc/private/petscimpl.h>
#include <string>
#include <vector>

struct _ContactProblemOps {
  PetscErrorCode (*unused)(void);
};

/* the contact solve's default relative tolerance (-contact_rtol) */
#define CONTACT_DEFAULT_RTOL 1e-6
/* The tighter solves after a solve whose own test passed but whose answer did not (ContactModelSolve(): the mechanical
   residuals; ContactProblemSolve() alone: the KKT residual). The next relative tolerance scales the last one by the
   excess of the worst residual over the acceptance, by a factor between 1e-4 and 0.1, and not below
   CONTACT_REFINE_TIGHTEST, but for one last solve, at most to CONTACT_REFINE_LAST, after a solve at the floor missed:
   the solver's tolerance is relative to |P(h - F l~)|, which holds every gap, and a gap far larger than what the
   forces need (a node 1e9 from contact) leaves the floor above it */
#define CONTACT_REFINE_TIGHTEST 1e-13
#define CONTACT_REFINE_LAST     1e-15
static inline PetscReal ContactTighterTolerance_Private(PetscReal tol, PetscReal acceptance, PetscReal worst)
{
  return PetscMax(tol * PetscMin(PetscMax(0.3 * acceptance / PetscMax(worst, acceptance), 1e-4), 0.1), tol > CONTACT_REFINE_TIGHTEST ? CONTACT_REFINE_TIGHTEST : CONTACT_REFINE_LAST);
}

/* the counts of one more solve added to those of the solves before it (the tighter solves of a ContactModel and of a
   ContactProblem alone) */
static inline void ContactStatisticsAccumulate_Private(ContactStatistics &total, const ContactStatistics &one)
{
  total.outer_iterations += one.outer_iterations;
  total.al_iterations += one.al_iterations;
  total.products_qpp += one.products_qpp;
  total.products_qpq += one.products_qpq;
  total.products_other += one.products_other;
  total.products_estimate += one.products_estimate;
}

/* The acceptance of a solve at the tolerance rtol: -contact_acceptance_factor times rtol, but by default not above
   0.1 or rtol, if that is larger: with -contact_rtol 0.09 the factor 10 accepted the indentation scene 62% off as
   converged. A factor the user gave is taken as given. */
#define CONTACT_ACCEPTANCE_LOOSEST 0.1
static inline PetscReal ContactAcceptance_Private(PetscReal factor, PetscBool given, PetscReal rtol)
{
  return given ? factor * rtol : PetscMin(factor * rtol, PetscMax(rtol, (PetscReal)CONTACT_ACCEPTANCE_LOOSEST));
}

/* a fixed-point tolerance the user gave (> 0), scaled with the tighter solve's relative tolerance rtol against the
   first one rtol0, at most 0.5; one not given (-1: it follows -contact_rtol) stays */
static inline PetscReal ContactScaledTolerance_Private(PetscReal given, PetscReal rtol, PetscReal rtol0) { return given > 0 ? PetscMin(given * rtol / rtol0, 0.5) : given; }

/* the smallest -contact_rtol at which a ContactModel stores the subdomains' factors in float (they perturb F by
   about 1e-7 relative, the floor of the mechanical residuals they reach) */
#define CONTACT_SINGLE_PRECISION_MIN_RTOL 1e-6

struct ContactProblemData {
  /* the problem */
  Mat F  = nullptr;
  Vec h  = nullptr;
  Mat G  = nullptr; /* equality G l = e (general form) */
  Vec e  = nullptr;
  Mat Q  = nullptr; /* projector form: Q and a particular solution l~ (FETI) */
  Vec lt = nullptr;

  /* contact nodes owned by this rank: global indices of the multipliers (t1 = t2 = -1 when frictionless) */
  std::vector<PetscInt>   normal, t1, t2;
  std::vector<ContactLaw> law;
  std::vector<PetscReal>  coef; /* Tresca: slip bound; Coulomb: friction coefficient; frictionless: unused */

  /* friction polygon (ContactProblemAddPolygonNodes()): `polygon` tangential multipliers per friction node, along
     directions spread evenly over [0, pi), each bounded by sin(pi/(2 polygon)) g (a regular 2*polygon-gon inscribed
     in the disk of radius g); their t1 = t2 = -1. 0: friction disks */
  PetscInt              polygon = 0;
  std::vector<PetscInt> tang; /* `polygon` global indices per node (-1 for frictionless nodes); empty with disks */

  /* derived at setup */
  PetscInt                rstart = 0, nlocal = 0;
  SeparableSet            set = nullptr;
  Vec                     lb  = nullptr;
  Vec                     ub  = nullptr; /* friction polygon: upper bounds (the lower ones are in lb) */
  std::vector<PetscInt>   disk_node;     /* node of each local disk or polygon (friction nodes, in order) */
  std::vector<PetscReal>  radius;        /* current slip bounds g, one per local disk or polygon */
  ContactPipeline         pipeline    = CONTACT_PIPELINE_LINEAR;
  ContactCoulombAlgorithm algorithm   = CONTACT_COULOMB_MONOLITHIC;
  PetscBool               has_coulomb = PETSC_FALSE, has_tresca = PETSC_FALSE, has_normal = PETSC_FALSE;
  Tao                     tao   = nullptr;
  PC                      pc    = nullptr; /* ContactProblemGetPC() (contactpc.cxx): the preconditioner of F in face; NULL or PCNONE: none */
  Mat                     C0    = nullptr; /* empty equality when the problem has none */
  Vec                     d0    = nullptr;
  PetscBool               setup = PETSC_FALSE;

  /* options */
  PetscReal rtol                   = CONTACT_DEFAULT_RTOL; /* -contact_rtol; smalxe: |gP| and feasibility relative to |h| */
  PetscReal msa_rtol               = -1;                   /* MSA: |g^(l+1) - g^(l)| <= msa_rtol |g^(l+1)| (< 0: rtol) */
  PetscInt  msa_max_it             = 100;
  PetscReal msa_start_rtol         = 1e-2;        /* MSA: tolerance of the first Tresca solve (bounds of the initial multipliers) */
  PetscBool msa_recycle            = PETSC_TRUE;  /* MSA: Tresca solves after the first keep the equality's multiplier */
  PetscReal fixed_point_rtol       = -1;          /* monolithic: radii consistent with F l_n to this relative tolerance (< 0: rtol) */
  PetscBool follow_radii           = PETSC_TRUE;  /* Coulomb: a tangential pair on its old circle moves onto the new one when the radius grows */
  PetscReal acceptance_factor      = 10;          /* converged only with the KKT residual <= factor * rtol */
  PetscBool acceptance_given       = PETSC_FALSE; /* -contact_acceptance_factor was given: no cap (ContactAcceptance_Private()) */
  PetscReal acceptance_outside     = 0;           /* inside a model's tighter solve: the model's acceptance (0: from rtol; SetSolverTolerance()) */
  PetscReal pc_contact_scale       = 30;          /* -contact_pc_contact_scale: the contact rows get c/||F|| in the preconditioner (contactpc.cxx) */
  PetscBool pc_contact_rows_scaled = PETSC_TRUE;  /* -contact_pc_contact_rows_scaled */
  PetscBool kkt_check              = PETSC_TRUE;  /* recompute the KKT residual before saying converged (a ContactModel judges by the mechanics instead) */
  PetscInt  refine_max             = 3;           /* -contact_refine_max: tighter warm solves when the KKT check fails after the solver's test passed */
  /* a ContactModel runs the tighter solves itself (ContactModelSolve(), judged by the mechanics and, if asked, this
     KKT check): the problem's own ones would nest inside the model's, each of its solves up to refine_max + 1 */
  PetscBool refine_outside    = PETSC_FALSE;
  PetscReal start_rtol        = 0.1; /* -contact_start_rtol: a cold solve starts with CG on the bonded problem to this (0: off; contactstart.cxx) */
  PetscInt  start_max_it      = 100; /* -contact_start_max_it */
  PetscReal start_compressive = 0.6; /* -contact_start_compressive: the start is kept only if this share of its sum |l_n| presses */
  PetscReal start_separated   = 0.6; /* -contact_start_separated: below this share the separated start is tried (contactstart.cxx) */

  /* -contact_pc_inner_projector: FETI's M as P M P (smalxe projects around it anyway; contactpc.cxx) */
  PetscBool pc_inner_projector = PETSC_FALSE;

  ContactStatistics stats = {};

  ConeFETIProgress progress;                      /* ContactProblemSetProgress(): outer iterations of the solve */
  PetscBool        progressmonitor = PETSC_FALSE; /* its TaoMonitor is on tao */
  PetscInt         progressstep    = 0;           /* the MSA step running (0: not MSA) */
};

struct _p_ContactProblem {
  PETSCHEADER(struct _ContactProblemOps);
  ContactProblemData *data;
};

PETSC_INTERN PetscErrorCode ContactProblemUpdateRadii_Private(ContactProblem, Vec, PetscReal *);
PETSC_INTERN PetscErrorCode ContactProblemSetUpPC_Private(ContactProblem);
PETSC_INTERN PetscErrorCode ContactProblemPCOptions_Private(ContactProblem, CONEFETI_OPTIONS_ITEMS);
PETSC_INTERN PetscErrorCode ContactProblemSetFromOptionsPC_Private(ContactProblem);
PETSC_INTERN PetscErrorCode ContactProblemStartOptions_Private(ContactProblem, CONEFETI_OPTIONS_ITEMS);
PETSC_INTERN PetscErrorCode ContactProblemStart_Private(ContactProblem, Vec, PetscInt *);

/* The friction polygon of k directions (contactpolygon.cxx): direction j is (cos, sin)(j pi / k) in the node's
   (t1, t2) frame, each multiplier is bounded by ContactPolygonBoundFactor(k) g. */
PETSC_INTERN PetscReal ContactPolygonBoundFactor(PetscInt);
PETSC_INTERN void      ContactPolygonDirection(PetscInt, PetscInt, PetscReal[2]);
PETSC_INTERN void      ContactPolygonTraction(PetscInt, const PetscReal[], PetscReal[2]);
PETSC_INTERN void      ContactPolygonTangentialMotion(PetscInt, const PetscReal[], PetscReal[2]);
PETSC_INTERN PetscReal ContactPolygonGauge(PetscInt, const PetscReal[2], PetscReal);

/* Stops with an error that names the rigid motions of the bodies that neither the Dirichlet conditions nor the
   given contact rows resist (contactrigidmotions.cxx; the motions from FEMComputeFreeRigidMotions()). The rows
   that can hold bodies: normal rows, and tangential rows that can carry a force (friction coefficient or slip
   bound > 0), each as appended to B. */
PETSC_INTERN PetscErrorCode ContactCheckRigidMotions_Private(ContactModel, FEM, const std::vector<ContactZone> &, const std::vector<FEMHoldingRow> &);
/* Where the contact solve stagnated: the rigid motion of the bodies along which the multiplier of G l = e grew, as
   "body 1 would turn about an axis through (3, 0.5, 0) along -x (the load's moment about that axis: 2e+07 N m)", or
   an empty phrase when the growth is no rigid motion the load drives (contactrigidmotions.cxx); alpha and u are
   templates of FETI's coarse and primal vectors; a phrase longer than the given length only names the bodies, as
   the brief phrase (the next argument) always does. The last argument says why the motion proves that no
   equilibrium exists ("no admissible contact force resists that motion": no support moves, no contact closes, no
   Coulomb node slides beyond its cone, and the load outworks what the Tresca bounds can resist), or is empty */
PETSC_INTERN PetscErrorCode ContactDescribeStagnatedMotion_Private(ContactModel, FEM, FETI, Tao, Vec, Vec, size_t, std::string &, std::string &, std::string &);
PETSC_INTERN PetscLogEvent  CONTACT_Solve;
