/* The defaults of TAO mprgp/mpgp that depend on the Hessian and the set: the preconditioner in face, the
   expansion step and Gamma, chosen from the preconditioning matrix the way PETSc's KSP picks its PC (ICC or
   ILU for an assembled matrix, block Jacobi on several ranks, none for a MATSHELL), and from the kind of
   blocks in the set.

   Why: without a preconditioner MPRGP's CG runs on a discretized PDE need about as many steps as
   unpreconditioned CG, and TAO's gpcg and tron (which precondition their inner KSP with ILU(0)) need
   fewer products. With ICC(0) in face the CG runs are short but their directions hit the bounds more
   often; the projected CG expansion then adds all the constraints a CG step crosses at once, and
   Gamma = 2 keeps the preconditioned CG runs going longer before a proportioning step. Together they
   need the fewest products of all solvers measured on the obstacle and journal-bearing problems
   (docs/qp-benchmark.md, 'Defaults chosen from the Hessian'). None of this can be done for a matrix-free
   Hessian (FETI's dual operator F is a MATSHELL; ICC needs the entries), so such a Hessian keeps the
   published algorithm: no preconditioner, Dostal's expansion, Gamma = 1.

   A set with cone blocks keeps the published algorithm too, whatever the Hessian. A cone block on its
   surface has no free direction in MPGP's split (arc steps exist for disks only), so its whole projected
   gradient is chopped gradient and only the fixed-length projected steps move it: on the random QPs with
   cones (tests/qp, alone or mixed with disks and bounds) at least 98 % of the iterations are proportioning steps,
   with the old defaults and with the assembled ones alike. The three choices only act on the few CG and
   expansion steps; they cannot shorten such a solve, they reshuffle it: over seeds the assembled defaults
   changed the products by -9 % to +26 % (+26 % and +23 % on two of seven mixed QPs at cond 1e4, ICC and
   Gamma = 2 each costing about as much alone), and every proportioning step still pays a PC application
   for the restart direction (an ICC solve, about a product). Disks (arc steps) and bounds gain from them
   on every seed measured (docs/qp-benchmark.md, 'Random ill-conditioned QPs'). Each option the user gives
   wins over its default. */
#include <conefeti/private/mpgpcore.h>
#include <petscksp.h>

PetscErrorCode MPGPHessianDefaultsGet(Mat P, SeparableSet set, MPGPHessianDefaults *d)
{
  PetscMPIInt size;
  PetscBool   icc = PETSC_FALSE, blocks = PETSC_FALSE;
  PetscInt    ncones = 0;
  MatType     type;

  PetscFunctionBegin;
  *d = MPGPHessianDefaults{};
  if (set) PetscCall(SeparableSetGetLocalBlockCounts(set, NULL, &ncones));
  d->cones = ncones > 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &d->cones, 1, MPIU_BOOL, MPI_LOR, PetscObjectComm((PetscObject)P)));
  PetscCall(MatGetType(P, &type));
  PetscCall(PetscStrncpy(d->mat_type, type ? type : "unknown", sizeof(d->mat_type)));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)P), &size));
  if (size == 1) PetscCall(MatGetFactorAvailable(P, MATSOLVERPETSC, MAT_FACTOR_ICC, &icc));
  else {
    /* block Jacobi factors each rank's diagonal block: it must have ICC (an MPIDENSE's dense block has not) */
    PetscCall(MatHasOperation(P, MATOP_GET_DIAGONAL_BLOCK, &blocks));
    if (blocks) {
      Mat Pd;
      PetscCall(MatGetDiagonalBlock(P, &Pd));
      PetscCall(MatGetFactorAvailable(Pd, MATSOLVERPETSC, MAT_FACTOR_ICC, &icc));
      /* every rank must choose the same */
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &icc, 1, MPIU_BOOL, MPI_LAND, PetscObjectComm((PetscObject)P)));
    }
  }
  d->assembled = icc;
  if (!icc || d->cones) PetscFunctionReturn(PETSC_SUCCESS);
  d->pc     = size == 1 ? PCICC : PCBJACOBI;
  d->projcg = PETSC_TRUE;
  d->gamma  = 2.0;
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MPGPHessianDefaultsReason(const MPGPHessianDefaults *d, char *text, size_t len)
{
  PetscFunctionBegin;
  if (d->assembled && d->cones) PetscCall(PetscSNPrintf(text, len, "because the set has cone blocks, moved by projected gradient steps only, although the Hessian is assembled (%s)", d->mat_type));
  else if (d->assembled) PetscCall(PetscSNPrintf(text, len, "because the Hessian is assembled (%s)", d->mat_type));
  else if (d->mat_type[0]) PetscCall(PetscSNPrintf(text, len, "because the Hessian is not an assembled sparse matrix (%s)", d->mat_type));
  else PetscCall(PetscSNPrintf(text, len, "from the Hessian at the first solve"));
  PetscFunctionReturn(PETSC_SUCCESS);
}
