/* Decomposition of bodies into subdomains (structured boxes of hexahedra, or METIS on the element dual
   graph), the distribution of subdomains over the ranks, and the replicated table of node copies. */
#include <conefeti/private/femimpl.h>
#include <conefeti/private/allgather.h>

#include <metis.h>
#include <algorithm>
#include <numeric>

static PetscErrorCode DecomposeStructured(FEMBody &b)
{
  std::vector<PetscInt> cut[3];

  PetscFunctionBegin;
  for (PetscInt d = 0; d < 3; d++) {
    PetscCheck(b.parts[d] >= 1 && b.parts[d] <= b.cells[d], PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "Structured decomposition: %" PetscInt_FMT " subdomains along axis %" PetscInt_FMT " but the box has %" PetscInt_FMT " cells there (-fem_subdomains px,py,pz needs 1 <= p <= cells)",
               b.parts[d], d, b.cells[d]);
    PetscCallCXX(cut[d].resize(b.cells[d]));
    for (PetscInt p = 0; p < b.parts[d]; p++)
      for (PetscInt c = p * b.cells[d] / b.parts[d]; c < (p + 1) * b.cells[d] / b.parts[d]; c++) cut[d][c] = p;
  }
  PetscCallCXX(b.part.resize(b.nelements));
  for (PetscInt e = 0; e < b.nelements; e++) {
    const PetscInt hex = e / 6;
    const PetscInt i = hex % b.cells[0], j = (hex / b.cells[0]) % b.cells[1], k = hex / (b.cells[0] * b.cells[1]);
    b.part[e] = cut[0][i] + b.parts[0] * (cut[1][j] + b.parts[1] * cut[2][k]);
  }
  b.nsub = b.parts[0] * b.parts[1] * b.parts[2];
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscInt UnionFind(std::vector<PetscInt> &parent, PetscInt x)
{
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

/* METIS k-way on the element dual graph (elements adjacent through a face), contiguous parts requested.
   A part that is still not face-connected would have more than 6 rigid modes; each face-connected
   component then becomes a subdomain of its own. Runs on rank 0 only. */
static PetscErrorCode DecomposeMETIS(FEMBody &b)
{
  /* a given mesh has no axes to cut along: structured counts px,py,pz ask for px py pz parts */
  const PetscInt        nparts = b.decomposition == FEM_DECOMPOSITION_METIS ? b.parts[0] : b.parts[0] * b.parts[1] * b.parts[2];
  idx_t                 ne = (idx_t)b.nelements, nn = (idx_t)b.nnodes, ncommon = 3, numflag = 0, *xadj = nullptr, *adjncy = nullptr;
  std::vector<idx_t>    eptr, eind, epart;
  std::vector<PetscInt> parent;

  PetscFunctionBegin;
  PetscCheck(nparts >= 1 && nparts <= b.nelements, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
             "METIS decomposition: %" PetscInt_FMT " subdomains requested for a body of %" PetscInt_FMT " elements (-fem_subdomains n)", nparts, b.nelements);
  PetscCallCXX(eptr.resize(ne + 1));
  PetscCallCXX(eind.resize(4 * (size_t)ne));
  for (PetscInt e = 0; e < b.nelements; e++) {
    PetscInt v[4];
    FEMElementNodes(b, e, v);
    eptr[e] = (idx_t)(4 * e);
    for (PetscInt a = 0; a < 4; a++) eind[4 * e + a] = (idx_t)v[a];
  }
  eptr[ne] = 4 * ne;
  PetscCheck(METIS_MeshToDual(&ne, &nn, eptr.data(), eind.data(), &ncommon, &numflag, &xadj, &adjncy) == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_MeshToDual failed");
  PetscCallCXX(epart.assign(ne, 0));
  if (nparts > 1) {
    idx_t ncon = 1, np = (idx_t)nparts, objval, options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_CONTIG] = 1;
    options[METIS_OPTION_SEED]   = 7; /* reproducible partitions */
    const int status             = METIS_PartGraphKway(&ne, &ncon, xadj, adjncy, nullptr, nullptr, nullptr, &np, nullptr, nullptr, options, &objval, epart.data());
    if (status != METIS_OK) {
      METIS_Free(xadj);
      METIS_Free(adjncy);
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_PartGraphKway failed (status %d) for %" PetscInt_FMT " parts", status, nparts);
    }
  }
  /* face-connected components of each part */
  PetscCallCXX(parent.resize(ne));
  std::iota(parent.begin(), parent.end(), 0);
  for (idx_t e = 0; e < ne; e++)
    for (idx_t k = xadj[e]; k < xadj[e + 1]; k++) {
      const idx_t o = adjncy[k];
      if (epart[o] != epart[e]) continue;
      const PetscInt re = UnionFind(parent, e), ro = UnionFind(parent, o);
      if (re != ro) parent[std::max(re, ro)] = std::min(re, ro);
    }
  METIS_Free(xadj);
  METIS_Free(adjncy);
  /* number the components by (part, smallest element) so the numbering is reproducible */
  std::vector<std::pair<PetscInt, PetscInt>> roots;
  for (idx_t e = 0; e < ne; e++)
    if (UnionFind(parent, e) == e) PetscCallCXX(roots.push_back({(PetscInt)epart[e], (PetscInt)e}));
  std::sort(roots.begin(), roots.end());
  std::map<PetscInt, PetscInt> rootid;
  for (size_t r = 0; r < roots.size(); r++) rootid[roots[r].second] = (PetscInt)r;
  PetscCallCXX(b.part.resize(ne));
  for (idx_t e = 0; e < ne; e++) b.part[e] = rootid[UnionFind(parent, e)];
  b.nsub = (PetscInt)roots.size();
  if (b.nsub != nparts) PetscCall(PetscInfo(NULL, "METIS: %" PetscInt_FMT " parts gave %" PetscInt_FMT " face-connected subdomains\n", nparts, b.nsub));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode FEMDecomposeBody(MPI_Comm comm, FEMBody &b)
{
  PetscMPIInt rank;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (b.decomposition == FEM_DECOMPOSITION_STRUCTURED && b.isbox) {
    PetscCall(DecomposeStructured(b));
  } else {
    PetscInt nsub = 0;
    if (rank == 0) {
      PetscCall(DecomposeMETIS(b));
      nsub = b.nsub;
    } else PetscCallCXX(b.part.resize(b.nelements));
    PetscCallMPI(MPI_Bcast(&nsub, 1, MPIU_INT, 0, comm));
    PetscCallMPI(MPI_Bcast(b.part.data(), (PetscMPIInt)b.nelements, MPIU_INT, 0, comm));
    b.nsub = nsub;
  }
  PetscCall(FEMMarkInterfaceNodes(b));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The table of copies from (body, node, subdomain, dof) quadruples, in any order */
static PetscErrorCode BuildCopyTable(const std::vector<PetscInt> &quad, FEMCopyTable &t)
{
  const size_t        n = quad.size() / 4;
  std::vector<size_t> order(n);

  PetscFunctionBegin;
  for (size_t i = 0; i < n; i++) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    for (size_t c = 0; c < 3; c++)
      if (quad[4 * a + c] != quad[4 * b + c]) return quad[4 * a + c] < quad[4 * b + c];
    return false;
  });
  t = FEMCopyTable();
  PetscCallCXX(t.subdomains.reserve(n));
  PetscCallCXX(t.dofs.reserve(n));
  for (size_t k = 0; k < n; k++) {
    const PetscInt *q = &quad[4 * order[k]];
    if (t.body.empty() || t.body.back() != q[0] || t.node.back() != q[1]) {
      PetscCallCXX(t.body.push_back(q[0]));
      PetscCallCXX(t.node.push_back(q[1]));
      PetscCallCXX(t.offset.push_back((PetscInt)k));
    }
    PetscCallCXX(t.subdomains.push_back(q[2]));
    PetscCallCXX(t.dofs.push_back(q[3]));
  }
  PetscCallCXX(t.offset.push_back((PetscInt)n));
  PetscCallCXX(t.body.shrink_to_fit());
  PetscCallCXX(t.node.shrink_to_fit());
  PetscCallCXX(t.offset.shrink_to_fit());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Build the subdomains of this rank (elements, nodes, connectivity), the primal offsets of all
   subdomains, and the replicated table of copies of nodes on body boundaries and interfaces. */
PetscErrorCode FEMBuildLocalSubdomains(FEM fem)
{
  FEM_Impl   &impl = *fem->impl;
  PetscMPIInt size, rank;
  MPI_Comm    comm = PetscObjectComm((PetscObject)fem);

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  impl.nsubdomains = 0;
  for (FEMBody &b : impl.bodies) {
    b.firstsub = impl.nsubdomains;
    impl.nsubdomains += b.nsub;
  }
  PetscCheck(impl.nsubdomains >= size, comm, PETSC_ERR_ARG_SIZ,
             "%" PetscInt_FMT " subdomains for %d MPI ranks: every rank needs at least one subdomain; ask for more subdomains (-fem_subdomains) or run on fewer ranks", impl.nsubdomains, size);
  impl.firstlocal = (impl.nsubdomains * rank) / size;
  impl.nlocal     = (impl.nsubdomains * (rank + 1)) / size - impl.firstlocal;

  impl.local.clear();
  PetscCallCXX(impl.local.resize(impl.nlocal));
  for (PetscInt s = 0; s < impl.nlocal; s++) {
    const PetscInt id = impl.firstlocal + s;
    impl.local[s].id  = id;
    for (PetscInt bi = 0; bi < (PetscInt)impl.bodies.size(); bi++)
      if (id >= impl.bodies[bi].firstsub && id < impl.bodies[bi].firstsub + impl.bodies[bi].nsub) impl.local[s].body = bi;
  }
  /* one pass over the elements of each body that has local subdomains */
  for (PetscInt bi = 0; bi < (PetscInt)impl.bodies.size(); bi++) {
    const FEMBody &b     = impl.bodies[bi];
    const PetscInt first = std::max(b.firstsub, impl.firstlocal), last = std::min(b.firstsub + b.nsub, impl.firstlocal + impl.nlocal);
    if (first >= last) continue;
    for (PetscInt e = 0; e < b.nelements; e++) {
      const PetscInt id = b.firstsub + b.part[e];
      if (id >= first && id < last) PetscCallCXX(impl.local[id - impl.firstlocal].elements.push_back(e));
    }
  }
  std::vector<PetscInt> ndofs(impl.nsubdomains, 0);
  for (FEMSubdomain &sd : impl.local) {
    const FEMBody &b = impl.bodies[sd.body];
    PetscCheck(!sd.elements.empty(), PETSC_COMM_SELF, PETSC_ERR_PLIB, "Subdomain %" PetscInt_FMT " has no element", sd.id);
    sd.nodes.clear();
    PetscCallCXX(sd.nodes.reserve(sd.elements.size()));
    for (PetscInt e : sd.elements) {
      PetscInt v[4];
      FEMElementNodes(b, e, v);
      for (PetscInt a = 0; a < 4; a++) PetscCallCXX(sd.nodes.push_back(v[a]));
    }
    std::sort(sd.nodes.begin(), sd.nodes.end());
    sd.nodes.erase(std::unique(sd.nodes.begin(), sd.nodes.end()), sd.nodes.end());
    PetscCallCXX(sd.conn.resize(4 * sd.elements.size()));
    for (size_t e = 0; e < sd.elements.size(); e++) {
      PetscInt v[4];
      FEMElementNodes(b, sd.elements[e], v);
      for (PetscInt a = 0; a < 4; a++) sd.conn[4 * e + a] = (PetscInt)(std::lower_bound(sd.nodes.begin(), sd.nodes.end(), v[a]) - sd.nodes.begin());
    }
    ndofs[sd.id] = 3 * (PetscInt)sd.nodes.size();
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, ndofs.data(), (PetscMPIInt)impl.nsubdomains, MPIU_INT, MPI_SUM, comm));
  {
    /* interface nodes have a copy in every subdomain: the primal dofs may not fit PetscInt where the mesh's do */
    PetscInt64 total = 0;
    for (PetscInt s = 0; s < impl.nsubdomains; s++) total += ndofs[s];
    PetscCheck(total <= PETSC_MAX_INT, comm, PETSC_ERR_ARG_OUTOFRANGE,
               "The %" PetscInt_FMT " subdomains have %lld primal dofs (interface nodes counted once per subdomain): they do not fit %d-bit PetscInt indices (at most %" PetscInt_FMT
               "); use fewer cells or fewer subdomains",
               impl.nsubdomains, (long long)total, (int)(8 * sizeof(PetscInt)), (PetscInt)PETSC_MAX_INT);
  }
  PetscCallCXX(impl.subprimaloffset.assign(impl.nsubdomains + 1, 0));
  for (PetscInt s = 0; s < impl.nsubdomains; s++) impl.subprimaloffset[s + 1] = impl.subprimaloffset[s] + ndofs[s];
  for (FEMSubdomain &sd : impl.local) sd.primaloffset = impl.subprimaloffset[sd.id];

  /* copies of boundary and interface nodes: (body, node, subdomain, primal dof) from every rank */
  std::vector<PetscInt> mine, all;
  for (FEMSubdomain &sd : impl.local) {
    const FEMBody &b = impl.bodies[sd.body];
    for (size_t l = 0; l < sd.nodes.size(); l++) {
      const PetscInt n = sd.nodes[l];
      if (!b.oninterface[n] && !b.onboundary[n]) continue;
      PetscCallCXX(mine.insert(mine.end(), {sd.body, n, sd.id, sd.primaloffset + 3 * (PetscInt)l}));
    }
  }
  PetscCall(ConeFETIAllgather(comm, mine, all));
  PetscCall(BuildCopyTable(all, impl.copies));
  PetscFunctionReturn(PETSC_SUCCESS);
}
