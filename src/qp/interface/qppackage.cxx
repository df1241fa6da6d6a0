/* QP layer package: registers the QP solver types, the SeparableSet class and log events. */
#include <conefeti/qp.h>
#include <conefeti/private/package.h>
#include <conefeti/private/mpgpcore.h>
#include <conefeti/private/reproduciblesum.h>

PETSC_INTERN PetscErrorCode TaoCreate_MPRGP(Tao);
PETSC_INTERN PetscErrorCode TaoCreate_MPGP(Tao);
PETSC_INTERN PetscErrorCode TaoCreate_SMALXE(Tao);
PETSC_INTERN PetscErrorCode KSPCreate_MPRGP(KSP);
PETSC_INTERN PetscErrorCode KSPCreate_MPGP(KSP);

PetscErrorCode ConeFETIQPInitializePackage(void)
{
  PetscClassId qp_classid;

  PetscFunctionBegin;
  PetscCall(PetscClassIdRegister("SeparableSet", &SEPARABLESET_CLASSID));
  PetscCall(PetscClassIdRegister("ConeFETI QP", &qp_classid));
  PetscCall(PetscLogEventRegister("QPSolve", qp_classid, &QP_Solve));
  PetscCall(PetscLogEventRegister("QPHessianMult", qp_classid, &QP_HessianMult));
  PetscCall(PetscLogEventRegister("QPNormEstimate", qp_classid, &QP_NormEstimate));
  PetscCall(PetscLogEventRegister("QPPrecondition", qp_classid, &QP_Precondition));
  PetscCall(PetscLogEventRegister("QPFeasibility", qp_classid, &QP_Feasibility));
  PetscCall(PetscLogEventRegister("QPMultUpdate", qp_classid, &QP_MultiplierUpdate));
  PetscCall(PetscLogEventRegister("QPVecReproduc", qp_classid, &QP_VecReproducible));
  PetscCall(PetscLogEventRegister("QPProject", SEPARABLESET_CLASSID, &QP_Project));
  PetscCall(PetscLogEventRegister("QPSplitGradient", SEPARABLESET_CLASSID, &QP_Split));
  PetscCall(ReproducibleSumSetFromOptions());
  PetscCall(TaoRegister(TAOMPRGP, TaoCreate_MPRGP));
  PetscCall(TaoRegister(TAOMPGP, TaoCreate_MPGP));
  PetscCall(TaoRegister(TAOSMALXE, TaoCreate_SMALXE));
  PetscCall(KSPRegister(KSPMPRGP, KSPCreate_MPRGP));
  PetscCall(KSPRegister(KSPMPGP, KSPCreate_MPGP));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ConeFETIQPFinalizePackage(void)
{
  PetscFunctionBegin;
  PetscCall(ReproducibleSumFinalize());
  PetscFunctionReturn(PETSC_SUCCESS);
}
