/* SeparableSet: creation, block description, in-place parameter updates, viewing. */
#include <conefeti/private/separablesetimpl.h>
#include <conefeti/sys.h>
#include <cmath>

PetscClassId SEPARABLESET_CLASSID;

static PetscErrorCode SeparableSetCheckIndex(SeparableSet set, PetscInt global, PetscInt *local)
{
  SeparableSetData *d = set->data;

  PetscFunctionBegin;
  PetscCheck(global >= d->rstart && global < d->rstart + d->n, PetscObjectComm((PetscObject)set), PETSC_ERR_ARG_OUTOFRANGE,
             "SeparableSet: block entry %" PetscInt_FMT " is not owned by this rank (owned range [%" PetscInt_FMT ", %" PetscInt_FMT ")); a block never straddles MPI ranks", global, d->rstart,
             d->rstart + d->n);
  *local = global - d->rstart;
  PetscCheck(d->kind[*local] == SEPARABLE_SCALAR, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "SeparableSet: entry %" PetscInt_FMT " already belongs to a disk or cone block", global);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetCreate - Create a separable convex set for vectors with the given layout; initially
  every entry is a free scalar.

  Collective

  Input Parameters:
+ comm - the MPI communicator of the vectors
. n    - local size (or `PETSC_DECIDE`)
- N    - global size (or `PETSC_DETERMINE`)

  Output Parameter:
. set - the set

  Level: beginner

.seealso: `SeparableSet`, `SeparableSetSetBounds()`, `SeparableSetAddDisks()`, `SeparableSetAddCones()`, `SeparableSetDestroy()`
@*/
PetscErrorCode SeparableSetCreate(MPI_Comm comm, PetscInt n, PetscInt N, SeparableSet *set)
{
  SeparableSet s;
  PetscLayout  map;

  PetscFunctionBegin;
  PetscAssertPointer(set, 4);
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscLayoutCreateFromSizes(comm, n, N, 1, &map));
  PetscCall(PetscHeaderCreate(s, SEPARABLESET_CLASSID, "SeparableSet", "Separable convex set", "QP", comm, SeparableSetDestroy, SeparableSetView));
  PetscCallCXX(s->data = new SeparableSetData);
  s->data->rstart = map->rstart;
  s->data->n      = map->n;
  s->data->N      = map->N;
  PetscCallCXX(s->data->kind.assign(map->n, SEPARABLE_SCALAR));
  PetscCall(PetscLayoutDestroy(&map));
  *set = s;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetDestroy - Destroy a separable set.

  Collective

  Input Parameter:
. set - the set

  Level: beginner

.seealso: `SeparableSetCreate()`
@*/
PetscErrorCode SeparableSetDestroy(SeparableSet *set)
{
  PetscFunctionBegin;
  if (!*set) PetscFunctionReturn(PETSC_SUCCESS);
  PetscValidHeaderSpecific(*set, SEPARABLESET_CLASSID, 1);
  if (--((PetscObject)(*set))->refct > 0) {
    *set = NULL;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(VecDestroy(&(*set)->data->lb));
  PetscCall(VecDestroy(&(*set)->data->ub));
  PetscCall(VecDestroy(&(*set)->data->shift));
  delete (*set)->data;
  PetscCall(PetscHeaderDestroy(set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Checks that a user vector has the set's layout. */
PetscErrorCode SeparableSetCheckCompatible_Private(SeparableSet set, Vec v)
{
  PetscInt n, N, rstart;

  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(VecGetSize(v, &N));
  PetscCall(VecGetOwnershipRange(v, &rstart, NULL));
  PetscCheck(n == set->data->n && N == set->data->N && rstart == set->data->rstart, PetscObjectComm((PetscObject)set), PETSC_ERR_ARG_SIZ,
             "SeparableSet: vector layout (local %" PetscInt_FMT ", global %" PetscInt_FMT ") differs from the set's (local %" PetscInt_FMT ", global %" PetscInt_FMT ")", n, N, set->data->n,
             set->data->N);
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode SeparableSetReplaceVec(Vec src, Vec *dst)
{
  PetscFunctionBegin;
  if (src) PetscCall(PetscObjectReference((PetscObject)src));
  PetscCall(VecDestroy(dst));
  *dst = src;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetSetBounds - Set lower and upper bounds for the scalar entries (those in no disk or cone).

  Logically Collective

  Input Parameters:
+ set - the set
. lb  - lower bounds, entries may be `PETSC_NINFINITY`; NULL means no lower bounds
- ub  - upper bounds, entries may be `PETSC_INFINITY`; NULL means no upper bounds

  Notes:
  The vectors are referenced, not copied: changing their values later changes the set (the set
  notices through the vectors' object states, as PETSc objects do). Entries of lb/ub at positions that belong
  to disk or cone blocks are ignored. lb > ub is an error.

  Level: beginner

.seealso: `SeparableSetCreate()`, `SeparableSetAddDisks()`
@*/
PetscErrorCode SeparableSetSetBounds(SeparableSet set, Vec lb, Vec ub)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  if (lb) PetscCall(SeparableSetCheckCompatible_Private(set, lb));
  if (ub) PetscCall(SeparableSetCheckCompatible_Private(set, ub));
  PetscCall(SeparableSetReplaceVec(lb, &set->data->lb));
  PetscCall(SeparableSetReplaceVec(ub, &set->data->ub));
  set->data->dirty = true;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetSetShift - Translate the set: it becomes { x : x + shift in Omega }.

  Logically Collective

  Input Parameters:
+ set   - the set
- shift - the translation (NULL removes it); referenced, not copied

  Notes:
  Used to homogenize an equality constraint C x = d by a particular solution x~ (C x~ = d): the
  solver then works with x - x~ over the translated set. Bounds, disk centers and cone apexes move;
  radii and cone coefficients do not.

  Level: advanced

.seealso: `SeparableSetCreate()`, `TaoSMALXESetProjector()`
@*/
PetscErrorCode SeparableSetSetShift(SeparableSet set, Vec shift)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  if (shift) PetscCall(SeparableSetCheckCompatible_Private(set, shift));
  PetscCall(SeparableSetReplaceVec(shift, &set->data->shift));
  set->data->dirty = true;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetAddDisks - Add 2D disk blocks {y in R^2 : |y - c| <= r}.

  Not Collective (each rank adds the disks whose entries it owns)

  Input Parameters:
+ set    - the set
. n      - number of disks added on this rank
. idx    - 2n global indices: entries (idx[2k], idx[2k+1]) form disk k; owned by this rank
. center - 2n center coordinates, or NULL for centers at the origin
- radius - n radii, r >= 0 (r = 0 pins the block at its center)

  Notes:
  Disks are numbered in the order they are added on each rank; `SeparableSetSetDiskRadii()` and
  `SeparableSetSetDiskCenters()` take arrays in that order.

  Level: beginner

.seealso: `SeparableSetSetDiskRadii()`, `SeparableSetAddCones()`, `SeparableSetCreate()`
@*/
PetscErrorCode SeparableSetAddDisks(SeparableSet set, PetscInt n, const PetscInt idx[], const PetscReal center[], const PetscReal radius[])
{
  SeparableSetData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  d = set->data;
  PetscCheck(n >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SeparableSetAddDisks: negative number of disks %" PetscInt_FMT, n);
  if (n) {
    PetscValidIntPointer(idx, 3);
    PetscValidRealPointer(radius, 5);
  }
  for (PetscInt k = 0; k < n; k++) {
    PetscInt i, j;
    PetscCheck(radius[k] >= 0 && radius[k] <= SEPARABLESET_DISK_RADIUS_MAX, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "SeparableSetAddDisks: disk %" PetscInt_FMT " has invalid radius %g (must be in [0, %g], SEPARABLESET_DISK_RADIUS_MAX: the solvers square radii)", k, (double)radius[k],
               (double)SEPARABLESET_DISK_RADIUS_MAX);
    PetscCheck(idx[2 * k] != idx[2 * k + 1], PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "SeparableSetAddDisks: disk %" PetscInt_FMT " uses entry %" PetscInt_FMT " twice", k, idx[2 * k]);
    PetscCheck(!center || (!PetscIsInfOrNanReal(center[2 * k]) && !PetscIsInfOrNanReal(center[2 * k + 1])), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "SeparableSetAddDisks: disk %" PetscInt_FMT " has a center (%g, %g) that is not finite", k, center ? (double)center[2 * k] : 0.0, center ? (double)center[2 * k + 1] : 0.0);
    PetscCall(SeparableSetCheckIndex(set, idx[2 * k], &i));
    PetscCall(SeparableSetCheckIndex(set, idx[2 * k + 1], &j));
    d->kind[i] = d->kind[j] = SEPARABLE_DISK;
    PetscCallCXX(d->disk_idx.push_back(i));
    PetscCallCXX(d->disk_idx.push_back(j));
    PetscCallCXX(d->disk_center.push_back(center ? center[2 * k] : 0.0));
    PetscCallCXX(d->disk_center.push_back(center ? center[2 * k + 1] : 0.0));
    PetscCallCXX(d->disk_radius.push_back(radius[k]));
  }
  d->dirty = true;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetAddCones - Add 3D second-order cone blocks {(y_n, y_1, y_2) : sqrt(y_1^2 + y_2^2) <= mu y_n}.

  Not Collective (each rank adds the cones whose entries it owns)

  Input Parameters:
+ set - the set
. n   - number of cones added on this rank
. idx - 3n global indices: (idx[3k], idx[3k+1], idx[3k+2]) = (normal, tangent 1, tangent 2) of cone k
- mu  - n coefficients mu >= 0 (mu = 0: the tangential entries are pinned at 0 and the normal one is >= 0)

  Level: beginner

.seealso: `SeparableSetSetConeCoefficients()`, `SeparableSetAddDisks()`
@*/
PetscErrorCode SeparableSetAddCones(SeparableSet set, PetscInt n, const PetscInt idx[], const PetscReal mu[])
{
  SeparableSetData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  d = set->data;
  PetscCheck(n >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SeparableSetAddCones: negative number of cones %" PetscInt_FMT, n);
  if (n) {
    PetscValidIntPointer(idx, 3);
    PetscValidRealPointer(mu, 4);
  }
  for (PetscInt k = 0; k < n; k++) {
    PetscInt loc[3];
    PetscCheck(mu[k] >= 0 && !PetscIsInfOrNanReal(mu[k]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "SeparableSetAddCones: cone %" PetscInt_FMT " has invalid coefficient mu = %g (must be finite and >= 0)", k, (double)mu[k]);
    for (PetscInt c = 0; c < 3; c++) PetscCall(SeparableSetCheckIndex(set, idx[3 * k + c], &loc[c]));
    PetscCheck(loc[0] != loc[1] && loc[0] != loc[2] && loc[1] != loc[2], PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "SeparableSetAddCones: cone %" PetscInt_FMT " repeats an entry", k);
    for (PetscInt c = 0; c < 3; c++) {
      d->kind[loc[c]] = SEPARABLE_CONE;
      PetscCallCXX(d->cone_idx.push_back(loc[c]));
    }
    PetscCallCXX(d->cone_mu.push_back(mu[k]));
  }
  d->dirty = true;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetSetDiskRadii - Change the radii of this rank's disks in place (no new setup).

  Not Collective

  Input Parameters:
+ set    - the set
- radius - one radius >= 0 per local disk, in the order the disks were added

  Level: intermediate

.seealso: `SeparableSetAddDisks()`, `SeparableSetGetLocalBlockCounts()`
@*/
PetscErrorCode SeparableSetSetDiskRadii(SeparableSet set, const PetscReal radius[])
{
  SeparableSetData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  d = set->data;
  for (size_t k = 0; k < d->disk_radius.size(); k++) {
    PetscCheck(radius[k] >= 0 && radius[k] <= SEPARABLESET_DISK_RADIUS_MAX, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "SeparableSetSetDiskRadii: disk %zu gets invalid radius %g (must be in [0, %g], SEPARABLESET_DISK_RADIUS_MAX: the solvers square radii)", k, (double)radius[k],
               (double)SEPARABLESET_DISK_RADIUS_MAX);
    d->disk_radius[k] = radius[k];
  }
  PetscCall(PetscObjectStateIncrease((PetscObject)set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetSetDiskCenters - Change the centers of this rank's disks in place.

  Not Collective

  Input Parameters:
+ set    - the set
- center - two coordinates per local disk, in the order the disks were added

  Level: intermediate

.seealso: `SeparableSetAddDisks()`, `SeparableSetSetDiskRadii()`
@*/
PetscErrorCode SeparableSetSetDiskCenters(SeparableSet set, const PetscReal center[])
{
  SeparableSetData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  d = set->data;
  for (size_t k = 0; k < d->disk_center.size(); k++) {
    PetscCheck(!PetscIsInfOrNanReal(center[k]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SeparableSetSetDiskCenters: center coordinate %zu is not finite", k);
    d->disk_center[k] = center[k];
  }
  d->dirty = true;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetSetConeCoefficients - Change the coefficients mu of this rank's cones in place.

  Not Collective

  Input Parameters:
+ set - the set
- mu  - one coefficient >= 0 per local cone, in the order the cones were added

  Level: intermediate

.seealso: `SeparableSetAddCones()`
@*/
PetscErrorCode SeparableSetSetConeCoefficients(SeparableSet set, const PetscReal mu[])
{
  SeparableSetData *d;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  d = set->data;
  for (size_t k = 0; k < d->cone_mu.size(); k++) {
    PetscCheck(mu[k] >= 0 && !PetscIsInfOrNanReal(mu[k]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SeparableSetSetConeCoefficients: cone %zu gets invalid mu %g (must be finite and >= 0)", k,
               (double)mu[k]);
    d->cone_mu[k] = mu[k];
  }
  PetscCall(PetscObjectStateIncrease((PetscObject)set));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetGetLocalBlockCounts - Number of disks and cones owned by this rank.

  Not Collective

  Input Parameter:
. set - the set

  Output Parameters:
+ ndisks - local disks (or NULL)
- ncones - local cones (or NULL)

  Level: intermediate

.seealso: `SeparableSetGetSizes()`
@*/
PetscErrorCode SeparableSetGetLocalBlockCounts(SeparableSet set, PetscInt *ndisks, PetscInt *ncones)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  if (ndisks) *ndisks = (PetscInt)set->data->disk_radius.size();
  if (ncones) *ncones = (PetscInt)set->data->cone_mu.size();
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetGetSizes - Local and global length of the vectors the set acts on.

  Not Collective

  Input Parameter:
. set - the set

  Output Parameters:
+ n - local size (or NULL)
- N - global size (or NULL)

  Level: intermediate

.seealso: `SeparableSetCreate()`
@*/
PetscErrorCode SeparableSetGetSizes(SeparableSet set, PetscInt *n, PetscInt *N)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  if (n) *n = set->data->n;
  if (N) *N = set->data->N;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetHasCurvedBlocks - Whether any rank has a disk or cone block (then only `mpgp` applies, not `mprgp`).

  Collective

  Input Parameter:
. set - the set

  Output Parameter:
. curved - `PETSC_TRUE` if some block is a disk or a cone

  Level: intermediate

.seealso: `SeparableSetIsUnconstrained()`
@*/
PetscErrorCode SeparableSetHasCurvedBlocks(SeparableSet set, PetscBool *curved)
{
  PetscInt local;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  local = (PetscInt)(set->data->disk_radius.size() + set->data->cone_mu.size());
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &local, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)set)));
  *curved = local ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetIsUnconstrained - Whether the set is the whole space (no finite bound, no block).

  Collective

  Input Parameter:
. set - the set

  Output Parameter:
. free - `PETSC_TRUE` if every entry is a free scalar

  Level: intermediate

.seealso: `SeparableSetHasCurvedBlocks()`
@*/
PetscErrorCode SeparableSetIsUnconstrained(SeparableSet set, PetscBool *free)
{
  SeparableSetData *d;
  PetscInt          constrained;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  PetscCall(SeparableSetSetUp_Private(set));
  d           = set->data;
  constrained = (d->has_bounds || !d->disk_radius.empty() || !d->cone_mu.empty()) ? 1 : 0;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &constrained, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)set)));
  *free = constrained ? PETSC_FALSE : PETSC_TRUE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Folds the shift into bounds, centers and apexes, and validates l <= u. Cheap; done when dirty,
   which includes new values written into the bound or shift vectors since (their object states). */
PetscErrorCode SeparableSetSetUp_Private(SeparableSet set)
{
  SeparableSetData  *d  = set->data;
  const PetscScalar *lb = NULL, *ub = NULL, *s = NULL;
  PetscInt           bad      = -1;
  PetscObjectState   state[3] = {0, 0, 0};

  PetscFunctionBegin;
  if (d->lb) PetscCall(PetscObjectStateGet((PetscObject)d->lb, &state[0]));
  if (d->ub) PetscCall(PetscObjectStateGet((PetscObject)d->ub, &state[1]));
  if (d->shift) PetscCall(PetscObjectStateGet((PetscObject)d->shift, &state[2]));
  if (!d->dirty && state[0] == d->lb_state && state[1] == d->ub_state && state[2] == d->shift_state) PetscFunctionReturn(PETSC_SUCCESS);
  d->lb_state    = state[0];
  d->ub_state    = state[1];
  d->shift_state = state[2];
  if (d->lb) PetscCall(VecGetArrayRead(d->lb, &lb));
  if (d->ub) PetscCall(VecGetArrayRead(d->ub, &ub));
  if (d->shift) PetscCall(VecGetArrayRead(d->shift, &s));
  PetscCallCXX(d->lo.assign(d->n, PETSC_NINFINITY));
  PetscCallCXX(d->hi.assign(d->n, PETSC_INFINITY));
  PetscCallCXX(d->split_work.resize(d->n));
  PetscCallCXX(d->split_free.assign(d->n, 0));
  PetscCallCXX(d->disk_arc.assign(d->disk_radius.size(), 0));
  PetscCallCXX(d->disk_curv.assign(d->disk_radius.size(), 0));
  d->has_bounds = false;
  for (PetscInt i = 0; i < d->n; i++) {
    if (d->kind[i] != SEPARABLE_SCALAR) continue;
    const PetscReal l = lb ? PetscRealPart(lb[i]) : PETSC_NINFINITY, u = ub ? PetscRealPart(ub[i]) : PETSC_INFINITY;
    const PetscReal si = s ? PetscRealPart(s[i]) : 0.0;
    if (PetscIsNanReal(l) || PetscIsNanReal(u) || l > u) {
      if (bad < 0) bad = i;
      continue;
    }
    if (l > PETSC_NINFINITY) {
      d->lo[i]      = l - si;
      d->has_bounds = true;
    }
    if (u < PETSC_INFINITY) {
      d->hi[i]      = u - si;
      d->has_bounds = true;
    }
  }
  PetscCheck(bad < 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SeparableSet: lower bound %g > upper bound %g (or NaN) at entry %" PetscInt_FMT, lb ? (double)PetscRealPart(lb[bad]) : 0.0,
             ub ? (double)PetscRealPart(ub[bad]) : 0.0, d->rstart + bad);
  PetscCallCXX(d->eff_center.resize(d->disk_center.size()));
  for (size_t k = 0; k < d->disk_center.size(); k++) d->eff_center[k] = d->disk_center[k] - (s ? PetscRealPart(s[d->disk_idx[k]]) : 0.0);
  PetscCallCXX(d->cone_apex.resize(d->cone_idx.size()));
  for (size_t k = 0; k < d->cone_idx.size(); k++) d->cone_apex[k] = s ? -PetscRealPart(s[d->cone_idx[k]]) : 0.0;
  if (d->lb) PetscCall(VecRestoreArrayRead(d->lb, &lb));
  if (d->ub) PetscCall(VecRestoreArrayRead(d->ub, &ub));
  if (d->shift) PetscCall(VecRestoreArrayRead(d->shift, &s));
  d->dirty = false;
  d->version++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The version of the set's effective data (after bringing them up to date) */
PetscErrorCode SeparableSetGetVersion_Private(SeparableSet set, PetscObjectState *version)
{
  PetscFunctionBegin;
  PetscCall(SeparableSetSetUp_Private(set));
  *version = set->data->version;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetView - Describe a separable set: block counts and parameter ranges.

  Collective

  Input Parameters:
+ set    - the set
- viewer - an ASCII viewer (or NULL for stdout)

  Level: beginner

.seealso: `SeparableSetCreate()`
@*/
PetscErrorCode SeparableSetView(SeparableSet set, PetscViewer viewer)
{
  SeparableSetData *d;
  PetscBool         iascii;
  PetscInt          counts[4] = {0, 0, 0, 0};                                                     /* free, bounded scalars, disks, cones */
  PetscReal         range[4]  = {PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL, PETSC_MAX_REAL}; /* -rmax, rmin, -mumax, mumin */
  MPI_Comm          comm;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  comm = PetscObjectComm((PetscObject)set);
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(comm, &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &iascii));
  if (!iascii) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(SeparableSetSetUp_Private(set));
  d = set->data;
  for (PetscInt i = 0; i < d->n; i++) {
    if (d->kind[i] != SEPARABLE_SCALAR) continue;
    if (d->lo[i] > PETSC_NINFINITY || d->hi[i] < PETSC_INFINITY) counts[1]++;
    else counts[0]++;
  }
  counts[2] = (PetscInt)d->disk_radius.size();
  counts[3] = (PetscInt)d->cone_mu.size();
  for (PetscReal r : d->disk_radius) {
    range[0] = PetscMin(range[0], -r);
    range[1] = PetscMin(range[1], r);
  }
  for (PetscReal m : d->cone_mu) {
    range[2] = PetscMin(range[2], -m);
    range[3] = PetscMin(range[3], m);
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 4, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, range, 4, MPIU_REAL, MPIU_MIN, comm));
  {                                                                                    /* a SeparableSet has no types: the header without PETSc's "type not yet set" */
    const char *name = ((PetscObject)set)->name, *prefix = ((PetscObject)set)->prefix; /* a generated name says nothing */
    PetscCall(PetscViewerASCIIPrintf(viewer, "SeparableSet Object:%s%s%s%s\n", name ? " " : "", name ? name : "", prefix ? " prefix " : "", prefix ? prefix : ""));
  }
  PetscCall(PetscViewerASCIIPushTab(viewer));
  PetscCall(PetscViewerASCIIPrintf(viewer, "length %" PetscInt_FMT ": %" PetscInt_FMT " free scalars, %" PetscInt_FMT " bounded scalars, %" PetscInt_FMT " disks, %" PetscInt_FMT " cones\n", d->N,
                                   counts[0], counts[1], counts[2], counts[3]));
  if (counts[2]) PetscCall(PetscViewerASCIIPrintf(viewer, "disk radii in [%g, %g]\n", (double)range[1], (double)-range[0]));
  if (counts[3]) PetscCall(PetscViewerASCIIPrintf(viewer, "cone coefficients in [%g, %g]\n", (double)range[3], (double)-range[2]));
  if (d->shift) PetscCall(PetscViewerASCIIPrintf(viewer, "translated by a shift vector\n"));
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  SeparableSetCreateSubset - The set restricted to the entries of an index set: the factor of the
  product that acts on those entries (a block must lie entirely inside or outside the index set).

  Collective

  Input Parameters:
+ set - the set
- is  - global indices owned by this rank (the subvector's ordering follows is)

  Output Parameter:
. subset - a new set for vectors of length |is| (with the same communicator), copying bounds,
           disks (with radii and centers) and cones of the selected entries

  Notes:
  The subset is independent of the parent: later changes of radii or bounds of one are not seen by
  the other. Used for block Gauss-Seidel sweeps (`TaoSMALXESetBlocks()`).

  Level: advanced

.seealso: `SeparableSetCreate()`, `TaoSMALXESetBlocks()`
@*/
PetscErrorCode SeparableSetCreateSubset(SeparableSet set, IS is, SeparableSet *subset)
{
  SeparableSetData      *d;
  SeparableSet           s;
  PetscInt               n, start;
  const PetscInt        *idx;
  std::vector<PetscInt>  where; /* parent local index -> subset global index, or -1 */
  std::vector<PetscInt>  bidx;
  std::vector<PetscReal> bc, br;
  Vec                    lb = NULL, ub = NULL;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(set, SEPARABLESET_CLASSID, 1);
  PetscValidHeaderSpecific(is, IS_CLASSID, 2);
  PetscCall(SeparableSetSetUp_Private(set));
  d = set->data;
  PetscCheck(!d->shift, PetscObjectComm((PetscObject)set), PETSC_ERR_SUP, "SeparableSetCreateSubset: not available for a shifted set");
  PetscCall(ISGetLocalSize(is, &n));
  PetscCall(SeparableSetCreate(PetscObjectComm((PetscObject)set), n, PETSC_DETERMINE, &s));
  start = s->data->rstart;
  PetscCallCXX(where.assign(d->n, -1));
  PetscCall(ISGetIndices(is, &idx));
  for (PetscInt k = 0; k < n; k++) {
    const PetscInt i = idx[k] - d->rstart;
    PetscCheck(i >= 0 && i < d->n, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "SeparableSetCreateSubset: index %" PetscInt_FMT " is not owned by this rank", idx[k]);
    where[i] = start + k;
  }
  PetscInt any_bounds = d->has_bounds ? 1 : 0; /* collective below: every rank must take the same branch */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &any_bounds, 1, MPIU_INT, MPI_MAX, PetscObjectComm((PetscObject)set)));
  if (any_bounds) {
    PetscScalar *l, *u;
    PetscCall(VecCreateMPI(PetscObjectComm((PetscObject)set), n, PETSC_DETERMINE, &lb));
    PetscCall(VecDuplicate(lb, &ub));
    PetscCall(VecGetArrayWrite(lb, &l));
    PetscCall(VecGetArrayWrite(ub, &u));
    for (PetscInt k = 0; k < n; k++) {
      l[k] = d->lo[idx[k] - d->rstart];
      u[k] = d->hi[idx[k] - d->rstart];
    }
    PetscCall(VecRestoreArrayWrite(lb, &l));
    PetscCall(VecRestoreArrayWrite(ub, &u));
  }
  PetscCall(ISRestoreIndices(is, &idx));
  for (size_t k = 0; k < d->disk_radius.size(); k++) {
    const PetscInt a = where[d->disk_idx[2 * k]], b = where[d->disk_idx[2 * k + 1]];
    PetscCheck((a < 0) == (b < 0), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "SeparableSetCreateSubset: the index set cuts disk %zu", k);
    if (a < 0) continue;
    PetscCallCXX(bidx.insert(bidx.end(), {a, b}));
    PetscCallCXX(bc.insert(bc.end(), {d->disk_center[2 * k], d->disk_center[2 * k + 1]}));
    PetscCallCXX(br.push_back(d->disk_radius[k]));
  }
  PetscCall(SeparableSetAddDisks(s, (PetscInt)br.size(), bidx.data(), bc.data(), br.data()));
  bidx.clear();
  br.clear();
  for (size_t k = 0; k < d->cone_mu.size(); k++) {
    const PetscInt a = where[d->cone_idx[3 * k]], b = where[d->cone_idx[3 * k + 1]], c = where[d->cone_idx[3 * k + 2]];
    PetscCheck((a < 0) == (b < 0) && (b < 0) == (c < 0), PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "SeparableSetCreateSubset: the index set cuts cone %zu", k);
    if (a < 0) continue;
    PetscCallCXX(bidx.insert(bidx.end(), {a, b, c}));
    PetscCallCXX(br.push_back(d->cone_mu[k]));
  }
  PetscCall(SeparableSetAddCones(s, (PetscInt)br.size(), bidx.data(), br.data()));
  PetscCall(SeparableSetSetBounds(s, lb, ub));
  PetscCall(VecDestroy(&lb));
  PetscCall(VecDestroy(&ub));
  *subset = s;
  PetscFunctionReturn(PETSC_SUCCESS);
}
