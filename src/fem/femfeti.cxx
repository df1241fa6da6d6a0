/* From the decomposed model to the FETI input: subdomain matrices and loads, coordinates, Dirichlet
   dofs (primal mode), and the constraint matrix B with its row kinds and right-hand side, including the rows
   the caller hands over (FEMCreateFETIWithRows(): contact).

   Gluing: at a node held by k >= 2 subdomains (copies 0..k-1 in increasing subdomain order) each
   free component gets the k-1 Helmert rows
       h_j = (1, ..., 1, -j, 0, ..., 0) / sqrt(j (j + 1)),   j = 1..k-1   (j ones, then -j at copy j),
   an orthonormal basis of {v in R^k : sum v = 0}; their common kernel is exactly "all copies equal".
   They are non-redundant (unique multipliers, full row rank as the
   augmented Lagrangian needs) and orthonormal, so B B' = I on the gluing block (docs/feti.md). */
#include <conefeti/private/femimpl.h>
#include <conefeti/private/fetiimpl.h>

#include <algorithm>
#include <cmath>

struct RowEntry {
  PetscInt    col;
  PetscScalar val;
};

struct LocalRow {
  FETIRowKind           kind;
  std::vector<RowEntry> entries;
  PetscScalar           rhs;
  PetscInt              extra; /* index into the caller's rows, or -1 */
};

/* A row of the caller's (contact) in body-node terms */
struct ExtraRow {
  FETIRowKind              kind;
  std::vector<PetscInt>    body, node, comp;
  std::vector<PetscScalar> coef;
  PetscScalar              rhs;
};

/* Primal dof of the lowest copy of a body node component */
static PetscErrorCode FirstCopyDof(FEM_Impl &impl, PetscInt body, PetscInt node, PetscInt comp, PetscInt *dof, PetscInt *sub)
{
  PetscFunctionBegin;
  const PetscInt i = impl.copies.Find(body, node);
  PetscCheck(i >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Node %" PetscInt_FMT " of body %" PetscInt_FMT " has no copy entry", node, body);
  *dof = impl.copies.Dofs(i)[0] + comp;
  *sub = impl.copies.Subdomains(i)[0];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The caller's rows, checked: every term on a boundary node of an existing body */
static PetscErrorCode GatherExtraRows(FEM fem, PetscInt nrows, const FETIRowKind kinds[], const PetscInt rowptr[], const PetscInt body[], const PetscInt node[], const PetscInt comp[],
                                      const PetscScalar coef[], const PetscScalar rhs[], std::vector<ExtraRow> &extra)
{
  FEM_Impl &impl = *fem->impl;

  PetscFunctionBegin;
  for (PetscInt r = 0; r < nrows; r++) {
    ExtraRow row;
    PetscCheck(rowptr[r + 1] > rowptr[r], PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "FEMCreateFETIWithRows(): row %" PetscInt_FMT " has no term", r);
    row.kind = kinds[r];
    row.rhs  = rhs ? rhs[r] : 0.0;
    for (PetscInt t = rowptr[r]; t < rowptr[r + 1]; t++) {
      PetscCheck(body[t] >= 0 && body[t] < (PetscInt)impl.bodies.size(), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                 "FEMCreateFETIWithRows(): row %" PetscInt_FMT ": body %" PetscInt_FMT " does not exist", r, body[t]);
      PetscCheck(comp[t] >= 0 && comp[t] < 3, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "FEMCreateFETIWithRows(): row %" PetscInt_FMT ": component %" PetscInt_FMT " must be 0, 1 or 2", r, comp[t]);
      PetscCheck(impl.copies.Find(body[t], node[t]) >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
                 "FEMCreateFETIWithRows(): row %" PetscInt_FMT ": node %" PetscInt_FMT " of body %" PetscInt_FMT " is not on the body's boundary", r, node[t], body[t]);
      PetscCallCXX(row.body.push_back(body[t]));
      PetscCallCXX(row.node.push_back(node[t]));
      PetscCallCXX(row.comp.push_back(comp[t]));
      PetscCallCXX(row.coef.push_back(coef[t]));
    }
    PetscCallCXX(extra.push_back(std::move(row)));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The rows of the local subdomains, subdomain by subdomain; persub: how many each subdomain anchors */
static PetscErrorCode BuildRows(FEM fem, const std::vector<ExtraRow> &extra, std::vector<LocalRow> &rows, std::vector<PetscInt> &persub)
{
  FEM_Impl                          &impl = *fem->impl;
  std::vector<std::vector<PetscInt>> extrabyanchor(impl.nlocal);

  PetscFunctionBegin;
  PetscCallCXX(persub.assign(impl.nlocal, 0));
  for (size_t a = 0; a < extra.size(); a++) {
    const ExtraRow &r      = extra[a];
    PetscInt        anchor = PETSC_MAX_INT;
    for (size_t t = 0; t < r.body.size(); t++) {
      PetscInt dof = -1, sub = -1;
      PetscCall(FirstCopyDof(impl, r.body[t], r.node[t], r.comp[t], &dof, &sub));
      anchor = std::min(anchor, sub);
    }
    if (anchor >= impl.firstlocal && anchor < impl.firstlocal + impl.nlocal) PetscCallCXX(extrabyanchor[anchor - impl.firstlocal].push_back((PetscInt)a));
  }
  for (PetscInt s = 0; s < impl.nlocal; s++) {
    const FEMSubdomain &sd    = impl.local[s];
    const FEMBody      &b     = impl.bodies[sd.body];
    const size_t        first = rows.size();
    for (PetscInt n : sd.nodes) {
      const PetscInt e = impl.copies.Find(sd.body, n);
      if (e < 0 || impl.copies.Subdomains(e)[0] != sd.id) continue; /* rows live with the lowest copy */
      const PetscInt  k    = impl.copies.Count(e);
      const PetscInt *dofs = impl.copies.Dofs(e);
      for (PetscInt comp = 0; comp < 3; comp++) {
        if (b.dirichletmask[n] & (1u << comp)) {
          /* a row per copy, except for copies removed from the primal (subdomains the Dirichlet dofs hold firmly) */
          for (PetscInt j = 0; j < k; j++)
            if (impl.dirichletrows[impl.copies.Subdomains(e)[j]]) PetscCallCXX(rows.push_back({FETI_ROW_DIRICHLET, {{dofs[j] + comp, 1.0}}, FEMDirichletValue(b, n, comp), -1}));
        } else {
          for (PetscInt j = 1; j < k; j++) {
            LocalRow        row{FETI_ROW_GLUING, {}, 0.0, -1};
            const PetscReal scale = 1.0 / std::sqrt((PetscReal)(j * (j + 1)));
            for (PetscInt i = 0; i < j; i++) PetscCallCXX(row.entries.push_back({dofs[i] + comp, scale}));
            PetscCallCXX(row.entries.push_back({dofs[j] + comp, -j * scale}));
            PetscCallCXX(rows.push_back(row));
          }
        }
      }
    }
    for (PetscInt a : extrabyanchor[s]) {
      const ExtraRow &r = extra[a];
      LocalRow        row{r.kind, {}, r.rhs, a};
      for (size_t t = 0; t < r.body.size(); t++) {
        PetscInt dof = -1, sub = -1;
        PetscCall(FirstCopyDof(impl, r.body[t], r.node[t], r.comp[t], &dof, &sub));
        PetscCallCXX(row.entries.push_back({dof, r.coef[t]}));
      }
      PetscCallCXX(rows.push_back(row));
    }
    persub[s] = (PetscInt)(rows.size() - first);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* How many of B's rows each rank owns (nowned) and, per row built here, the rank that owns it (dest).
   The rows keep their global order (by lowest subdomain); only the cuts between the ranks move. Kept with the
   rank of their lowest subdomain, the rows are uneven: the rows between two ranks' subdomains and every contact
   row of a zone that lies in one rank's subdomains fall to one rank (on the brick at 2 ranks 38055 against
   25836), and the dual vector operations of the QP solver, a sizeable part of its time, follow the rows. With
   -fem_balance_multipliers each rank gets about its share of the rows, cut only between the row groups of two
   subdomains (so a contact node's rows, anchored at one subdomain, never straddle two ranks). */
static PetscErrorCode LayoutRows(FEM fem, const std::vector<PetscInt> &persub, PetscInt firstrow, std::vector<PetscMPIInt> &dest, PetscInt *nowned)
{
  FEM_Impl             &impl = *fem->impl;
  MPI_Comm              comm = PetscObjectComm((PetscObject)fem);
  PetscMPIInt           size, rank;
  std::vector<PetscInt> counts(impl.nsubdomains, 0), cut;
  PetscInt              total = 0;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscInt nlocalrows = 0;
  for (PetscInt s = 0; s < impl.nlocal; s++) nlocalrows += persub[s];
  PetscCallCXX(dest.assign(nlocalrows, rank));
  *nowned = nlocalrows;
  if (size == 1 || !impl.balancerows) PetscFunctionReturn(PETSC_SUCCESS);
  for (PetscInt s = 0; s < impl.nlocal; s++) counts[impl.firstlocal + s] = persub[s];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts.data(), (PetscMPIInt)impl.nsubdomains, MPIU_INT, MPI_SUM, comm));
  for (PetscInt c : counts) total += c;
  /* cut[q]: the first global row of rank q, at the subdomain group boundary nearest to q total / size */
  PetscCallCXX(cut.assign(size + 1, total));
  cut[0] = 0;
  {
    PetscInt    prefix = 0, s = 0;
    PetscMPIInt q = 1;
    for (; q < size; q++) {
      const PetscReal target = (PetscReal)total * q / size;
      while (s < impl.nsubdomains && std::abs((PetscReal)(prefix + counts[s]) - target) <= std::abs((PetscReal)prefix - target)) prefix += counts[s++];
      cut[q] = std::max(prefix, cut[q - 1]);
    }
  }
  *nowned = cut[rank + 1] - cut[rank];
  for (PetscInt r = 0; r < nlocalrows; r++) {
    const PetscInt row = firstrow + r;
    PetscMPIInt    q   = 0;
    while (row >= cut[q + 1]) q++;
    dest[r] = q;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMCreateFETI - Build the FETI problem of the model: subdomain stiffness matrices, loads, coordinates,
  Dirichlet dofs (primal mode) and the constraint matrix B with gluing and Dirichlet rows.

  Collective

  Input Parameter:
. fem - the model, set up

  Output Parameter:
. feti - the FETI problem, not yet set up: call `FETISetFromOptions()` and `FETISetUp()` (its options prefix is the model's)

  Notes:
  Gluing uses, at a node held by k subdomains, k - 1 orthonormal (Helmert) rows per free component;
  in Total FETI a Dirichlet component gets one identity row per copy and no gluing rows, its right-hand side c the
  prescribed value (`FEMSetDisplacement()`; 0 when clamped). In the primal
  mode the Dirichlet dofs are handed to `FETISetSubdomainDirichletDofs()` (and nonzero values to
  `FETISetSubdomainDirichletValues()`, which lifts them into the load) and get no rows at all, except in
  subdomains they hold weakly: the smallest RMS value on the subdomain's Dirichlet dofs over its RMS value
  overall of a unit combination of its rigid-body modes (about 0.43 for a cube clamped on a whole face, 0
  for one touching Gamma_u at a node or along a line, about a/H for a patch of size a) below
  -fem_dirichlet_min_hold (0.25). Such a subdomain would swing about its small support (K_s nearly singular,
  F many times larger); it floats instead and its Dirichlet dofs get rows as in Total FETI (-info lists the
  subdomains and their values).
  Rows are ordered by the lowest subdomain they touch, so the problem (and the iterates) do not depend on the
  number of ranks. They are owned by the rank of that subdomain with -fem_balance_multipliers 0; by default the
  cuts between the ranks move (only between two subdomains' rows) so that every rank owns about as many rows.

  Level: beginner

.seealso: `FEMSetUp()`, `FETISetUp()`, `FETISolveLinear()`, `FEMCreateFETIWithRows()`
@*/
PetscErrorCode FEMCreateFETI(FEM fem, FETI *feti)
{
  PetscFunctionBegin;
  PetscCall(FEMCreateFETIWithRows(fem, 0, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, feti));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMCreateFETIWithRows - Build the FETI problem of the model (`FEMCreateFETI()`) with more constraint rows in B, given in
  body-node terms (the rows of contact).

  Collective (the same rows on every rank)

  Input Parameters:
+ fem    - the model, set up
. nrows  - number of rows
. kinds  - kind of each row (typically `FETI_ROW_CONTACT_NORMAL` or `FETI_ROW_CONTACT_TANGENTIAL`)
. rowptr - nrows + 1 offsets: row r has the terms rowptr[r] <= t < rowptr[r+1]
. body   - per term: the body
. node   - per term: the body node (on the body's boundary)
. comp   - per term: the displacement component 0, 1, 2
. coef   - per term: the coefficient
- rhs    - per row: the right-hand side c (the gap for a contact row), or NULL for zeros

  Output Parameters:
+ rowindex - per row: its global row in B (its multiplier index), the same on every rank (may be NULL)
- feti     - the new FETI object, not yet set up

  Notes:
  Row r reads sum_t coef[t] u(body[t], node[t])[comp[t]] (<= or =) rhs[r]. A node held by several subdomains is
  addressed through its copy in the lowest subdomain (the copies are glued). The rows are placed after the gluing
  and Dirichlet rows of the lowest subdomain they touch, in the order given, and owned by the rank that owns that
  subdomain's rows (`FEMCreateFETI()`); consecutive rows stay consecutive there (so a normal and its two
  tangential rows form one block on one rank).
  The model keeps none of them: they pass through, from the caller to the FETI object.

  Level: intermediate

.seealso: `FEMCreateFETI()`, `FEMGetNodeCopies()`, `FEMGetTaggedNodes()`
@*/
PetscErrorCode FEMCreateFETIWithRows(FEM fem, PetscInt nextra, const FETIRowKind kinds[], const PetscInt rowptr[], const PetscInt body[], const PetscInt node[], const PetscInt comp[],
                                     const PetscScalar coef[], const PetscScalar rhs[], PetscInt rowindex[], FETI *feti)
{
  FEM_Impl                &impl = *fem->impl;
  MPI_Comm                 comm = PetscObjectComm((PetscObject)fem);
  std::vector<Mat>         K(impl.nlocal);
  std::vector<Vec>         f(impl.nlocal);
  std::vector<LocalRow>    rows;
  std::vector<ExtraRow>    extra;
  PetscInt                 nprimal = 0, nrows, firstrow, nowned;
  std::vector<PetscInt>    persub;
  std::vector<PetscMPIInt> dest;
  PetscMPIInt              size;
  const char              *prefix;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscAssertPointer(feti, 11);
  PetscCheck(impl.setupcalled, comm, PETSC_ERR_ORDER, "Call FEMSetUp() before FEMCreateFETI()");
  PetscCheck(nextra >= 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "FEMCreateFETIWithRows(): %" PetscInt_FMT " rows", nextra);
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(GatherExtraRows(fem, nextra, kinds, rowptr, body, node, comp, coef, rhs, extra));
  PetscCall(FETICreate(comm, feti));
  PetscCall(PetscObjectGetOptionsPrefix((PetscObject)fem, &prefix));
  PetscCall(FETISetOptionsPrefix(*feti, prefix));
  for (PetscInt s = 0; s < impl.nlocal; s++) {
    PetscCall(FEMAssembleSubdomain(fem, impl.local[s], &K[s], &f[s]));
    nprimal += 3 * (PetscInt)impl.local[s].nodes.size();
  }
  PetscCall(FETISetSubdomains(*feti, impl.nlocal, K.data(), f.data()));
  /* which subdomains get their Dirichlet dofs as rows of B: all in Total FETI; in the primal mode those
     that Gamma_u holds less firmly than -fem_dirichlet_min_hold (decided below, then shared) */
  PetscCallCXX(impl.dirichletrows.assign(impl.nsubdomains, impl.dirichletmode == FEM_DIRICHLET_PRIMAL ? 0 : 1));
  for (PetscInt s = 0; s < impl.nlocal; s++) {
    const FEMSubdomain   &sd = impl.local[s];
    const FEMBody        &b  = impl.bodies[sd.body];
    Vec                   coords;
    PetscScalar          *a;
    std::vector<PetscInt> dirichlet;
    PetscCall(MatDestroy(&K[s]));
    PetscCall(VecDestroy(&f[s]));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * (PetscInt)sd.nodes.size(), &coords));
    PetscCall(VecSetBlockSize(coords, 3));
    PetscCall(VecGetArray(coords, &a));
    for (size_t l = 0; l < sd.nodes.size(); l++)
      for (PetscInt d = 0; d < 3; d++) a[3 * l + d] = b.coords[3 * sd.nodes[l] + d];
    PetscCall(VecRestoreArray(coords, &a));
    PetscCall(FETISetSubdomainCoordinates(*feti, s, coords));
    if (impl.dirichletmode == FEM_DIRICHLET_PRIMAL) {
      IS        is;
      PetscReal hold = PETSC_MAX_REAL;
      for (size_t l = 0; l < sd.nodes.size(); l++)
        for (PetscInt c = 0; c < 3; c++)
          if (b.dirichletmask[sd.nodes[l]] & (1u << c)) PetscCallCXX(dirichlet.push_back(3 * (PetscInt)l + c));
      /* A subdomain that Gamma_u holds only at a small patch (METIS cuts the clamped face anywhere) keeps
         near-zero-energy modes, swinging about the patch: K_NN is nearly singular, K+ and with it F are
         huge on its interface. Such a subdomain floats instead, its Dirichlet dofs imposed by
         multipliers as in Total FETI (docs/feti.md, "Two modes") */
      if (!dirichlet.empty() && impl.dirichlethold > 0) PetscCall(FETIDirichletHold(coords, 3 * (PetscInt)sd.nodes.size(), dirichlet, &hold));
      if (hold < impl.dirichlethold) {
        PetscCall(PetscInfo(fem, "Subdomain %" PetscInt_FMT ": Gamma_u holds it at %zu dofs, hold %g < -fem_dirichlet_min_hold %g: its Dirichlet dofs become multipliers\n", sd.id, dirichlet.size(),
                            (double)hold, (double)impl.dirichlethold));
        impl.dirichletrows[sd.id] = 1;
        dirichlet.clear();
      } else if (!dirichlet.empty() && impl.dirichlethold > 0) PetscCall(PetscInfo(fem, "Subdomain %" PetscInt_FMT ": Dirichlet dofs kept in the primal, hold %g\n", sd.id, (double)hold));
      else if (!dirichlet.empty()) PetscCall(PetscInfo(fem, "Subdomain %" PetscInt_FMT ": Dirichlet dofs kept in the primal (hold not computed: -fem_dirichlet_min_hold 0)\n", sd.id));
      PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)dirichlet.size(), dirichlet.data(), PETSC_COPY_VALUES, &is));
      PetscCall(FETISetSubdomainDirichletDofs(*feti, s, is));
      PetscCall(ISDestroy(&is));
      if (!dirichlet.empty() && !b.dirichletvalue.empty()) { /* prescribed displacements: FETI lifts them */
        Vec uD;
        PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * (PetscInt)sd.nodes.size(), &uD));
        PetscCall(VecGetArray(uD, &a));
        for (size_t l = 0; l < sd.nodes.size(); l++)
          for (PetscInt c = 0; c < 3; c++) a[3 * l + c] = FEMDirichletValue(b, sd.nodes[l], c);
        PetscCall(VecRestoreArray(uD, &a));
        PetscCall(FETISetSubdomainDirichletValues(*feti, s, uD));
        PetscCall(VecDestroy(&uD));
      }
    }
    PetscCall(VecDestroy(&coords));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, impl.dirichletrows.data(), (PetscMPIInt)impl.nsubdomains, MPIU_INT, MPI_MAX, comm));

  /* B: rows numbered rank by rank, subdomain by subdomain; owned as LayoutRows() says */
  PetscCall(BuildRows(fem, extra, rows, persub));
  nrows = (PetscInt)rows.size();
  PetscCallMPI(MPI_Scan(&nrows, &firstrow, 1, MPIU_INT, MPI_SUM, comm));
  firstrow -= nrows;
  PetscCall(LayoutRows(fem, persub, firstrow, dest, &nowned));
  {
    Mat                      B;
    Vec                      c, meta; /* meta: per owned row its kind, diagonal and off-diagonal nonzeros */
    std::vector<PetscInt>    dnnz(nowned), onnz(nowned), extrarows(nextra, -1), primalstart(size + 1, 0);
    std::vector<FETIRowKind> kinds(nowned);
    /* every rank's first primal dof: the preallocation of a row counts its entries against its owner's columns */
    {
      const PetscInt mine = impl.subprimaloffset[impl.firstlocal];
      PetscCallMPI(MPI_Allgather(&mine, 1, MPIU_INT, primalstart.data(), 1, MPIU_INT, comm));
      primalstart[size] = impl.subprimaloffset[impl.nsubdomains];
    }
    PetscCall(VecCreateMPI(comm, 3 * nowned, PETSC_DETERMINE, &meta)); /* B's row layout, three numbers per row */
    for (PetscInt r = 0; r < nrows; r++) {
      const PetscMPIInt q    = dest[r];
      PetscScalar       v[3] = {(PetscScalar)rows[r].kind, 0, 0};
      PetscInt          idx[3];
      for (const RowEntry &e : rows[r].entries) {
        if (e.col >= primalstart[q] && e.col < primalstart[q + 1]) v[1] += 1;
        else v[2] += 1;
      }
      for (PetscInt k = 0; k < 3; k++) idx[k] = 3 * (firstrow + r) + k;
      PetscCall(VecSetValues(meta, 3, idx, v, INSERT_VALUES));
      if (rows[r].extra >= 0) extrarows[rows[r].extra] = firstrow + r;
    }
    PetscCall(VecAssemblyBegin(meta));
    PetscCall(VecAssemblyEnd(meta));
    {
      const PetscScalar *m;
      PetscCall(VecGetArrayRead(meta, &m));
      for (PetscInt r = 0; r < nowned; r++) {
        kinds[r] = (FETIRowKind)(PetscInt)PetscRealPart(m[3 * r]);
        dnnz[r]  = (PetscInt)PetscRealPart(m[3 * r + 1]);
        onnz[r]  = (PetscInt)PetscRealPart(m[3 * r + 2]);
      }
      PetscCall(VecRestoreArrayRead(meta, &m));
    }
    PetscCall(VecDestroy(&meta));
    PetscCall(MatCreate(comm, &B));
    PetscCall(MatSetSizes(B, nowned, nprimal, PETSC_DETERMINE, PETSC_DETERMINE));
    PetscCall(MatSetType(B, MATAIJ));
    PetscCall(MatXAIJSetPreallocation(B, 1, dnnz.data(), onnz.data(), NULL, NULL));
    PetscCall(MatCreateVecs(B, NULL, &c));
    for (PetscInt r = 0; r < nrows; r++) { /* rows owned elsewhere go there at the assembly */
      const PetscInt row = firstrow + r;
      for (const RowEntry &e : rows[r].entries) PetscCall(MatSetValue(B, row, e.col, e.val, ADD_VALUES));
      if (rows[r].rhs != 0.0) PetscCall(VecSetValue(c, row, rows[r].rhs, INSERT_VALUES));
    }
    PetscCall(MatAssemblyBegin(B, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(B, MAT_FINAL_ASSEMBLY));
    PetscCall(VecAssemblyBegin(c));
    PetscCall(VecAssemblyEnd(c));
    PetscCall(FETISetConstraints(*feti, B, c, kinds.data()));
    PetscCall(MatDestroy(&B));
    PetscCall(VecDestroy(&c));
    /* every rank learns where every extra row went */
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, extrarows.data(), (PetscMPIInt)nextra, MPIU_INT, MPI_MAX, comm));
    if (rowindex) std::copy(extrarows.begin(), extrarows.end(), rowindex);
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
