/* The one implementation of MPRGP and MPGP, shared by the TAO and KSP types. */
#pragma once

#include <conefeti/private/separablesetimpl.h>

enum class MPGPVariant {
  MPRGP, /* bounds only; proportioning step along the chopped gradient with exact line search */
  MPGP   /* any separable set; proportioning step is a projected gradient step of fixed length */
};

enum class MPGPStatus {
  STOPPED,        /* the owner's report callback asked to stop (converged or out of iterations) */
  INDEFINITE,     /* p'Ap < 0: the Hessian is not positive semidefinite on the search space */
  UNBOUNDED,      /* p'Ap = 0 along a descent direction that no constraint stops: q is unbounded below */
  NORM_TOO_SMALL, /* q rose in a step: the fixed step length 1/||A|| is too long, the norm estimate too small */
  NOT_A_NUMBER,
  ACCURACY_FLOOR, /* verify: the exact projected gradient stayed above the tolerance that recurred ones met (rounding) */
  NOT_SYMMETRIC   /* one of the failures above, on an A that is not symmetric (MPGPCoreDiagnose()): the cause */
};

/* Stops that the exact gradient refused (mpgp's verify, smalxe's exact stop): where rounding sets a floor
   (an ill-conditioned A) the exact |gP| stops falling, and three refusals in a row that do not halve it say so */
struct QPRefusedStops {
  PetscReal best   = PETSC_INFINITY; /* the smallest exact |gP| refused */
  PetscInt  stalls = 0;              /* refusals in a row that did not halve it */
  /* one more refusal at |gP| = gp: whether the floor is reached */
  bool AtFloor(PetscReal gp)
  {
    stalls = gp < 0.5 * best ? 0 : stalls + 1;
    best   = PetscMin(best, gp);
    return stalls >= 3;
  }
  void Accepted() { stalls = 0; }
};

/* Called at iteration 0 and after every iteration; sets *stop to end the solve. */
typedef PetscErrorCode (*MPGPReportFn)(void *ctx, PetscInt it, PetscReal f, PetscReal gpnorm, PetscReal step, PetscBool *stop);
/* z = M^{-1} g. The core restricts z to the free entries (preconditioning in face: [M^-1]_FF, a
   principal submatrix of an SPD matrix, so an SPD preconditioner of the face's A_FF); without
   constraints every entry is free and the solver is PCG. */
typedef PetscErrorCode (*MPGPPreconditionFn)(void *ctx, Vec g, Vec z);

struct MPGPCore {
  MPGPVariant variant     = MPGPVariant::MPGP;
  PetscReal   gamma       = 1.0;         /* proportioning parameter Gamma */
  PetscReal   alpha_scale = 1.95;        /* fixed step alpha = alpha_scale / ||A||, in (0, 2] */
  PetscReal   normA       = 0;           /* estimate of ||A||, provided by the owner before the solve */
  PetscBool   bb          = PETSC_FALSE; /* MPGP: try Barzilai-Borwein lengths in gradient projection steps */
  PetscBool   projcg      = PETSC_FALSE; /* expansion: first try the projected full CG step P(x - a_cg p) (see MPGPCoreSolve) */
  PetscReal   arc         = 1.0;         /* MPGP: > 0 lets CG steps move disk blocks along their circle while alpha |g.nu|/r <= arc (arc steps, see MPGPCoreSolve); 0: off */
  PetscBool   provisional = PETSC_FALSE; /* set while report() is only asked whether the solve may stop (on an updated gradient) */
  PetscBool   resume      = PETSC_FALSE; /* continue an interrupted solve: iteration 0 is not reported (the owner's test keeps its reference) */
  PetscBool   verify      = PETSC_FALSE; /* stop only on an exact gradient also after CG steps (their recurred g drifts on ill-conditioned A) */

  Mat          A   = nullptr; /* not owned */
  Vec          b   = nullptr; /* not owned */
  SeparableSet set = nullptr; /* not owned */

  MPGPReportFn       report           = nullptr;
  void              *report_ctx       = nullptr;
  MPGPPreconditionFn precondition     = nullptr;
  void              *precondition_ctx = nullptr;
  QPCounters        *counters         = nullptr; /* owner's counters, updated in place */

  Vec       g = nullptr, p = nullptr, Ap = nullptr, phi = nullptr, beta = nullptr, z = nullptr; /* work */
  Vec       dx = nullptr;                                                                       /* the step of a projected CG expansion */
  Vec       Wp = nullptr, ApW = nullptr;                                                        /* arc steps: the curvature term W p, and Ap + Wp */
  Vec       xsave = nullptr, gsave = nullptr;                                                   /* arc steps: x and the updated g before a step, for its certificate */
  PetscBool updated  = PETSC_FALSE;                                                             /* g was updated after steps along arcs, not recomputed */
  PetscReal drift    = 0;                                                                       /* then a bound on its error: ||A|| times the sum of the retractions' lengths */
  PetscInt  recurred = 0;                                                                       /* updates g - a Ap since g was last computed as A x - b */
  PetscInt  verified = 0, verify_failed = 0;                                                    /* verify: exact gradients computed to confirm a stop; stops they refused */
  PetscInt  arc_steps = 0, arc_rejected = 0, arc_refreshed = 0;                                 /* CG steps along arcs; steps not taken or taken again; gradients recomputed for them */
  Vec       xprev = nullptr, gprev = nullptr;                                                   /* the previous iterate and gradient (Barzilai-Borwein lengths) */
  PetscInt  bb_rejected     = 0;                                                                /* BB steps that did not decrease q and fell back to the fixed length */
  PetscInt  projcg_rejected = 0;                                                                /* projected CG steps not kept (q above the feasible half step's) */
  PetscBool lagged          = PETSC_FALSE; /* with projcg: expansions first try a lagged length, without the product A p (see MPGPCoreLaggedExpansion()) */
  PetscReal lag = 0, lag_used = 0;         /* the length to try next (0: none) and that of the last try */
  PetscInt  lagged_steps = 0, lagged_rejected = 0;
  PetscBool projcg_gradient = PETSC_FALSE; /* with projcg: the tried point is P(y - alpha g(y)), y = x - a_cg p, instead of P(y) (see MPGPCoreSolve) */
  PetscInt  lookahead       = 0;           /* with projcg: the projected CG step first takes this many more CG steps in the face, past the set (see MPGPCoreLookahead()) */
  PetscInt  lookahead_kept = 0, lookahead_rejected = 0;
  Vec       psave = nullptr, Apsave = nullptr, wt = nullptr; /* look-ahead: the direction and its product before it, and a scratch vector */

  /* with a preconditioner: the restart direction M phi is due, computed when a CG or expansion step needs it */
  PetscBool pending = PETSC_FALSE;

  /* state after a solve: g = A x - b is valid for the returned x */
  PetscInt   its       = 0;
  PetscReal  f         = 0;
  PetscReal  gpnorm    = 0;
  MPGPStatus status    = MPGPStatus::STOPPED;
  PetscReal  asymmetry = 0, asymmetry_scale = 0; /* NOT_SYMMETRIC: x'Ay - y'Ax for random x, y, and ||A|| |x| |y| */
};

PETSC_INTERN PetscErrorCode MPGPCoreSetUp(MPGPCore *, Vec);
PETSC_INTERN PetscErrorCode MPGPCoreSolve(MPGPCore *, Vec);
PETSC_INTERN PetscErrorCode MPGPCoreConfirmGradient(MPGPCore *, Vec, PetscReal *);
PETSC_INTERN PetscErrorCode TaoQPConfirmGradient_Private(Tao, PetscReal *, PetscBool *);
PETSC_INTERN PetscErrorCode MPGPCoreReset(MPGPCore *);
PETSC_INTERN PetscErrorCode MPGPCoreDiagnose(MPGPCore *);

PETSC_INTERN PetscLogEvent QP_HessianMult, QP_Solve, QP_NormEstimate;
/* the QP's own work between the Hessian products (-log_view): the preconditioner in face, smalxe's |Cx - d|
   and multiplier update, the rank-independent dot products and updates (reproduciblesum.cxx) */
PETSC_INTERN PetscLogEvent QP_Precondition, QP_Feasibility, QP_MultiplierUpdate, QP_VecReproducible;

/* How ||A|| is obtained for the fixed step length, shared by the TAO and KSP wrappers. */
struct QPNormSettings {
  QPNormMethod method = QP_NORM_SLEPC;
  PetscReal    margin = -1; /* < 0: the method's default (0.01 slepc, 0.05 power) */
  PetscReal    user   = 0;  /* > 0: given, not estimated */
  PetscReal    used   = 0;  /* the value of the last solve */
};

/* The options of one of the four types (TAO or KSP, mprgp or mpgp), each name spelled out so that a search
   for an option finds where it is read; bb and arc are NULL for mprgp. The prefixes have no leading dash. */
struct MPGPOptionNames {
  const char *title;
  const char *gamma, *alpha, *bb, *arc, *expansion_projcg, *expansion_lagged, *expansion_lookahead, *expansion_gradient, *norm, *norm_method, *norm_margin, *counters_view;
  const char *pc_prefix;   /* the preconditioner in face: -<prefix>tao_mpgp_pc_type ... */
  const char *norm_prefix; /* the norm estimate's eigensolver: -<prefix>tao_mpgp_norm_eps_... */
};
PETSC_INTERN const MPGPOptionNames MPGPOptionsTaoMPRGP, MPGPOptionsTaoMPGP, MPGPOptionsKSPMPRGP, MPGPOptionsKSPMPGP;

/* Reads the options of `names`; the object's options prefix (may be NULL) only for the messages:
   PetscOptions*() add it themselves. */
PETSC_INTERN PetscErrorCode MPGPCoreSetFromOptions(CONEFETI_OPTIONS_ITEMS, MPI_Comm, const char *, const MPGPOptionNames *, MPGPCore *, QPNormSettings *, PetscBool *);
PETSC_INTERN PetscErrorCode MPGPCoreViewExpansion(const MPGPCore *, PetscViewer);
/* ||A|| for a solve: the given value, or the cached or new estimate (products added to the counters). */
PETSC_INTERN PetscErrorCode QPNormSettingsApply(QPNormSettings *, Mat, const char *, const MPGPOptionNames *, QPCounters *);
/* At the start of a solve: TAO's gatol, gttol and grtol (or with an equality catol and crtol) are finite and >= 0. */
PETSC_INTERN PetscErrorCode TaoQPCheckTolerances_Private(Tao, PetscBool);
PETSC_INTERN PetscErrorCode TaoQPCheckMaxIt_Private(Tao);

/* The defaults of the TAO types that depend on the Hessian and the set (mpgpdefaults.cxx): as PETSc's KSP picks
   its PC from the matrix, an assembled sparse Hessian gets a preconditioner in face (ICC, block Jacobi with ICC
   on several ranks), the projected CG expansion and Gamma 2, unless the set has cone blocks; any other Hessian
   (a MATSHELL such as FETI's dual operator, a dense matrix) or a set with cones keeps no preconditioner,
   Dostal's expansion and Gamma 1. */
struct MPGPHessianDefaults {
  PetscBool assembled    = PETSC_FALSE; /* ICC is available for the (rank-local diagonal block of the) preconditioning matrix */
  PetscBool cones        = PETSC_FALSE; /* the set has cone blocks (on some rank) */
  PCType    pc           = PCNONE;      /* PCICC, PCBJACOBI (with ICC in its blocks) or PCNONE */
  PetscBool projcg       = PETSC_FALSE;
  PetscReal gamma        = 1.0;
  char      mat_type[64] = ""; /* the preconditioning matrix's type, for the view */
};
PETSC_INTERN PetscErrorCode MPGPHessianDefaultsGet(Mat, SeparableSet, MPGPHessianDefaults *);
/* "because the Hessian is assembled (seqaij)", "because the Hessian is not an assembled sparse matrix (shell)" or
   "because the set has cone blocks ..." */
PETSC_INTERN PetscErrorCode MPGPHessianDefaultsReason(const MPGPHessianDefaults *, char *, size_t);
