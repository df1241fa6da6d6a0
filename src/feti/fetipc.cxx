/* FETI preconditioners for the projected CG on P F P, applied as P M^-1 P:
     lumped     M^-1 = B K_bb B'                            (b: the dofs B touches)
     dirichlet  M^-1 = B S_bb B',  S_bb = K_bb - K_bi K_ii^-1 K_ib   (Schur complement on b)
   With orthonormal B rows (Helmert gluing, identity Dirichlet rows) no further scaling is needed for
   bodies of one material. They are PC types ("lumped", "dirichlet") so that -feti_pc_type selects
   them; they find their FETI object through the P F P shell they precondition. */
#include <conefeti/private/fetiimpl.h>
#include <petsc/private/pcimpl.h>

#include <algorithm>
#include <array>

struct PC_FETI {
  PetscBool dirichlet;
  FETI      feti; /* not referenced: the FETI object owns the KSP that owns this PC */
  Vec       wd, wp1, wp2;
  PetscBool projected; /* P M^-1 P; false: M^-1 alone, for a caller that projects around it (PCFETISetProjected()) */
};

/* The primal mask of the dofs touched by B (1 there, 0 elsewhere); built once */
PetscErrorCode FETISetUpBoundaryMask(FETI feti)
{
  FETI_Impl &impl = *feti->impl;
  PetscInt   rstart, rend;

  PetscFunctionBegin;
  if (impl.boundarymask) PetscFunctionReturn(PETSC_SUCCESS);
  PetscCall(VecDuplicate(impl.wp1, &impl.boundarymask));
  PetscCall(VecSet(impl.boundarymask, 0.0));
  PetscCall(MatGetOwnershipRange(impl.B, &rstart, &rend));
  for (PetscInt r = rstart; r < rend; r++) {
    const PetscInt    *cols;
    const PetscScalar *vals;
    PetscInt           ncols;
    PetscCall(MatGetRow(impl.B, r, &ncols, &cols, &vals));
    for (PetscInt j = 0; j < ncols; j++)
      if (vals[j] != 0.0) PetscCall(VecSetValue(impl.boundarymask, cols[j], 1.0, INSERT_VALUES));
    PetscCall(MatRestoreRow(impl.B, r, &ncols, &cols, &vals));
  }
  PetscCall(VecAssemblyBegin(impl.boundarymask));
  PetscCall(VecAssemblyEnd(impl.boundarymask));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* K_ii of K_V as PETSc's block Cholesky takes it: SBAIJ of block size 3 over whole nodes, its nodes permuted by the
   fill-reducing ordering (FETIPermuteByNodes()). A node with only some of its dofs interior (one component on a Dirichlet
   face, a contact row along one axis) keeps the others as padding rows decoupled with the diagonal d, as Kreg keeps its
   removed dofs: the solve is zero there. iimap[k]: the interior index of the factor's row k, -1 at a padding row. */
static PetscErrorCode InteriorByNodes(FETISubdomain &sd, Mat KV, const std::vector<PetscInt> &interior, MatOrderingType ordering, Mat *Kperm)
{
  std::vector<PetscInt> ipos(sd.n, -1), node(sd.n / 3, -1), nodes; /* dof -> interior index, node -> padded node, padded node -> node */
  Mat                   A;

  PetscFunctionBegin;
  for (size_t k = 0; k < interior.size(); k++) {
    ipos[interior[k]] = (PetscInt)k;
    if (node[interior[k] / 3] < 0) {
      node[interior[k] / 3] = (PetscInt)nodes.size();
      PetscCallCXX(nodes.push_back(interior[k] / 3));
    }
  }
  const PetscInt nn = (PetscInt)nodes.size();
  /* the upper block triangle, block row by block row: the 3x3 blocks (row-major) of the interior entries */
  std::vector<std::vector<std::pair<PetscInt, std::array<PetscScalar, 9>>>> rows(nn);
  std::vector<PetscInt>                                                     slot(nn, -1);
  std::vector<PetscInt>                                                     nnz(nn);
  for (PetscInt I = 0; I < nn; I++) {
    auto &row = rows[I];
    for (PetscInt r = 0; r < 3; r++) {
      const PetscInt     dof = 3 * nodes[I] + r;
      const PetscInt    *cols;
      const PetscScalar *vals;
      PetscInt           ncols;
      if (ipos[dof] < 0) continue;
      PetscCall(MatGetRow(KV, dof, &ncols, &cols, &vals));
      for (PetscInt j = 0; j < ncols; j++) {
        if (ipos[cols[j]] < 0) continue;
        const PetscInt J = node[cols[j] / 3];
        if (J < I) continue;
        if (slot[J] < 0) {
          slot[J] = (PetscInt)row.size();
          PetscCallCXX(row.push_back({J, {}}));
        }
        row[slot[J]].second[3 * r + cols[j] % 3] = vals[j];
      }
      PetscCall(MatRestoreRow(KV, dof, &ncols, &cols, &vals));
    }
    if (slot[I] < 0) PetscCallCXX(row.push_back({I, {}})); /* a node whose interior dofs couple to nothing: cannot be (K_V is SPD), but keep the diagonal block */
    for (auto &b : row) {
      if (b.first == I)
        for (PetscInt r = 0; r < 3; r++)
          if (ipos[3 * nodes[I] + r] < 0) b.second[4 * r] = sd.regdiag;
      slot[b.first] = -1;
    }
    slot[I] = -1;
    nnz[I]  = (PetscInt)row.size();
  }
  PetscCall(MatCreateSeqSBAIJ(PETSC_COMM_SELF, 3, 3 * nn, 3 * nn, 0, nnz.data(), &A));
  for (PetscInt I = 0; I < nn; I++)
    for (auto &b : rows[I]) PetscCall(MatSetValuesBlocked(A, 1, &I, 1, &b.first, b.second.data(), INSERT_VALUES));
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  {
    std::vector<PetscInt> perm, iperm;
    PetscCall(FETIPermuteByNodes(A, ordering, perm, iperm, Kperm));
    PetscCallCXX(sd.iimap.resize(perm.size()));
    for (size_t k = 0; k < perm.size(); k++) sd.iimap[k] = ipos[3 * nodes[perm[k] / 3] + perm[k] % 3];
  }
  PetscCall(MatDestroy(&A));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* y_i = K_ii^-1 x_i with the subdomain's interior factor (both in interior order) */
static PetscErrorCode InteriorSolve(FETISubdomain &sd, Vec x, Vec y)
{
  const PetscScalar *xa;
  PetscScalar       *ya, *w;
  const PetscInt     nf = (PetscInt)sd.iimap.size();

  PetscFunctionBegin;
  if (sd.iimap.empty()) {
    PetscCall(MatSolve(sd.Fii, x, y));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (sd.fii.nb) w = sd.iiwork.data();
  else PetscCall(VecGetArrayWrite(sd.wi, &w));
  PetscCall(VecGetArrayRead(x, &xa));
  for (PetscInt k = 0; k < nf; k++) w[k] = sd.iimap[k] >= 0 ? xa[sd.iimap[k]] : 0.0;
  PetscCall(VecRestoreArrayRead(x, &xa));
  if (sd.fii.nb) PetscCall(FETIFloatFactorSolve(sd.fii, w));
  else {
    PetscCall(VecRestoreArrayWrite(sd.wi, &w));
    PetscCall(MatSolve(sd.Fii, sd.wi, sd.wi2));
    PetscCall(VecGetArray(sd.wi2, &w));
  }
  PetscCall(VecGetArrayWrite(y, &ya));
  for (PetscInt k = 0; k < nf; k++)
    if (sd.iimap[k] >= 0) ya[sd.iimap[k]] = w[k];
  PetscCall(VecRestoreArrayWrite(y, &ya));
  if (!sd.fii.nb) PetscCall(VecRestoreArray(sd.wi2, &w));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* With -info :feti, every rank's share of an application's work: the products with K_V (entries of K_reg), the
   interior solves (interior dofs, their squares: the factors of K_ii grow faster than their dofs) and the products
   with K_bi. The subdomains are spread over the ranks by count, and a subdomain's interior depends on where it
   sits (a free surface adds to it, a face B touches takes from it), so the shares can differ (docs/scale.md,
   "Two ranks: where the time goes"). */
static PetscErrorCode InfoLoad(FETI feti)
{
  FETI_Impl  &impl = *feti->impl;
  MPI_Comm    comm = PetscObjectComm((PetscObject)feti);
  PetscBool   info;
  PetscMPIInt size, rank;
  const int   nv       = 6;
  double      mine[nv] = {0, 0, 0, 0, 0, 0};

  PetscFunctionBegin;
  PetscCall(PetscInfoEnabled(FETI_CLASSID, &info));
  if (!info) PetscFunctionReturn(PETSC_SUCCESS);
  for (FETISubdomain &sd : impl.sub) {
    PetscInt ni = 0, nb = 0;
    MatInfo  mi;
    if (sd.interior) PetscCall(ISGetLocalSize(sd.interior, &ni));
    if (sd.boundary) PetscCall(ISGetLocalSize(sd.boundary, &nb));
    mine[0] += sd.Fii ? 1 : 0;
    mine[1] += (double)ni;
    mine[2] += (double)ni * (double)ni;
    mine[3] += (double)nb;
    if (sd.Kbi) {
      PetscCall(MatGetInfo(sd.Kbi, MAT_LOCAL, &mi));
      mine[4] += mi.nz_used;
    }
    if (sd.Kreg) { /* stored entries: the upper triangle of an SBAIJ K_reg */
      PetscCall(MatGetInfo(sd.Kreg, MAT_LOCAL, &mi));
      mine[5] += mi.nz_used;
    }
  }
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  std::vector<double> all((size_t)nv * size);
  PetscCallMPI(MPI_Gather(mine, nv, MPI_DOUBLE, all.data(), nv, MPI_DOUBLE, 0, comm));
  for (PetscMPIInt r = 0; r < size; r++) { /* PetscInfo() prints on the first rank only: it prints every rank's line */
    const double *v = &all[(size_t)nv * r];
    PetscCall(PetscInfo(feti, "FETI preconditioner work of rank %d: %.0f interior solves, %.0f interior dofs (sum of squares %.4g), %.0f boundary dofs, K_bi entries %.0f, K_reg entries stored %.0f\n",
                        r, v[0], v[1], v[2], v[3], v[4], v[5]));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* Boundary dofs (touched by B, not Dirichlet in the primal) and interior dofs of each subdomain; for the
   Dirichlet preconditioner also the factored K_ii and the block K_bi. Built once. K_bb and K_ib are not
   copied: one product of the subdomain's own K_V with [x_b; 0] gives both, and K_bb is most of K (at
   H/h = 4, 98 of a subdomain's 125 nodes are on its boundary). K_bi y_i, the second half of the Schur
   product, is kept as its block: only the boundary nodes next to the interior couple to it, so its
   product costs a fraction of a second one with K_V (on the brick at H/h = 6 an application's flops fell
   from 0.72 to 0.55 of an F product's, docs/scale.md), for about 0.1 KB per unknown.

   K_ii is factored as the subdomains' K_s for F (options prefix feti_dirichlet_): PETSc's block Cholesky of its
   nodes permuted by a fill-reducing ordering (-feti_dirichlet_pc_factor_mat_ordering_type, default amd) up to
   FETI_BLOCK_CHOLESKY_MAX_DOFS dofs, the subdomains' package (CHOLMOD) above; the block factors kept as float
   copies (-feti_dirichlet_pc_precision single, the default): their triangular solves are bound by memory
   traffic as those of F, and a preconditioner's rounding changes the convergence rate, not the solution
   (docs/scale.md, "Lever: the Dirichlet preconditioner's interior factors"). */
PetscErrorCode FETISetUpPreconditionerData(FETI feti, PetscBool dirichlet)
{
  FETI_Impl &impl  = *feti->impl;
  PetscBool  built = PETSC_FALSE;

  PetscFunctionBegin;
  PetscCall(FETISetUpBoundaryMask(feti));
  const PetscScalar *mask;
  PetscCall(VecGetArrayRead(impl.boundarymask, &mask));
  for (PetscInt s = 0; s < (PetscInt)impl.sub.size(); s++) {
    FETISubdomain &sd        = impl.sub[s];
    PetscInt       ninterior = 0;
    if (sd.interior) PetscCall(ISGetLocalSize(sd.interior, &ninterior));
    if (sd.boundary && (!dirichlet || sd.Fii || sd.fii.nb || !ninterior)) continue; /* built already */
    std::vector<PetscInt> b, i;
    std::vector<char>     isD(sd.n, 0);
    for (PetscInt d : sd.dirichletdofs) isD[d] = 1;
    for (PetscInt k = 0; k < sd.n; k++) {
      if (isD[k]) continue;
      if (mask[sd.localoffset + k] != 0.0) PetscCallCXX(b.push_back(k));
      else PetscCallCXX(i.push_back(k));
    }
    PetscCall(ISDestroy(&sd.boundary));
    PetscCall(ISDestroy(&sd.interior));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)b.size(), b.data(), PETSC_COPY_VALUES, &sd.boundary));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)i.size(), i.data(), PETSC_COPY_VALUES, &sd.interior));
    if (dirichlet && !i.empty()) {
      Mat         KV, Kii, Kfactor;
      KSP         ksp;
      PC          pc;
      Mat         factor;
      PetscBool   failed, set, petsc, bynodes;
      const char *fetiprefix;
      char        prefix[256], solver[64], ordering[64] = MATORDERINGAMD;
      built = PETSC_TRUE;
      PetscCall(PetscObjectGetOptionsPrefix((PetscObject)feti, &fetiprefix));
      PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "%sfeti_dirichlet_", fetiprefix ? fetiprefix : ""));
      /* the package, as for the subdomains' factors for F (FETISubdomainSetUpFactorization()): the options decide
         before the matrix is built, since PETSc's block Cholesky factors K_ii with its nodes permuted */
      PetscCall(PetscStrncpy(solver, (PetscInt)i.size() <= FETI_BLOCK_CHOLESKY_MAX_DOFS ? MATSOLVERPETSC : impl.subsolver, sizeof(solver)));
      PetscCall(PetscOptionsGetString(((PetscObject)feti)->options, prefix, "-pc_factor_mat_solver_type", solver, sizeof(solver), &set));
      PetscCall(PetscOptionsGetString(((PetscObject)feti)->options, prefix, "-pc_factor_mat_ordering_type", ordering, sizeof(ordering), &set));
      PetscCall(PetscStrcmp(solver, MATSOLVERPETSC, &petsc));
      bynodes = (PetscBool)(petsc && sd.n % 3 == 0);
      /* K_ii of K_V = Kreg + C - d I_removed (transient, one subdomain at a time) */
      PetscCall(MatConvert(sd.Kreg, MATSEQAIJ, MAT_INITIAL_MATRIX, &KV));
      if (sd.correction) PetscCall(MatAXPY(KV, 1.0, sd.correction, DIFFERENT_NONZERO_PATTERN));
      for (PetscInt r : sd.removed) PetscCall(MatSetValue(KV, r, r, -sd.regdiag, ADD_VALUES));
      PetscCall(MatAssemblyBegin(KV, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(KV, MAT_FINAL_ASSEMBLY));
      PetscCall(MatCreateSubMatrix(KV, sd.boundary, sd.interior, MAT_INITIAL_MATRIX, &sd.Kbi));
      if (bynodes) {
        PetscCall(InteriorByNodes(sd, KV, i, ordering, &Kfactor));
        Kii = nullptr;
      } else {
        PetscCall(MatCreateSubMatrix(KV, sd.interior, sd.interior, MAT_INITIAL_MATRIX, &Kii));
        PetscCall(MatSetOption(Kii, MAT_SPD, PETSC_TRUE));
        Kfactor = Kii;
        PetscCall(PetscObjectReference((PetscObject)Kfactor));
      }
      PetscCall(MatDestroy(&KV));
      /* factored by the function every FETI factorization goes through (a MUMPS workspace estimate that is too
         small is raised and the factorization repeated; package failures name the options prefix); only the
         factor is kept: K_ii itself is not needed afterwards */
      PetscCall(KSPCreate(PETSC_COMM_SELF, &ksp));
      PetscCall(KSPSetOptionsPrefix(ksp, prefix));
      PetscCall(KSPSetType(ksp, KSPPREONLY));
      PetscCall(KSPSetOperators(ksp, Kfactor, Kfactor));
      PetscCall(KSPGetPC(ksp, &pc));
      PetscCall(PCSetType(pc, PCCHOLESKY));
      PetscCall(PCFactorSetMatSolverType(pc, solver));
      PetscCall(KSPSetFromOptions(ksp));                                          /* -feti_dirichlet_pc_factor_*, -feti_dirichlet_mat_mumps_*, ... */
      if (bynodes) PetscCall(PCFactorSetMatOrderingType(pc, MATORDERINGNATURAL)); /* the ordering is in Kfactor already */
      PetscCall(FETIKSPSetUpFactorization(feti, ksp, NULL, NULL, &failed));
      PetscCheck(!failed, PETSC_COMM_SELF, PETSC_ERR_CONV_FAILED,
                 "Dirichlet preconditioner: the interior block K_ii of subdomain %" PetscInt_FMT " is singular (a part of the subdomain not connected to its interface?)", impl.firstsub + s);
      PetscCall(PCFactorGetMatrix(pc, &factor));
      PetscCall(PetscObjectReference((PetscObject)factor));
      sd.Fii = factor;
      PetscCall(KSPDestroy(&ksp));
      PetscCall(MatCreateVecs(sd.Kbi, &sd.xi, &sd.yb)); /* interior-, boundary-sized */
      PetscCall(VecDuplicate(sd.xi, &sd.yi));
      if (bynodes) {
        PetscBool sbaij;
        PetscCall(MatCreateVecs(Kfactor, &sd.wi, &sd.wi2));
        PetscCall(PetscObjectTypeCompare((PetscObject)sd.Fii, MATSEQSBAIJ, &sbaij));
        if (sbaij && impl.pcprecision == FETI_KPLUS_PRECISION_SINGLE) {
          Vec       x, yd;
          PetscReal diff = 0, norm = 1;
          if (impl.check) { /* a wrong reading of PETSc's layout would solve O(1) away; the rounding to float by about cond(K_ii) 6e-8 */
            PetscRandom rnd;
            PetscCall(VecDuplicate(sd.xi, &x));
            PetscCall(VecDuplicate(sd.xi, &yd));
            PetscCall(PetscRandomCreate(PETSC_COMM_SELF, &rnd));
            PetscCall(PetscRandomSetSeed(rnd, 12345));
            PetscCall(PetscRandomSeed(rnd));
            PetscCall(VecSetRandom(x, rnd));
            PetscCall(PetscRandomDestroy(&rnd));
            PetscCall(InteriorSolve(sd, x, yd));
          }
          PetscCall(FETIFloatFactorCreate(sd.Fii, "-feti_dirichlet_pc_precision", sd.fii));
          PetscCallCXX(sd.iiwork.resize(sd.iimap.size()));
          if (impl.check) {
            PetscCall(InteriorSolve(sd, x, sd.yi));
            PetscCall(VecAXPY(sd.yi, -1.0, yd));
            PetscCall(VecNorm(sd.yi, NORM_2, &diff));
            PetscCall(VecNorm(yd, NORM_2, &norm));
            diff = norm > 0 ? diff / norm : diff;
            PetscCall(VecDestroy(&x));
            PetscCall(VecDestroy(&yd));
            PetscCheck(diff <= 0.25, PETSC_COMM_SELF, PETSC_ERR_LIB,
                       "-feti_dirichlet_pc_precision single: subdomain %" PetscInt_FMT
                       ": the float copy of the interior factor solves %g away from MatSolve() (relative): use -feti_dirichlet_pc_precision double",
                       impl.firstsub + s, (double)diff);
            PetscCall(PetscInfo(NULL, "Subdomain %" PetscInt_FMT ": Dirichlet preconditioner's float interior factor %.3f MB (double %.3f MB), solve %.2e from MatSolve()\n", impl.firstsub + s,
                                FETIFloatFactorBytes(sd.fii) / 1048576.0, sd.fii.doublebytes / 1048576.0, (double)diff));
          }
          PetscCall(MatDestroy(&sd.Fii)); /* the float copy replaces it */
          PetscCall(VecDestroy(&sd.wi));
          PetscCall(VecDestroy(&sd.wi2));
        } else if (sbaij) {
          const PetscInt *ai, *aj;
          PetscInt        mbs;
          PetscBool       done;
          PetscCall(MatGetRowIJ(sd.Fii, 0, PETSC_FALSE, PETSC_TRUE, &mbs, &ai, &aj, &done));
          if (done) sd.fii.doublebytes = (double)9 * ai[mbs] * sizeof(PetscScalar) + (double)ai[mbs] * sizeof(PetscInt) + (double)(mbs + 1) * sizeof(PetscInt);
          PetscCall(MatRestoreRowIJ(sd.Fii, 0, PETSC_FALSE, PETSC_TRUE, &mbs, &ai, &aj, &done));
        }
      }
      PetscCall(MatDestroy(&Kfactor));
      PetscCall(MatDestroy(&Kii));
    }
  }
  PetscCall(VecRestoreArrayRead(impl.boundarymask, &mask));
  { /* the interior factors as kept, all ranks (the PC's view; collective: every rank sets the preconditioner up) */
    PetscMPIInt any = built;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_MAX, PetscObjectComm((PetscObject)feti)));
    if (any) {
      double   bytes[2]  = {0, 0};
      PetscInt counts[2] = {0, 0};
      for (FETISubdomain &sd : impl.sub) {
        if (sd.fii.nb) counts[0]++;
        if (sd.fii.doublebytes > 0) counts[1]++;
        bytes[0] += sd.fii.nb ? FETIFloatFactorBytes(sd.fii) : sd.fii.doublebytes;
        bytes[1] += sd.fii.doublebytes;
      }
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)feti)));
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, bytes, 2, MPI_DOUBLE, MPI_SUM, PetscObjectComm((PetscObject)feti)));
      impl.npcsingle     = counts[0];
      impl.npcblock      = counts[1];
      impl.pcfactorbytes = bytes[0];
      impl.pcdoublebytes = bytes[1];
    }
  }
  PetscCall(InfoLoad(feti));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode PCSetUp_FETI(PC pc)
{
  PC_FETI *data = (PC_FETI *)pc->data;

  PetscFunctionBegin;
  PetscCall(FETIFromMat(pc->pmat, &data->feti));
  PetscCheck(data->feti, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONG, "PC %s preconditions only the P F P operator of a FETI problem (use it through FETIGetKSP() / -feti_pc_type)",
             ((PetscObject)pc)->type_name);
  PetscCall(PetscLogEventBegin(FETI_SetUp, data->feti, 0, 0, 0));
  PetscCall(PetscLogEventBegin(FETI_PCSetUp, data->feti, 0, 0, 0));
  PetscCall(FETISetUpPreconditionerData(data->feti, data->dirichlet));
  PetscCall(PetscLogEventEnd(FETI_PCSetUp, data->feti, 0, 0, 0));
  PetscCall(PetscLogEventEnd(FETI_SetUp, data->feti, 0, 0, 0));
  if (!data->wd) {
    PetscCall(FETICreateVecs(data->feti, &data->wp1, &data->wd, NULL));
    PetscCall(VecDuplicate(data->wp1, &data->wp2));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode PCApply_FETI(PC pc, Vec x, Vec y)
{
  PC_FETI           *data = (PC_FETI *)pc->data;
  const PetscScalar *in;
  PetscScalar       *out;

  PetscFunctionBegin;
  PetscCall(FETIFromMat(pc->pmat, &data->feti)); /* an error, not freed memory, once the FETI object is gone */
  PetscCheck(data->feti, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONGSTATE, "PC %s: its operator is no longer one of a FETI problem", ((PetscObject)pc)->type_name);
  FETI_Impl &impl = *data->feti->impl;
  PetscCall(PetscLogEventBegin(FETI_Preconditioner, data->feti, 0, 0, 0));
  if (data->projected) PetscCall(FETIApplyP(data->feti, x, data->wd));
  else PetscCall(VecCopy(x, data->wd));
  PetscCall(FETIRowSumApply(impl.Btsum, data->wd, data->wp1));
  PetscCall(VecSet(data->wp2, 0.0));
  PetscCall(VecGetArrayRead(data->wp1, &in));
  PetscCall(VecGetArray(data->wp2, &out));
  for (FETISubdomain &sd : impl.sub) {
    const PetscInt *b;
    PetscInt        nb;
    PetscScalar    *x;
    PetscCall(ISGetLocalSize(sd.boundary, &nb));
    if (!nb) continue;
    PetscCall(ISGetIndices(sd.boundary, &b));
    /* y = K_V [x_b; 0]: its b part is K_bb x_b, its i part K_ib x_b */
    PetscCall(VecSet(sd.x, 0.0));
    PetscCall(VecGetArray(sd.x, &x));
    for (PetscInt k = 0; k < nb; k++) x[b[k]] = in[sd.localoffset + b[k]];
    PetscCall(VecRestoreArray(sd.x, &x));
    PetscCall(FETISubdomainApplyK(sd, sd.x, sd.y));
    {
      const PetscScalar *y;
      PetscCall(VecGetArrayRead(sd.y, &y));
      for (PetscInt k = 0; k < nb; k++) out[sd.localoffset + b[k]] = y[b[k]];
      PetscCall(VecRestoreArrayRead(sd.y, &y));
    }
    if (data->dirichlet && (sd.Fii || sd.fii.nb)) {                    /* S x_b = K_bb x_b - K_bi K_ii^-1 K_ib x_b */
      PetscCall(VecISCopy(sd.y, sd.interior, SCATTER_REVERSE, sd.xi)); /* K_ib x_b */
      PetscCall(InteriorSolve(sd, sd.xi, sd.yi));
      /* K_bi y_i with the stored block: a second product with all of K_V would cost as much as the first */
      PetscCall(MatMult(sd.Kbi, sd.yi, sd.yb));
      {
        const PetscScalar *y;
        PetscCall(VecGetArrayRead(sd.yb, &y));
        for (PetscInt k = 0; k < nb; k++) out[sd.localoffset + b[k]] -= y[k];
        PetscCall(VecRestoreArrayRead(sd.yb, &y));
      }
    }
    PetscCall(ISRestoreIndices(sd.boundary, &b));
  }
  PetscCall(VecRestoreArray(data->wp2, &out));
  PetscCall(VecRestoreArrayRead(data->wp1, &in));
  PetscCall(FETIRowSumApply(impl.Bsum, data->wp2, y));
  if (data->projected) PetscCall(FETIApplyP(data->feti, y, y));
  PetscCall(PetscLogEventEnd(FETI_Preconditioner, data->feti, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode PCReset_FETI(PC pc)
{
  PC_FETI *data = (PC_FETI *)pc->data;

  PetscFunctionBegin;
  PetscCall(VecDestroy(&data->wd));
  PetscCall(VecDestroy(&data->wp1));
  PetscCall(VecDestroy(&data->wp2));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode PCDestroy_FETI(PC pc)
{
  PetscFunctionBegin;
  PetscCall(PCReset_FETI(pc));
  PetscCall(PetscObjectComposeFunction((PetscObject)pc, "PCFETISetProjected_C", NULL));
  PetscCall(PetscFree(pc->data));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode PCView_FETI(PC pc, PetscViewer viewer)
{
  PC_FETI  *data = (PC_FETI *)pc->data;
  PetscBool ascii;

  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (ascii)
    PetscCall(PetscViewerASCIIPrintf(viewer, "FETI %s preconditioner, applied as %s\n", data->dirichlet ? "Dirichlet (B S_bb B')" : "lumped (B K_bb B')",
                                     data->projected ? "P M^-1 P" : "M^-1 (the caller projects)"));
  if (data->feti && pc->pmat) { /* the FETI object may be gone (FETIReset() took it from its operators) */
    void *ctx = NULL;
    PetscCall(MatShellGetContext(pc->pmat, &ctx));
    if (!ctx) data->feti = NULL;
  }
  if (ascii && data->dirichlet && data->feti && pc->setupcalled) {
    const FETI_Impl &impl = *data->feti->impl;
    PetscCall(PetscViewerASCIIPushTab(viewer));
    PetscCall(PetscViewerASCIIPrintf(viewer,
                                     "interior blocks K_ii (options prefix -feti_dirichlet_): %" PetscInt_FMT " of %" PetscInt_FMT " subdomains by PETSc's block Cholesky, %" PetscInt_FMT
                                     " of them stored in float (-feti_dirichlet_pc_precision %s): %.3f MB, in double %.3f MB "
                                     "(all ranks; doublebytes %.0f)\n",
                                     impl.npcblock, impl.nglobalsub, impl.npcsingle, FETIKplusPrecisions[impl.pcprecision], impl.pcfactorbytes / 1048576.0, impl.pcdoublebytes / 1048576.0,
                                     impl.pcdoublebytes));
    PetscCall(PetscViewerASCIIPopTab(viewer));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode PCFETISetProjected_FETI(PC pc, PetscBool flg)
{
  PetscFunctionBegin;
  ((PC_FETI *)pc->data)->projected = flg;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@
  PCFETISetProjected - Whether a FETI preconditioner applies the projector P on both sides (P M^-1 P, the default) or
  M^-1 alone.

  Logically Collective

  Input Parameters:
+ pc  - a `PCFETILUMPED` or `PCFETIDIRICHLET` preconditioner (other types ignore the call)
- flg - `PETSC_FALSE`: M^-1 alone

  Notes:
  For a caller that projects around the preconditioner itself, e.g. smalxe's P M P + Q/rho
  (`TaoSMALXESetProjectedPreconditioner()`): each P is a coarse solve (with G and G'), and P (P M^-1 P) P = P M^-1 P,
  so the inner pair is redundant there. `FETISolveLinear()`'s projected CG needs the default.

  Level: developer

.seealso: `PCFETILUMPED`, `PCFETIDIRICHLET`, `ContactProblemGetPC()`
@*/
PetscErrorCode PCFETISetProjected(PC pc, PetscBool flg)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(pc, PC_CLASSID, 1);
  PetscValidLogicalCollectiveBool(pc, flg, 2);
  PetscTryMethod(pc, "PCFETISetProjected_C", (PC, PetscBool), (pc, flg));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode PCCreate_FETI(PC pc, PetscBool dirichlet)
{
  PC_FETI *data;

  PetscFunctionBegin;
  PetscCall(PetscNew(&data));
  data->dirichlet  = dirichlet;
  data->projected  = PETSC_TRUE;
  pc->data         = data;
  pc->ops->setup   = PCSetUp_FETI;
  pc->ops->apply   = PCApply_FETI;
  pc->ops->reset   = PCReset_FETI;
  pc->ops->destroy = PCDestroy_FETI;
  pc->ops->view    = PCView_FETI;
  PetscCall(PetscObjectComposeFunction((PetscObject)pc, "PCFETISetProjected_C", PCFETISetProjected_FETI));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*MC
  PCFETILUMPED - "lumped": the FETI lumped preconditioner B K_bb B', applied as P M^-1 P.

  Options Database Key:
. -feti_pc_type lumped - select it for `FETISolveLinear()`

  Notes:
  Cheap (one sparse product with K_s per subdomain, no copy of its boundary block); weaker than `PCFETIDIRICHLET`.
  Usable only on the P F P operator of a FETI problem.

  Level: intermediate

.seealso: `PCFETIDIRICHLET`, `FETISolveLinear()`, `FETIGetKSP()`
M*/
PetscErrorCode PCCreate_FETILumped(PC pc)
{
  PetscFunctionBegin;
  PetscCall(PCCreate_FETI(pc, PETSC_FALSE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*MC
  PCFETIDIRICHLET - "dirichlet": the FETI Dirichlet preconditioner B S_bb B' with the Schur complement of each
  subdomain on the dofs B touches, applied as P M^-1 P.

  Options Database Keys:
+ -feti_pc_type dirichlet                                  - select it (the default of `FETISolveLinear()`)
. -feti_dirichlet_pc_factor_mat_solver_type <petsc,cholmod,mumps> - the factorization of the interior blocks K_ii (default petsc, the node-ordered
  block Cholesky, up to 3000 interior dofs; the subdomains' package, cholmod, above)
. -feti_dirichlet_pc_factor_mat_ordering_type <amd>        - its fill-reducing ordering (with petsc: of the node graph of K_ii)
. -feti_dirichlet_pc_precision <single,double>             - storage of the block Cholesky factors: single (the default) keeps float copies, sums in double
- -feti_dirichlet_pc_factor_*, -feti_dirichlet_mat_mumps_* - the other options of that factorization

  Notes:
  Costs one more sparse Cholesky per subdomain (of the interior block), a copy of the block K_bi, and per
  application one solve with K_ii, one product with the subdomain's K and one with K_bi; gives iteration counts
  that grow only like (1 + log(H/h))^2. The interior factors are shared by every Dirichlet preconditioner of the
  same FETI object (`FETISolveLinear()`'s and the contact problem's), so their options have the FETI object's
  prefix whatever the PC's. Float factors change the preconditioner by about cond(K_ii) times the float
  rounding, which moves the convergence rate a little and the solution not at all (docs/scale.md, "Lever: the
  Dirichlet preconditioner's interior factors").

  Level: intermediate

.seealso: `PCFETILUMPED`, `FETISolveLinear()`, `FETIGetKSP()`
M*/
PetscErrorCode PCCreate_FETIDirichlet(PC pc)
{
  PetscFunctionBegin;
  PetscCall(PCCreate_FETI(pc, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}
