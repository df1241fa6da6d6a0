/* Assembly of subdomain stiffness matrices and loads, of the undecomposed global system (for
   comparison with direct and multigrid solvers), and of a body's load resultant (net force and moment,
   for the check that the supports can hold the load). */
#include <conefeti/private/femimpl.h>

#include <algorithm>

static void ElementCoordinates(const FEMBody &b, const PetscInt v[4], PetscReal X[12])
{
  for (PetscInt a = 0; a < 4; a++)
    for (PetscInt d = 0; d < 3; d++) X[3 * a + d] = b.coords[3 * v[a] + d];
}

/* Loads of one element (volume force) and of the boundary triangles it owns with a traction, in element dof order */
static PetscErrorCode ElementRHS(const FEMBody &b, PetscInt e, const PetscInt v[4], const std::vector<std::vector<PetscInt>> &tractiontris, PetscReal fe[12], PetscBool *nonzero)
{
  PetscReal X[12];

  PetscFunctionBegin;
  *nonzero = PETSC_FALSE;
  for (PetscInt i = 0; i < 12; i++) fe[i] = 0;
  ElementCoordinates(b, v, X);
  if (b.bodyforce) {
    PetscCall(FEMElementLoad(X, b.bodyforce, b.bodyforcectx, fe));
    *nonzero = PETSC_TRUE;
  }
  for (size_t ts = 0; ts < b.tractions.size(); ts++) {
    const FEMTractionSpec &spec = b.tractions[ts];
    for (PetscInt t : tractiontris[ts]) {
      const FEMBoundaryTriangle &tri = b.boundary[t];
      if (tri.element != e) continue;
      PetscReal Xt[9], ft[9];
      for (PetscInt a = 0; a < 3; a++)
        for (PetscInt d = 0; d < 3; d++) Xt[3 * a + d] = b.coords[3 * tri.v[a] + d];
      PetscCall(FEMTriangleLoad(Xt, tri.area, spec.field, spec.ctx, spec.value.data(), ft));
      for (PetscInt a = 0; a < 3; a++) {
        const PetscInt loc = (PetscInt)(std::find(v, v + 4, tri.v[a]) - v);
        for (PetscInt d = 0; d < 3; d++) fe[3 * loc + d] += ft[3 * a + d];
      }
      *nonzero = PETSC_TRUE;
    }
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* The boundary triangles with tractions owned by the elements of one subdomain (sorted body element ids), per
   traction spec in the order of the tag, and the elements that own them (sorted). Only the subdomain's own: a
   list of the whole body's triangles, searched for each loaded element, made the loads of all subdomains cost
   (subdomains x loaded triangles of the body). */
static PetscErrorCode TractionTriangles(const FEMBody &b, const std::vector<PetscInt> &sdelements, std::vector<std::vector<PetscInt>> &tris, std::vector<PetscInt> &elements)
{
  PetscFunctionBegin;
  tris.assign(b.tractions.size(), {});
  elements.clear();
  if (sdelements.empty()) PetscFunctionReturn(PETSC_SUCCESS);
  const PetscInt lo = sdelements.front(), hi = sdelements.back();
  for (size_t ts = 0; ts < b.tractions.size(); ts++) {
    for (PetscInt t : b.tags.at(b.tractions[ts].name)) {
      const PetscInt e = b.boundary[t].element;
      if (e < lo || e > hi || !std::binary_search(sdelements.begin(), sdelements.end(), e)) continue;
      PetscCallCXX(tris[ts].push_back(t));
      PetscCallCXX(elements.push_back(e));
    }
  }
  std::sort(elements.begin(), elements.end());
  elements.erase(std::unique(elements.begin(), elements.end()), elements.end());
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* K_s (SEQSBAIJ or SEQAIJ, block size 3) and f_s of one subdomain, without any boundary condition */
PetscErrorCode FEMAssembleSubdomain(FEM fem, const FEMSubdomain &sd, Mat *K, Vec *f)
{
  const FEMBody                     &b  = fem->impl->bodies[sd.body];
  const PetscInt                     nn = (PetscInt)sd.nodes.size();
  std::vector<std::vector<PetscInt>> adj(nn), tractiontris;
  std::vector<PetscInt>              nnz(nn), tractionelements;
  PetscScalar                       *fa;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(FEM_Assembly, fem, 0, 0, 0));
  /* block adjacency: the upper triangle for SBAIJ, all for AIJ */
  for (size_t e = 0; e < sd.elements.size(); e++)
    for (PetscInt a = 0; a < 4; a++)
      for (PetscInt c = 0; c < 4; c++) {
        const PetscInt r = sd.conn[4 * e + a], col = sd.conn[4 * e + c];
        if (!fem->impl->sbaij || col >= r) PetscCallCXX(adj[r].push_back(col));
      }
  for (PetscInt r = 0; r < nn; r++) {
    std::sort(adj[r].begin(), adj[r].end());
    nnz[r] = (PetscInt)(std::unique(adj[r].begin(), adj[r].end()) - adj[r].begin());
  }
  PetscCallCXX(adj.clear());
  PetscCall(MatCreate(PETSC_COMM_SELF, K));
  PetscCall(MatSetSizes(*K, 3 * nn, 3 * nn, 3 * nn, 3 * nn));
  PetscCall(MatSetBlockSize(*K, 3));
  PetscCall(MatSetType(*K, fem->impl->sbaij ? MATSEQSBAIJ : MATSEQAIJ));
  PetscCall(MatXAIJSetPreallocation(*K, 3, nnz.data(), NULL, fem->impl->sbaij ? nnz.data() : NULL, NULL));
  if (fem->impl->sbaij) PetscCall(MatSetOption(*K, MAT_IGNORE_LOWER_TRIANGULAR, PETSC_TRUE));
  PetscCall(MatSetOption(*K, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(*K, MAT_SPD, PETSC_FALSE));

  PetscCall(VecCreateSeq(PETSC_COMM_SELF, 3 * nn, f));
  PetscCall(VecSetBlockSize(*f, 3));
  PetscCall(TractionTriangles(b, sd.elements, tractiontris, tractionelements));
  PetscCall(VecGetArray(*f, &fa));
  for (size_t e = 0; e < sd.elements.size(); e++) {
    PetscInt  v[4], loc[4];
    PetscReal X[12], Ke[144], fe[12];
    PetscBool loaded;
    FEMElementNodes(b, sd.elements[e], v);
    ElementCoordinates(b, v, X);
    PetscCall(FEMElementStiffness(X, b.E, b.nu, Ke, NULL));
    for (PetscInt a = 0; a < 4; a++) loc[a] = sd.conn[4 * e + a];
    PetscCall(MatSetValuesBlocked(*K, 4, loc, 4, loc, Ke, ADD_VALUES));
    if (!b.bodyforce && !std::binary_search(tractionelements.begin(), tractionelements.end(), sd.elements[e])) continue;
    PetscCall(ElementRHS(b, sd.elements[e], v, tractiontris, fe, &loaded));
    for (PetscInt a = 0; a < 4; a++)
      for (PetscInt d = 0; d < 3; d++) fa[3 * loc[a] + d] += fe[3 * a + d];
  }
  PetscCall(VecRestoreArray(*f, &fa));
  PetscCall(MatAssemblyBegin(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscLogEventEnd(FEM_Assembly, fem, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMComputeLoadResultant - The net force and moment of a body's load (tractions and volume force), as
  assembled into the nodal loads of the FETI problem.

  Collective

  Input Parameters:
+ fem   - the model, set up
. body  - the body
- point - the point about which the moment is taken

  Output Parameters:
+ force     - the sum of the nodal loads (3 components), or NULL
. moment    - the sum of (x - point) x (nodal load) over the nodes x (3 components), or NULL
- magnitude - the sum of the lengths of the element load vectors at the element nodes, or NULL: the scale
              of the load, above which force and moment differ from zero beyond roundoff (a self-balanced
              load has force and moment zero but a positive magnitude)

  Notes:
  The work of the load along a rigid motion u(x) = t + w x (x - point) of the body is force . t + moment . w:
  the load is in equilibrium with what holds the body only if that work vanishes along every rigid
  motion nothing resists (`ContactModelSetUp()` checks it). Only the nodal loads are summed, so the
  result is the resultant of the discrete load vector, whatever the quadrature.

  Level: intermediate

.seealso: `FEMSetTraction()`, `FEMSetBodyForce()`, `FEMAssembleGlobal()`
@*/
PetscErrorCode FEMComputeLoadResultant(FEM fem, PetscInt body, const PetscReal point[3], PetscReal force[3], PetscReal moment[3], PetscReal *magnitude)
{
  FEM_Impl &impl   = *fem->impl;
  PetscReal sum[7] = {0, 0, 0, 0, 0, 0, 0}; /* force, moment, magnitude */
  MPI_Comm  comm   = PetscObjectComm((PetscObject)fem);

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscValidRealPointer(point, 3);
  PetscCheck(impl.setupcalled, comm, PETSC_ERR_ORDER, "Call FEMSetUp() before FEMComputeLoadResultant()");
  PetscCheck(body >= 0 && body < (PetscInt)impl.bodies.size(), comm, PETSC_ERR_ARG_OUTOFRANGE, "FEMComputeLoadResultant(): body %" PetscInt_FMT " does not exist (%zu bodies)", body,
             impl.bodies.size());
  {
    const FEMBody                     &b = impl.bodies[body];
    std::vector<std::vector<PetscInt>> tractiontris;
    std::vector<PetscInt>              tractionelements;
    /* every element lies in exactly one subdomain: the local subdomains' elements, summed over the ranks */
    for (const FEMSubdomain &sd : impl.local) {
      if (sd.body != body) continue;
      PetscCall(TractionTriangles(b, sd.elements, tractiontris, tractionelements));
      for (PetscInt e : sd.elements) {
        PetscInt  v[4];
        PetscReal fe[12];
        PetscBool loaded;
        if (!b.bodyforce && !std::binary_search(tractionelements.begin(), tractionelements.end(), e)) continue;
        FEMElementNodes(b, e, v);
        PetscCall(ElementRHS(b, e, v, tractiontris, fe, &loaded));
        for (PetscInt a = 0; a < 4; a++) {
          const PetscReal *f = &fe[3 * a], *x = &b.coords[3 * v[a]];
          const PetscReal  y[3] = {x[0] - point[0], x[1] - point[1], x[2] - point[2]};
          for (PetscInt d = 0; d < 3; d++) sum[d] += f[d];
          sum[3] += y[1] * f[2] - y[2] * f[1];
          sum[4] += y[2] * f[0] - y[0] * f[2];
          sum[5] += y[0] * f[1] - y[1] * f[0];
          sum[6] += PetscSqrtReal(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        }
      }
    }
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sum, 7, MPIU_REAL, MPIU_SUM, comm));
  for (PetscInt d = 0; d < 3; d++) {
    if (force) force[d] = sum[d];
    if (moment) moment[d] = sum[3 + d];
  }
  if (magnitude) *magnitude = sum[6];
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMAssembleGlobal - Assemble the undecomposed global stiffness matrix and load vector of all bodies,
  with the Dirichlet conditions imposed by identity rows and columns.

  Collective

  Input Parameter:
. fem - the model, set up

  Output Parameters:
+ K - MPIAIJ matrix of size 3 x (number of nodes of all bodies), block size 3, marked symmetric positive definite
- f - the load vector: zero at clamped dofs; with prescribed displacements u_D lifted (f - K u_D elsewhere, the diagonal entry times u_D at those dofs), so that the solution takes u_D there

  Notes:
  Global dof 3 (first node of body b + body node) + component, bodies concatenated (see `FEMGetBodyNodeOffset()`).
  This is the system the FETI solution must reproduce; it serves for tests and for comparisons with
  single-domain solvers (CG + GAMG with `FEMCreateGlobalCoordinates()` for the near-null space, or Cholesky).
  The identity rows carry the mean diagonal entry so that they do not spoil the conditioning.
  Bodies are not connected to each other: each must have enough Dirichlet conditions to be fixed.

  Level: intermediate

.seealso: `FEMPrimalToGlobal()`, `FEMCreateGlobalCoordinates()`, `FEMCreateFETI()`
@*/
PetscErrorCode FEMAssembleGlobal(FEM fem, Mat *K, Vec *f)
{
  FEM_Impl             &impl        = *fem->impl;
  PetscInt              nlocalnodes = PETSC_DECIDE, nglobal = impl.nglobalnodes, first, last;
  std::vector<PetscInt> dnnz, onnz, zero;
  MPI_Comm              comm = PetscObjectComm((PetscObject)fem);

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCheck(impl.setupcalled, comm, PETSC_ERR_ORDER, "Call FEMSetUp() before FEMAssembleGlobal()");
  PetscCall(PetscLogEventBegin(FEM_Assembly, fem, 0, 0, 0));
  PetscCall(PetscSplitOwnership(comm, &nlocalnodes, &nglobal));
  PetscCallMPI(MPI_Scan(&nlocalnodes, &last, 1, MPIU_INT, MPI_SUM, comm));
  first = last - nlocalnodes;
  PetscCallCXX(dnnz.assign(nlocalnodes, 0));
  PetscCallCXX(onnz.assign(nlocalnodes, 0));
  /* block nonzeros of the local rows: the nodes that share an element with the row's node */
  for (const FEMBody &b : impl.bodies) {
    const PetscInt lo = std::max(first, b.nodeoffset), hi = std::min(last, b.nodeoffset + b.nnodes);
    if (lo >= hi) continue;
    std::vector<std::vector<PetscInt>> adj(hi - lo);
    for (PetscInt e = 0; e < b.nelements; e++) {
      PetscInt v[4];
      FEMElementNodes(b, e, v);
      for (PetscInt a = 0; a < 4; a++) {
        const PetscInt g = b.nodeoffset + v[a];
        if (g < lo || g >= hi) continue;
        for (PetscInt c = 0; c < 4; c++) PetscCallCXX(adj[g - lo].push_back(b.nodeoffset + v[c]));
      }
    }
    for (PetscInt g = lo; g < hi; g++) {
      std::vector<PetscInt> &cols = adj[g - lo];
      std::sort(cols.begin(), cols.end());
      cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
      for (PetscInt col : cols) {
        if (col >= first && col < last) dnnz[g - first]++;
        else onnz[g - first]++;
      }
    }
  }
  PetscCall(MatCreate(comm, K));
  PetscCall(MatSetSizes(*K, 3 * nlocalnodes, 3 * nlocalnodes, 3 * nglobal, 3 * nglobal));
  PetscCall(MatSetBlockSize(*K, 3));
  PetscCall(MatSetType(*K, MATAIJ));
  PetscCall(MatXAIJSetPreallocation(*K, 3, dnnz.data(), onnz.data(), NULL, NULL));
  PetscCall(MatCreateVecs(*K, NULL, f));

  for (const FEMSubdomain &sd : impl.local) {
    const FEMBody                     &b = impl.bodies[sd.body];
    std::vector<std::vector<PetscInt>> tractiontris;
    std::vector<PetscInt>              tractionelements;
    PetscCall(TractionTriangles(b, sd.elements, tractiontris, tractionelements));
    for (PetscInt e : sd.elements) {
      PetscInt  v[4], rows[4];
      PetscReal X[12], Ke[144], fe[12];
      PetscBool loaded;
      FEMElementNodes(b, e, v);
      ElementCoordinates(b, v, X);
      PetscCall(FEMElementStiffness(X, b.E, b.nu, Ke, NULL));
      for (PetscInt a = 0; a < 4; a++) rows[a] = b.nodeoffset + v[a];
      PetscCall(MatSetValuesBlocked(*K, 4, rows, 4, rows, Ke, ADD_VALUES));
      if (!b.bodyforce && !std::binary_search(tractionelements.begin(), tractionelements.end(), e)) continue;
      PetscCall(ElementRHS(b, e, v, tractiontris, fe, &loaded));
      PetscCall(VecSetValuesBlocked(*f, 4, rows, fe, ADD_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*K, MAT_FINAL_ASSEMBLY));
  PetscCall(VecAssemblyBegin(*f));
  PetscCall(VecAssemblyEnd(*f));

  /* Dirichlet: identity rows and columns scaled by the mean diagonal entry */
  Vec       diag;
  PetscReal sum;
  PetscCall(MatCreateVecs(*K, &diag, NULL));
  PetscCall(MatGetDiagonal(*K, diag));
  PetscCall(VecSum(diag, &sum));
  PetscCall(VecDestroy(&diag));
  std::vector<PetscScalar> values;
  PetscBool                lift = PETSC_FALSE;
  for (const FEMBody &b : impl.bodies) {
    const PetscInt lo = std::max(first, b.nodeoffset), hi = std::min(last, b.nodeoffset + b.nnodes);
    for (PetscInt g = lo; g < hi; g++)
      for (PetscInt c = 0; c < 3; c++)
        if (b.dirichletmask[g - b.nodeoffset] & (1u << c)) {
          PetscCallCXX(zero.push_back(3 * g + c));
          PetscCallCXX(values.push_back(FEMDirichletValue(b, g - b.nodeoffset, c)));
        }
    if (!b.dirichletvalue.empty()) lift = PETSC_TRUE;
  }
  if (lift) { /* prescribed displacements: f - K u_D on the free rows, diag * u_D on the Dirichlet rows (MatZeroRowsColumns() lifts) */
    Vec uD;
    PetscCall(VecDuplicate(*f, &uD));
    PetscCall(VecSetValues(uD, (PetscInt)zero.size(), zero.data(), values.data(), INSERT_VALUES));
    PetscCall(VecAssemblyBegin(uD));
    PetscCall(VecAssemblyEnd(uD));
    PetscCall(MatZeroRowsColumns(*K, (PetscInt)zero.size(), zero.data(), sum / (3 * nglobal), uD, *f));
    PetscCall(VecDestroy(&uD));
  } else {
    PetscCall(MatZeroRowsColumns(*K, (PetscInt)zero.size(), zero.data(), sum / (3 * nglobal), NULL, NULL));
    PetscCall(VecSetValues(*f, (PetscInt)zero.size(), zero.data(), std::vector<PetscScalar>(zero.size(), 0.0).data(), INSERT_VALUES));
    PetscCall(VecAssemblyBegin(*f));
    PetscCall(VecAssemblyEnd(*f));
  }
  PetscCall(MatSetOption(*K, MAT_SPD, PETSC_TRUE));
  PetscCall(PetscLogEventEnd(FEM_Assembly, fem, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMCreateGlobalCoordinates - The node coordinates in the layout of `FEMAssembleGlobal()`'s vectors.

  Collective

  Input Parameter:
. fem - the model, set up

  Output Parameter:
. coords - vector with 3 entries (x, y, z) per node, block size 3

  Notes:
  Pass it to `MatNullSpaceCreateRigidBody()` to give GAMG the rigid-body near-null space.

  Level: intermediate

.seealso: `FEMAssembleGlobal()`
@*/
PetscErrorCode FEMCreateGlobalCoordinates(FEM fem, Vec *coords)
{
  FEM_Impl    &impl = *fem->impl;
  PetscInt     lo, hi, nlocalnodes = PETSC_DECIDE, nglobal = impl.nglobalnodes;
  PetscScalar *a;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscCheck(impl.setupcalled, PetscObjectComm((PetscObject)fem), PETSC_ERR_ORDER, "Call FEMSetUp() before FEMCreateGlobalCoordinates()");
  PetscCall(PetscSplitOwnership(PetscObjectComm((PetscObject)fem), &nlocalnodes, &nglobal)); /* the layout of FEMAssembleGlobal() */
  PetscCall(VecCreate(PetscObjectComm((PetscObject)fem), coords));
  PetscCall(VecSetSizes(*coords, 3 * nlocalnodes, 3 * nglobal));
  PetscCall(VecSetBlockSize(*coords, 3));
  PetscCall(VecSetFromOptions(*coords));
  PetscCall(VecGetOwnershipRange(*coords, &lo, &hi));
  PetscCall(VecGetArray(*coords, &a));
  for (const FEMBody &b : impl.bodies)
    for (PetscInt d = std::max(lo, 3 * b.nodeoffset); d < std::min(hi, 3 * (b.nodeoffset + b.nnodes)); d++) a[d - lo] = b.coords[d - 3 * b.nodeoffset];
  PetscCall(VecRestoreArray(*coords, &a));
  PetscFunctionReturn(PETSC_SUCCESS);
}
