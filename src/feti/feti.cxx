/* The FETI object: creation, input, options, FETISetUp(), viewing, queries. */
#include <conefeti/private/fetiimpl.h>
#include <conefeti/qp.h>

#include <algorithm>
#include <cstdlib>

const char *const FETIRowKinds[]        = {"gluing", "dirichlet", "contact_normal", "contact_tangential", "FETIRowKind", "FETI_ROW_", NULL};
const char *const FETIKplusTypes[]      = {"auto", "explicit", "implicit", "FETIKplusType", "FETI_KPLUS_", NULL};
const char *const FETIKplusPrecisions[] = {"double", "single", "FETIKplusPrecision", "FETI_KPLUS_PRECISION_", NULL};

static PetscErrorCode FETIReset(FETI feti)
{
  FETI_Impl &impl = *feti->impl;

  PetscFunctionBegin;
  for (FETISubdomain &sd : impl.sub) PetscCall(FETISubdomainDestroy(sd));
  impl.sub.clear();
  PetscCall(MatDestroy(&impl.B));
  PetscCall(FETIRowSumDestroy(impl.Bsum));
  PetscCall(FETIRowSumDestroy(impl.Btsum));
  PetscCall(VecDestroy(&impl.c));
  PetscCall(VecDestroy(&impl.f));
  PetscCall(MatDestroy(&impl.R));
  PetscCall(MatDestroy(&impl.Gt));
  PetscCallCXX(std::vector<PetscInt>().swap(impl.grows));
  PetscCallCXX(std::vector<PetscInt>().swap(impl.gptr));
  PetscCallCXX(std::vector<PetscInt>().swap(impl.gcols));
  PetscCallCXX(std::vector<PetscInt>().swap(impl.gfirst));
  PetscCallCXX(std::vector<PetscScalar>().swap(impl.gvals));
  PetscCallCXX(std::vector<PetscInt>().swap(impl.ghptr));
  PetscCallCXX(std::vector<PetscInt>().swap(impl.ghcols));
  PetscCallCXX(std::vector<PetscScalar>().swap(impl.ghvals));
  impl.ghostrows     = 0;
  impl.growsset      = PETSC_FALSE;
  impl.ncoarsesolves = 0;
  PetscCall(FETICoarseSolverDestroy(impl.coarse));
  /* an operator that the caller still holds (a ContactProblem's F and Q) loses its FETI object: a product with it is
     then an error naming it (ShellGetFETI()), not a read of freed memory */
  for (Mat A : {impl.F, impl.G, impl.P, impl.Q, impl.Kplus, impl.PFP})
    if (A) PetscCall(MatShellSetContext(A, NULL));
  PetscCall(MatDestroy(&impl.F));
  PetscCall(MatDestroy(&impl.G));
  PetscCall(MatDestroy(&impl.P));
  PetscCall(MatDestroy(&impl.Q));
  PetscCall(MatDestroy(&impl.Kplus));
  PetscCall(MatDestroy(&impl.PFP));
  PetscCall(VecDestroy(&impl.h));
  PetscCall(VecDestroy(&impl.e));
  PetscCall(VecDestroy(&impl.lambdatilde));
  PetscCall(VecDestroy(&impl.boundarymask));
  PetscCall(VecDestroy(&impl.wp1));
  PetscCall(VecDestroy(&impl.wp2));
  PetscCall(VecDestroy(&impl.wd1));
  PetscCall(VecDestroy(&impl.wd2));
  PetscCall(VecDestroy(&impl.wc1));
  PetscCall(VecDestroy(&impl.wc2));
  PetscCall(VecDestroy(&impl.wp3));
  PetscCall(VecDestroy(&impl.wd3));
  PetscCall(VecDestroy(&impl.wcr));
  PetscCall(VecDestroy(&impl.wcdy));
  PetscCall(VecDestroy(&impl.wdr));
  impl.coarsesteps = 0;
  impl.coarseres0  = -1;
  PetscCall(VecDestroy(&impl.rhs));
  PetscCall(VecDestroy(&impl.residual));
  PetscCall(VecDestroy(&impl.alpha));
  impl.setupcalled = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETICreate - Create an empty FETI problem.

  Collective

  Input Parameter:
. comm - MPI communicator; every rank must own at least one subdomain

  Output Parameter:
. feti - the FETI problem

  Notes:
  Typical use:
.vb
  FETICreate(comm, &feti);
  FETISetSubdomains(feti, nlocal, K, f);          // per local subdomain: K_s, f_s
  FETISetSubdomainCoordinates(feti, s, coords);   // or FETISetSubdomainKernel()
  FETISetConstraints(feti, B, c, kinds);
  FETISetFromOptions(feti);
  FETISetUp(feti);
  FETISolveLinear(feti, lambda, u);               // or hand FETIGetOperators() to a QP solver
.ve

  Level: beginner

.seealso: `FETISetSubdomains()`, `FETISetConstraints()`, `FETISetUp()`, `FETIDestroy()`, `FEMCreateFETI()`
@*/
PetscErrorCode FETICreate(MPI_Comm comm, FETI *feti)
{
  FETI f;

  PetscFunctionBegin;
  PetscAssertPointer(feti, 2);
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscHeaderCreate(f, FETI_CLASSID, "FETI", "FETI dual problem", "FETI", comm, FETIDestroy, FETIView));
  PetscCallCXX(f->impl = new FETI_Impl());
  PetscCall(PetscStrncpy(f->impl->subsolver, MATSOLVERCHOLMOD, sizeof(f->impl->subsolver)));
  *feti = f;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FETICheckVec_Private(FETI feti, Vec v, FETIVecSpace space, const char fn[], const char arg[])
{
  FETI_Impl  &impl = *feti->impl;
  const Vec   ref  = space == FETI_VEC_PRIMAL ? impl.wp1 : space == FETI_VEC_DUAL ? impl.wd1 : impl.wc1;
  const char *name = space == FETI_VEC_PRIMAL ? "primal" : space == FETI_VEC_DUAL ? "dual" : "coarse";
  PetscInt    n, N, rn, rN;

  PetscFunctionBegin;
  if (!ref) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(VecGetSize(v, &N));
  PetscCall(VecGetLocalSize(ref, &rn));
  PetscCall(VecGetSize(ref, &rN));
  /* the global sizes are the same on every rank; a local size may differ on one rank only */
  PetscCheck(N == rN, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_SIZ, "%s(): %s has %" PetscInt_FMT " entries, a %s vector %" PetscInt_FMT " (FETICreateVecs())", fn, arg, N, name, rN);
  PetscCheck(n == rn, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "%s(): %s has %" PetscInt_FMT " entries on this rank, a %s vector %" PetscInt_FMT " (FETICreateVecs())", fn, arg, n, name, rn);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIDestroy - Destroy a FETI problem.

  Collective

  Input Parameter:
. feti - the FETI problem

  Level: beginner

.seealso: `FETICreate()`
@*/
PetscErrorCode FETIDestroy(FETI *feti)
{
  PetscFunctionBegin;
  if (!feti || !*feti) PetscFunctionReturn(PETSC_SUCCESS);
  PetscValidHeaderSpecific(*feti, FETI_CLASSID, 1);
  if (--((PetscObject)(*feti))->refct > 0) {
    *feti = NULL;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(FETIReset(*feti));
  PetscCall(KSPDestroy(&(*feti)->impl->ksp));
  PetscCallCXX(delete (*feti)->impl);
  PetscCall(PetscHeaderDestroy(feti));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* FETISetUp() takes the subdomain data (copies the loads, consumes or copies K_s, factors it): a setter called
   afterwards would change nothing the solver uses, and a second setup on the consumed data would crash */
static PetscErrorCode CheckNotSetUp(FETI feti, MPI_Comm comm, const char fn[])
{
  PetscFunctionBegin;
  PetscCheck(!feti->impl->setupcalled, comm, PETSC_ERR_ORDER,
             "%s() after FETISetUp(): the subdomain data and constraints are taken at FETISetUp() and cannot be changed afterwards; give them before FETISetUp(), or start a new "
             "problem with FETISetSubdomains() and give everything again",
             fn);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* a vector handed over for one subdomain is read as a local array of n_s entries: one on a parallel communicator
   holds only part of them on this rank, and the reads run past its end */
static PetscErrorCode CheckSubdomainVec(Vec v, const char fn[], const char arg[], PetscInt s, PetscInt n, const char hint[])
{
  MPI_Comm    comm;
  PetscMPIInt size, rank;
  PetscInt    nv;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(PetscObjectGetComm((PetscObject)v, &comm));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCheck(size == 1, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "%s(): %s of local subdomain %" PetscInt_FMT " on rank %d is on a communicator of %d ranks; it must be sequential (PETSC_COMM_SELF)", fn,
             arg, s, rank, size);
  PetscCall(VecGetLocalSize(v, &nv));
  PetscCheck(nv == n, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "%s(): %s of local subdomain %" PetscInt_FMT " on rank %d has %" PetscInt_FMT " entries but K_s has %" PetscInt_FMT " rows%s", fn, arg, s,
             rank, nv, n, hint);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* NaN or Inf in the input runs through every operator and comes out as a NaN solution or a diverged KSP: name the
   first non-finite entry where it is given */
static PetscErrorCode CheckFiniteArray(PetscInt n, const PetscScalar a[], const char fn[], const char arg[], PetscInt s)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < n; i++) {
    if (!PetscIsInfOrNanScalar(a[i])) continue;
    PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "%s(): %s of local subdomain %" PetscInt_FMT " on rank %d has a non-finite entry %g at index %" PetscInt_FMT, fn, arg, s, rank,
            (double)PetscRealPart(a[i]), i);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETISetSubdomains - Give the subdomains owned by this rank: stiffness matrices and loads.

  Collective

  Input Parameters:
+ feti   - the FETI problem
. nlocal - number of subdomains on this rank (>= 1)
. K      - nlocal sequential matrices (SEQAIJ or SEQSBAIJ), square, block size 3, dofs interleaved x, y, z per node, without Dirichlet conditions
- f      - nlocal sequential load vectors of matching size (NULL entries or a NULL array: zero load)

  Notes:
  Subdomains are numbered globally rank by rank; the primal vector is their concatenation in that
  order, so this rank's subdomains occupy a contiguous range of it (the column layout of B).
  The FETI object keeps a reference to each K_s. If the caller destroys its own reference before
  `FETISetUp()`, K_s is regularized in place and no copy is made; otherwise a copy is regularized.
  Do not change K_s after this call. The loads f_s are copied at `FETISetUp()`: changing them afterwards has no
  effect. The subdomain setters and `FETISetConstraints()` are refused after `FETISetUp()`; to solve another problem
  call `FETISetSubdomains()` again (it starts a new problem) and give everything again. Give the subdomains before
  `FETISetConstraints()`.

  Level: beginner

.seealso: `FETISetSubdomainCoordinates()`, `FETISetSubdomainKernel()`, `FETISetSubdomainDirichletDofs()`, `FETISetConstraints()`
@*/
PetscErrorCode FETISetSubdomains(FETI feti, PetscInt nlocal, const Mat K[], const Vec f[])
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)feti);
  PetscMPIInt rank;

  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  FETI_Impl &impl = *feti->impl;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCheck(nlocal >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "FETISetSubdomains(): negative subdomain count %" PetscInt_FMT, nlocal);
  PetscCall(FETIReset(feti));
  impl.subdomainsgiven = PETSC_TRUE;
  PetscCallCXX(impl.sub.resize(nlocal));
  for (PetscInt s = 0; s < nlocal; s++) {
    FETISubdomain &sd = impl.sub[s];
    PetscInt       m, n, bs;
    PetscBool      ok;
    MPI_Comm       kcomm;
    PetscValidHeaderSpecific(K[s], MAT_CLASSID, 3);
    PetscCall(PetscObjectGetComm((PetscObject)K[s], &kcomm));
    PetscCallMPI(MPI_Comm_size(kcomm, &m));
    PetscCheck(m == 1, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "FETISetSubdomains(): K[%" PetscInt_FMT "] on rank %d must be sequential (PETSC_COMM_SELF)", s, rank);
    PetscCall(MatGetSize(K[s], &m, &n));
    PetscCheck(m == n, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "FETISetSubdomains(): K[%" PetscInt_FMT "] on rank %d is %" PetscInt_FMT " x %" PetscInt_FMT ", not square", s, rank, m, n);
    PetscCheck(m > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "FETISetSubdomains(): K[%" PetscInt_FMT "] on rank %d has 0 rows; a subdomain needs at least one node (leave empty subdomains out)", s, rank);
    PetscCall(MatGetBlockSize(K[s], &bs));
    PetscCheck(bs == 3, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
               "FETISetSubdomains(): K[%" PetscInt_FMT "] on rank %d has block size %" PetscInt_FMT "; 3D elasticity needs block size 3 (MatSetBlockSize(K, 3), dofs x,y,z per node)", s, rank, bs);
    PetscCall(PetscObjectTypeCompareAny((PetscObject)K[s], &ok, MATSEQAIJ, MATSEQSBAIJ, MATSEQBAIJ, ""));
    PetscCheck(ok, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "FETISetSubdomains(): K[%" PetscInt_FMT "] on rank %d has type %s; use MATSEQAIJ or MATSEQSBAIJ", s, rank, ((PetscObject)K[s])->type_name);
    PetscCall(PetscObjectReference((PetscObject)K[s]));
    sd.K = K[s];
    sd.n = m;
    if (f && f[s]) {
      PetscInt nf;
      PetscValidHeaderSpecific(f[s], VEC_CLASSID, 4);
      PetscCall(VecGetSize(f[s], &nf));
      PetscCheck(nf == m, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "FETISetSubdomains(): f[%" PetscInt_FMT "] on rank %d has %" PetscInt_FMT " entries but K has %" PetscInt_FMT " rows", s, rank, nf, m);
      PetscCall(CheckSubdomainVec(f[s], "FETISetSubdomains", "the load f[s]", s, m, ""));
      PetscCall(PetscObjectReference((PetscObject)f[s]));
      sd.f = f[s];
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode CheckLocal(FETI feti, PetscInt s)
{
  PetscFunctionBegin;
  PetscCheck(s >= 0 && s < (PetscInt)feti->impl->sub.size(), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
             "Local subdomain %" PetscInt_FMT " does not exist (this rank has %d; call FETISetSubdomains() first)", s, (int)feti->impl->sub.size());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETISetSubdomainCoordinates - Give the node coordinates of a subdomain, from which its six rigid-body modes are computed.

  Not Collective

  Input Parameters:
+ feti   - the FETI problem
. s      - local subdomain index
- coords - sequential vector, 3 entries (x, y, z) per node in the node order of K_s

  Notes:
  The coordinates also place the fixing nodes of the generalized inverse far apart.

  Level: beginner

.seealso: `FETISetSubdomainKernel()`, `FETISetSubdomains()`
@*/
PetscErrorCode FETISetSubdomainCoordinates(FETI feti, PetscInt s, Vec coords)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(CheckNotSetUp(feti, PETSC_COMM_SELF, "FETISetSubdomainCoordinates"));
  PetscCall(CheckLocal(feti, s));
  if (coords) {
    const PetscScalar *x;
    PetscValidHeaderSpecific(coords, VEC_CLASSID, 3);
    PetscCall(CheckSubdomainVec(coords, "FETISetSubdomainCoordinates", "coords", s, feti->impl->sub[s].n, " (need 3 per node, interleaved like the dofs)"));
    PetscCall(VecGetArrayRead(coords, &x));
    PetscCall(CheckFiniteArray(feti->impl->sub[s].n, x, "FETISetSubdomainCoordinates", "coords", s));
    PetscCall(VecRestoreArrayRead(coords, &x));
  }
  PetscCall(PetscObjectReference((PetscObject)coords));
  PetscCall(VecDestroy(&feti->impl->sub[s].coords));
  feti->impl->sub[s].coords = coords;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETISetSubdomainKernel - Give a basis of the null space of K_s instead of coordinates.

  Not Collective

  Input Parameters:
+ feti - the FETI problem
. s    - local subdomain index
- R    - sequential matrix n_s x k (any type convertible to MATSEQDENSE); k = 0 means K_s is nonsingular

  Notes:
  The columns are orthonormalized, unless they already are to 1e-12 (then they are kept to the bit, so that
  a problem read back with `FETILoad()` is the one written). With Dirichlet dofs kept in the primal, only the
  combinations vanishing on them are kept. The basis is checked against K_s (-feti_check).

  Level: intermediate

.seealso: `FETISetSubdomainCoordinates()`, `FETIGetSubdomainKernel()`
@*/
PetscErrorCode FETISetSubdomainKernel(FETI feti, PetscInt s, Mat R)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(CheckNotSetUp(feti, PETSC_COMM_SELF, "FETISetSubdomainKernel"));
  PetscCall(CheckLocal(feti, s));
  PetscCall(PetscObjectReference((PetscObject)R));
  PetscCall(MatDestroy(&feti->impl->sub[s].Ruser));
  feti->impl->sub[s].Ruser = R;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETISetSubdomainDirichletDofs - Keep u = 0 on some dofs of a subdomain in the primal space (FETI with Dirichlet conditions kept in the primal).

  Not Collective

  Input Parameters:
+ feti - the FETI problem
. s    - local subdomain index
- is   - local dof indices (0 <= i < n_s) where u = 0

  Notes:
  These dofs are removed from the subdomain space: K+ and R vanish there, K_s needs no modification,
  B's entries in these columns are ignored, and no gluing rows are needed at these dofs.
  The kernel of K_s becomes the rigid modes vanishing on them: none for a subdomain clamped on a face,
  one rotation for a subdomain touching them along an edge, three for a single node; it is computed,
  not assumed.

  Level: beginner

.seealso: `FETISetSubdomains()`, `FEMSetDirichletMode()`
@*/
PetscErrorCode FETISetSubdomainDirichletDofs(FETI feti, PetscInt s, IS is)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(CheckNotSetUp(feti, PETSC_COMM_SELF, "FETISetSubdomainDirichletDofs"));
  PetscCall(CheckLocal(feti, s));
  PetscCall(PetscObjectReference((PetscObject)is));
  PetscCall(ISDestroy(&feti->impl->sub[s].dirichlet));
  feti->impl->sub[s].dirichlet = is;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETISetSubdomainDirichletValues - Give the prescribed (nonzero) values of the Dirichlet dofs a subdomain keeps in the primal.

  Not Collective

  Input Parameters:
+ feti - the FETI problem
. s    - local subdomain index
- uD   - sequential vector of the subdomain's length n_s; its entries at the dofs of `FETISetSubdomainDirichletDofs()` are the
         prescribed displacements, the others are ignored (NULL: zero, the default)

  Notes:
  The values are lifted: `FETISetUp()` takes f_s - K_s u_D as the subdomain's load (K_s whole, before its
  Dirichlet rows and columns are removed), so that the problem on the free dofs is K u = f - K u_D, and
  `FETIRecoverPrimal()` puts u_D at those dofs. `FETIGetLoad()` returns the lifted load, which is what
  `FETIApplyK()` (zero on the Dirichlet dofs) balances. `FETIWrite()` writes the lifted problem: read back, it has
  the same multipliers and free dofs, and zeros at the Dirichlet dofs.

  Level: intermediate

.seealso: `FETISetSubdomainDirichletDofs()`, `FETIRecoverPrimal()`, `FEMSetDisplacement()`
@*/
PetscErrorCode FETISetSubdomainDirichletValues(FETI feti, PetscInt s, Vec uD)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(CheckNotSetUp(feti, PETSC_COMM_SELF, "FETISetSubdomainDirichletValues"));
  PetscCall(CheckLocal(feti, s));
  if (uD) PetscValidHeaderSpecific(uD, VEC_CLASSID, 3);
  if (uD) PetscCall(CheckSubdomainVec(uD, "FETISetSubdomainDirichletValues", "uD", s, feti->impl->sub[s].n, ""));
  if (uD) PetscCall(PetscObjectReference((PetscObject)uD));
  PetscCall(VecDestroy(&feti->impl->sub[s].uD));
  feti->impl->sub[s].uD = uD;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETISetConstraints - Give the constraint matrix B, the right-hand side c of B u = c, and the kind of each row.

  Collective

  Input Parameters:
+ feti  - the FETI problem
. B     - parallel AIJ matrix; rows are the multipliers (any row distribution), columns the primal vector
          with the column layout of the subdomains (local columns = this rank's subdomain dofs)
. c     - vector with B's row layout (NULL: zero)
- kinds - the kind of each locally owned row of B

  Notes:
  Rows of kind gluing and Dirichlet are equalities. Orthonormal rows (as `FEMCreateFETI()` makes)
  give the best conditioned F. `FETISolveLinear()` takes gluing and Dirichlet rows only; contact rows need the
  contact solver (`ContactProblem`). Call after `FETISetSubdomains()` and before `FETISetUp()`.

  Level: beginner

.seealso: `FETIRowKind`, `FETISetSubdomains()`, `FETIGetConstraints()`
@*/
PetscErrorCode FETISetConstraints(FETI feti, Mat B, Vec c, const FETIRowKind kinds[])
{
  MPI_Comm comm = PetscObjectComm((PetscObject)feti);
  PetscInt m;

  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  FETI_Impl &impl = *feti->impl;
  PetscValidHeaderSpecific(B, MAT_CLASSID, 2);
  if (c) PetscValidHeaderSpecific(c, VEC_CLASSID, 3);
  PetscCall(CheckNotSetUp(feti, comm, "FETISetConstraints"));
  /* FETISetSubdomains() starts a new problem (FETIReset()), which drops B: constraints given before it were lost */
  PetscCheck(impl.subdomainsgiven, comm, PETSC_ERR_ORDER,
             "FETISetConstraints() before FETISetSubdomains(): give the subdomains first (FETISetSubdomains() starts a new problem and would drop B), then the constraints");
  PetscCall(MatGetLocalSize(B, &m, NULL));
  PetscCheck(m == 0 || kinds, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "FETISetConstraints(): give the kind of each of the %" PetscInt_FMT " local rows of B", m);
  { /* NaN or Inf in B or c would come out as a NaN solution: name the first such row (collective, as is the call) */
    PetscInt           lo, hi, bad[2] = {PETSC_MAX_INT, PETSC_MAX_INT};
    const PetscScalar *ca;
    PetscCall(MatGetOwnershipRange(B, &lo, &hi));
    for (PetscInt r = lo; r < hi && bad[0] == PETSC_MAX_INT; r++) {
      PetscInt           nc;
      const PetscScalar *v;
      PetscCall(MatGetRow(B, r, &nc, NULL, &v));
      for (PetscInt j = 0; j < nc; j++)
        if (PetscIsInfOrNanScalar(v[j])) bad[0] = r;
      PetscCall(MatRestoreRow(B, r, &nc, NULL, &v));
    }
    if (c) {
      PetscInt mc;
      PetscCall(VecGetLocalSize(c, &mc));
      PetscCall(VecGetArrayRead(c, &ca));
      for (PetscInt r = 0; r < mc && r < hi - lo; r++)
        if (PetscIsInfOrNanScalar(ca[r])) {
          bad[1] = lo + r;
          break;
        }
      PetscCall(VecRestoreArrayRead(c, &ca));
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, bad, 2, MPIU_INT, MPI_MIN, comm));
    PetscCheck(bad[0] == PETSC_MAX_INT, comm, PETSC_ERR_ARG_OUTOFRANGE, "FETISetConstraints(): row %" PetscInt_FMT " of B has a non-finite entry (NaN or Inf)", bad[0]);
    PetscCheck(bad[1] == PETSC_MAX_INT, comm, PETSC_ERR_ARG_OUTOFRANGE, "FETISetConstraints(): entry %" PetscInt_FMT " of c (the right-hand side of B u = c) is not finite (NaN or Inf)", bad[1]);
  }
  PetscCall(PetscObjectReference((PetscObject)B));
  PetscCall(MatDestroy(&impl.B));
  impl.B = B;
  PetscCall(VecDestroy(&impl.c));
  if (c) {
    PetscInt mc;
    PetscCall(VecGetLocalSize(c, &mc));
    PetscCheck(mc == m, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "FETISetConstraints(): c has %" PetscInt_FMT " local entries but B has %" PetscInt_FMT " local rows", mc, m);
    PetscCall(PetscObjectReference((PetscObject)c));
    impl.c = c;
  }
  PetscCallCXX(impl.kinds.assign(kinds, kinds + m));
  for (PetscInt r = 0; r < m; r++)
    PetscCheck(kinds[r] >= FETI_ROW_GLUING && kinds[r] <= FETI_ROW_CONTACT_TANGENTIAL, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "FETISetConstraints(): local row %" PetscInt_FMT " has an unknown kind %d", r, (int)kinds[r]);
  impl.setupcalled = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETISetOptionsPrefix - Set the prefix of the FETI options (-<prefix>feti_...), of its KSP (-<prefix>feti_ksp_...),
  subdomain solvers (-<prefix>feti_sub_...) and coarse solver (-<prefix>feti_coarse_...).

  Logically Collective

  Input Parameters:
+ feti   - the FETI problem
- prefix - the prefix

  Level: intermediate

.seealso: `FETISetFromOptions()`
@*/
PetscErrorCode FETISetOptionsPrefix(FETI feti, const char prefix[])
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(PetscObjectSetOptionsPrefix((PetscObject)feti, prefix));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIAppendOptionsPrefix - Append to the prefix of the FETI options.

  Logically Collective

  Input Parameters:
+ feti   - the FETI problem
- prefix - the text to append

  Level: intermediate

.seealso: `FETISetOptionsPrefix()`
@*/
PetscErrorCode FETIAppendOptionsPrefix(FETI feti, const char prefix[])
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(PetscObjectAppendOptionsPrefix((PetscObject)feti, prefix));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The KSP of FETISolveLinear(): projected CG on P F P with a FETI preconditioner applied as P M^-1 P */
static PetscErrorCode FETICreateKSP(FETI feti)
{
  FETI_Impl  &impl = *feti->impl;
  const char *prefix;
  char        kspprefix[256];
  PC          pc;

  PetscFunctionBegin;
  if (impl.ksp) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)feti), &impl.ksp));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)feti, &prefix));
  PetscCall(PetscSNPrintf(kspprefix, sizeof(kspprefix), "%sfeti_", prefix ? prefix : ""));
  PetscCall(KSPSetOptionsPrefix(impl.ksp, kspprefix));
  /* KSPMPRGP without bounds is CG with reproducible (rank-count independent) inner products, so the iteration
     count does not depend on the number of MPI ranks; KSPCG's MPI_Allreduce of BLAS partial sums can move it by one */
  PetscCall(KSPSetType(impl.ksp, KSPMPRGP));
  PetscCall(KSPSetNormType(impl.ksp, KSP_NORM_UNPRECONDITIONED));
  PetscCall(KSPSetTolerances(impl.ksp, 1e-8, PETSC_DEFAULT, PETSC_DEFAULT, 1000));
  PetscCall(KSPGetPC(impl.ksp, &pc));
  PetscCall(PCSetType(pc, PCFETIDIRICHLET));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETISetFromOptions - Read the FETI options.

  Collective

  Input Parameter:
. feti - the FETI problem

  Options Database Keys:
+ -feti_kernel_tol <1e-8>      - a rigid mode counts as vanishing on the Dirichlet dofs when its RMS there is below this times its RMS overall
. -feti_check <true>           - check K_s R_s = 0 and K_s K_s+ K_s = K_s at setup (one solve per subdomain)
. -feti_check_tol <1e-6>       - relative tolerance of these checks
. -feti_fixing_nodes <8>       - well-separated candidate nodes among which the fixing dofs are pivoted
. -feti_kplus <implicit,explicit,auto> - how F products apply K+ (`FETISetKplusType()`): the factor, dense blocks on the dofs B touches, or per subdomain by the
  reads a block saves and the memory it takes (the contact layer's default: auto)
. -feti_kplus_explicit <bool>  - the same as -feti_kplus explicit (true) or implicit (false) (`FETISetKplusExplicit()`)
. -feti_kplus_memory_ratio <1> - auto: all dense blocks together take at most this many times the entries of all the sparse factors (`FETISetKplusMemoryRatio()`)
. -feti_kplus_precision <double,single> - storage of PETSc's block Cholesky factors for the F products (`FETISetKplusPrecision()`): single keeps a float copy (half the
  factor's memory traffic and memory, sums in double) and frees the double factor
. -feti_kplus_refine <false>  - with single: F products refine the float solves to double accuracy (`FETISetKplusRefine()`)
. -feti_dirichlet_pc_precision <single,double> - storage of the Dirichlet preconditioner's block Cholesky factors of K_ii (`PCFETIDIRICHLET`): single (the default) keeps float copies
. -feti_kplus_speedup <2>     - auto: a block is a candidate when an F product reads at least this many times fewer numbers of it than of the factor (`FETISetKplusSpeedup()`)
. -feti_kplus_memory_budget <MB> - auto: all dense blocks together take at most this many megabytes (all ranks; default: no bound but the ratio) (`FETISetKplusMemoryBudget()`)
. -feti_kplus_explicit_schur <true> - build those blocks from a MUMPS Schur complement (when MUMPS is there); false: by solves with the subdomain factor
. -feti_memory_budget <MB>     - memory the factorizations and explicit K+ blocks may take per node (default: what the node has available at setup); `FETISetUp()` drops
  the explicit blocks when only they exceed it and stops when the factorizations do
. -feti_view                   - view the problem after setup
. -feti_ksp_type, -feti_ksp_rtol, -feti_ksp_monitor, ... - the projected CG of `FETISolveLinear()` (default mprgp without bounds, i.e. CG with reproducible sums; rtol 1e-8,
  unpreconditioned norm)
. -feti_pc_type <dirichlet,lumped,none> - its preconditioner, applied as P M^-1 P
. -feti_sub_pc_factor_mat_solver_type <cholmod,mumps,petsc> - the sparse Cholesky of the subdomains
. -feti_coarse_mode <auto,single,redundant,parallel,split> - the direct solver of G G': factored once on rank 0 (solves gather there; the same numbers as on one rank), on
  every rank, in parallel (MUMPS), or by two parts and a separator, rank 0 solving one part and rank 1 the other (split; the same numbers on any number of ranks, one
  included); auto (default): split from -feti_coarse_split_dim and redundant below it, both below -feti_coarse_redundant_dim, single below -feti_coarse_parallel_dim,
  parallel from there
. -feti_coarse_split_dim <1000> - the coarse dimension from which auto splits (each of two ranks reads half of the factor per solve; docs/scale.md)
. -feti_coarse_redundant_dim <10000> - the coarse dimension below which auto factors on every rank (a small factor per rank; no rank waits for the coarse solves of rank 0)
. -feti_coarse_parallel_dim <50000> - the coarse dimension from which auto factors in parallel (a larger factor does not fit one rank's memory and time; docs/scale.md)
. -feti_coarse_check_tol <1e-3> - at setup the factors of G G' must solve a pseudo-random system to this fraction after one refinement, else G G' is singular (a motion
  nothing holds, which a Cholesky factorization lets through as a rounding-sized pivot) or hopelessly ill-conditioned; 0: no refusal (the check's solves still run
  when -feti_coarse_refine is -1, which they choose)
. -feti_coarse_refine <-1>     - steps of iterative refinement in every coarse solve (each one more product with G' and G and one more solve); -1 (default): chosen at
  setup from the check's residual r0 without refinement: none up to 1e-12 (every scene of this repository), else the fewest k with (100 r0)^k r0 <= 1e-12, at most 10
. -feti_rigid_rows <true>      - G = R'B' and G' = B R from each touched node's coordinates and each subdomain's 6 x k transform of its rigid-body modes, where every
  kernel is spanned by them (built from coordinates); false: from R's stored rows (k numbers per dof)
- -feti_coarse_pc_factor_mat_solver_type ... - its options (single: on rank 0; redundant: -feti_coarse_redundant_...)

  Level: beginner

.seealso: `FETISetUp()`, `FETISolveLinear()`
@*/
PetscErrorCode FETISetFromOptions(FETI feti)
{
  FETIKplusType kplustype;
  PetscBool     kplusexplicit, typeset, explicitset;
  const char   *prefix;

  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  FETI_Impl &impl = *feti->impl;
  kplustype       = impl.kplustype;
  kplusexplicit   = impl.kplustype == FETI_KPLUS_EXPLICIT ? PETSC_TRUE : PETSC_FALSE;
  PetscObjectOptionsBegin((PetscObject)feti);
  PetscCall(PetscOptionsReal("-feti_kernel_tol", "Relative RMS below which a rigid mode vanishes on the Dirichlet dofs", "FETISetSubdomainDirichletDofs", impl.kerneltol, &impl.kerneltol, NULL));
  PetscCall(PetscOptionsBool("-feti_check", "Check K R = 0 and K K+ K = K at setup", "FETISetUp", impl.check, &impl.check, NULL));
  PetscCall(PetscOptionsReal("-feti_check_tol", "Relative tolerance of the setup checks", "FETISetUp", impl.checktol, &impl.checktol, NULL));
  PetscCall(PetscOptionsInt("-feti_fixing_nodes", "Candidate nodes for the fixing dofs of K+", "FETISetUp", impl.nfixingcandidates, &impl.nfixingcandidates, NULL));
  PetscCall(PetscOptionsEnum("-feti_kplus",
                             "How F = B K+ B' applies K+: two triangular solves with the sparse factor (implicit), a dense block on the dofs B touches (explicit: cheaper products when they "
                             "are few, |b|^2 memory and a Schur complement at setup per subdomain), or per subdomain by the reads a block saves and its memory (auto, -feti_kplus_speedup, "
                             "-feti_kplus_memory_ratio, -feti_kplus_memory_budget)",
                             "FETISetKplusType", FETIKplusTypes, (PetscEnum)impl.kplustype, (PetscEnum *)&kplustype, &typeset));
  PetscCall(PetscOptionsBool("-feti_kplus_explicit", "The same as -feti_kplus explicit (true) or implicit (false)", "FETISetKplusExplicit", kplusexplicit, &kplusexplicit, &explicitset));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)feti, &prefix));
  if (explicitset) {
    PetscCheck(!typeset || kplustype == (kplusexplicit ? FETI_KPLUS_EXPLICIT : FETI_KPLUS_IMPLICIT), PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_INCOMP,
               "-%sfeti_kplus %s and -%sfeti_kplus_explicit %s contradict each other: give one of them", prefix ? prefix : "", FETIKplusTypes[kplustype], prefix ? prefix : "",
               kplusexplicit ? "true" : "false");
    kplustype = kplusexplicit ? FETI_KPLUS_EXPLICIT : FETI_KPLUS_IMPLICIT;
  }
  { /* PETSc's own message for a word that is not a number does not name the option */
    const char *const names[] = {"-feti_kplus_memory_ratio", "-feti_kplus_speedup", "-feti_kplus_memory_budget"};
    const char *const whats[] = {"the ratio of all blocks' numbers to all factors' entries, >= 0", "how many times fewer reads a block must cost than the factor, >= 1", "megabytes, > 0"};
    for (int i = 0; i < 3; i++) {
      char      text[64];
      PetscBool given;
      PetscCall(PetscOptionsGetString(((PetscObject)feti)->options, prefix, names[i], text, sizeof(text), &given));
      if (given) {
        char *end;
        (void)std::strtod(text, &end);
        PetscCheck(text[0] && !*end, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_WRONG, "-%s%s %s: not a number (%s)", prefix ? prefix : "", names[i] + 1, text, whats[i]);
      }
    }
  }
  PetscCall(PetscOptionsReal("-feti_kplus_memory_ratio", "-feti_kplus auto: all dense blocks (K+)_bb together (|b|^2 numbers each) take at most this many times the entries of all the sparse factors",
                             "FETISetKplusMemoryRatio", impl.kplusratio, &impl.kplusratio, NULL));
  PetscCheck(
      impl.kplusratio >= 0 && !PetscIsInfOrNanReal(impl.kplusratio), PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE,
      "-%sfeti_kplus_memory_ratio %g: the ratio of all blocks' numbers to all factors' entries is a finite number >= 0 (0: no block; 1, the default: the blocks at most as large as the factors)",
      prefix ? prefix : "", (double)impl.kplusratio);
  PetscCall(PetscOptionsEnum("-feti_kplus_precision",
                             "Storage of PETSc's block Cholesky factors of the subdomains: double, or single (a float copy, sums in double; the double factor is freed; K+ x outside F "
                             "products is refined against Kreg)",
                             "FETISetKplusPrecision", FETIKplusPrecisions, (PetscEnum)impl.kplusprecision, (PetscEnum *)&impl.kplusprecision, NULL));
  PetscCall(PetscOptionsBool("-feti_kplus_refine",
                             "With -feti_kplus_precision single: F products refine each float solve against Kreg to double accuracy (2 to 4 more solves each; for tolerances below "
                             "about 1e-6)",
                             "FETISetKplusRefine", impl.kplusrefine, &impl.kplusrefine, NULL));
  PetscCall(PetscOptionsEnum("-feti_dirichlet_pc_precision",
                             "Storage of the Dirichlet preconditioner's block Cholesky factors of the interior blocks K_ii: single (the default: a float copy, sums in double; "
                             "a preconditioner changes the convergence rate only) or double",
                             "PCFETIDIRICHLET", FETIKplusPrecisions, (PetscEnum)impl.pcprecision, (PetscEnum *)&impl.pcprecision, NULL));
  PetscCall(PetscOptionsReal("-feti_kplus_speedup",
                             "-feti_kplus auto: a subdomain's block is a candidate when an F product reads at least this many times fewer numbers of it (its triangle) than of the factor (twice)",
                             "FETISetKplusSpeedup", impl.kplusspeedup, &impl.kplusspeedup, NULL));
  PetscCheck(impl.kplusspeedup >= 1 && !PetscIsInfOrNanReal(impl.kplusspeedup), PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE,
             "-%sfeti_kplus_speedup %g: the factor's reads per F product over the block's is a finite number >= 1 (1: every block that is not slower; 2, the default: blocks that at least halve them)",
             prefix ? prefix : "", (double)impl.kplusspeedup);
  {
    PetscReal mb = impl.kplusbudget >= 0 ? impl.kplusbudget / 1048576.0 : 0;
    PetscBool set;
    PetscCall(PetscOptionsReal("-feti_kplus_memory_budget", "-feti_kplus auto: megabytes all dense blocks (K+)_bb together may take, all ranks (default: no bound but -feti_kplus_memory_ratio)",
                               "FETISetKplusMemoryBudget", mb, &mb, &set));
    if (set) {
      PetscCheck(mb > 0 && !PetscIsInfOrNanReal(mb), PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE,
                 "-%sfeti_kplus_memory_budget %g: the megabytes all blocks may take is a finite number > 0 (-feti_kplus_memory_ratio 0 for no block)", prefix ? prefix : "", (double)mb);
      impl.kplusbudget = mb * 1048576.0;
    }
  }
  PetscCall(PetscOptionsBool("-feti_kplus_explicit_schur", "Build the explicit K+ blocks from a MUMPS Schur complement (false: by solves with the subdomain factor)", "FETISetKplusExplicit",
                             impl.kplusschur, &impl.kplusschur, NULL));
  PetscCall(PetscOptionsEnum(
      "-feti_coarse_mode",
      "Direct solver of G G': factored on rank 0 only (single), on every rank (redundant), in parallel by MUMPS (parallel), by two parts and a separator, one part per "
      "rank (split), or auto: split from -feti_coarse_split_dim and redundant below it, both below -feti_coarse_redundant_dim, single below -feti_coarse_parallel_dim, parallel from there",
      "FETISetUp", FETICoarseModes, (PetscEnum)impl.coarsemode, (PetscEnum *)&impl.coarsemode, NULL));
  PetscCall(PetscOptionsInt("-feti_coarse_redundant_dim", "Coarse dimension below which -feti_coarse_mode auto factors G G' on every rank (redundant) instead of on rank 0 alone", "FETISetUp",
                            impl.coarseredundantdim, &impl.coarseredundantdim, NULL));
  PetscCheck(impl.coarseredundantdim >= 0, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE, "-%sfeti_coarse_redundant_dim %" PetscInt_FMT " must be >= 0", prefix ? prefix : "",
             impl.coarseredundantdim);
  PetscCall(PetscOptionsInt("-feti_coarse_split_dim",
                            "Coarse dimension from which -feti_coarse_mode auto solves G G' by two parts and a separator, one part per rank (split), below -feti_coarse_redundant_dim", "FETISetUp",
                            impl.coarsesplitdim, &impl.coarsesplitdim, NULL));
  PetscCheck(impl.coarsesplitdim >= 0, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE, "-%sfeti_coarse_split_dim %" PetscInt_FMT " must be >= 0", prefix ? prefix : "",
             impl.coarsesplitdim);
  PetscCall(PetscOptionsReal(
      "-feti_coarse_check_tol",
      "At setup the factors of G G' must solve (G G') x = b for a pseudo-random b to this fraction of |b| after one refinement, else G G' is singular (a motion nothing holds); 0: no check",
      "FETISetUp", impl.coarsechecktol, &impl.coarsechecktol, NULL));
  PetscCheck(impl.coarsechecktol >= 0 && impl.coarsechecktol < 1, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE, "-%sfeti_coarse_check_tol %g must be in [0, 1) (0: no check)",
             prefix ? prefix : "", (double)impl.coarsechecktol);
  PetscCall(PetscOptionsInt("-feti_coarse_refine",
                            "Steps of iterative refinement in every coarse solve (G G')^-1 x, each one more product with G' and G; -1: chosen at setup from the coarse check's unrefined residual r0 "
                            "(none up to 1e-12, else the fewest k with (100 r0)^k r0 <= 1e-12, at most 10)",
                            "FETISetUp", impl.coarserefine, &impl.coarserefine, NULL));
  PetscCheck(impl.coarserefine >= -1 && impl.coarserefine <= 10, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE,
             "-%sfeti_coarse_refine %" PetscInt_FMT " must be in [-1, 10] (-1: chosen at setup)", prefix ? prefix : "", impl.coarserefine);
  PetscCall(PetscOptionsInt("-feti_coarse_parallel_dim", "Coarse dimension from which -feti_coarse_mode auto factors G G' in parallel (MUMPS) instead of on rank 0", "FETISetUp",
                            impl.coarseparalleldim, &impl.coarseparalleldim, NULL));
  PetscCheck(impl.coarseparalleldim >= 0, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE, "-%sfeti_coarse_parallel_dim %" PetscInt_FMT " must be >= 0", prefix ? prefix : "",
             impl.coarseparalleldim);
  PetscCall(PetscOptionsBool("-feti_rigid_rows", "G and G' from the node coordinates and each subdomain's transform of its rigid-body modes (false: from the stored rows of R)", "FETISetUp",
                             impl.rigidrows, &impl.rigidrows, NULL));
  {
    PetscReal mb = impl.membudget > 0 ? impl.membudget / 1048576.0 : 0; /* read by FETIGetMemoryBudget() at setup; listed here for -help */
    PetscCall(PetscOptionsReal("-feti_memory_budget", "Megabytes the factorizations and explicit K+ blocks may take per node (default: what the node has available at setup)", "FETIGetMemoryBudget",
                               mb, &mb, NULL));
  }
  PetscCall(PetscOptionsName("-feti_view", "View the FETI problem after setup", "FETIView", NULL));
  PetscOptionsEnd();
  PetscCall(FETISetKplusType(feti, kplustype));
  PetscCheck(impl.kerneltol > 0, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE, "-%sfeti_kernel_tol %g must be positive", prefix ? prefix : "", (double)impl.kerneltol);
  PetscCheck(impl.checktol > 0, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE, "-%sfeti_check_tol %g must be positive", prefix ? prefix : "", (double)impl.checktol);
  PetscCheck(impl.nfixingcandidates >= 0, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE, "-%sfeti_fixing_nodes %" PetscInt_FMT " must be non-negative", prefix ? prefix : "",
             impl.nfixingcandidates);
  PetscCall(FETICreateKSP(feti));
  PetscCall(KSPSetFromOptions(impl.ksp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETISetProgress - A hook told how the setup and the linear solve progress: the phases of `FETISetUp()` (kernels,
  memory estimate, coarse problem, factorization of subdomain k of n, explicit (K+)_bb of subdomain k of n,
  operators) and the iterations of `FETISolveLinear()`.

  Logically Collective

  Input Parameters:
+ feti - the FETI problem
. fn   - the hook (NULL: none)
- ctx  - its context

  Notes:
  The library prints nothing; the hook decides (the conefeti program prints one line, docs/output.md). It is
  called on every rank with that rank's subdomain counts. A `ContactModel` passes its own hook on
  (`ContactModelSetProgress()`).

  Level: intermediate

.seealso: `ConeFETIProgressFn`, `ConeFETIProgressInfo`, `FETISetUp()`, `ContactModelSetProgress()`
@*/
PetscErrorCode FETISetProgress(FETI feti, ConeFETIProgressFn fn, void *ctx)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  feti->impl->progress.fn  = fn;
  feti->impl->progress.ctx = ctx;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  FETISetKplusExplicit - Apply K+ inside F = B K+ B' as a dense block on the dofs B touches, instead of two
  sparse triangular solves per subdomain.

  Logically Collective

  Input Parameters:
+ feti - the FETI problem
- flg  - `PETSC_TRUE` to build the dense blocks at setup

  Options Database Key:
. -feti_kplus_explicit <bool> - the same; read by `FETISetFromOptions()`, overrides this call

  Notes:
  The same as `FETISetKplusType()` with `FETI_KPLUS_EXPLICIT` (true) or `FETI_KPLUS_IMPLICIT` (false).

  Each local subdomain keeps a dense |b| x |b| block, b the dofs B touches (gluing, Dirichlet and contact
  dofs): the inverse of the Schur complement of the regularized K_s on b, which the subdomain's MUMPS
  factorization keeps (the subdomain solver becomes MUMPS unless -feti_sub_pc_factor_mat_solver_type names
  another package, which then costs a second, MUMPS, factorization; without MUMPS, |b| solves with the factor).
  Every F product then reads one triangle of the |b|^2 block (BLAS dsymv) per subdomain instead of twice the
  Cholesky factor. Worth it
  when an F product is needed many times (contact and friction: hundreds of products) and |b| is small
  against the subdomain; a linear FETI solve (tens of products) rarely recovers the setup. The contact
  layer asks for `FETI_KPLUS_AUTO`, which builds a block only where it costs at most the factor's memory; the
  default of a bare FETI object is off. Products with K+ itself (`FETIGetGeneralizedInverse()`)
  always use the factor.

  Level: intermediate

.seealso: `FETISetKplusType()`, `FETISetUp()`, `FETIGetOperators()`
@*/
PetscErrorCode FETISetKplusExplicit(FETI feti, PetscBool flg)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscValidLogicalCollectiveBool(feti, flg, 2);
  PetscCall(FETISetKplusType(feti, flg ? FETI_KPLUS_EXPLICIT : FETI_KPLUS_IMPLICIT));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  FETISetKplusType - How F = B K+ B' applies K+ in each subdomain: two sparse triangular solves with its factor,
  a dense block (K+)_bb on the dofs B touches, or a choice per subdomain by what each costs in memory.

  Logically Collective

  Input Parameters:
+ feti - the FETI problem
- type - `FETI_KPLUS_IMPLICIT` (the default of a bare FETI object), `FETI_KPLUS_EXPLICIT` (`FETISetKplusExplicit()`),
         or `FETI_KPLUS_AUTO` (the contact layer's default)

  Options Database Keys:
+ -feti_kplus <implicit,explicit,auto> - the same; read by `FETISetFromOptions()`, overrides this call
. -feti_kplus_explicit <bool>           - the same as explicit (true) or implicit (false)
. -feti_kplus_speedup <2>               - auto: the least ratio of a factor's reads per F product to its block's (`FETISetKplusSpeedup()`)
. -feti_kplus_memory_ratio <1>          - auto: the largest ratio of all blocks' numbers to all factors' entries (`FETISetKplusMemoryRatio()`)
- -feti_kplus_memory_budget <MB>        - auto: the most megabytes all blocks may take (`FETISetKplusMemoryBudget()`)

  Notes:
  auto factors every subdomain with its own package (the factor path's: PETSc's block Cholesky up to 3000 dofs,
  CHOLMOD above), then chooses from counts, the same way on any number of ranks. Time: a subdomain's block is a
  candidate when an F product reads at least -feti_kplus_speedup times fewer numbers of it (dsymv reads its
  triangle, |b|^2/2) than of the factor (two triangular solves read its entries, as the package reports them,
  twice). Memory: the block is |b|^2 numbers stored square next to the factor (which products with K+ itself still
  use); the candidates that save the most reads per stored number get their blocks first, while all blocks
  together stay within -feti_kplus_memory_ratio times the entries of all the factors and -feti_kplus_memory_budget.
  Those blocks come from a second, transient, MUMPS factorization that keeps the Schur complement on b (or,
  without MUMPS, |b| solves with the factor). On the brick at H/h = 6 (1029 dofs, |b| up to 654) only subdomains
  with |b| <= 455 qualify (30 of 1536 at 10^6, on the brick's edges); on the seed paper's three large cubes all three get their blocks (docs/scale.md).
  `FETIGetKplusType()` says how many did.

  explicit is the behaviour of `FETISetKplusExplicit()`: blocks in every subdomain whose block's triangle is not
  larger than twice its (estimated) factor, the subdomain's solver becomes MUMPS keeping the Schur complement
  (its factor and workspace stay beside the block); the results of the options that choose it are unchanged.

  Level: intermediate

.seealso: `FETIKplusType`, `FETIGetKplusType()`, `FETISetKplusExplicit()`, `FETISetKplusMemoryRatio()`, `FETISetUp()`
@*/
PetscErrorCode FETISetKplusType(FETI feti, FETIKplusType type)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscValidLogicalCollectiveEnum(feti, type, 2);
  PetscCheck(type >= FETI_KPLUS_AUTO && type <= FETI_KPLUS_IMPLICIT, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE, "Unknown FETIKplusType %d", (int)type);
  PetscCheck(!feti->impl->setupcalled || feti->impl->kplustype == type, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER,
             "FETISetKplusType() (-feti_kplus, -feti_kplus_explicit) must come before FETISetUp()");
  if (!feti->impl->setupcalled) {
    feti->impl->kplustype     = type;
    feti->impl->kplusexplicit = type == FETI_KPLUS_IMPLICIT ? PETSC_FALSE : PETSC_TRUE;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  FETIGetKplusType - How F products apply K+: the type asked for, and after `FETISetUp()` in how many subdomains a dense block was used.

  Not Collective

  Input Parameter:
. feti - the FETI problem

  Output Parameters:
+ type   - the type asked for (`FETISetKplusType()`); NULL if not needed
- blocks - after `FETISetUp()`, the subdomains (all ranks) whose F products use a dense block (K+)_bb (0 when they
           were dropped for memory, `FETIGetKplusExplicit()`); before it 0; NULL if not needed

  Level: intermediate

.seealso: `FETISetKplusType()`, `FETIGetKplusExplicit()`, `FETIView()`
@*/
PetscErrorCode FETIGetKplusType(FETI feti, FETIKplusType *type, PetscInt *blocks)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  if (type) *type = feti->impl->kplustype;
  if (blocks) *blocks = feti->impl->setupcalled && feti->impl->kplusexplicit ? feti->impl->nkplusblocks : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  FETISetKplusMemoryRatio - With `FETI_KPLUS_AUTO`, the largest ratio of all the dense blocks (K+)_bb (|b|^2
  numbers each, stored square) to the entries of all the subdomains' sparse factors.

  Logically Collective

  Input Parameters:
+ feti  - the FETI problem
- ratio - a finite number >= 0; 0: no block; 1 (the default): the blocks at most as large as the factors, i.e.
          at most twice the memory of F

  Options Database Key:
. -feti_kplus_memory_ratio <1> - the same; read by `FETISetFromOptions()`, overrides this call

  Notes:
  Only the candidates of -feti_kplus_speedup get blocks, those that save the most reads per stored number first;
  a candidate whose block would exceed the ratio is left out and the next ones are tried. The node's memory
  budget (-feti_memory_budget) can still drop every block.

  Level: advanced

.seealso: `FETISetKplusType()`, `FETIGetKplusType()`, `FETISetKplusSpeedup()`, `FETISetKplusMemoryBudget()`, `FETIGetMemoryEstimate()`
@*/
PetscErrorCode FETISetKplusMemoryRatio(FETI feti, PetscReal ratio)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscValidLogicalCollectiveReal(feti, ratio, 2);
  PetscCheck(ratio >= 0 && !PetscIsInfOrNanReal(ratio), PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE,
             "FETISetKplusMemoryRatio() (-feti_kplus_memory_ratio) %g: the ratio is a finite number >= 0", (double)ratio);
  PetscCheck(!feti->impl->setupcalled || feti->impl->kplusratio == ratio, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER,
             "FETISetKplusMemoryRatio() (-feti_kplus_memory_ratio) must come before FETISetUp()");
  feti->impl->kplusratio = ratio;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  FETISetKplusPrecision - The precision in which the subdomains' block Cholesky factors are stored for the F products.

  Logically Collective

  Input Parameters:
+ feti      - the FETI problem
- precision - `FETI_KPLUS_PRECISION_DOUBLE` (the default) or `FETI_KPLUS_PRECISION_SINGLE`

  Options Database Key:
. -feti_kplus_precision <double,single> - the same; read by `FETISetFromOptions()`, overrides this call

  Notes:
  The two triangular solves with a subdomain's factor read the whole factor twice and are bound by memory
  traffic. single copies each factor made by PETSc's own block Cholesky (the default package for subdomains of
  up to 3000 dofs in the F products, -feti_sub_pc_factor_mat_solver_type petsc) into float storage right after
  its factorization and frees the double factor: the factor takes about half the memory, and the solves read
  half as much. Vectors and sums stay double, so the solve is exact for the factor rounded to float, a symmetric
  operator that differs from K_s^-1 by about cond(K_s) times 6e-8. F products use it as it is (`FETISetKplusRefine()` refines them too); K+ x for the
  dual right-hand side h, the primal recovery and explicit blocks built by solves is refined against Kreg in
  double until it is as accurate as the double solve. Factors of other packages (CHOLMOD, MUMPS) stay double.
  With -feti_check the float copy is compared with the double solve at setup.

  Level: advanced

.seealso: `FETIKplusPrecision`, `FETIGetKplusPrecision()`, `FETISetKplusType()`, `FETISetUp()`
@*/
PetscErrorCode FETISetKplusPrecision(FETI feti, FETIKplusPrecision precision)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscValidLogicalCollectiveEnum(feti, precision, 2);
  PetscCheck(precision == FETI_KPLUS_PRECISION_DOUBLE || precision == FETI_KPLUS_PRECISION_SINGLE, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE,
             "FETISetKplusPrecision() (-feti_kplus_precision): unknown FETIKplusPrecision %d (double or single)", (int)precision);
  PetscCheck(!feti->impl->setupcalled || feti->impl->kplusprecision == precision, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER,
             "FETISetKplusPrecision() (-feti_kplus_precision) must come before FETISetUp()");
  feti->impl->kplusprecision = precision;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  FETISetKplusRefine - Whether F products refine the float factors' solves to double accuracy.

  Logically Collective

  Input Parameters:
+ feti   - the FETI problem
- refine - `PETSC_TRUE`: refine; `PETSC_FALSE` (the default): F products take the float solve as it is

  Options Database Key:
. -feti_kplus_refine <false> - the same; read by `FETISetFromOptions()`, overrides this call

  Notes:
  Matters only for the subdomains whose factor is stored in float (`FETISetKplusPrecision()`). Their solve is exact
  for the factor rounded to float, which perturbs F by about cond(K_s) times 6e-8 (relative); a solve of the dual
  problem to a tighter relative tolerance then stalls at that floor. With refinement every F product corrects each
  such solve against Kreg in double, as K+ x outside F products always is, until it is as accurate as the double
  solve: F is then the double operator, at 2 to 4 more float solves (and products with Kreg) per subdomain and
  product. Unlike the precision, it may be changed at any time, also between solves: the contact layer turns it
  on for its solves below a relative tolerance of 1e-6 (`ContactModelSolve()`), and off again after them.

  Level: advanced

.seealso: `FETIGetKplusRefine()`, `FETISetKplusPrecision()`, `FETIGetKplusPrecision()`
@*/
PetscErrorCode FETISetKplusRefine(FETI feti, PetscBool refine)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscValidLogicalCollectiveBool(feti, refine, 2);
  feti->impl->kplusrefine = refine;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  FETIGetKplusRefine - Whether F products refine the float factors' solves to double accuracy.

  Not Collective

  Input Parameter:
. feti - the FETI problem

  Output Parameter:
. refine - as set by `FETISetKplusRefine()` or -feti_kplus_refine

  Level: advanced

.seealso: `FETISetKplusRefine()`, `FETIGetKplusPrecision()`
@*/
PetscErrorCode FETIGetKplusRefine(FETI feti, PetscBool *refine)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscAssertPointer(refine, 2);
  *refine = feti->impl->kplusrefine;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  FETIGetKplusPrecision - The precision of the subdomains' factors: asked for, and after `FETISetUp()` how many
  factors are stored in float and how much memory the block Cholesky factors take.

  Not Collective

  Input Parameter:
. feti - the FETI problem

  Output Parameters:
+ precision   - what was asked for (`FETISetKplusPrecision()`); NULL if not needed
. nsingle     - after `FETISetUp()`, the subdomains (all ranks) whose factor is stored in float; 0 before; NULL if not needed
. factorbytes - after `FETISetUp()`, bytes (all ranks) of PETSc's block Cholesky factors as they are kept (float copies
                or double factors: values, block columns, row starts); 0 before or without such factors; NULL if not needed
- doublebytes - the same factors as PETSc stores them in double (equal to factorbytes with double); NULL if not needed

  Level: advanced

.seealso: `FETISetKplusPrecision()`, `FETIView()`
@*/
PetscErrorCode FETIGetKplusPrecision(FETI feti, FETIKplusPrecision *precision, PetscInt *nsingle, PetscReal *factorbytes, PetscReal *doublebytes)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  if (precision) *precision = feti->impl->kplusprecision;
  if (nsingle) *nsingle = feti->impl->setupcalled ? feti->impl->nkplussingle : 0;
  if (factorbytes) *factorbytes = feti->impl->setupcalled ? feti->impl->kplusfactorbytes : 0;
  if (doublebytes) *doublebytes = feti->impl->setupcalled ? feti->impl->kplusdoublebytes : 0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  FETISetKplusSpeedup - With `FETI_KPLUS_AUTO`, how many times fewer numbers an F product must read of a
  subdomain's dense block (K+)_bb than of its sparse factor for the block to be a candidate.

  Logically Collective

  Input Parameters:
+ feti    - the FETI problem
- speedup - a finite number >= 1; 1: every block that is not slower; 2 (the default): blocks that at least halve
            the reads

  Options Database Key:
. -feti_kplus_speedup <2> - the same; read by `FETISetFromOptions()`, overrides this call

  Notes:
  The reads are counts, not timings (the choice is the same on every run and number of ranks): the factor's
  entries as its package reports them, read twice (forward and backward solve; PETSc's block Cholesky counts its
  column indices too), against the block's triangle, |b|^2/2 numbers. The candidates then share the memory of
  `FETISetKplusMemoryRatio()` and `FETISetKplusMemoryBudget()`.

  Level: advanced

.seealso: `FETISetKplusType()`, `FETISetKplusMemoryRatio()`, `FETISetKplusMemoryBudget()`
@*/
PetscErrorCode FETISetKplusSpeedup(FETI feti, PetscReal speedup)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscValidLogicalCollectiveReal(feti, speedup, 2);
  PetscCheck(speedup >= 1 && !PetscIsInfOrNanReal(speedup), PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE,
             "FETISetKplusSpeedup() (-feti_kplus_speedup) %g: the speedup is a finite number >= 1", (double)speedup);
  PetscCheck(!feti->impl->setupcalled || feti->impl->kplusspeedup == speedup, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER,
             "FETISetKplusSpeedup() (-feti_kplus_speedup) must come before FETISetUp()");
  feti->impl->kplusspeedup = speedup;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  FETISetKplusMemoryBudget - With `FETI_KPLUS_AUTO`, the most megabytes all the dense blocks (K+)_bb together may
  take, over all ranks.

  Logically Collective

  Input Parameters:
+ feti - the FETI problem
- mb   - megabytes, a finite number > 0; `PETSC_DETERMINE`: no bound but `FETISetKplusMemoryRatio()` (the default)

  Options Database Key:
. -feti_kplus_memory_budget <MB> - the same; read by `FETISetFromOptions()`, overrides this call

  Notes:
  A bound in absolute terms beside the ratio to the factors; the tighter of the two holds. Not the node's budget
  of -feti_memory_budget, which bounds the factors and blocks of each node before they are built.

  Level: advanced

.seealso: `FETISetKplusType()`, `FETISetKplusMemoryRatio()`, `FETISetKplusSpeedup()`
@*/
PetscErrorCode FETISetKplusMemoryBudget(FETI feti, PetscReal mb)
{
  PetscReal bytes = mb == (PetscReal)PETSC_DETERMINE ? -1 : mb * 1048576.0;

  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscValidLogicalCollectiveReal(feti, mb, 2);
  PetscCheck(mb == (PetscReal)PETSC_DETERMINE || (mb > 0 && !PetscIsInfOrNanReal(mb)), PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_OUTOFRANGE,
             "FETISetKplusMemoryBudget() (-feti_kplus_memory_budget) %g: megabytes, a finite number > 0 (or PETSC_DETERMINE: no bound)", (double)mb);
  PetscCheck(!feti->impl->setupcalled || feti->impl->kplusbudget == bytes, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER,
             "FETISetKplusMemoryBudget() (-feti_kplus_memory_budget) must come before FETISetUp()");
  feti->impl->kplusbudget = bytes;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  FETIGetKplusExplicit - Whether F products use the explicit dense blocks of K+: before `FETISetUp()` what was asked
  for, after it what was actually chosen.

  Not Collective

  Input Parameter:
. feti - the FETI problem

  Output Parameters:
+ flg      - `PETSC_TRUE` when the explicit blocks are (or will be) used, in at least one subdomain (a subdomain
             whose block would be larger than its sparse factor, e.g. a wide slab one cell thick, keeps the factor;
             `FETIView()` counts them)
- fallback - `PETSC_TRUE` when they were asked for but `FETISetUp()` did not build them because they would not fit
             in memory (`FETIGetMemoryEstimate()`, -feti_memory_budget); NULL if not needed

  Level: intermediate

.seealso: `FETISetKplusExplicit()`, `FETIGetMemoryEstimate()`, `FETISetUp()`
@*/
PetscErrorCode FETIGetKplusExplicit(FETI feti, PetscBool *flg, PetscBool *fallback)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscValidBoolPointer(flg, 2);
  *flg = feti->impl->kplusexplicit;
  if (fallback) *fallback = feti->impl->kplusfallback;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetKSP - The KSP that `FETISolveLinear()` uses (prefix feti_).

  Not Collective

  Input Parameter:
. feti - the FETI problem

  Output Parameter:
. ksp - the KSP (do not destroy)

  Level: intermediate

.seealso: `FETISolveLinear()`
@*/
PetscErrorCode FETIGetKSP(FETI feti, KSP *ksp)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(FETICreateKSP(feti));
  *ksp = feti->impl->ksp;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIView - Print the sizes of the FETI problem: subdomains, primal, dual and coarse dimensions, kernel dimensions, solvers.

  Collective

  Input Parameters:
+ feti   - the FETI problem
- viewer - an ASCII viewer (NULL: stdout)

  Options Database Key:
. -feti_view - view after `FETISetUp()`

  Level: beginner

.seealso: `FETISetUp()`
@*/
PetscErrorCode FETIView(FETI feti, PetscViewer viewer)
{
  PetscBool ascii;
  MPI_Comm  comm = PetscObjectComm((PetscObject)feti);

  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  FETI_Impl &impl = *feti->impl;
  if (!viewer) PetscCall(PetscViewerASCIIGetStdout(comm, &viewer));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(PETSC_SUCCESS);
  {
    PetscMPIInt size;
    const char *prefix;
    PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)feti), &size));
    PetscCall(PetscObjectGetOptionsPrefix((PetscObject)feti, &prefix));
    PetscCall(PetscViewerASCIIPrintf(viewer, "FETI Object: %s%s%s%d MPI process%s\n", prefix ? "(" : "", prefix ? prefix : "", prefix ? ") " : "", size, size > 1 ? "es" : ""));
  }
  PetscCall(PetscViewerASCIIPushTab(viewer));
  if (!impl.setupcalled) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "not set up\n"));
  } else {
    PetscInt nd, counts[4] = {0, 0, 0, 0}, kmin = PETSC_MAX_INT, kmax = 0, nmin = PETSC_MAX_INT, nmax = 0, removed = 0;
    for (FETIRowKind k : impl.kinds) counts[k]++;
    for (const FETISubdomain &sd : impl.sub) {
      kmin = std::min(kmin, sd.nkernel);
      kmax = std::max(kmax, sd.nkernel);
      nmin = std::min(nmin, sd.n);
      nmax = std::max(nmax, sd.n);
      removed += (PetscInt)sd.fixing.size();
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 4, MPIU_INT, MPI_SUM, comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &kmin, 1, MPIU_INT, MPI_MIN, comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nmin, 1, MPIU_INT, MPI_MIN, comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &kmax, 1, MPIU_INT, MPI_MAX, comm));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nmax, 1, MPIU_INT, MPI_MAX, comm));
    PetscCall(MatGetSize(impl.B, &nd, NULL));
    PetscCall(PetscViewerASCIIPrintf(viewer, "subdomains: %" PetscInt_FMT " (dofs per subdomain %" PetscInt_FMT "..%" PetscInt_FMT ", kernel dimension %" PetscInt_FMT "..%" PetscInt_FMT ")\n",
                                     impl.nglobalsub, nmin, nmax, kmin, kmax));
    PetscCall(PetscViewerASCIIPrintf(viewer, "primal dimension %" PetscInt_FMT ", dual dimension %" PetscInt_FMT ", coarse dimension %" PetscInt_FMT "\n", impl.nprimal, nd, impl.ncoarse));
    PetscCall(PetscViewerASCIIPrintf(viewer, "rows: %" PetscInt_FMT " gluing, %" PetscInt_FMT " dirichlet, %" PetscInt_FMT " contact normal, %" PetscInt_FMT " contact tangential\n", counts[0],
                                     counts[1], counts[2], counts[3]));
    if (impl.growsset) { /* the choice of FETISetUpCoarseRows(), made at the first product with G or G' */
      PetscInt nodes = (PetscInt)impl.rigid.nodebase.size(), rows = (PetscInt)impl.grows.size();
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nodes, 1, MPIU_INT, MPI_SUM, comm));
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &rows, 1, MPIU_INT, MPI_SUM, comm));
      if (impl.rigid.use) PetscCall(PetscViewerASCIIPrintf(viewer, "G and G': through the rigid-body modes of the %" PetscInt_FMT " nodes B touches (-feti_rigid_rows)\n", nodes));
      else PetscCall(PetscViewerASCIIPrintf(viewer, "G and G': through the stored rows of R at the %" PetscInt_FMT " dofs B touches\n", rows));
    }
    if (!impl.sub.empty()) {
      PC            pc;
      MatSolverType type;
      PetscCall(KSPGetPC(impl.sub[0].ksp, &pc));
      PetscCall(PCFactorGetMatSolverType(pc, &type));
      PetscCall(PetscViewerASCIIPrintf(viewer, "generalized inverse: Cholesky (%s) with fixing dofs; first local subdomain: %" PetscInt_FMT " fixing dofs\n", type ? type : "petsc",
                                       (PetscInt)impl.sub[0].fixing.size()));
    }
    if (impl.kplustype == FETI_KPLUS_AUTO && !impl.kplusfallback) {
      PetscInt nbmax = 0;
      for (const FETISubdomain &sd : impl.sub)
        if (!sd.kplusimplicit) nbmax = std::max(nbmax, (PetscInt)sd.kb.size());
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nbmax, 1, MPIU_INT, MPI_MAX, comm));
      PetscCall(PetscViewerASCIIPrintf(viewer,
                                       "F products (-feti_kplus auto): explicit dense K+ blocks in %" PetscInt_FMT " of %" PetscInt_FMT " subdomains (at most %" PetscInt_FMT
                                       " dofs), two triangular solves with the factor in %" PetscInt_FMT "\n",
                                       impl.nkplusblocks, impl.nglobalsub, nbmax, impl.nkplusimplicit));
      PetscCall(PetscViewerASCIIPrintf(viewer,
                                       "  a block where an F product reads at least %g times fewer numbers of it than of the factor (-feti_kplus_speedup), the most reads saved per number "
                                       "first, all blocks within %g times the factors' entries (-feti_kplus_memory_ratio)%s; factors %.1f MB, blocks %.1f MB (all ranks, 8 bytes per entry)\n",
                                       (double)impl.kplusspeedup, (double)impl.kplusratio, impl.kplusbudget >= 0 ? " and -feti_kplus_memory_budget" : "", 8.0 * impl.kplusfactorentries / 1048576.0,
                                       8.0 * impl.kplusblockentries / 1048576.0));
    } else if (impl.kplusexplicit) {
      PetscInt nbmax = 0;
      for (const FETISubdomain &sd : impl.sub) nbmax = std::max(nbmax, (PetscInt)sd.kb.size());
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nbmax, 1, MPIU_INT, MPI_MAX, comm));
      PetscCall(PetscViewerASCIIPrintf(viewer, "F products: explicit dense K+ on the dofs B touches (at most %" PetscInt_FMT " per subdomain)\n", nbmax));
      if (impl.nkplusimplicit)
        PetscCall(PetscViewerASCIIPrintf(viewer, "  except %" PetscInt_FMT " subdomain(s) whose block would be larger than the factor: two triangular solves there\n", impl.nkplusimplicit));
    } else if (impl.nkplusimplicit)
      PetscCall(PetscViewerASCIIPrintf(viewer, "F products: two triangular solves per subdomain (explicit K+ asked for, but every block would be larger than its factor)\n"));
    else
      PetscCall(
          PetscViewerASCIIPrintf(viewer, "F products: two triangular solves per subdomain%s\n", impl.kplusfallback ? " (explicit K+ blocks asked for, dropped: they would not fit in memory)" : ""));
    if (impl.kplusdoublebytes > 0)
      PetscCall(PetscViewerASCIIPrintf(viewer, "block Cholesky factors (-feti_kplus_precision %s): %" PetscInt_FMT " of %" PetscInt_FMT " stored in float, %.1f MB (%.1f MB in double; all ranks)\n",
                                       FETIKplusPrecisions[impl.kplusprecision], impl.nkplussingle, impl.nglobalsub, impl.kplusfactorbytes / 1048576.0, impl.kplusdoublebytes / 1048576.0));
    if (impl.memfactors >= 0)
      PetscCall(PetscViewerASCIIPrintf(viewer, "memory estimate (node of rank 0): factors %.1f MB, explicit K+ blocks %.1f MB, budget %.1f MB\n", impl.memfactors / 1048576.0,
                                       impl.memblocks / 1048576.0, impl.membudget / 1048576.0));
    if (impl.ncoarse) {
      PetscCall(FETICoarseSolverView(impl.coarse, viewer));
      if (impl.coarsesteps && impl.coarseres0 >= 0)
        PetscCall(PetscViewerASCIIPrintf(viewer, "coarse solves refined by %" PetscInt_FMT " step(s) each (-feti_coarse_refine %" PetscInt_FMT "; unrefined residual of the check %.1e)\n",
                                         impl.coarsesteps, impl.coarserefine, (double)impl.coarseres0));
      else if (impl.coarsesteps) PetscCall(PetscViewerASCIIPrintf(viewer, "coarse solves refined by %" PetscInt_FMT " step(s) each (-feti_coarse_refine)\n", impl.coarsesteps));
    }
  }
  PetscCall(PetscViewerASCIIPopTab(viewer));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIViewFromOptions - View the FETI problem if an option asks for it.

  Collective

  Input Parameters:
+ feti - the FETI problem
. obj  - optional object whose prefix is used
- name - the option name, e.g. "-feti_view"

  Level: intermediate

.seealso: `FETIView()`
@*/
PetscErrorCode FETIViewFromOptions(FETI feti, PetscObject obj, const char name[])
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCall(PetscObjectViewFromOptions((PetscObject)feti, obj, name));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetNumSubdomains - Subdomain counts.

  Not Collective

  Input Parameter:
. feti - the FETI problem, set up

  Output Parameters:
+ nglobal - total number of subdomains
. nlocal  - number on this rank
- first   - global index of this rank's first subdomain

  Level: intermediate

.seealso: `FETIGetSubdomainOffset()`
@*/
PetscErrorCode FETIGetNumSubdomains(FETI feti, PetscInt *nglobal, PetscInt *nlocal, PetscInt *first)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCheck(feti->impl->setupcalled, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER, "Call FETISetUp() first");
  if (nglobal) *nglobal = feti->impl->nglobalsub;
  if (nlocal) *nlocal = (PetscInt)feti->impl->sub.size();
  if (first) *first = feti->impl->firstsub;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetSubdomainOffset - Where a local subdomain's dofs and rigid modes are in the global primal and coarse vectors.

  Not Collective

  Input Parameters:
+ feti - the FETI problem, set up
- s    - local subdomain index

  Output Parameters:
+ primal - global index of its first primal dof
- coarse - global index of its first kernel column (its modes are coarse + 0 .. k-1)

  Level: intermediate

.seealso: `FETIGetNumSubdomains()`, `FETIGetSubdomainKernel()`
@*/
PetscErrorCode FETIGetSubdomainOffset(FETI feti, PetscInt s, PetscInt *primal, PetscInt *coarse)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCheck(feti->impl->setupcalled, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER, "Call FETISetUp() first");
  PetscCall(CheckLocal(feti, s));
  if (primal) *primal = feti->impl->sub[s].offset;
  if (coarse) *coarse = feti->impl->sub[s].coarseoffset;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetSizes - Global dimensions of the FETI problem.

  Not Collective

  Input Parameter:
. feti - the FETI problem, set up

  Output Parameters:
+ nprimal - primal dimension (sum of subdomain dofs)
. ndual   - number of multipliers (rows of B)
- ncoarse - coarse dimension (total kernel dimension; rows of G)

  Level: beginner

.seealso: `FETICreateVecs()`
@*/
PetscErrorCode FETIGetSizes(FETI feti, PetscInt *nprimal, PetscInt *ndual, PetscInt *ncoarse)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCheck(feti->impl->setupcalled, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER, "Call FETISetUp() first");
  if (nprimal) *nprimal = feti->impl->nprimal;
  if (ndual) PetscCall(MatGetSize(feti->impl->B, ndual, NULL));
  if (ncoarse) *ncoarse = feti->impl->ncoarse;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetSubdomainKernel - The kernel basis used for a local subdomain (orthonormal columns).

  Not Collective

  Input Parameters:
+ feti - the FETI problem, set up
- s    - local subdomain index

  Output Parameter:
. R - new sequential dense matrix n_s x k (destroy it)

  Level: intermediate

.seealso: `FETISetSubdomainKernel()`, `FETIGetKernel()`
@*/
PetscErrorCode FETIGetSubdomainKernel(FETI feti, PetscInt s, Mat *R)
{
  Mat      Rd;
  PetscInt cstart;

  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCheck(feti->impl->setupcalled, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER, "Call FETISetUp() first");
  PetscCall(CheckLocal(feti, s));
  const FETISubdomain &sd = feti->impl->sub[s];
  /* the kernels live in the block-diagonal global R: copy this subdomain's block */
  PetscCall(MatGetOwnershipRangeColumn(feti->impl->R, &cstart, NULL));
  PetscCall(MatGetDiagonalBlock(feti->impl->R, &Rd));
  PetscCall(MatCreateSeqDense(PETSC_COMM_SELF, sd.n, sd.nkernel, NULL, R));
  for (PetscInt i = 0; i < sd.n; i++) {
    const PetscInt    *cols;
    const PetscScalar *vals;
    PetscInt           ncols;
    PetscCall(MatGetRow(Rd, sd.localoffset + i, &ncols, &cols, &vals));
    for (PetscInt k = 0; k < ncols; k++) PetscCall(MatSetValue(*R, i, cols[k] - (sd.coarseoffset - cstart), vals[k], INSERT_VALUES));
    PetscCall(MatRestoreRow(Rd, sd.localoffset + i, &ncols, &cols, &vals));
  }
  PetscCall(MatAssemblyBegin(*R, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*R, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETIGetSubdomainFixingDofs - The dofs removed to make the regularized K_s nonsingular.

  Not Collective

  Input Parameters:
+ feti - the FETI problem, set up
- s    - local subdomain index

  Output Parameter:
. is - new index set of local dofs (destroy it)

  Level: developer

.seealso: `FETIGetGeneralizedInverse()`
@*/
PetscErrorCode FETIGetSubdomainFixingDofs(FETI feti, PetscInt s, IS *is)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  PetscCheck(feti->impl->setupcalled, PetscObjectComm((PetscObject)feti), PETSC_ERR_ORDER, "Call FETISetUp() first");
  PetscCall(CheckLocal(feti, s));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)feti->impl->sub[s].fixing.size(), feti->impl->sub[s].fixing.data(), PETSC_COPY_VALUES, is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

#define FETI_SINGULAR_COARSE_MESSAGE                                                                                                                                     \
  "some combination of the subdomains' rigid-body modes satisfies every row of B, so nothing holds it: a body (or a part of one) without a Dirichlet row, held only by " \
  "frictionless contact rows, or touching only along a line it can turn about. A FEM model's ContactModelSetUp() names such a motion before this point; with "           \
  "FETISetConstraints() directly, check that the rows hold every floating subdomain"

/* A Cholesky factorization meets a zero pivot only when G G' is singular to the last bits: with more than two
   subdomains in a chain, the pivot of a motion that nothing holds is rounding noise of the other pivots' size, no
   failure, and every solve then came out "converged" with a rigid motion of arbitrary size (the tip of a free
   cantilever moved by whatever the rounding gave, one value per solver package). So the factors must solve
   (G G') x = b for a b that is no combination of G's rows: a fixed pseudo-random vector (its entries from their global
   index, the same on any number of ranks), with one step of iterative refinement. A singular G G' keeps b's part in
   its null space and more: the refinement diverges, the residual is about |b| (1 to 6 on the handoff bar without its
   clamp). A nonsingular one leaves rounding times its condition, which grows like the length of a chain of subdomains
   to the fourth (the clamped bar of tutorials/feti/ex1_handoff: 7e-14 at 8 slabs of one cell, 2e-10 at 64, 1.4e-6 at
   1024), hence the tolerance 1e-3. -info prints the residual and a condition estimate (|G G' b| / |b| times |x| / |b|).
   The residual of the first solve, before the refinement, also chooses the refinement of every coarse solve
   (SetUpCoarseRefinement()). Two coarse solves and three products with G and G' at setup; no count of the solve changes. */
static PetscErrorCode CheckCoarseSolvable(FETI feti)
{
  FETI_Impl &impl = *feti->impl;
  Vec        b, x, dx, r, w;
  PetscReal  bnorm, rnorm, xnorm, abnorm, r0norm = 0;

  PetscFunctionBegin;
  PetscCall(VecDuplicate(impl.wc1, &b));
  PetscCall(VecDuplicate(impl.wc1, &x));
  PetscCall(VecDuplicate(impl.wc1, &dx));
  PetscCall(VecDuplicate(impl.wc1, &r));
  PetscCall(VecDuplicate(impl.wd1, &w));
  PetscCall(FETISetPseudoRandom_Private(b));
  PetscCall(VecSet(x, 0.0));
  PetscCall(VecCopy(b, r));
  for (int step = 0; step < 2; step++) { /* x += (G G')^-1 r, r = b - G G' x */
    PetscCall(FETICoarseSolverApply(impl.coarse, r, dx));
    PetscCall(VecAXPY(x, 1.0, dx));
    PetscCall(FETIApplyGt(feti, x, w));
    PetscCall(FETIApplyG(feti, w, r));
    PetscCall(VecAYPX(r, -1.0, b));
    if (!step) PetscCall(VecNorm(r, NORM_2, &r0norm));
  }
  PetscCall(VecNorm(b, NORM_2, &bnorm));
  PetscCall(VecNorm(r, NORM_2, &rnorm));
  PetscCall(VecNorm(x, NORM_2, &xnorm));
  PetscCall(FETIApplyGt(feti, b, w));
  PetscCall(FETIApplyG(feti, w, dx));
  PetscCall(VecNorm(dx, NORM_2, &abnorm));
  PetscCall(PetscInfo(feti, "coarse problem: |b - G G' x| / |b| = %g for a pseudo-random b, %g after one refinement (%s -feti_coarse_check_tol %g); condition estimate %g\n", (double)(r0norm / bnorm),
                      (double)(rnorm / bnorm), impl.coarsechecktol > 0 ? "singular above" : "no refusal:", (double)impl.coarsechecktol, (double)(abnorm / bnorm * xnorm / bnorm)));
  for (Vec *v : {&b, &x, &dx, &r, &w}) PetscCall(VecDestroy(v));
  impl.coarseres0 = r0norm / bnorm;
  PetscCheck(!(impl.coarsechecktol > 0) || rnorm <= impl.coarsechecktol * bnorm, PetscObjectComm((PetscObject)feti), PETSC_ERR_CONV_FAILED,
             "The coarse matrix G G' is singular, or so ill-conditioned that its factors solve (G G') x = b only to %.1e of |b| for a pseudo-random b (-feti_coarse_check_tol %g; 0 "
             "skips this check): " FETI_SINGULAR_COARSE_MESSAGE,
             (double)(rnorm / bnorm), (double)impl.coarsechecktol);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The projector P = I - G'(G G')^-1 G is only as good as G (P x) = 0 holds: a coarse solve whose residual is
   rounding times |G G'| |y| leaves that much of range(G') in P x. With a well-conditioned G G' that is rounding of
   |G x|; on a long chain of subdomains, where G G' gets ill-conditioned like the chain's length to the fourth, it
   is not: the projected CG of the clamped bar of tutorials/feti/ex1_handoff (slabs of one cell) then stalls at a
   relative residual of about ten times the check's unrefined residual (1.6e-8 at 96 slabs, above the default rtol
   1e-8), and ended DIVERGED_BREAKDOWN from 96 slabs on. A step of iterative refinement with the residual formed
   through G' and G, r = x - G (G' y), brings it down to rounding of |G' y|, what the projector needs: with one step
   the bar converges in 8-9 iterations up to 512 slabs (unrefined residual 3e-7), with two at 1024 (2e-6), to the
   deflections that follow the shorter bars'. The check's unrefined residual r0 for a pseudo-random b, about 2e-16
   times G G''s condition, chooses the steps: none up to 1e-12 (every shipped scene: 6e-15 to 1.5e-13; the bar up to
   16 slabs), else the fewest k with (100 r0)^k r0 <= 1e-12 (a step multiplies the error by about 100 r0: one step up
   to r0 = 1e-7, 2 at 1024 slabs, 4 at 2048, 7 at 4096), at most 10. Inside FETIApplyCoarseInverse() the
   FETI_CoarseSolve event then holds these G and G' products too (-log_view). */
#define FETI_COARSE_REFINED_RESIDUAL 1e-12
#define FETI_COARSE_REFINE_MAX       10
static PetscErrorCode SetUpCoarseRefinement(FETI feti)
{
  FETI_Impl &impl = *feti->impl;

  PetscFunctionBegin;
  if (impl.coarserefine >= 0) impl.coarsesteps = impl.coarserefine;
  else {
    PetscReal left = impl.coarseres0; /* a step multiplies it by about 100 times itself (the fit above) */
    for (impl.coarsesteps = 0; !(left <= FETI_COARSE_REFINED_RESIDUAL) && impl.coarsesteps < FETI_COARSE_REFINE_MAX; impl.coarsesteps++) left *= std::min((PetscReal)1, 100 * impl.coarseres0);
  }
  if (impl.coarsesteps > 0) {
    PetscCall(VecDuplicate(impl.wc1, &impl.wcr));
    PetscCall(VecDuplicate(impl.wc1, &impl.wcdy));
    PetscCall(VecDuplicate(impl.wd1, &impl.wdr));
  }
  PetscCall(PetscInfo(feti, "coarse solves: %" PetscInt_FMT " step(s) of iterative refinement each (-feti_coarse_refine %" PetscInt_FMT "%s)\n", impl.coarsesteps, impl.coarserefine,
                      impl.coarserefine < 0 ? ": chosen from the check's unrefined residual" : ""));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode SetUpCoarse(FETI feti)
{
  FETI_Impl &impl = *feti->impl;
  PetscBool  failed;
  Mat        GGt;
  PetscInt   nrows;

  PetscFunctionBegin;
  PetscCall(MatGetSize(impl.B, &nrows, NULL));
  PetscCheck(nrows > 0, PetscObjectComm((PetscObject)feti), PETSC_ERR_ARG_WRONG,
             "B has no rows, so nothing holds the %" PetscInt_FMT " rigid-body modes of the floating subdomains (G G' = 0): give the gluing and Dirichlet rows with FETISetConstraints()",
             impl.ncoarse);
  PetscCall(PetscLogEventBegin(FETI_Assembly, feti, 0, 0, 0));
  PetscCall(FETICreateCoarseMatrix(feti, NULL, &GGt));
  PetscCall(PetscLogEventEnd(FETI_Assembly, feti, 0, 0, 0));
  PetscCall(FETICoarseSolverCreate(feti, GGt, impl.coarse, &failed));
  PetscCall(MatDestroy(&GGt));
  PetscCheck(!failed, PetscObjectComm((PetscObject)feti), PETSC_ERR_CONV_FAILED, "The coarse matrix G G' is singular: " FETI_SINGULAR_COARSE_MESSAGE);
  /* before the subdomains are factored: a refused setup pays for no factorization */
  if (impl.coarsechecktol > 0 || impl.coarserefine < 0) PetscCall(CheckCoarseSolvable(feti));
  PetscCall(SetUpCoarseRefinement(feti));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FETISetUp - Kernels, factorizations, the coarse problem, the operators and right-hand sides.

  Collective

  Input Parameter:
. feti - the FETI problem with subdomains and constraints set

  Notes:
  Per subdomain: the kernel basis (rigid modes from coordinates, or the user's, restricted to those
  vanishing on Dirichlet dofs kept in the primal), fixing dofs, the regularized matrix and its sparse
  Cholesky factorization (prefix feti_sub_). Then Gt = B R, the coarse matrix G G' and its
  factorization (prefix feti_coarse_), h = B K+ f - c, e = R' f and the particular solution
  lambda~ = G'(G G')^-1 e. Everything is done once; products and solves allocate nothing.

  Level: beginner

.seealso: `FETISetFromOptions()`, `FETIGetOperators()`, `FETIGetRHS()`, `FETISolveLinear()`
@*/
PetscErrorCode FETISetUp(FETI feti)
{
  MPI_Comm    comm = PetscObjectComm((PetscObject)feti);
  PetscMPIInt size, rank;
  PetscInt    nlocal, minlocal, ncols, nlocalcols, nd, mlocal, offset, coarseoffset;

  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  FETI_Impl &impl = *feti->impl; /* only after the check: FETISetUp(NULL) is an error, not a crash */
  nlocal          = (PetscInt)impl.sub.size();
  if (impl.setupcalled) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(MPIU_Allreduce(&nlocal, &minlocal, 1, MPIU_INT, MPI_MIN, comm));
  PetscCheck(minlocal >= 1, comm, PETSC_ERR_ARG_WRONGSTATE, "Every rank needs at least one subdomain (FETISetSubdomains()); some rank has none: use more subdomains than the %d ranks", size);
  PetscCheck(impl.B, comm, PETSC_ERR_ARG_WRONGSTATE, "Call FETISetConstraints() before FETISetUp()");
  PetscCall(PetscLogEventBegin(FETI_SetUp, feti, 0, 0, 0));
  PetscCall(ConeFETIProgressBegin_Private(impl.progress, CONEFETI_PHASE_KERNELS, nlocal));

  /* primal layout: this rank's subdomains, contiguous */
  impl.nlocalprimal = 0;
  for (FETISubdomain &sd : impl.sub) {
    sd.localoffset = impl.nlocalprimal;
    impl.nlocalprimal += sd.n;
  }
  PetscCallMPI(MPI_Scan(&impl.nlocalprimal, &offset, 1, MPIU_INT, MPI_SUM, comm));
  offset -= impl.nlocalprimal;
  PetscCall(MPIU_Allreduce(&impl.nlocalprimal, &impl.nprimal, 1, MPIU_INT, MPI_SUM, comm));
  for (FETISubdomain &sd : impl.sub) sd.offset = offset + sd.localoffset;
  PetscCallMPI(MPI_Scan(&nlocal, &impl.firstsub, 1, MPIU_INT, MPI_SUM, comm));
  impl.firstsub -= nlocal;
  PetscCall(MPIU_Allreduce(&nlocal, &impl.nglobalsub, 1, MPIU_INT, MPI_SUM, comm));

  PetscCall(MatGetSize(impl.B, &nd, &ncols));
  PetscCall(MatGetLocalSize(impl.B, &mlocal, &nlocalcols));
  PetscCheck(ncols == impl.nprimal, comm, PETSC_ERR_ARG_SIZ, "B has %" PetscInt_FMT " columns but the subdomains have %" PetscInt_FMT " dofs in total", ncols, impl.nprimal);
  PetscCheck(nlocalcols == impl.nlocalprimal, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
             "B has %" PetscInt_FMT " local columns on rank %d but the rank's subdomains have %" PetscInt_FMT " dofs; create B with MatSetSizes(B, m, %" PetscInt_FMT ", M, N)", nlocalcols, rank,
             impl.nlocalprimal, impl.nlocalprimal);

  PetscCall(MatCreateVecs(impl.B, &impl.wp1, &impl.wd1));
  if (impl.kplusexplicit) PetscCall(FETISetUpBoundaryMask(feti)); /* the subdomain factorizations may keep a Schur complement on it */
  /* kernels first: the coarse problem is assembled and factored before the subdomain factors exist, so
     that the memory its assembly needs for a moment is reused by them rather than stacked on them */
  PetscCall(PetscLogEventBegin(FETI_Kernels, feti, 0, 0, 0));
  for (PetscInt s = 0; s < nlocal; s++) {
    PetscCall(FETISubdomainSetUpKernel(feti, impl.sub[s], impl.firstsub + s));
    PetscCall(ConeFETIProgressStep_Private(impl.progress, s + 1));
  }
  PetscCall(PetscLogEventEnd(FETI_Kernels, feti, 0, 0, 0));
  PetscCall(ConeFETIProgressEnd_Private(impl.progress));
  /* before anything large: the factors and explicit blocks must fit (the blocks are dropped when only they do not) */
  PetscCall(ConeFETIProgressBegin_Private(impl.progress, CONEFETI_PHASE_MEMORY, 0));
  PetscCall(FETICheckMemory(feti));
  PetscCall(ConeFETIProgressEnd_Private(impl.progress));
  PetscCall(ConeFETIProgressBegin_Private(impl.progress, CONEFETI_PHASE_COARSE, 0));

  /* coarse layout */
  impl.nlocalcoarse = 0;
  for (FETISubdomain &sd : impl.sub) {
    sd.coarseoffset = impl.nlocalcoarse;
    impl.nlocalcoarse += sd.nkernel;
  }
  PetscCallMPI(MPI_Scan(&impl.nlocalcoarse, &coarseoffset, 1, MPIU_INT, MPI_SUM, comm));
  coarseoffset -= impl.nlocalcoarse;
  for (FETISubdomain &sd : impl.sub) sd.coarseoffset += coarseoffset;
  PetscCall(MPIU_Allreduce(&impl.nlocalcoarse, &impl.ncoarse, 1, MPIU_INT, MPI_SUM, comm));

  PetscCall(PetscLogEventBegin(FETI_Assembly, feti, 0, 0, 0));
  /* global load; the subdomain loads are not needed any more */
  PetscCall(VecDuplicate(impl.wp1, &impl.f));
  PetscCall(VecDuplicate(impl.wp1, &impl.wp2));
  PetscCall(VecDuplicate(impl.wd1, &impl.wd2));
  {
    PetscScalar *fa;
    PetscCall(VecGetArray(impl.f, &fa));
    for (FETISubdomain &sd : impl.sub) {
      const PetscScalar *a;
      if (!sd.f) {
        for (PetscInt i = 0; i < sd.n; i++) fa[sd.localoffset + i] = 0;
      } else {
        PetscCall(VecGetArrayRead(sd.f, &a));
        PetscCall(CheckFiniteArray(sd.n, a, "FETISetUp", "the load f_s (f[s] of FETISetSubdomains())", (PetscInt)(&sd - impl.sub.data())));
        for (PetscInt i = 0; i < sd.n; i++) fa[sd.localoffset + i] = a[i];
        PetscCall(VecRestoreArrayRead(sd.f, &a));
        PetscCall(VecDestroy(&sd.f));
      }
      sd.dirichletvalues.clear();
      if (sd.uD && !sd.dirichletdofs.empty()) { /* lifting: f - K u_D with K_s still whole (FETISetSubdomainDirichletValues()) */
        Vec          w, Kw;
        PetscScalar *wa;
        PetscInt     n;
        PetscCall(VecGetSize(sd.uD, &n));
        PetscCheck(n == sd.n, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "FETISetSubdomainDirichletValues(): subdomain %" PetscInt_FMT ": %" PetscInt_FMT " values for %" PetscInt_FMT " dofs",
                   impl.firstsub + (PetscInt)(&sd - impl.sub.data()), n, sd.n);
        PetscCall(VecDuplicate(sd.uD, &w));
        PetscCall(VecDuplicate(sd.uD, &Kw));
        PetscCall(VecGetArray(w, &wa));
        PetscCall(VecGetArrayRead(sd.uD, &a));
        for (PetscInt i = 0; i < sd.n; i++) wa[i] = 0;
        PetscCallCXX(sd.dirichletvalues.resize(sd.dirichletdofs.size()));
        for (size_t k = 0; k < sd.dirichletdofs.size(); k++) {
          PetscCheck(!PetscIsInfOrNanScalar(a[sd.dirichletdofs[k]]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                     "FETISetSubdomainDirichletValues(): uD of local subdomain %" PetscInt_FMT " on rank %d has a non-finite value %g at Dirichlet dof %" PetscInt_FMT,
                     (PetscInt)(&sd - impl.sub.data()), rank, (double)PetscRealPart(a[sd.dirichletdofs[k]]), sd.dirichletdofs[k]);
          wa[sd.dirichletdofs[k]] = sd.dirichletvalues[k] = a[sd.dirichletdofs[k]];
        }
        PetscCall(VecRestoreArrayRead(sd.uD, &a));
        PetscCall(VecRestoreArray(w, &wa));
        PetscCall(MatMult(sd.K, w, Kw));
        PetscCall(VecGetArrayRead(Kw, &a));
        for (PetscInt i = 0; i < sd.n; i++) fa[sd.localoffset + i] -= a[i];
        PetscCall(VecRestoreArrayRead(Kw, &a));
        PetscCall(VecDestroy(&w));
        PetscCall(VecDestroy(&Kw));
        if (std::all_of(sd.dirichletvalues.begin(), sd.dirichletvalues.end(), [](PetscScalar v) { return v == 0.0; })) sd.dirichletvalues.clear();
      }
      PetscCall(VecDestroy(&sd.uD));
      for (PetscInt d : sd.dirichletdofs) fa[sd.localoffset + d] = 0; /* no work on prescribed dofs */
    }
    PetscCall(VecRestoreArray(impl.f, &fa));
  }
  /* R: block diagonal, primal x coarse */
  {
    std::vector<PetscInt> nnz(impl.nlocalprimal), cols;
    for (FETISubdomain &sd : impl.sub)
      for (PetscInt i = 0; i < sd.n; i++) nnz[sd.localoffset + i] = sd.nkernel;
    PetscCall(MatCreate(comm, &impl.R));
    PetscCall(MatSetSizes(impl.R, impl.nlocalprimal, impl.nlocalcoarse, impl.nprimal, impl.ncoarse));
    PetscCall(MatSetType(impl.R, MATAIJ));
    PetscCall(MatSeqAIJSetPreallocation(impl.R, 0, nnz.data()));
    PetscCall(MatMPIAIJSetPreallocation(impl.R, 0, nnz.data(), 0, NULL));
    for (FETISubdomain &sd : impl.sub) {
      std::vector<PetscScalar> row(sd.nkernel);
      PetscCallCXX(cols.resize(sd.nkernel));
      for (PetscInt j = 0; j < sd.nkernel; j++) cols[j] = sd.coarseoffset + j;
      for (PetscInt i = 0; i < sd.n; i++) {
        const PetscInt grow = sd.offset + i;
        for (PetscInt j = 0; j < sd.nkernel; j++) row[j] = sd.R[(size_t)j * sd.n + i];
        PetscCall(MatSetValues(impl.R, 1, &grow, sd.nkernel, cols.data(), row.data(), INSERT_VALUES));
      }
    }
    PetscCall(MatAssemblyBegin(impl.R, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(impl.R, MAT_FINAL_ASSEMBLY));
    for (FETISubdomain &sd : impl.sub) PetscCallCXX(std::vector<PetscScalar>().swap(sd.R)); /* R holds the kernels now */
  }
  PetscCall(MatCreateVecs(impl.R, &impl.wc1, NULL));
  PetscCall(VecDuplicate(impl.wc1, &impl.wc2));
  PetscCall(VecDuplicate(impl.wp1, &impl.wp3));
  PetscCall(VecDuplicate(impl.wd1, &impl.wd3));
  PetscCall(FETIRowSumCreate(impl.B, PETSC_FALSE, impl.Bsum));
  PetscCall(FETIRowSumCreate(impl.B, PETSC_TRUE, impl.Btsum));
  PetscCall(PetscLogEventEnd(FETI_Assembly, feti, 0, 0, 0));
  if (impl.ncoarse) PetscCall(SetUpCoarse(feti));
  PetscCall(ConeFETIProgressEnd_Private(impl.progress));
  PetscCall(ConeFETIProgressBegin_Private(impl.progress, CONEFETI_PHASE_FACTORIZATION, nlocal));
  for (PetscInt s = 0; s < nlocal; s++) {
    PetscCall(FETISubdomainSetUpFactorization(feti, impl.sub[s], impl.firstsub + s));
    PetscCall(ConeFETIProgressStep_Private(impl.progress, s + 1));
  }
  PetscCall(ConeFETIProgressEnd_Private(impl.progress));
  if (impl.kplusexplicit) {
    PetscCall(PetscLogEventBegin(FETI_Factorization, feti, 0, 0, 0));
    PetscCall(ConeFETIProgressBegin_Private(impl.progress, CONEFETI_PHASE_EXPLICIT, nlocal));
    PetscCall(FETISetUpExplicitKplus(feti)); /* counts the subdomains */
    PetscCall(ConeFETIProgressEnd_Private(impl.progress));
    PetscCall(PetscLogEventEnd(FETI_Factorization, feti, 0, 0, 0));
  }
  { /* the block Cholesky factors as kept: float copies (-feti_kplus_precision single) or PETSc's double factors */
    double bytes[2]   = {0, 0};
    impl.nkplussingle = 0;
    for (FETISubdomain &sd : impl.sub) {
      if (sd.ffactor.nb) impl.nkplussingle++;
      bytes[0] += sd.ffactor.nb ? FETIFloatFactorBytes(sd.ffactor) : sd.ffactor.doublebytes;
      bytes[1] += sd.ffactor.doublebytes;
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &impl.nkplussingle, 1, MPIU_INT, MPI_SUM, comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, bytes, 2, MPI_DOUBLE, MPI_SUM, comm));
    impl.kplusfactorbytes = bytes[0];
    impl.kplusdoublebytes = bytes[1];
  }

  PetscCall(ConeFETIProgressBegin_Private(impl.progress, CONEFETI_PHASE_OPERATORS, 0));
  PetscCall(FETICreateOperators_Private(feti));
  impl.setupcalled = PETSC_TRUE;

  /* h = B K+ f - c, e = R' f, lambda~ = Gt (G Gt)^-1 e */
  PetscCall(VecDuplicate(impl.wd1, &impl.h));
  PetscCall(VecDuplicate(impl.wd1, &impl.lambdatilde));
  PetscCall(VecDuplicate(impl.wc1, &impl.e));
  PetscCall(VecDuplicate(impl.wc1, &impl.alpha));
  PetscCall(VecDuplicate(impl.wd1, &impl.rhs));
  PetscCall(VecDuplicate(impl.wd1, &impl.residual));
  PetscCall(FETIApplyKplus(feti, impl.f, impl.wp1, PETSC_TRUE));
  PetscCall(FETIRowSumApply(impl.Bsum, impl.wp1, impl.h));
  if (impl.c) PetscCall(VecAXPY(impl.h, -1.0, impl.c));
  PetscCall(MatMultTranspose(impl.R, impl.f, impl.e));
  if (impl.ncoarse) {
    PetscCall(FETIApplyCoarseInverse(feti, impl.e, impl.wc2));
    PetscCall(FETIApplyGt(feti, impl.wc2, impl.lambdatilde));
  } else PetscCall(VecSet(impl.lambdatilde, 0.0));
  PetscCall(ConeFETIProgressEnd_Private(impl.progress));
  PetscCall(PetscLogEventEnd(FETI_SetUp, feti, 0, 0, 0));
  PetscCall(PetscObjectViewFromOptions((PetscObject)feti, NULL, "-feti_view"));
  PetscFunctionReturn(PETSC_SUCCESS);
}
