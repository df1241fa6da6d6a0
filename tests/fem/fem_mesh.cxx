/* FEMAddMesh() and FEMAddFacetSet(): a body given as a mesh is the same body as the box that generated
   it. The box's own mesh is handed back to FEMAddMesh() with its nodes renumbered backwards and its
   tetrahedra in reverse order, the top face given as a facet set "top"; then, with the same supports and
   traction (on "top" for the mesh, on z1 for the box):
   - the tagged nodes of "top" and of the built-in z1 agree (nodes, lumped areas, normals);
   - the assembled K and f agree, node for node through the renumbering (K x for a smooth x, and f);
   - the displacements of K u = f agree.
   Each would fail if the boundary extraction, the orientation, the facet-set matching or the node
   numbering of a given mesh went wrong.
   -pieces instead gives one body made of two disjoint copies of the box: without any decomposition option
   each piece must become a subdomain of its own (one subdomain of two pieces would have 12 rigid motions
   and a wrong kernel), and the FETI solution must equal the direct one.
   -case <name> instead hands FEMAddMesh()/FEMAddFacetSet() one mistake (inverted, degenerate, unused_node,
   out_of_range, inner_facet): the program must stop with an error whose text the test matches. */
#include <conefeti.h>
#include <conefeti/compat.h>
#include "femsolve.h"

#include <cstring>
#include <vector>

static const PetscReal LO[3] = {0, 0, 0}, HI[3] = {1.0, 0.5, 2.0};

/* The box's mesh on every rank: generated on PETSC_COMM_SELF in one subdomain, so the subdomain is the body */
static PetscErrorCode BoxMesh(const PetscInt cells[3], std::vector<PetscReal> &X, std::vector<PetscInt> &tets)
{
  FEM              fem;
  PetscInt         body, nn, ne;
  const PetscInt  *nodes, *conn;
  const PetscReal *x;

  PetscFunctionBeginUser;
  PetscCall(FEMCreate(PETSC_COMM_SELF, &fem));
  PetscCall(FEMAddBox(fem, LO, HI, cells, NULL));
  PetscCall(FEMSetUp(fem));
  PetscCall(FEMGetSubdomainMesh(fem, 0, &body, &nn, &nodes, &ne, &conn));
  PetscCall(FEMGetBodyNodes(fem, body, NULL, &x));
  X.assign(3 * nn, 0);
  for (PetscInt l = 0; l < nn; l++)
    for (PetscInt d = 0; d < 3; d++) X[3 * l + d] = x[3 * nodes[l] + d];
  tets.assign(conn, conn + 4 * ne);
  PetscCall(FEMDestroy(&fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The faces of the tetrahedra with all three nodes on z = HI[2] */
static void TopTriangles(const std::vector<PetscReal> &X, const std::vector<PetscInt> &tets, std::vector<PetscInt> &tri)
{
  tri.clear();
  for (size_t e = 0; e < tets.size() / 4; e++)
    for (int k = 0; k < 4; k++) {
      std::vector<PetscInt> f;
      for (int a = 0; a < 4; a++)
        if (a != k && X[3 * tets[4 * e + a] + 2] == HI[2]) f.push_back(tets[4 * e + a]);
      if (f.size() == 3) tri.insert(tri.end(), f.begin(), f.end());
    }
}

static PetscErrorCode RunCase(const char *name, const PetscInt cells[3])
{
  std::vector<PetscReal> X;
  std::vector<PetscInt>  tets, tri;
  FEM                    fem;

  PetscFunctionBeginUser;
  PetscCall(BoxMesh(cells, X, tets));
  TopTriangles(X, tets, tri);
  if (!strcmp(name, "inverted")) std::swap(tets[4 * 7 + 1], tets[4 * 7 + 2]);
  else if (!strcmp(name, "degenerate")) {
    for (int d = 0; d < 3; d++) X[3 * tets[4 * 7 + 3] + d] = X[3 * tets[4 * 7 + 0] + d]; /* two nodes of element 7 coincide */
  } else if (!strcmp(name, "unused_node")) {
    X.insert(X.end(), {5.0, 5.0, 5.0});
  } else if (!strcmp(name, "out_of_range")) tets[4 * 3 + 2] = (PetscInt)(X.size() / 3);
  else if (!strcmp(name, "inner_facet")) {
    /* a face with a node strictly inside the box is no boundary face */
    for (size_t e = 0; e < tets.size() / 4; e++) {
      int inside = 0;
      for (int a = 0; a < 3; a++) {
        const PetscReal *x = &X[3 * tets[4 * e + a]];
        if (x[0] > LO[0] && x[0] < HI[0] && x[1] > LO[1] && x[1] < HI[1] && x[2] > LO[2] && x[2] < HI[2]) inside++;
      }
      if (inside) {
        tri.insert(tri.end(), tets.begin() + 4 * e, tets.begin() + 4 * e + 3);
        break;
      }
    }
  } else SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "-case %s: unknown case", name);
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
  PetscCall(FEMAddMesh(fem, (PetscInt)X.size() / 3, X.data(), (PetscInt)tets.size() / 4, tets.data(), NULL));
  PetscCall(FEMAddFacetSet(fem, 0, "top", (PetscInt)tri.size() / 3, tri.data()));
  PetscCall(FEMSetUp(fem));
  PetscCall(FEMDestroy(&fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Model(FEM fem, PetscInt body, const char *top)
{
  const PetscReal t[3] = {1e6, -2e6, -5e6};

  PetscFunctionBeginUser;
  PetscCall(FEMSetMaterial(fem, body, 2.0e11, 0.3));
  PetscCall(FEMSetDirichlet(fem, body, "z0", NULL));
  PetscCall(FEMSetTraction(fem, body, top, t));
  PetscCall(FEMSetFromOptions(fem));
  PetscCall(FEMSetUp(fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* One body of two disjoint copies of the box, 2 along x apart, each clamped at its base */
static PetscErrorCode Pieces(const PetscInt cells[3])
{
  std::vector<PetscReal> X;
  std::vector<PetscInt>  tets;
  FEM                    fem;
  FETI                   feti;
  Mat                    K;
  Vec                    u, lambda, f, ug, ud;
  KSP                    ksp;
  PetscInt               nsub;
  PetscReal              err, norm;
  const PetscReal        t[3] = {1e6, -2e6, -5e6};

  PetscFunctionBeginUser;
  PetscCall(BoxMesh(cells, X, tets));
  const PetscInt N = (PetscInt)X.size() / 3, E = (PetscInt)tets.size() / 4;
  for (PetscInt n = 0; n < N; n++) X.insert(X.end(), {X[3 * n] + 2.0, X[3 * n + 1], X[3 * n + 2]});
  for (PetscInt i = 0; i < 4 * E; i++) tets.push_back(tets[i] + N);
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
  PetscCall(FEMAddMesh(fem, 2 * N, X.data(), 2 * E, tets.data(), NULL));
  PetscCall(FEMSetMaterial(fem, 0, 2.0e11, 0.3));
  PetscCall(FEMSetDirichlet(fem, 0, "z0", NULL));
  PetscCall(FEMSetTraction(fem, 0, "z1", t));
  PetscCall(FEMSetFromOptions(fem));
  PetscCall(FEMSetUp(fem));
  PetscCall(FEMGetNumSubdomains(fem, &nsub, NULL, NULL));
  PetscCheck(nsub == 2, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "a body of two disjoint pieces gave %" PetscInt_FMT " subdomains, expected 2", nsub);
  PetscCall(FEMCreateFETI(fem, &feti));
  PetscCall(FETISetFromOptions(feti));
  PetscCall(FETISetUp(feti));
  PetscCall(FETICreateVecs(feti, &u, &lambda, NULL));
  PetscCall(FETISolveLinear(feti, lambda, u));
  PetscCall(FEMAssembleGlobal(fem, &K, &f));
  PetscCall(MatCreateVecs(K, &ud, &ug));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, K, K));
  PetscCall(KSPSetType(ksp, KSPCG));
  PetscCall(KSPSetTolerances(ksp, 1e-13, 1e-50, PETSC_DEFAULT, 10000));
  PetscCall(KSPSolve(ksp, f, ud));
  PetscCall(FEMPrimalToGlobal(fem, u, ug));
  PetscCall(VecNorm(ud, NORM_2, &norm));
  PetscCall(VecAXPY(ug, -1.0, ud));
  PetscCall(VecNorm(ug, NORM_2, &err));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "two pieces: %" PetscInt_FMT " subdomains, FETI against direct %.2e relative\n", nsub, (double)(err / norm)));
  PetscCheck(err <= 1e-7 * norm, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "FETI and direct solutions of the two pieces differ by %g relative", (double)(err / norm));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(VecDestroy(&ud));
  PetscCall(VecDestroy(&ug));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&lambda));
  PetscCall(MatDestroy(&K));
  PetscCall(FETIDestroy(&feti));
  PetscCall(FEMDestroy(&fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscInt               cells[3] = {3, 2, 4}, ncells = 3, nb, nm;
  char                   casename[64] = "";
  PetscBool              hascase, pieces;
  std::vector<PetscReal> X;
  std::vector<PetscInt>  tets, tri;
  FEM                    box, mesh;
  PetscMPIInt            rank;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "FEMAddMesh: a given mesh equals the box that generated it"));
  PetscCall(ConeFETIInitializePackage());
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-cells", cells, &ncells, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", casename, sizeof(casename), &hascase));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-pieces", &pieces));
  if (pieces) {
    PetscCall(Pieces(cells));
    PetscCall(PetscFinalize());
    return 0;
  }
  if (hascase) {
    PetscCall(RunCase(casename, cells)); /* must fail, with PETSc's report of the mistake */
    PetscCall(PetscFinalize());
    return 0;
  }

  PetscCall(BoxMesh(cells, X, tets));
  TopTriangles(X, tets, tri);
  /* renumber: node n becomes N-1-n; tetrahedra in reverse order, each with its nodes rotated (same orientation) */
  const PetscInt         N = (PetscInt)X.size() / 3, E = (PetscInt)tets.size() / 4;
  std::vector<PetscReal> Y(3 * N);
  std::vector<PetscInt>  T(4 * E), U(tri.size());
  for (PetscInt n = 0; n < N; n++)
    for (int d = 0; d < 3; d++) Y[3 * (N - 1 - n) + d] = X[3 * n + d];
  for (PetscInt e = 0; e < E; e++) {
    const PetscInt *v    = &tets[4 * (E - 1 - e)];
    const PetscInt  w[4] = {v[1], v[2], v[0], v[3]}; /* an even permutation keeps the orientation */
    for (int a = 0; a < 4; a++) T[4 * e + a] = N - 1 - w[a];
  }
  for (size_t i = 0; i < tri.size(); i++) U[i] = N - 1 - tri[i];

  PetscCall(FEMCreate(PETSC_COMM_WORLD, &box));
  PetscCall(FEMAddBox(box, LO, HI, cells, NULL));
  PetscCall(Model(box, 0, "z1"));
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &mesh));
  PetscCall(FEMAddMesh(mesh, N, Y.data(), E, T.data(), NULL));
  PetscCall(FEMAddFacetSet(mesh, 0, "top", (PetscInt)U.size() / 3, U.data()));
  PetscCall(Model(mesh, 0, "top"));

  /* the facet set "top" of the mesh, its built-in z1, and the box's z1: the same nodes, areas and normals */
  {
    const PetscInt  *nodesb, *nodesm, *nodesz;
    const PetscReal *ab, *am, *az, *nrb, *nrm, *nrz;
    PetscReal        err = 0;
    PetscCall(FEMGetTaggedNodes(box, 0, "z1", &nb, &nodesb, &ab, &nrb));
    PetscCall(FEMGetTaggedNodes(mesh, 0, "top", &nm, &nodesm, &am, &nrm));
    PetscCheck(nb == nm && nb > 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "top has %" PetscInt_FMT " nodes, z1 of the box %" PetscInt_FMT, nm, nb);
    PetscCall(FEMGetTaggedNodes(mesh, 0, "z1", &nm, &nodesz, &az, &nrz));
    PetscCheck(nb == nm, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the built-in z1 of the mesh has %" PetscInt_FMT " nodes, z1 of the box %" PetscInt_FMT, nm, nb);
    for (PetscInt i = 0; i < nb; i++) {
      const PetscInt j = nb - 1 - i; /* the renumbering reverses the sorted order */
      PetscCheck(nodesm[j] == N - 1 - nodesb[i] && nodesz[j] == nodesm[j], PETSC_COMM_WORLD, PETSC_ERR_PLIB, "tagged node %" PetscInt_FMT " differs", i);
      err = PetscMax(err, PetscMax(PetscAbsReal(am[j] - ab[i]), PetscAbsReal(az[j] - ab[i])));
      for (int d = 0; d < 3; d++) err = PetscMax(err, PetscMax(PetscAbsReal(nrm[3 * j + d] - nrb[3 * i + d]), PetscAbsReal(nrz[3 * j + d] - nrb[3 * i + d])));
    }
    PetscCheck(err < 1e-14, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "areas or normals of the top face differ by %g", (double)err);
  }

  /* K x, f and u node for node */
  {
    Vec                vb[3], vm[3];
    const PetscScalar *a[6];
    PetscReal          err[3] = {0, 0, 0}, scale[3] = {0, 0, 0};
    PetscCall(FEMTestSolveGathered(box, vb));
    PetscCall(FEMTestSolveGathered(mesh, vm));
    Vec v[6] = {vb[0], vb[1], vb[2], vm[0], vm[1], vm[2]};
    if (rank == 0) {
      for (int i = 0; i < 6; i++) PetscCall(VecGetArrayRead(v[i], &a[i]));
      for (PetscInt n = 0; n < N; n++)
        for (int d = 0; d < 3; d++)
          for (int q = 0; q < 3; q++) {
            err[q]   = PetscMax(err[q], PetscAbsScalar(a[q][3 * n + d] - a[3 + q][3 * (N - 1 - n) + d]));
            scale[q] = PetscMax(scale[q], PetscAbsScalar(a[q][3 * n + d]));
          }
      for (int i = 0; i < 6; i++) PetscCall(VecRestoreArrayRead(v[i], &a[i]));
    }
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "relative differences: K x %.2e, f %.2e, u %.2e\n", (double)(err[0] / scale[0]), (double)(err[1] / scale[1]), (double)(err[2] / scale[2])));
    if (rank == 0) PetscCheck(err[0] < 1e-12 * scale[0] && err[1] < 1e-12 * scale[1] && err[2] < 1e-8 * scale[2], PETSC_COMM_SELF, PETSC_ERR_PLIB, "the mesh body differs from the box");
    for (int i = 0; i < 6; i++) PetscCall(VecDestroy(&v[i]));
  }
  PetscCall(FEMDestroy(&box));
  PetscCall(FEMDestroy(&mesh));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "mesh equals box\n"));
  PetscCall(PetscFinalize());
  return 0;
}
