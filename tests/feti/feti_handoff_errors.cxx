/* A user handing their own subdomain matrices to FETI (handoffbar.h) with a mistake: each -case must stop with a
   PETSc error naming the function, argument and value, never a crash, a NaN or a wrong answer called converged.
   A case that does not fail ends with status 0 and fails its test (conefeti_error_test). */
#include "handoffbar.h"
#include <limits>

static const PetscReal NaN = std::numeric_limits<PetscReal>::quiet_NaN(), Inf = std::numeric_limits<PetscReal>::infinity(); /* PETSC_INFINITY is finite */

/* v[i] = value, assembled (the user's "bug" in a vector) */
static PetscErrorCode SetVecEntry(Vec v, PetscInt i, PetscScalar value)
{
  PetscFunctionBeginUser;
  PetscCall(VecSetValue(v, i, value, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(v));
  PetscCall(VecAssemblyEnd(v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the dofs of the face x = 0 of a slab (local numbering) */
static PetscErrorCode FaceDofs(Problem &p, IS *is)
{
  std::vector<PetscInt> d;
  const PetscInt        nx = p.cells + 1;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < nx; k++)
    for (PetscInt j = 0; j < nx; j++)
      for (PetscInt c = 0; c < 3; c++) d.push_back(3 * (nx * (j + nx * k)) + c);
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)d.size(), d.data(), PETSC_COPY_VALUES, is));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode RunCase(const char *name, Problem &p)
{
  FETI        feti = NULL;
  PetscMPIInt rank;
  auto        is = [&](const char *c) { return !strcmp(name, c); };

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (is("empty_subdomain")) { /* every rank hands one more subdomain with 0 dofs: the factorization crashed on it */
    Mat K0;
    PetscCall(BuildBar(p));
    PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, 0, 0, 0, NULL, &K0));
    PetscCall(MatSetBlockSize(K0, 3));
    PetscCall(MatAssemblyBegin(K0, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(K0, MAT_FINAL_ASSEMBLY));
    std::vector<Mat> K = p.K;
    std::vector<Vec> f = p.f;
    K.push_back(K0);
    f.push_back(NULL);
    PetscCall(FETICreate(PETSC_COMM_WORLD, &feti));
    PetscCall(FETISetSubdomains(feti, (PetscInt)K.size(), K.data(), f.data()));
    PetscCall(MatDestroy(&K0));
  } else if (is("f_mpi") || is("coords_mpi") || is("dirichlet_values_mpi")) {
    /* a subdomain vector created on PETSC_COMM_WORLD, as the user does for everything else: FETI read n_s entries
       from its local part (heap over-read, a wrong answer) */
    PetscCall(BuildBar(p));
    std::vector<Vec> g(p.nlocal);
    for (PetscInt s = 0; s < p.nlocal; s++) { /* collective: every rank has the same number of slabs here */
      PetscCall(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, p.ndofslab, &g[s]));
      PetscCall(VecSet(g[s], 1e-6));
    }
    PetscCall(FETICreate(PETSC_COMM_WORLD, &feti));
    PetscCall(FETISetSubdomains(feti, p.nlocal, p.K.data(), is("f_mpi") ? g.data() : p.f.data()));
    for (PetscInt s = 0; s < p.nlocal; s++) PetscCall(FETISetSubdomainCoordinates(feti, s, is("coords_mpi") ? g[s] : p.coords[s]));
    if (is("dirichlet_values_mpi"))
      for (PetscInt s = 0; s < p.nlocal; s++) {
        IS face;
        PetscCall(FaceDofs(p, &face));
        PetscCall(FETISetSubdomainDirichletDofs(feti, s, face));
        PetscCall(ISDestroy(&face));
        PetscCall(FETISetSubdomainDirichletValues(feti, s, g[s]));
      }
    PetscCall(FETISetConstraints(feti, p.B, NULL, p.kinds.data()));
    PetscCall(FETISetUp(feti));
    PetscCall(SolveAndReport(p, feti, name));
    for (auto &v : g) PetscCall(VecDestroy(&v));
  } else if (is("constraints_after_setup")) { /* B given again after a solve: the second setup read the consumed K_s */
    PetscCall(BuildBar(p));
    PetscCall(HandOver(p, &feti));
    PetscCall(FETISetUp(feti));
    PetscCall(SolveAndReport(p, feti, "first solve"));
    PetscCall(FETISetConstraints(feti, p.B, NULL, p.kinds.data()));
    PetscCall(SolveAndReport(p, feti, "after FETISetConstraints(same B)"));
  } else if (is("coords_after_setup") || is("kernel_after_setup") || is("dirichlet_dofs_after_setup") || is("dirichlet_values_after_setup")) {
    /* changes after the setup were ignored and the old answer reported converged */
    PetscCall(BuildBar(p));
    PetscCall(HandOver(p, &feti));
    PetscCall(FETISetUp(feti));
    if (is("coords_after_setup")) PetscCall(FETISetSubdomainCoordinates(feti, 0, p.coords[0]));
    else if (is("kernel_after_setup")) PetscCall(FETISetSubdomainKernel(feti, 0, NULL));
    else {
      IS face;
      PetscCall(FaceDofs(p, &face));
      if (is("dirichlet_dofs_after_setup")) PetscCall(FETISetSubdomainDirichletDofs(feti, 0, face));
      else PetscCall(FETISetSubdomainDirichletValues(feti, 0, p.f[0]));
      PetscCall(ISDestroy(&face));
    }
    PetscCall(SolveAndReport(p, feti, "after the change"));
  } else if (is("contact_kinds_linear")) { /* gluing rows declared contact rows: FETISolveLinear() took them as equalities */
    PetscCall(BuildBar(p));
    for (auto &k : p.kinds)
      if (k == FETI_ROW_GLUING) k = FETI_ROW_CONTACT_NORMAL;
    PetscCall(HandOver(p, &feti));
    PetscCall(FETISetUp(feti));
    PetscCall(SolveAndReport(p, feti, name));
  } else if (is("nan_K") || is("inf_K")) { /* the kernel check missed a NaN and blamed the coordinates for an Inf */
    PetscCall(BuildBar(p));
    PetscCall(MatSetValue(p.K[p.nlocal - 1], 4, 4, is("nan_K") ? NaN : Inf, INSERT_VALUES));
    PetscCall(MatAssemblyBegin(p.K[p.nlocal - 1], MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(p.K[p.nlocal - 1], MAT_FINAL_ASSEMBLY));
    PetscCall(HandOver(p, &feti));
    PetscCall(FETISetUp(feti));
    PetscCall(SolveAndReport(p, feti, name));
  } else if (is("negated_K_explicit")) { /* K_s assembled with the wrong sign, explicit K+ blocks: a raw dense-Cholesky error */
    PetscCall(BuildBar(p));
    PetscCall(MatScale(p.K[p.nlocal - 1], -1.0));
    PetscCall(PetscOptionsSetValue(NULL, "-feti_kplus", "explicit"));
    PetscCall(HandOver(p, &feti));
    PetscCall(FETISetUp(feti));
    PetscCall(SolveAndReport(p, feti, name));
  } else if (is("coords_nan")) { /* an internal "inconsistent data" error came from the choice of fixing nodes */
    PetscCall(BuildBar(p));
    PetscCall(SetVecEntry(p.coords[0], 4, NaN));
    PetscCall(HandOver(p, &feti));
    PetscCall(FETISetUp(feti));
  } else if (is("constraints_before_subdomains")) { /* FETISetSubdomains() dropped B, and FETISetUp() asked for it */
    PetscCall(BuildBar(p));
    PetscCall(FETICreate(PETSC_COMM_WORLD, &feti));
    PetscCall(FETISetConstraints(feti, p.B, NULL, p.kinds.data()));
    PetscCall(FETISetSubdomains(feti, p.nlocal, p.K.data(), p.f.data()));
    for (PetscInt s = 0; s < p.nlocal; s++) PetscCall(FETISetSubdomainCoordinates(feti, s, p.coords[s]));
    PetscCall(FETISetUp(feti));
  } else if (is("f_nan") || is("f_inf") || is("c_nan") || is("B_nan") || is("dirichlet_values_nan")) { /* setup and solve succeeded with u = NaN */
    Vec c = NULL, uD = NULL;
    PetscCall(BuildBar(p));
    if (is("f_nan") || is("f_inf")) PetscCall(SetVecEntry(p.f[p.nlocal - 1], 5, is("f_nan") ? NaN : Inf));
    else if (is("c_nan")) {
      PetscInt lo, hi;
      PetscCall(MatCreateVecs(p.B, NULL, &c));
      PetscCall(VecGetOwnershipRange(c, &lo, &hi));
      if (hi > lo) PetscCall(VecSetValue(c, lo, NaN, INSERT_VALUES)); /* the first row of every rank that has rows */
      PetscCall(VecAssemblyBegin(c));
      PetscCall(VecAssemblyEnd(c));
    } else if (is("B_nan")) {
      PetscInt           lo, nc, col;
      const PetscInt    *cc;
      const PetscScalar *v;
      PetscCall(MatGetOwnershipRange(p.B, &lo, NULL));
      PetscCall(MatGetRow(p.B, lo, &nc, &cc, &v));
      col = cc[0];
      PetscCall(MatRestoreRow(p.B, lo, &nc, &cc, &v));
      PetscCall(MatSetValue(p.B, lo, col, NaN, INSERT_VALUES));
      PetscCall(MatAssemblyBegin(p.B, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(p.B, MAT_FINAL_ASSEMBLY));
    }
    PetscCall(FETICreate(PETSC_COMM_WORLD, &feti));
    PetscCall(FETISetSubdomains(feti, p.nlocal, p.K.data(), p.f.data()));
    for (PetscInt s = 0; s < p.nlocal; s++) PetscCall(FETISetSubdomainCoordinates(feti, s, p.coords[s]));
    if (is("dirichlet_values_nan")) { /* u_D = NaN at a Dirichlet dof of the last slab (dof 9: node (0, 1, 0), x) */
      IS face;
      PetscCall(FaceDofs(p, &face));
      PetscCall(FETISetSubdomainDirichletDofs(feti, p.nlocal - 1, face));
      PetscCall(ISDestroy(&face));
      PetscCall(VecDuplicate(p.f[p.nlocal - 1], &uD));
      PetscCall(SetVecEntry(uD, 9, NaN));
      PetscCall(FETISetSubdomainDirichletValues(feti, p.nlocal - 1, uD));
    }
    PetscCall(FETISetConstraints(feti, p.B, c, p.kinds.data()));
    PetscCall(VecDestroy(&c));
    PetscCall(VecDestroy(&uD));
    PetscCall(FETISetUp(feti));
    PetscCall(SolveAndReport(p, feti, name));
  } else if (is("unclamped")) {
    /* the bar's clamp forgotten: nothing holds it. With two slabs the coarse factorization met a zero pivot; with three
       or more the pivot was rounding noise, and the solve came out "converged" with a tip deflection that depended on
       the coarse solver package; with one slab B had no rows and CHOLMOD failed with a message about its options */
    p.unclamped = PETSC_TRUE;
    PetscCall(BuildBar(p));
    PetscCall(FETICreate(PETSC_COMM_WORLD, &feti));
    PetscCall(FETISetSubdomains(feti, p.nlocal, p.K.data(), p.f.data()));
    for (PetscInt s = 0; s < p.nlocal; s++) PetscCall(FETISetSubdomainCoordinates(feti, s, p.coords[s]));
    PetscCall(FETISetConstraints(feti, p.B, NULL, p.kinds.data()));
    PetscCall(FETISetFromOptions(feti));
    PetscCall(FETISetUp(feti));
    PetscCall(SolveAndReport(p, feti, name));
  } else if (is("null_setup")) { /* FETICreate() forgotten: *feti->impl was read before the header check */
    PetscCall(FETISetUp(feti));
  } else if (is("null_solve")) {
    Vec l;
    PetscCall(VecCreateMPI(PETSC_COMM_WORLD, 3, PETSC_DETERMINE, &l));
    PetscCall(FETISolveLinear(feti, l, NULL));
  } else if (is("null_subdomains")) {
    PetscCall(FETISetSubdomains(feti, 0, NULL, NULL));
  } else if (is("null_constraints")) {
    PetscCall(BuildBar(p));
    PetscCall(FETISetConstraints(feti, p.B, NULL, p.kinds.data()));
  } else SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "unknown -case %s", name);
  PetscCall(FETIDestroy(&feti));
  PetscCall(DestroyBar(p));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char    name[64] = "";
  Problem p;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Mistakes in handing subdomains to FETI give clear errors"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", name, sizeof(name), NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-slabs", &p.slabs, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-cells", &p.cells, NULL));
  PetscCall(RunCase(name, p)); /* the error ends the program here */
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "case %s: the bad input was accepted\n", name));
  PetscCall(PetscFinalize());
  return 0;
}
