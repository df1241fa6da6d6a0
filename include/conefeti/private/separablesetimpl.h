/* SeparableSet internals shared by the set's files and the QP solvers. */
#pragma once

#include <conefeti/qp.h>
#include <conefeti/compat.h>
#include <petsc/private/petscimpl.h>
#include <vector>

struct _SeparableSetOps {
  PetscErrorCode (*unused)(void);
};

/* What a local entry belongs to. Scalars are bounded by lb/ub (or free); block members are
   handled through the block lists, never through lb/ub. */
enum SeparableEntryKind : unsigned char {
  SEPARABLE_SCALAR = 0,
  SEPARABLE_DISK   = 1,
  SEPARABLE_CONE   = 2
};

struct SeparableSetData {
  PetscInt rstart = 0, n = 0, N = 0; /* owned range [rstart, rstart+n) and global size */

  /* blocks, with local indices */
  std::vector<PetscInt>  disk_idx;    /* 2 per disk */
  std::vector<PetscReal> disk_center; /* 2 per disk, as given by the user */
  std::vector<PetscReal> disk_radius; /* 1 per disk */
  std::vector<PetscInt>  cone_idx;    /* 3 per cone: normal, tangent 1, tangent 2 */
  std::vector<PetscReal> cone_mu;     /* 1 per cone */

  std::vector<unsigned char> kind; /* SeparableEntryKind per local entry */

  Vec lb = nullptr, ub = nullptr; /* user bounds for scalar entries (may be NULL) */
  Vec shift = nullptr;            /* the set is {x : x + shift in Omega} (may be NULL) */

  /* Effective data with the shift folded in, so that projections land exactly on bounds:
     scalar bounds lb - shift, ub - shift; disk centers c - shift; cone apexes -shift. */
  std::vector<PetscReal>     lo, hi;     /* n entries; +-infinity when absent */
  std::vector<PetscReal>     eff_center; /* 2 per disk */
  std::vector<PetscReal>     cone_apex;  /* 3 per cone */
  std::vector<PetscReal>     split_work; /* n entries (sized at setup), scratch of SeparableSetSplitGradient_Private() */
  std::vector<unsigned char> split_free; /* n entries: 1 where the last split found the entry's block free (interior, or an arc block) */
  std::vector<unsigned char> disk_arc;   /* per disk: 1 where the last split let the block move along its circle (see SeparableSetSplitGradient_Private()) */
  std::vector<PetscReal>     disk_curv;  /* per disk: the curvature term -g.nu/r of an arc block (0 otherwise) */
  bool                       has_bounds = false;
  bool                       dirty      = true;
  PetscObjectState           lb_state = 0, ub_state = 0, shift_state = 0; /* of lb, ub, shift when the effective data were made */
  PetscObjectState           version = 0;                                 /* counts the times the effective data were made: subsets copied from an older version are stale */
};

struct _p_SeparableSet {
  PETSCHEADER(struct _SeparableSetOps);
  SeparableSetData *data;
};

/* Relative distance to a curved boundary under which a disk or cone block counts as on it. */
#define SEPARABLE_BOUNDARY_RTOL 1e-10

/* The quantities one pass over the blocks gives at a point x with gradient g. */
struct SeparableSplit {
  PetscReal gp2;     /* |projected gradient|^2 = |phi|^2 + |beta|^2 */
  PetscReal beta2;   /* |chopped gradient|^2 */
  PetscReal phitphi; /* reduced free gradient . free gradient (proportioning test) */
  PetscReal phiAp;   /* phi . Ap when Ap is given (CG update), else 0 */
  PetscReal xg, xb;  /* x.g and x.b when b is given (objective 1/2 x.(g - b)), else 0 */
  PetscInt  narc;    /* disk blocks that move along their circle (arc blocks; 0 unless asked for) */
};

PETSC_INTERN PetscErrorCode SeparableSetSetUp_Private(SeparableSet);
PETSC_INTERN PetscErrorCode SeparableSetGetVersion_Private(SeparableSet, PetscObjectState *);
PETSC_INTERN PetscErrorCode SeparableSetSplitGradient_Private(SeparableSet, Vec, Vec, PetscReal, PetscReal, PetscBool, Vec, Vec, Vec, Vec, SeparableSplit *);
PETSC_INTERN PetscErrorCode SeparableSetFeasibleStep_Private(SeparableSet, Vec, Vec, PetscReal *);
PETSC_INTERN PetscErrorCode SeparableSetArcTangent_Private(SeparableSet, Vec, Vec, Vec, PetscReal *);
PETSC_INTERN PetscErrorCode SeparableSetArcRetraction_Private(SeparableSet, Vec, PetscReal, Vec, Vec, Vec, PetscReal *, PetscReal *);
PETSC_INTERN PetscErrorCode SeparableSetMaskFree_Private(SeparableSet, Vec);
PETSC_INTERN PetscErrorCode SeparableSetProjectedStep_Private(SeparableSet, Vec, PetscReal, Vec, Vec);
PETSC_INTERN PetscErrorCode SeparableSetCheckCompatible_Private(SeparableSet, Vec);

PETSC_INTERN PetscLogEvent QP_Project, QP_Split;
