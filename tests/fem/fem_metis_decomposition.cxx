/* METIS decomposition (FEMSetDecomposition(..., FEM_DECOMPOSITION_METIS, ...)), checked through the public API:
   - at least the requested number of subdomains (a part that is not face-connected becomes several);
   - every element of the body in exactly one subdomain, every body node in at least one;
   - every subdomain face-connected (its tetrahedra joined through shared triangles);
   - balanced: with as many subdomains as requested, none has more than 1.1 times the mean element count
     (METIS's own tolerance is 1.03);
   - the subdomains spread over the ranks in contiguous ranges, at least one per rank.
   Prints "RESULT subdomains=<n> elements=<counts> nodes=<counts>" so that runs on different rank counts can
   be compared (the partition must not depend on them). -cells nx,ny,nz and -parts n choose the body. */
#include <conefeti.h>
#include <conefeti/compat.h>
#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <vector>

/* whether the tetrahedra of one subdomain form one face-connected piece */
static bool FaceConnected(PetscInt ne, const PetscInt *conn, const PetscInt *nodes)
{
  std::map<std::array<PetscInt, 3>, std::vector<PetscInt>> faces;
  for (PetscInt e = 0; e < ne; e++)
    for (int skip = 0; skip < 4; skip++) {
      std::array<PetscInt, 3> f;
      int                     k = 0;
      for (int v = 0; v < 4; v++)
        if (v != skip) f[k++] = nodes[conn[4 * e + v]];
      std::sort(f.begin(), f.end());
      faces[f].push_back(e);
    }
  std::vector<std::vector<PetscInt>> adj(ne);
  for (const auto &kv : faces)
    if (kv.second.size() == 2) {
      adj[kv.second[0]].push_back(kv.second[1]);
      adj[kv.second[1]].push_back(kv.second[0]);
    }
  std::vector<char>     seen(ne, 0);
  std::vector<PetscInt> stack   = {0};
  PetscInt              reached = 0;
  if (ne == 0) return false;
  seen[0] = 1;
  while (!stack.empty()) {
    const PetscInt e = stack.back();
    stack.pop_back();
    reached++;
    for (PetscInt o : adj[e])
      if (!seen[o]) {
        seen[o] = 1;
        stack.push_back(o);
      }
  }
  return reached == ne;
}

int main(int argc, char **argv)
{
  FEM         fem;
  PetscReal   lo[3] = {0, 0, 0}, hi[3] = {3, 1, 2};
  PetscInt    cells[3] = {6, 3, 4}, three = 3, parts[3] = {5, 0, 0}, body, nglobal, nlocal, first, nbodynodes, total, mean;
  PetscMPIInt rank;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "METIS decomposition properties"));
  PetscCall(ConeFETIInitializePackage());
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-cells", cells, &three, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-parts", &parts[0], NULL));
  PetscCall(FEMCreate(PETSC_COMM_WORLD, &fem));
  PetscCall(FEMAddBox(fem, lo, hi, cells, &body));
  PetscCall(FEMSetMaterial(fem, body, 2.0e11, 0.3));
  PetscCall(FEMSetDecomposition(fem, body, FEM_DECOMPOSITION_METIS, parts));
  PetscCall(FEMSetUp(fem));
  PetscCall(FEMGetNumSubdomains(fem, &nglobal, &nlocal, &first));
  PetscCall(FEMGetBodyNodes(fem, body, &nbodynodes, NULL));
  PetscCheck(nglobal >= parts[0], PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%" PetscInt_FMT " subdomains for %" PetscInt_FMT " requested", nglobal, parts[0]);

  /* the spread over the ranks: contiguous ranges, at least one subdomain each */
  {
    PetscInt start = 0, minlocal, sum;
    PetscCallMPI(MPI_Exscan(&nlocal, &start, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    if (rank == 0) start = 0;
    PetscCall(MPIU_Allreduce(&nlocal, &minlocal, 1, MPIU_INT, MPI_MIN, PETSC_COMM_WORLD));
    PetscCall(MPIU_Allreduce(&nlocal, &sum, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    PetscCheck(first == start && sum == nglobal && minlocal >= 1, PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "rank %d holds subdomains %" PetscInt_FMT "..%" PetscInt_FMT " of %" PetscInt_FMT " (expected a contiguous range from %" PetscInt_FMT ", at least one per rank)", rank, first,
               first + nlocal - 1, nglobal, start);
  }

  /* elements and nodes per subdomain (global arrays, each rank fills its own), node coverage, connectivity */
  std::vector<PetscInt> elements(nglobal, 0), nodes(nglobal, 0), covered(nbodynodes, 0);
  for (PetscInt s = 0; s < nlocal; s++) {
    PetscInt        b, nn, ne;
    const PetscInt *sn, *conn;
    PetscCall(FEMGetSubdomainMesh(fem, s, &b, &nn, &sn, &ne, &conn));
    PetscCheck(b == body, PETSC_COMM_SELF, PETSC_ERR_PLIB, "subdomain %" PetscInt_FMT " belongs to body %" PetscInt_FMT, first + s, b);
    PetscCheck(FaceConnected(ne, conn, sn), PETSC_COMM_SELF, PETSC_ERR_PLIB, "subdomain %" PetscInt_FMT " (%" PetscInt_FMT " elements) is not face-connected", first + s, ne);
    elements[first + s] = ne;
    nodes[first + s]    = nn;
    for (PetscInt i = 0; i < nn; i++) covered[sn[i]] = 1;
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, elements.data(), (PetscMPIInt)nglobal, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, nodes.data(), (PetscMPIInt)nglobal, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, covered.data(), (PetscMPIInt)nbodynodes, MPIU_INT, MPI_MAX, PETSC_COMM_WORLD));
  total = 0;
  for (PetscInt e : elements) total += e;
  PetscCheck(total == 6 * cells[0] * cells[1] * cells[2], PETSC_COMM_WORLD, PETSC_ERR_PLIB, "the subdomains hold %" PetscInt_FMT " elements, the body has %" PetscInt_FMT, total,
             6 * cells[0] * cells[1] * cells[2]);
  PetscCheck(std::count(covered.begin(), covered.end(), 0) == 0, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "%d body nodes are in no subdomain", (int)std::count(covered.begin(), covered.end(), 0));
  mean = total / nglobal;
  if (nglobal == parts[0])
    PetscCheck(10 * *std::max_element(elements.begin(), elements.end()) <= 11 * mean, PETSC_COMM_WORLD, PETSC_ERR_PLIB,
               "unbalanced: the largest subdomain has %" PetscInt_FMT " elements, the mean is %" PetscInt_FMT, *std::max_element(elements.begin(), elements.end()), mean);

  {
    std::string line = "RESULT subdomains=" + std::to_string(nglobal) + " elements=";
    for (PetscInt s = 0; s < nglobal; s++) line += (s ? "," : "") + std::to_string(elements[s]);
    line += " nodes=";
    for (PetscInt s = 0; s < nglobal; s++) line += (s ? "," : "") + std::to_string(nodes[s]);
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s\n", line.c_str()));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "METIS decomposition check passed\n"));
  PetscCall(FEMDestroy(&fem));
  PetscCall(PetscFinalize());
  return 0;
}
