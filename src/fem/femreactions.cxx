/* Reaction forces: the resultant force each Dirichlet condition (a clamped or a displaced face) exerts on its body.

   With L(u, l) = 1/2 u'K u - u'f + l'(B u - c), the solution satisfies K u - f = -B'l: at a dof held by a Dirichlet
   row (Total FETI, or a subdomain the -fem_dirichlet_min_hold fallback let float) the support's force is minus the
   row's multiplier; at a dof kept in the primal it is K_s u_s - f_s there, with the subdomain's whole K_s and its own
   load (not the lifted one). Both are the force the support exerts on the body, as it enters K u = f + r. A node
   component counts for the first condition that prescribes it, so the conditions' resultants add up to the total
   reaction even where two faces share an edge. */
#include <conefeti/private/femimpl.h>

/* per body node component: the index of the first condition of the body prescribing it, or -1 */
static PetscErrorCode ConditionOwners(const FEMBody &b, std::vector<int> &owner)
{
  PetscFunctionBegin;
  PetscCallCXX(owner.assign(3 * (size_t)b.nnodes, -1));
  for (size_t k = 0; k < b.dirichlet.size(); k++) {
    const FEMDirichletSpec &ds = b.dirichlet[k];
    for (PetscInt t : b.tags.at(ds.name))
      for (PetscInt n : b.boundary[t].v)
        for (PetscInt c = 0; c < 3; c++)
          if ((ds.components & (1u << c)) && owner[3 * (size_t)n + c] < 0) owner[3 * (size_t)n + c] = (int)k;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  FEMComputeReactions - The resultant force of every Dirichlet condition (clamped or displaced face) on its body.

  Collective

  Input Parameters:
+ fem    - the model, set up
. feti   - the FETI problem `FEMCreateFETI()` or `FEMCreateFETIWithRows()` built from it, set up
. u      - the primal solution (`FETIRecoverPrimal()`: the prescribed values at the Dirichlet dofs)
- lambda - the multipliers

  Output Parameter:
. reaction - 3 entries (fx, fy, fz) per condition: body 0's conditions in the order set (`FEMSetDirichlet()`,
             `FEMSetDisplacement()`; `FEMGetNumDirichlet()` counts them), then body 1's, ...; the same on every rank

  Notes:
  The force the support exerts on the body (K u = f + r): a block pressed down by a displaced top reports an upward
  force on its bottom and a downward one on its top, the load's direction being negative along the pull. On a Dirichlet
  row (Total FETI, `-fem_dirichlet multipliers`) the force is minus the row's multiplier; on a dof kept in the primal
  (`-fem_dirichlet primal`) it is K_s u_s - f_s at the dof, from the subdomain's stiffness assembled again (only for the
  subdomains that keep Dirichlet dofs). The two agree to the solver's tolerance. A node component prescribed by several
  conditions counts for the first one. With the resultants of the loads (`FEMComputeLoadResultant()`) and of the contact
  forces, every body is in equilibrium: reactions + loads + contact forces = 0.

  Level: intermediate

.seealso: `FEMSetDisplacement()`, `FEMSetDirichlet()`, `FEMGetNumDirichlet()`, `FEMComputeLoadResultant()`
@*/
PetscErrorCode FEMComputeReactions(FEM fem, FETI feti, Vec u, Vec lambda, PetscReal reaction[])
{
  FEM_Impl             &impl = *fem->impl;
  MPI_Comm              comm = PetscObjectComm((PetscObject)fem);
  std::vector<PetscInt> first(impl.bodies.size() + 1, 0);
  Mat                   B;
  Vec                   c, ld, Btl;
  const FETIRowKind    *kinds;
  const PetscScalar    *ua, *bl;
  PetscInt              ustart, m;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(fem, FEM_CLASSID, 1);
  PetscValidHeaderSpecific(feti, FETI_CLASSID, 2);
  PetscValidHeaderSpecific(u, VEC_CLASSID, 3);
  PetscValidHeaderSpecific(lambda, VEC_CLASSID, 4);
  PetscCheck(impl.setupcalled && (PetscInt)impl.dirichletrows.size() == impl.nsubdomains, comm, PETSC_ERR_ORDER, "FEMComputeReactions(): call FEMSetUp() and FEMCreateFETI() first");
  for (size_t b = 0; b < impl.bodies.size(); b++) first[b + 1] = first[b] + (PetscInt)impl.bodies[b].dirichlet.size();
  std::vector<PetscReal> sum(3 * (size_t)first.back(), 0.0);

  /* B' l over the Dirichlet rows only */
  PetscCall(FETIGetConstraints(feti, &B, &c, &kinds));
  PetscCall(VecDuplicate(lambda, &ld));
  PetscCall(VecCopy(lambda, ld));
  PetscCall(VecGetLocalSize(ld, &m));
  {
    PetscScalar *a;
    PetscCall(VecGetArray(ld, &a));
    for (PetscInt i = 0; i < m; i++)
      if (kinds[i] != FETI_ROW_DIRICHLET) a[i] = 0;
    PetscCall(VecRestoreArray(ld, &a));
  }
  PetscCall(VecDuplicate(u, &Btl));
  PetscCall(MatMultTranspose(B, ld, Btl));
  PetscCall(VecDestroy(&ld));

  PetscCall(VecGetOwnershipRange(u, &ustart, NULL));
  PetscCall(VecGetArrayRead(u, &ua));
  PetscCall(VecGetArrayRead(Btl, &bl));
  {
    PetscInt         ownerbody = -1;
    std::vector<int> owner;
    for (const FEMSubdomain &sd : impl.local) {
      const FEMBody &b = impl.bodies[sd.body];
      if (b.dirichlet.empty()) continue;
      if (ownerbody != sd.body) {
        PetscCall(ConditionOwners(b, owner));
        ownerbody = sd.body;
      }
      const PetscInt base = sd.primaloffset - ustart;
      PetscBool      any  = PETSC_FALSE;
      for (PetscInt n : sd.nodes)
        if (b.dirichletmask[n]) any = PETSC_TRUE;
      if (!any) continue;
      if (impl.dirichletrows[sd.id]) { /* rows of B: minus the multipliers */
        for (size_t l = 0; l < sd.nodes.size(); l++)
          for (PetscInt k = 0; k < 3; k++) {
            const int o = owner[3 * (size_t)sd.nodes[l] + k];
            if (o >= 0) sum[3 * (first[sd.body] + o) + k] -= PetscRealPart(bl[base + 3 * l + k]);
          }
      } else { /* kept in the primal: K_s u_s - f_s at the Dirichlet dofs */
        Mat                K;
        Vec                f, us, Ku;
        const PetscScalar *ka, *fa;
        PetscScalar       *a;
        const PetscInt     n = 3 * (PetscInt)sd.nodes.size();
        PetscCall(FEMAssembleSubdomain(fem, sd, &K, &f));
        PetscCall(VecDuplicate(f, &us));
        PetscCall(VecDuplicate(f, &Ku));
        PetscCall(VecGetArray(us, &a));
        for (PetscInt i = 0; i < n; i++) a[i] = ua[base + i];
        PetscCall(VecRestoreArray(us, &a));
        PetscCall(MatMult(K, us, Ku));
        PetscCall(VecGetArrayRead(Ku, &ka));
        PetscCall(VecGetArrayRead(f, &fa));
        for (size_t l = 0; l < sd.nodes.size(); l++)
          for (PetscInt k = 0; k < 3; k++) {
            const int o = owner[3 * (size_t)sd.nodes[l] + k];
            if (o >= 0) sum[3 * (first[sd.body] + o) + k] += PetscRealPart(ka[3 * l + k] - fa[3 * l + k]);
          }
        PetscCall(VecRestoreArrayRead(Ku, &ka));
        PetscCall(VecRestoreArrayRead(f, &fa));
        PetscCall(VecDestroy(&us));
        PetscCall(VecDestroy(&Ku));
        PetscCall(VecDestroy(&f));
        PetscCall(MatDestroy(&K));
      }
    }
  }
  PetscCall(VecRestoreArrayRead(u, &ua));
  PetscCall(VecRestoreArrayRead(Btl, &bl));
  PetscCall(VecDestroy(&Btl));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, sum.data(), (PetscMPIInt)sum.size(), MPIU_REAL, MPIU_SUM, comm));
  for (size_t i = 0; i < sum.size(); i++) reaction[i] = sum[i];
  PetscFunctionReturn(PETSC_SUCCESS);
}
