/* FEMCreateDMPlexFromFile() + FEMAddDMPlex(): the box mesh the generator makes, written to a Gmsh file by
   write-box-msh.py (MSH 2.2 or 4.1, ASCII or binary) and read back, is the same body as the generated box:
   - the physical surfaces select the box's faces: "top" = z1, "left" = x0, the unnamed surface "7" = x1 (same
     nodes, lumped areas and normals), and the mesh's own built-in z1 too;
   - the assembled K x (x a smooth field), f and u = K^-1 f agree node for node, the nodes matched by position
     (DMPlex numbers them its own way).
   Each would fail if the orientation, the facet sets from the labels, the physical names or the coordinates
   of the conversion went wrong.

   Options: -file <msh> (required), -lower, -upper, -cells as given to write-box-msh.py */
#include <conefeti.h>
#include <conefeti/compat.h>
#include "femsolve.h"

#include <algorithm>
#include <array>
#include <map>
#include <vector>

/* node of the box -> node of the mesh, matched by coordinates (exact: both come from the same arithmetic,
   printed by Gmsh with 17 significant digits) */
static PetscErrorCode MatchNodes(FEM box, FEM mesh, std::vector<PetscInt> &map)
{
  PetscInt                                     nb, nm;
  const PetscReal                             *xb, *xm;
  std::map<std::array<PetscReal, 3>, PetscInt> where;

  PetscFunctionBeginUser;
  PetscCall(FEMGetBodyNodes(box, 0, &nb, &xb));
  PetscCall(FEMGetBodyNodes(mesh, 0, &nm, &xm));
  PetscCheck(nb == nm, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the mesh has %" PetscInt_FMT " nodes, the box %" PetscInt_FMT, nm, nb);
  for (PetscInt n = 0; n < nm; n++) where[{xm[3 * n], xm[3 * n + 1], xm[3 * n + 2]}] = n;
  map.assign(nb, -1);
  for (PetscInt n = 0; n < nb; n++) {
    auto it = where.find({xb[3 * n], xb[3 * n + 1], xb[3 * n + 2]});
    PetscCheck(it != where.end(), PETSC_COMM_WORLD, PETSC_ERR_PLIB, "box node %" PetscInt_FMT " at (%g,%g,%g) is no node of the mesh", n, (double)xb[3 * n], (double)xb[3 * n + 1],
               (double)xb[3 * n + 2]);
    map[n] = it->second;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* tag a of the box and tag b of the mesh: the same nodes with the same areas and normals */
static PetscErrorCode SameTag(FEM box, const char *a, FEM mesh, const char *b, const std::vector<PetscInt> &map)
{
  PetscInt         na, nb;
  const PetscInt  *nodesa, *nodesb;
  const PetscReal *areaa, *areab, *nra, *nrb;
  PetscReal        err = 0;

  PetscFunctionBeginUser;
  PetscCall(FEMGetTaggedNodes(box, 0, a, &na, &nodesa, &areaa, &nra));
  PetscCall(FEMGetTaggedNodes(mesh, 0, b, &nb, &nodesb, &areab, &nrb));
  PetscCheck(na == nb && na > 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "tag %s of the mesh has %" PetscInt_FMT " nodes, %s of the box %" PetscInt_FMT, b, nb, a, na);
  for (PetscInt i = 0; i < na; i++) {
    const PetscInt *j = std::lower_bound(nodesb, nodesb + nb, map[nodesa[i]]);
    PetscCheck(j < nodesb + nb && *j == map[nodesa[i]], PETSC_COMM_WORLD, PETSC_ERR_PLIB, "node %" PetscInt_FMT " of %s (box) is not in %s (mesh)", nodesa[i], a, b);
    const PetscInt k = (PetscInt)(j - nodesb);
    err              = PetscMax(err, PetscAbsReal(areaa[i] - areab[k]));
    for (int d = 0; d < 3; d++) err = PetscMax(err, PetscAbsReal(nra[3 * i + d] - nrb[3 * k + d]));
  }
  PetscCheck(err < 1e-13, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "areas or normals of %s and %s differ by %g", a, b, (double)err);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "tag %s of the mesh = %s of the box (%" PetscInt_FMT " nodes)\n", b, a, na));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static PetscErrorCode Model(FEM fem, const char *bottom, const char *top)
{
  const PetscReal t[3] = {1e6, -2e6, -5e6};

  PetscFunctionBeginUser;
  PetscCall(FEMSetMaterial(fem, 0, 2.0e11, 0.3));
  PetscCall(FEMSetDirichlet(fem, 0, bottom, NULL));
  PetscCall(FEMSetTraction(fem, 0, top, t));
  PetscCall(FEMSetFromOptions(fem));
  PetscCall(FEMSetUp(fem));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  PetscReal             lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  PetscInt              cells[3] = {2, 2, 2}, three = 3, body;
  char                  file[PETSC_MAX_PATH_LEN] = "";
  PetscBool             set;
  FEM                   box, mesh;
  DM                    dm;
  PetscMPIInt           rank;
  std::vector<PetscInt> map;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "FEMAddDMPlex: the generator's box mesh read back from a Gmsh file is the same body"));
  PetscCall(ConeFETIInitializePackage());
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-file", file, sizeof(file), &set));
  PetscCheck(set, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "give -file <msh>");
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-lower", lo, &three, NULL));
  three = 3;
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-upper", hi, &three, NULL));
  three = 3;
  PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-cells", cells, &three, NULL));

  PetscCall(FEMCreate(PETSC_COMM_WORLD, &box));
  PetscCall(FEMAddBox(box, lo, hi, cells, NULL));
  PetscCall(Model(box, "z0", "z1"));
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &mesh));
  PetscCall(FEMCreateDMPlexFromFile(PETSC_COMM_WORLD, file, &dm));
  PetscCall(FEMAddDMPlex(mesh, dm, &body));
  PetscCall(DMDestroy(&dm));
  PetscCheck(body == 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "body %" PetscInt_FMT, body);
  PetscCall(Model(mesh, "bottom", "top"));

  PetscCall(MatchNodes(box, mesh, map));
  PetscCall(SameTag(box, "z1", mesh, "top", map));
  PetscCall(SameTag(box, "z1", mesh, "5", map));
  PetscCall(SameTag(box, "z1", mesh, "z1", map));
  PetscCall(SameTag(box, "x0", mesh, "left", map));
  PetscCall(SameTag(box, "x1", mesh, "7", map));
  PetscCall(SameTag(box, "y1", mesh, "back", map));
  {
    Vec                vb[3], vm[3];
    const PetscScalar *a, *b;
    PetscReal          err[3] = {0, 0, 0}, scale[3] = {0, 0, 0};
    PetscCall(FEMTestSolveGathered(box, vb));
    PetscCall(FEMTestSolveGathered(mesh, vm));
    if (rank == 0)
      for (int q = 0; q < 3; q++) {
        PetscCall(VecGetArrayRead(vb[q], &a));
        PetscCall(VecGetArrayRead(vm[q], &b));
        for (size_t n = 0; n < map.size(); n++)
          for (int d = 0; d < 3; d++) {
            err[q]   = PetscMax(err[q], PetscAbsScalar(a[3 * n + d] - b[3 * map[n] + d]));
            scale[q] = PetscMax(scale[q], PetscAbsScalar(a[3 * n + d]));
          }
        PetscCall(VecRestoreArrayRead(vb[q], &a));
        PetscCall(VecRestoreArrayRead(vm[q], &b));
      }
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "relative differences: K x %.2e, f %.2e, u %.2e\n", (double)(err[0] / scale[0]), (double)(err[1] / scale[1]), (double)(err[2] / scale[2])));
    if (rank == 0)
      PetscCheck(scale[1] > 0 && err[0] < 1e-12 * scale[0] && err[1] < 1e-12 * scale[1] && err[2] < 1e-8 * scale[2], PETSC_COMM_SELF, PETSC_ERR_PLIB, "the body from the file differs from the box");
    for (int q = 0; q < 3; q++) {
      PetscCall(VecDestroy(&vb[q]));
      PetscCall(VecDestroy(&vm[q]));
    }
  }
  PetscCall(FEMDestroy(&box));
  PetscCall(FEMDestroy(&mesh));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "file body equals box\n"));
  PetscCall(PetscFinalize());
  return 0;
}
