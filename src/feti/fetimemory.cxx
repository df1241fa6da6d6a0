/* The memory of the FETI setup, estimated before anything large is allocated.

   A scene too large for the machine used to run for a minute and then die somewhere inside a factorization
   (MUMPS out of memory, an allocation failure deep in a package). The two big consumers are known in advance:
   the sparse Cholesky factors of the subdomains and, with -feti_kplus_explicit, the dense blocks (K+)_bb
   (|b|^2 numbers per subdomain). FETISetUp() estimates both, compares them with the memory the node has left
   (or -feti_memory_budget), drops the explicit blocks when only they do not fit, and stops at once with the
   estimate when even the factors do not. A subdomain whose dense block would be larger than its factor
   (a wide slab one cell thick: B touches every node) keeps the factor for F in any case: the block would cost
   more memory, more setup (|b| solves) and more time per product than the two triangular solves it replaces.

   -feti_kplus auto (the contact layer's default) chooses after the factorizations, from what is really stored
   and read (FETIChooseKplusBlocks()): the block is |b|^2 numbers (stored square, for dsymv) on top of the factor,
   which K+ x (h, the primal recovery) needs anyway. Time: a block is a candidate when an F product reads at least
   -feti_kplus_speedup (2) times fewer numbers of it (its triangle) than of the factor (twice, as the package
   reports its entries). Memory: the candidates that save the most reads per stored number get their blocks
   first, while all blocks together stay within -feti_kplus_memory_ratio (1) times the entries of all the factors
   and -feti_kplus_memory_budget. On the brick at H/h = 6 (1029 dofs, |b| up to 654) only the subdomains with
   |b| <= 455 qualify (30 of 1536 at 10^6, on the brick's edges); on the paper's three large cubes all three get blocks (docs/scale.md, lever (a)). */
#include <conefeti/private/fetiimpl.h>
#include <conefeti/private/allgather.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <unistd.h>

/* Entries of a sparse Cholesky factor of a 3D finite element matrix with n dofs and nnzhalf nonzeros in one
   triangle, at most the dense triangle. Above FETI_BLOCK_CHOLESKY_MAX_DOFS (CHOLMOD or MUMPS, nested dissection):
   about 0.75 nnzhalf n^(1/3), as MUMPS measures them on the brick's cubes (-feti_sub_mat_mumps_icntl_4 2:
   n = 6591: 1.9M entries (INFOG(29)), 22 MB used (INFOG(22)); n = 2187: 5 MB), 12 bytes each (values, integer
   structure, workspace). Up to it (PETSc's block Cholesky of the node graph in AMD order, the factor path's
   default there, fetisubdomain.cxx): BLOCK_COEF nnzhalf n^(1/2), fitted to the entries it reports on the brick's
   cubes of 4, 6 and 8 cells (375, 1029, 2187 dofs; docs/feti.md gives the error), 8 bytes of value and 4 of
   column index per 3x3 block: 8.5 bytes each. */
#define BLOCK_COEF 0.155
static PetscReal FactorEntries(PetscReal n, PetscReal nnzhalf)
{
  const PetscReal fill = n <= FETI_BLOCK_CHOLESKY_MAX_DOFS ? BLOCK_COEF * std::sqrt(n) : 0.75 * std::cbrt(n);
  return std::min(0.5 * n * (n + 1), std::max(nnzhalf, fill * nnzhalf));
}

static PetscReal FactorBytes(PetscReal n, PetscReal nnzhalf) { return (n <= FETI_BLOCK_CHOLESKY_MAX_DOFS ? 8.5 : 12.0) * FactorEntries(n, nnzhalf); }

/*@
  FETIEstimateFactorMemory - A rough estimate of the memory a subdomain's sparse Cholesky factorization takes.

  Not Collective

  Input Parameters:
+ n       - the subdomain's dofs
- nnzhalf - the nonzeros of one triangle of K_s, diagonal included

  Output Parameter:
. bytes - the estimate

  Notes:
  The estimate is of the factor the factor path uses by default. Up to 3000 dofs PETSc's block Cholesky (SBAIJ,
  block size 3, AMD order of the nodes): about 0.155 nnzhalf n^(1/2) entries (fitted to the entries it reports on
  the brick's cubes of 375 to 2187 dofs) at 8.5 bytes each (values, one column index per 3x3 block). Above, CHOLMOD
  or MUMPS with nested dissection: about 0.75 nnzhalf n^(1/3) entries (measured with MUMPS on the brick's cubes)
  at 12 bytes each (values, integer structure, MUMPS's workspace). At most the dense triangle. Meant to stop a
  scene that cannot fit before it is assembled, not to size anything.

  Level: developer

.seealso: `FETISetUp()`, `FETIGetMemoryBudget()`, `FETIGetMemoryEstimate()`
@*/
PetscErrorCode FETIEstimateFactorMemory(PetscReal n, PetscReal nnzhalf, PetscReal *bytes)
{
  PetscFunctionBegin;
  PetscValidRealPointer(bytes, 3);
  *bytes = FactorBytes(n, nnzhalf);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One "Key:   <value> kB" line of a /proc file, in bytes; -1 when absent */
static PetscReal ProcKilobytes(const char *path, const char *key)
{
  FILE     *f = fopen(path, "r");
  char      line[256];
  PetscReal value = -1;

  if (!f) return -1;
  while (fgets(line, sizeof(line), f)) {
    double kb;
    if (!strncmp(line, key, strlen(key)) && sscanf(line + strlen(key), " %lf", &kb) == 1) {
      value = 1024.0 * kb;
      break;
    }
  }
  fclose(f);
  return value;
}

/* One number in a file (cgroup limits); -1 when absent or "max" */
static PetscReal FileNumber(const char *path)
{
  FILE  *f = fopen(path, "r");
  double v = -1;

  if (!f) return -1;
  if (fscanf(f, "%lf", &v) != 1) v = -1;
  fclose(f);
  return v;
}

/* What this node can still give: MemAvailable (the kernel's own estimate of what can be allocated without
   swapping), bounded by a cgroup memory limit (containers, batch jobs) */
static PetscReal NodeAvailable(void)
{
  PetscReal avail = ProcKilobytes("/proc/meminfo", "MemAvailable:"), limit, usage;

  if (avail < 0) {
    const long pages = sysconf(_SC_AVPHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    avail = pages > 0 && size > 0 ? (PetscReal)pages * (PetscReal)size : -1;
  }
  limit = FileNumber("/sys/fs/cgroup/memory.max"); /* cgroup v2 */
  usage = FileNumber("/sys/fs/cgroup/memory.current");
  if (limit < 0) { /* cgroup v1 */
    limit = FileNumber("/sys/fs/cgroup/memory/memory.limit_in_bytes");
    usage = FileNumber("/sys/fs/cgroup/memory/memory.usage_in_bytes");
  }
  if (limit > 0 && limit < 1e18 && usage >= 0) avail = avail < 0 ? limit - usage : std::min(avail, limit - usage);
  return avail;
}

/*@C
  FETIGetMemoryBudget - The memory the FETI setup may use on each node (shared-memory domain) of a communicator.

  Collective

  Input Parameters:
+ comm   - the communicator
- prefix - the options prefix of the FETI object (or NULL)

  Output Parameters:
+ bytes - the budget of the node of this rank, in bytes (all ranks of the node together); a negative value when unknown
- given - whether -feti_memory_budget gave it (NULL if not needed)

  Options Database Key:
. -feti_memory_budget <MB> - the budget; default: what the node has available now (MemAvailable of /proc/meminfo,
  bounded by a cgroup memory limit)

  Level: developer

.seealso: `FETISetUp()`, `FETIEstimateFactorMemory()`, `FETIGetMemoryEstimate()`
@*/
PetscErrorCode FETIGetMemoryBudget(MPI_Comm comm, const char prefix[], PetscReal *bytes, PetscBool *given)
{
  PetscReal   mb = -1;
  PetscBool   set;
  MPI_Comm    node;
  PetscMPIInt noderank;
  double      avail;

  PetscFunctionBegin;
  PetscValidRealPointer(bytes, 3);
  PetscCall(PetscOptionsGetReal(NULL, prefix, "-feti_memory_budget", &mb, &set));
  PetscCheck(!set || mb > 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "-%sfeti_memory_budget %g: the budget is a positive number of megabytes", prefix ? prefix : "", (double)mb);
  if (given) *given = set;
  if (set) {
    *bytes = mb * 1048576.0;
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  /* one reading per node, shared by its ranks (they would otherwise see each other's allocations in between) */
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Comm_rank(node, &noderank));
  avail = noderank ? 0 : (double)NodeAvailable();
  PetscCallMPI(MPI_Bcast(&avail, 1, MPI_DOUBLE, 0, node));
  PetscCallMPI(MPI_Comm_free(&node));
  *bytes = (PetscReal)avail;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* nonzeros of one triangle of K_s (diagonal included), whatever its storage */
static PetscErrorCode HalfNonzeros(Mat K, PetscInt n, PetscReal *nnzhalf)
{
  MatInfo   info;
  PetscBool sbaij;

  PetscFunctionBegin;
  PetscCall(MatGetInfo(K, MAT_LOCAL, &info));
  PetscCall(PetscObjectTypeCompareAny((PetscObject)K, &sbaij, MATSEQSBAIJ, MATMPISBAIJ, ""));
  *nnzhalf = sbaij ? (PetscReal)info.nz_used : 0.5 * ((PetscReal)info.nz_used + (PetscReal)n);
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Before the factorizations (the kernels, hence the Dirichlet dofs, and the boundary mask are known):
   estimate, compare with the budget of each node, drop the explicit blocks or stop */
PetscErrorCode FETICheckMemory(FETI feti)
{
  FETI_Impl  &impl = *feti->impl;
  MPI_Comm    comm = PetscObjectComm((PetscObject)feti), node;
  const char *prefix;
  PetscReal   budget;
  PetscBool   given;
  PetscMPIInt rank;
  double      mine[2] = {0, 0}, onnode[2]; /* factors, explicit blocks: this rank, this node */
  PetscInt    nmax = 0, nbmax = 0, nimplicit = 0, nexplicit;
  double      autoentries = 0, autoblocks = 0; /* auto: estimated factor entries, candidate blocks' bytes (this rank) */
  int         fits[2], allfit[2];              /* factors fit, factors and blocks fit: this node, every node */

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)feti, &prefix));
  PetscCall(FETIGetMemoryBudget(comm, prefix, &budget, &given));
  const PetscScalar *mask = NULL;
  if (impl.kplusexplicit) PetscCall(VecGetArrayRead(impl.boundarymask, &mask));
  for (FETISubdomain &sd : impl.sub) {
    PetscReal nnzhalf = 0;
    PetscCall(HalfNonzeros(sd.K, sd.n, &nnzhalf));
    mine[0] += FactorBytes(sd.n, nnzhalf);
    nmax = std::max(nmax, sd.n);
    /* auto: every subdomain is factored by its own package first (no Schur complement kept);
       FETISetUpExplicitKplus() then chooses with the real size of that factor */
    sd.kplusimplicit = impl.kplustype == FETI_KPLUS_AUTO ? PETSC_TRUE : PETSC_FALSE;
    if (mask) { /* |b| counted with the fixing dofs (an upper bound); the dense block, and the n x 128 work blocks of the solves that may build it */
      std::vector<char> isD(sd.n, 0);
      PetscInt          nb = 0;
      for (PetscInt d : sd.dirichletdofs) isD[d] = 1;
      for (PetscInt k = 0; k < sd.n; k++)
        if (mask[sd.localoffset + k] != 0.0 && !isD[k]) nb++;
      if (impl.kplustype == FETI_KPLUS_AUTO) { /* the candidates the estimated factor would let through, capped below: for the budget only */
        const PetscReal entries = FactorEntries(sd.n, nnzhalf);
        autoentries += entries;
        if (!(nb > 0 && 2.0 * entries >= impl.kplusspeedup * 0.5 * (double)nb * nb)) continue;
        autoblocks += 8.0 * (double)nb * nb;
        nbmax = std::max(nbmax, nb);
        continue;
      } else if (0.5 * (double)nb * nb > 2.0 * FactorEntries(sd.n, nnzhalf)) { /* dsymv reads the triangle, nb^2/2 numbers; the two triangular solves read the factor twice */
        sd.kplusimplicit = PETSC_TRUE;
        nimplicit++;
        continue;
      }
      nbmax = std::max(nbmax, nb);
      mine[1] += 8.0 * ((double)nb * nb + 2.0 * sd.n * std::min<PetscInt>(nb, 128));
    }
  }
  if (mask) PetscCall(VecRestoreArrayRead(impl.boundarymask, &mask));
  if (impl.kplustype == FETI_KPLUS_AUTO) { /* FETIChooseKplusBlocks() keeps them within the ratio and the budget (of all ranks: a bound of this rank's share) */
    double cap = impl.kplusratio * 8.0 * autoentries;
    if (impl.kplusbudget >= 0) cap = std::min(cap, impl.kplusbudget);
    mine[1] += std::min(autoblocks, cap);
  }
  PetscCallMPI(MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node));
  PetscCallMPI(MPI_Allreduce(mine, onnode, 2, MPI_DOUBLE, MPI_SUM, node));
  PetscCallMPI(MPI_Comm_free(&node));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nmax, 1, MPIU_INT, MPI_MAX, comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nbmax, 1, MPIU_INT, MPI_MAX, comm));
  if (impl.kplusexplicit && impl.kplustype == FETI_KPLUS_EXPLICIT) {
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nimplicit, 1, MPIU_INT, MPI_SUM, comm));
    impl.nkplusimplicit = nimplicit;
    nexplicit           = impl.nglobalsub - nimplicit;
    impl.nkplusblocks   = nexplicit;
    if (nimplicit)
      PetscCall(PetscInfo(feti, "%" PetscInt_FMT " of %" PetscInt_FMT " subdomains keep their factor for F: their explicit K+ block would be larger than the factor\n", nimplicit, impl.nglobalsub));
    if (!nexplicit) impl.kplusexplicit = PETSC_FALSE; /* no block anywhere: the plain implicit products */
  }
  impl.memfactors = onnode[0];
  impl.memblocks  = onnode[1];
  impl.membudget  = budget;
  if (budget < 0) { /* nothing known about the machine: no check */
    PetscCall(PetscInfo(feti, "Memory estimate: factors %.1f MB, explicit K+ blocks %.1f MB on this node; available memory unknown (-feti_memory_budget sets it)\n", onnode[0] / 1048576.0,
                        onnode[1] / 1048576.0));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  fits[0] = onnode[0] <= budget;
  fits[1] = onnode[0] + onnode[1] <= budget;
  PetscCallMPI(MPI_Allreduce(fits, allfit, 2, MPI_INT, MPI_MIN, comm));
  PetscCall(PetscInfo(feti, "Memory estimate on the node of rank %d: factors %.1f MB, explicit K+ blocks %.1f MB; budget %.1f MB (%s)\n", rank, onnode[0] / 1048576.0, onnode[1] / 1048576.0,
                      budget / 1048576.0, given ? "-feti_memory_budget" : "available now"));
  if (!allfit[0]) {
    /* the numbers of a node that does not fit (the one short of most), for the message */
    struct {
      double v;
      int    r;
    } in          = {fits[0] ? -1e300 : onnode[0] - budget, (int)rank}, at;
    double out[2] = {onnode[0], budget};
    PetscCallMPI(MPI_Allreduce(&in, &at, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm));
    PetscCallMPI(MPI_Bcast(out, 2, MPI_DOUBLE, at.r, comm));
    SETERRQ(comm, PETSC_ERR_ARG_OUTOFRANGE, /* not PETSC_ERR_MEM: nothing failed to allocate */
            "The subdomain factorizations need about %.1f MB on one node (estimated from the nonzeros of K_s: subdomains of up to %" PetscInt_FMT
            " dofs), more than the %.1f MB %s; nothing large was allocated. Lower it: a coarser mesh (conefeti: -scene_refine, -scene_body<b>_cells), more subdomains (-scene_body<b>_subdomains: the "
            "factors shrink faster than the subdomains), more nodes%s; or, if the estimate is too pessimistic, -%sfeti_memory_budget <MB>",
            out[0] / 1048576.0, nmax, out[1] / 1048576.0, given ? "of -feti_memory_budget" : "the node has available (MemAvailable)",
            impl.kplusexplicit ? " (the explicit K+ blocks, which -feti_kplus_explicit 0 drops, are not even counted here)" : "", prefix ? prefix : "");
  }
  if (impl.kplusexplicit && !allfit[1]) {
    impl.kplusexplicit = PETSC_FALSE;
    impl.kplusfallback = PETSC_TRUE;
    impl.nkplusblocks  = 0;
    for (FETISubdomain &sd : impl.sub) sd.kplusimplicit = PETSC_FALSE; /* as -feti_kplus implicit */
    PetscCall(PetscInfo(feti,
                        "The explicit K+ blocks (%.1f MB on the node of rank %d, |b| up to %" PetscInt_FMT
                        ") and the factors (%.1f MB) exceed the budget of %.1f MB: F products use the factors (implicit K+, "
                        "as -feti_kplus_explicit 0)\n",
                        onnode[1] / 1048576.0, rank, nbmax, onnode[0] / 1048576.0, budget / 1048576.0));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Reads (8-byte numbers) one F product costs a subdomain: its factor, read twice by the forward and the backward
   triangular solve, at c numbers per entry (PETSc's block Cholesky stores one 4-byte column index per bs x bs
   block beside the values; CHOLMOD's supernodes and MUMPS's fronts are dense panels: c = 1), against the
   block's triangle, |b|^2/2 numbers (dsymv reads one triangle). Counts, not timings: the choice must be the same
   on every run and every number of ranks. */
static PetscReal FactorReadsPerEntry(Mat factor, PetscBool petsc)
{
  PetscInt bs = 1;

  if (!petsc || MatGetBlockSize(factor, &bs) != PETSC_SUCCESS || bs < 1) return 1.0;
  return 1.0 + 0.5 / ((PetscReal)bs * bs);
}

/* -feti_kplus auto, after the subdomain's factorization: the size of its factor (as the package reports it after
   the factorization: CHOLMOD the nonzeros of L, MUMPS INFOG(20), PETSc's block Cholesky its stored entries; else
   the estimate from the nonzeros of K_s) and what one F product reads of it */
PetscErrorCode FETISubdomainKplusCosts(FETI feti, FETISubdomain &sd, PetscReal *factorentries, PetscReal *factorreads, PetscBool *measured)
{
  PC            pc;
  Mat           factor;
  MatInfo       info;
  PetscReal     entries = 0, nnzhalf;
  MatSolverType type;
  PetscBool     known, petsc = PETSC_FALSE;

  PetscFunctionBegin;
  (void)feti;
  *measured = PETSC_FALSE;
  if (sd.ffactor.nb) { /* the double factor was replaced by its float copy (-feti_kplus_precision single): its entries as measured
                          before, each read as half a number, and half a number per 3 x 3 block for its column index */
    entries        = sd.factorentries;
    *measured      = entries > 0 ? PETSC_TRUE : PETSC_FALSE;
    *factorentries = entries > 0 ? entries : FactorEntries(sd.n, 0);
    *factorreads   = 2.0 * (0.5 + 0.5 / 9.0) * *factorentries;
    if (*measured) PetscCall(PetscInfo(NULL, "Factor of %" PetscInt_FMT " dofs (float): %.0f entries measured before its float copy\n", sd.n, (double)entries));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(KSPGetPC(sd.ksp, &pc));
  PetscCall(PCFactorGetMatrix(pc, &factor));
  PetscCall(MatFactorGetSolverType(factor, &type));
  if (type) petsc = !strcmp(type, MATSOLVERPETSC) ? PETSC_TRUE : PETSC_FALSE;
  known = type && (!strcmp(type, MATSOLVERCHOLMOD) || !strcmp(type, MATSOLVERMUMPS) || petsc) ? PETSC_TRUE : PETSC_FALSE;
  if (known) { /* the packages whose factors report their size to MatGetInfo() */
    PetscCall(MatGetInfo(factor, MAT_LOCAL, &info));
    entries   = (PetscReal)info.nz_used;
    *measured = entries > 0 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(HalfNonzeros(sd.Kreg, sd.n, &nnzhalf)); /* K_s's pattern (the removed dofs' rows and columns are zeroed in place) */
  if (!*measured) entries = FactorEntries(sd.n, nnzhalf);
  else
    PetscCall(PetscInfo(NULL, "Factor of %" PetscInt_FMT " dofs (%s): %.0f entries measured, %.0f estimated by FETIEstimateFactorMemory() from %.0f nonzeros in a triangle of K_s (%+.0f%%)\n", sd.n,
                        type, (double)entries, (double)FactorEntries(sd.n, nnzhalf), (double)nnzhalf, 100.0 * (FactorEntries(sd.n, nnzhalf) / entries - 1.0)));
  *factorentries = entries;
  *factorreads   = 2.0 * FactorReadsPerEntry(factor, *measured ? petsc : PETSC_FALSE) * entries;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* -feti_kplus auto: which subdomains get their dense block (K+)_bb, from every subdomain's counts (collective).
   A block is a candidate when one F product reads at least -feti_kplus_speedup (2) times less of it than of the
   factor (the time); the candidates get their blocks in decreasing order of the reads saved per F product per
   number stored (the time bought per byte), skipping a block that does not fit, while all blocks together stay
   within -feti_kplus_memory_ratio (1) times the entries of all factors and within -feti_kplus_memory_budget
   (the memory). Every rank sees the counts of every subdomain in the order of their global numbers and makes the
   same choice, whatever the number of ranks. gidx, nb (|b|), entries, reads: of the local subdomains. */
PetscErrorCode FETIChooseKplusBlocks(FETI feti, const std::vector<PetscInt> &gidx, const std::vector<PetscReal> &nb, const std::vector<PetscReal> &entries, const std::vector<PetscReal> &reads,
                                     std::vector<char> &chosen)
{
  FETI_Impl          &impl = *feti->impl;
  MPI_Comm            comm = PetscObjectComm((PetscObject)feti);
  std::vector<double> local, all;
  PetscInt            nall;
  double              totalentries = 0, cap, used = 0;
  std::vector<size_t> order;

  PetscFunctionBegin;
  for (size_t i = 0; i < gidx.size(); i++) PetscCallCXX(local.insert(local.end(), {(double)gidx[i], (double)nb[i], (double)entries[i], (double)reads[i]}));
  PetscCall(ConeFETIAllgather(comm, local, all));
  nall = (PetscInt)(all.size() / 4);
  for (PetscInt k = 0; k < nall; k++) totalentries += all[4 * k + 2]; /* in the ranks' order = the global numbers' order */
  cap = impl.kplusratio * totalentries;
  if (impl.kplusbudget >= 0) cap = std::min(cap, impl.kplusbudget / 8.0);
  for (PetscInt k = 0; k < nall; k++) {
    const double b = all[4 * k + 1], blockreads = 0.5 * b * b;
    if (b > 0 && all[4 * k + 3] >= impl.kplusspeedup * blockreads) PetscCallCXX(order.push_back((size_t)k));
  }
  auto saving = [&](size_t k) { return (all[4 * k + 3] - 0.5 * all[4 * k + 1] * all[4 * k + 1]) / (all[4 * k + 1] * all[4 * k + 1]); };
  PetscCallCXX(std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const double sa = saving(a), sb = saving(b);
    return sa != sb ? sa > sb : all[4 * a] < all[4 * b];
  }));
  std::vector<char> got(nall, 0);
  for (size_t k : order) {
    const double numbers = all[4 * k + 1] * all[4 * k + 1];
    if (used + numbers <= cap) {
      got[k] = 1;
      used += numbers;
    }
  }
  PetscCallCXX(chosen.assign(gidx.size(), 0));
  for (PetscInt k = 0; k < nall; k++) {
    const PetscInt g = (PetscInt)all[4 * k];
    const size_t   i = gidx.empty() ? 0 : (size_t)(g - gidx[0]); /* the local subdomains are numbered consecutively */
    if (i < gidx.size() && gidx[i] == g) {
      const double b = nb[i], blockreads = 0.5 * b * b;
      chosen[i] = got[k];
      PetscCall(PetscInfo(
          NULL, "Subdomain %" PetscInt_FMT ": %s: block (K+)_bb %.0f^2 = %.0f numbers, factor %.0f entries; reads per F product: factor %.0f, block %.0f, speedup %.3f (-feti_kplus_speedup %g)\n", g,
          got[k] ? "dense block" : "factor", b, b * b, (double)entries[i], (double)reads[i], blockreads, b > 0 ? (double)reads[i] / blockreads : 0.0, (double)impl.kplusspeedup));
    }
  }
  PetscCall(PetscInfo(feti, "-feti_kplus auto: blocks take %.0f numbers, at most %.0f allowed: -feti_kplus_memory_ratio %g times the factors' %.0f entries%s (-feti_kplus_speedup %g)\n", used, cap,
                      (double)impl.kplusratio, totalentries, impl.kplusbudget >= 0 ? ", -feti_kplus_memory_budget" : "", (double)impl.kplusspeedup));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  FETIGetMemoryEstimate - The memory estimates `FETISetUp()` compared with the budget, on the node of this rank.

  Not Collective

  Input Parameter:
. feti - the FETI problem, set up

  Output Parameters:
+ factors - bytes of the subdomain factorizations (a rough estimate from the nonzeros of K_s; NULL if not needed)
. blocks  - bytes of the explicit dense K+ blocks asked for (0 without -feti_kplus_explicit; NULL if not needed)
- budget  - the budget in bytes (-feti_memory_budget, else what the node had available; negative when unknown; NULL if not needed)

  Notes:
  All three are -1 before `FETISetUp()`. When factors + blocks exceeded the budget but factors alone did not,
  the blocks were not built (`FETIGetKplusExplicit()` says so).

  Level: intermediate

.seealso: `FETIGetKplusExplicit()`, `FETIGetMemoryBudget()`, `FETISetUp()`
@*/
PetscErrorCode FETIGetMemoryEstimate(FETI feti, PetscReal *factors, PetscReal *blocks, PetscReal *budget)
{
  PetscFunctionBegin;
  FETIValidHeader(feti, 1);
  if (factors) *factors = feti->impl->memfactors;
  if (blocks) *blocks = feti->impl->memblocks;
  if (budget) *budget = feti->impl->membudget;
  PetscFunctionReturn(PETSC_SUCCESS);
}
