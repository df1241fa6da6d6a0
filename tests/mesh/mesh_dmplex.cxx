/* FEMAddDMPlex() on a DMPlex built by the user's own code (DMPlexCreateFromCellListPetsc(), all cells on rank 0,
   the DM on PETSC_COMM_WORLD): a unit cube of 2 x 2 x 2 Kuhn-split hexahedra in DMPlex's vertex order, with a
   label "loaded" of the user's marking the top triangles.
   - the body has the cube's nodes, and its facet set "loaded" the same nodes, areas and normals as the built-in
     z1 of the generated box;
   -case plain_order: the cells in the right-handed (Gmsh, Exodus) order instead: each is inverted in DMPlex's
     convention, and the error says so;
   -case distributed: the DM distributed over the ranks first (DMPlexDistribute()): an error that says to pass it
     before. */
#include <conefeti.h>
#include <conefeti/compat.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

static PetscErrorCode PrintInitialError(MPI_Comm, int, const char *, const char *, PetscErrorCode n, PetscErrorType p, const char *mess, void *)
{
  if (p == PETSC_ERROR_INITIAL) printf("caught: %s\n", mess);
  return n;
}

static const PetscInt N = 2;
static PetscInt       Node(PetscInt i, PetscInt j, PetscInt k) { return i + (N + 1) * (j + (N + 1) * k); }

/* The Kuhn split of the cube (tests/mesh/write-box-msh.py), positively oriented */
static void Cube(std::vector<PetscReal> &X, std::vector<PetscInt> &tets)
{
  const PetscInt  kuhn[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const PetscBool odd[6]     = {PETSC_FALSE, PETSC_TRUE, PETSC_TRUE, PETSC_FALSE, PETSC_FALSE, PETSC_TRUE};
  for (PetscInt k = 0; k <= N; k++)
    for (PetscInt j = 0; j <= N; j++)
      for (PetscInt i = 0; i <= N; i++) X.insert(X.end(), {(PetscReal)i / N, (PetscReal)j / N, (PetscReal)k / N});
  for (PetscInt k = 0; k < N; k++)
    for (PetscInt j = 0; j < N; j++)
      for (PetscInt i = 0; i < N; i++)
        for (PetscInt t = 0; t < 6; t++) {
          PetscInt off[3] = {0, 0, 0}, v[4];
          v[0]            = Node(i, j, k);
          for (PetscInt s = 0; s < 3; s++) {
            off[kuhn[t][s]] = 1;
            v[s + 1]        = Node(i + off[0], j + off[1], k + off[2]);
          }
          if (odd[t]) std::swap(v[1], v[2]);
          tets.insert(tets.end(), v, v + 4);
        }
}

static PetscErrorCode Run(const char *casename)
{
  std::vector<PetscReal> X;
  std::vector<PetscInt>  tets;
  PetscMPIInt            rank;
  DM                     dm;
  FEM                    mesh, box;
  PetscInt               body, n;
  const PetscBool        plain = !strcmp(casename, "plain_order") ? PETSC_TRUE : PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  Cube(X, tets);
  if (!plain)
    for (size_t e = 0; e < tets.size() / 4; e++) std::swap(tets[4 * e], tets[4 * e + 1]); /* DMPlex's order: the other orientation */
  PetscCall(DMPlexCreateFromCellListPetsc(PETSC_COMM_WORLD, 3, rank ? 0 : (PetscInt)tets.size() / 4, rank ? 0 : (PetscInt)X.size() / 3, 4, PETSC_TRUE, tets.data(), 3, X.data(), &dm));
  PetscCall(PetscObjectSetName((PetscObject)dm, "user cube"));
  if (!rank) { /* the top triangles: the faces whose three vertices lie at z = 1 */
    PetscInt fStart, fEnd, vStart, vEnd;
    PetscCall(DMPlexGetDepthStratum(dm, 2, &fStart, &fEnd));
    PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    for (PetscInt f = fStart; f < fEnd; f++) {
      PetscInt *closure = NULL, nc, top = 0;
      PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &nc, &closure));
      for (PetscInt c = 0; c < nc; c++)
        if (closure[2 * c] >= vStart && closure[2 * c] < vEnd && X[3 * (closure[2 * c] - vStart) + 2] == 1) top++;
      PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &nc, &closure));
      if (top == 3) PetscCall(DMSetLabelValue(dm, "loaded", f, 1));
    }
  } else PetscCall(DMCreateLabel(dm, "loaded"));
  if (!strcmp(casename, "distributed")) {
    DM dist = NULL;
    PetscCall(DMPlexDistribute(dm, 0, NULL, &dist));
    if (dist) {
      PetscCall(DMDestroy(&dm));
      dm = dist;
    }
  }
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &mesh));
  PetscCall(FEMAddDMPlex(mesh, dm, &body));
  PetscCall(DMDestroy(&dm));
  PetscCall(FEMSetMaterial(mesh, body, 2e11, 0.3));
  PetscCall(FEMSetDirichlet(mesh, body, "z0", NULL));
  {
    PetscMPIInt size;
    PetscInt    parts[3] = {1, 1, 1};
    PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
    parts[0] = size;
    PetscCall(FEMSetDecomposition(mesh, body, FEM_DECOMPOSITION_METIS, parts));
  }
  PetscCall(FEMSetUp(mesh));
  PetscCall(FEMGetBodyNodes(mesh, body, &n, NULL));
  PetscCheck(n == (N + 1) * (N + 1) * (N + 1), PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%" PetscInt_FMT " nodes", n);
  {
    const PetscReal  lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    const PetscInt   cells[3] = {N, N, N};
    PetscInt         nb, nm;
    const PetscInt  *nodesb, *nodesm;
    const PetscReal *ab, *am, *nrb, *nrm, *xm;
    PetscReal        err = 0;
    PetscCall(FEMCreate(PETSC_COMM_SELF, &box)); /* the reference, on every rank */
    PetscCall(FEMAddBox(box, lo, hi, cells, NULL));
    PetscCall(FEMSetUp(box));
    PetscCall(FEMGetTaggedNodes(box, 0, "z1", &nb, &nodesb, &ab, &nrb));
    PetscCall(FEMGetTaggedNodes(mesh, 0, "loaded", &nm, &nodesm, &am, &nrm));
    PetscCall(FEMGetBodyNodes(mesh, 0, NULL, &xm));
    PetscCheck(nb == nm, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "loaded has %" PetscInt_FMT " nodes, z1 of the box %" PetscInt_FMT, nm, nb);
    for (PetscInt i = 0; i < nm; i++) { /* the same node (by position), area and normal */
      const PetscReal *x  = &xm[3 * nodesm[i]];
      const PetscInt   id = Node((PetscInt)std::lround(x[0] * N), (PetscInt)std::lround(x[1] * N), (PetscInt)std::lround(x[2] * N));
      const PetscInt  *j  = std::lower_bound(nodesb, nodesb + nb, id);
      PetscCheck(j < nodesb + nb && *j == id, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "node %" PetscInt_FMT " of loaded, at (%g,%g,%g), is no node of z1", nodesm[i], (double)x[0], (double)x[1],
                 (double)x[2]);
      const PetscInt k = (PetscInt)(j - nodesb);
      err              = PetscMax(err, PetscAbsReal(am[i] - ab[k]));
      for (int d = 0; d < 3; d++) err = PetscMax(err, PetscAbsReal(nrm[3 * i + d] - nrb[3 * k + d]));
    }
    PetscCheck(err < 1e-14, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "areas or normals differ by %g", (double)err);
    PetscCall(FEMDestroy(&box));
  }
  PetscCall(FEMDestroy(&mesh));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char      casename[64] = "";
  PetscBool hascase;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "FEMAddDMPlex on a DMPlex built by the user's code"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", casename, sizeof(casename), &hascase));
  if (hascase) {
    PetscErrorCode ierr;
    PetscCall(PetscPushErrorHandler(PrintInitialError, NULL));
    ierr = Run(casename);
    PetscCall(PetscPopErrorHandler());
    PetscCheck(ierr, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "-case %s: the mistake was not detected", casename);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "error caught\n"));
  } else {
    PetscCall(Run(""));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "user DMPlex body and its label as expected\n"));
  }
  PetscCall(PetscFinalize());
  return 0;
}
