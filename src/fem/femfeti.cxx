/* From the decomposed model to the FETI input: subdomain matrices and loads, coordinates, Dirichlet
   dofs (primal mode), and the constraint matrix B with its row kinds and right-hand side.

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
  PetscInt              appended; /* index into the appended rows, or -1 */
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

static PetscErrorCode BuildRows(FEM fem, std::vector<LocalRow> &rows)
{
  FEM_Impl                          &impl = *fem->impl;
  std::vector<std::vector<PetscInt>> appendedbyanchor(impl.nlocal);

  PetscFunctionBegin;
  for (size_t a = 0; a < impl.appended.size(); a++) {
    const FEMAppendedRow &r      = impl.appended[a];
    PetscInt              anchor = PETSC_MAX_INT;
    for (size_t t = 0; t < r.body.size(); t++) {
      PetscInt dof = -1, sub = -1;
      PetscCall(FirstCopyDof(impl, r.body[t], r.node[t], r.comp[t], &dof, &sub));
      anchor = std::min(anchor, sub);
    }
    if (anchor >= impl.firstlocal && anchor < impl.firstlocal + impl.nlocal) PetscCallCXX(appendedbyanchor[anchor - impl.firstlocal].push_back((PetscInt)a));
  }
  for (PetscInt s = 0; s < impl.nlocal; s++) {
    const FEMSubdomain &sd = impl.local[s];
    const FEMBody      &b  = impl.bodies[sd.body];
    for (PetscInt n : sd.nodes) {
      const PetscInt e = impl.copies.Find(sd.body, n);
      if (e < 0 || impl.copies.Subdomains(e)[0] != sd.id) continue; /* rows live with the lowest copy */
      const PetscInt  k    = impl.copies.Count(e);
      const PetscInt *dofs = impl.copies.Dofs(e);
      for (PetscInt comp = 0; comp < 3; comp++) {
        if (b.dirichletmask[n] & (1u << comp)) {
          /* a row per copy, except for copies removed from the primal (subdomains the Dirichlet dofs hold firmly) */
          for (PetscInt j = 0; j < k; j++)
            if (impl.dirichletrows[impl.copies.Subdomains(e)[j]]) PetscCallCXX(rows.push_back({FETI_ROW_DIRICHLET, {{dofs[j] + comp, 1.0}}, 0.0, -1}));
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
    for (PetscInt a : appendedbyanchor[s]) {
      const FEMAppendedRow &r = impl.appended[a];
      LocalRow              row{r.kind, {}, r.rhs, a};
      for (size_t t = 0; t < r.body.size(); t++) {
        PetscInt dof = -1, sub = -1;
        PetscCall(FirstCopyDof(impl, r.body[t], r.node[t], r.comp[t], &dof, &sub));
        PetscCallCXX(row.entries.push_back({dof, r.coef[t]}));
      }
      PetscCallCXX(rows.push_back(row));
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMCreateFETI - Build the FETI problem of the model: subdomain stiffness matrices, loads, coordinates,
  Dirichlet dofs (primal mode) and the constraint matrix B with gluing, Dirichlet and appended rows.

  Collective

  Input Parameter:
. fem - the model, set up (and with any `FEMAddConstraintRows()` done)

  Output Parameter:
. feti - the FETI problem, not yet set up: call `FETISetFromOptions()` and `FETISetUp()` (its options prefix is the model's)

  Notes:
  Gluing uses, at a node held by k subdomains, k - 1 orthonormal (Helmert) rows per free component;
  in Total FETI a Dirichlet component gets one identity row per copy and no gluing rows. In the primal
  mode the Dirichlet dofs are handed to `FETISetSubdomainDirichletDofs()` and get no rows at all, except in
  subdomains they hold weakly: the smallest RMS value on the subdomain's Dirichlet dofs over its RMS value
  overall of a unit combination of its rigid-body modes (about 0.43 for a cube clamped on a whole face, 0
  for one touching Gamma_u at a node or along a line, about a/H for a patch of size a) below
  -fem_dirichlet_min_hold (0.25). Such a subdomain would swing about its small support (K_s nearly singular,
  F many times larger); it floats instead and its Dirichlet dofs get rows as in Total FETI (-info lists the
  subdomains and their values).
  Rows are owned by the rank of the lowest subdomain they touch and ordered by that subdomain, so
  the problem (and the iterates) do not depend on the number of ranks.

  Level: beginner

.seealso: `FEMSetUp()`, `FETISetUp()`, `FETISolveLinear()`, `FEMAddConstraintRows()`
@*/
PetscErrorCode FEMCreateFETI(FEM fem, FETI *feti)
{
  FEM_Impl             &impl = *fem->impl;
  MPI_Comm              comm = PetscObjectComm((PetscObject)fem);
  std::vector<Mat>      K(impl.nlocal);
  std::vector<Vec>      f(impl.nlocal);
  std::vector<LocalRow> rows;
  PetscInt              nprimal = 0, first, nrows, firstrow;
  const char           *prefix;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscAssertPointer(feti, 2);
  PetscCheck(impl.setupcalled, comm, PETSC_ERR_ORDER, "Call FEMSetUp() before FEMCreateFETI()");
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
      } else if (!dirichlet.empty()) PetscCall(PetscInfo(fem, "Subdomain %" PetscInt_FMT ": Dirichlet dofs kept in the primal, hold %g\n", sd.id, (double)hold));
      PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)dirichlet.size(), dirichlet.data(), PETSC_COPY_VALUES, &is));
      PetscCall(FETISetSubdomainDirichletDofs(*feti, s, is));
      PetscCall(ISDestroy(&is));
    }
    PetscCall(VecDestroy(&coords));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, impl.dirichletrows.data(), (PetscMPIInt)impl.nsubdomains, MPIU_INT, MPI_MAX, comm));

  /* B: rows numbered rank by rank */
  PetscCall(BuildRows(fem, rows));
  nrows = (PetscInt)rows.size();
  PetscCallMPI(MPI_Scan(&nrows, &firstrow, 1, MPIU_INT, MPI_SUM, comm));
  firstrow -= nrows;
  first = impl.subprimaloffset[impl.firstlocal];
  {
    Mat                      B;
    Vec                      c;
    std::vector<PetscInt>    dnnz(nrows), onnz(nrows);
    std::vector<FETIRowKind> kinds(nrows);
    std::vector<PetscInt>    appendedrows(impl.appended.size(), -1);
    for (PetscInt r = 0; r < nrows; r++) {
      for (const RowEntry &e : rows[r].entries) {
        if (e.col >= first && e.col < first + nprimal) dnnz[r]++;
        else onnz[r]++;
      }
      kinds[r] = rows[r].kind;
      if (rows[r].appended >= 0) appendedrows[rows[r].appended] = firstrow + r;
    }
    PetscCall(MatCreate(comm, &B));
    PetscCall(MatSetSizes(B, nrows, nprimal, PETSC_DETERMINE, PETSC_DETERMINE));
    PetscCall(MatSetType(B, MATAIJ));
    PetscCall(MatXAIJSetPreallocation(B, 1, dnnz.data(), onnz.data(), NULL, NULL));
    PetscCall(MatCreateVecs(B, NULL, &c));
    for (PetscInt r = 0; r < nrows; r++) {
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
    /* every rank learns where every appended row went */
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, appendedrows.data(), (PetscMPIInt)appendedrows.size(), MPIU_INT, MPI_MAX, comm));
    impl.appendedrows = appendedrows;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}
