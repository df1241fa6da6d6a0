/* The FETI solution of the test scene (tests/feti/scene.h) equals the undecomposed direct solution
   (MUMPS Cholesky of the assembled global system) to 1e-8 relative, and the glued copies agree.
   Prints the projected-CG iteration count, which the tests compare across rank counts. */
#include "scene.h"

int main(int argc, char **argv)
{
  FEM                fem;
  FETI               feti;
  KSP                ksp, direct;
  PC                 pc;
  Mat                K, B;
  Vec                f, udirect, ufeti, lambda, u, Bu;
  PetscInt           its;
  PetscReal          err, norm, gluing, unorm;
  KSPConvergedReason reason;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "FETI solution versus undecomposed direct solution"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(CreateTestScene(PETSC_COMM_WORLD, &fem));

  PetscCall(FEMCreateFETI(fem, &feti));
  PetscCall(FETISetFromOptions(feti));
  PetscCall(FETISetUp(feti));
  PetscCall(FETICreateVecs(feti, &u, &lambda, NULL));
  PetscCall(FETISolveLinear(feti, lambda, u));
  PetscCall(FETIGetKSP(feti, &ksp));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  PetscCheck(reason > 0, PETSC_COMM_WORLD, PETSC_ERR_CONV_FAILED, "FETI CG did not converge: %s", KSPConvergedReasons[reason]);

  PetscCall(FEMAssembleGlobal(fem, &K, &f));
  PetscCall(VecDuplicate(f, &udirect));
  PetscCall(VecDuplicate(f, &ufeti));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &direct));
  PetscCall(KSPSetOperators(direct, K, K));
  PetscCall(KSPSetType(direct, KSPPREONLY));
  PetscCall(KSPGetPC(direct, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSolve(direct, f, udirect));

  PetscCall(FEMPrimalToGlobal(fem, u, ufeti));
  PetscCall(VecAXPY(ufeti, -1.0, udirect));
  PetscCall(VecNorm(ufeti, NORM_2, &err));
  PetscCall(VecNorm(udirect, NORM_2, &norm));
  /* gluing and Total-FETI Dirichlet rows hold in the primal: ||B u|| relative to ||u|| */
  PetscCall(FETIGetConstraints(feti, &B, NULL, NULL));
  PetscCall(MatCreateVecs(B, NULL, &Bu));
  PetscCall(MatMult(B, u, Bu));
  PetscCall(VecNorm(Bu, NORM_2, &gluing));
  PetscCall(VecNorm(u, NORM_2, &unorm));
  {
    PetscInt nprimal, ndual, ncoarse;
    PetscCall(FETIGetSizes(feti, &nprimal, &ndual, &ncoarse));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "primal %d, dual %d, coarse dimension %d\n", (int)nprimal, (int)ndual, (int)ncoarse));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "FETI iterations %d\n", (int)its));
  {
    char fl[17], fu[17];
    PetscCall(ConeFETIVecFingerprint(lambda, fl));
    PetscCall(ConeFETIVecFingerprint(u, fu));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "RESULT iterations=%d lambda=%s u=%s\n", (int)its, fl, fu));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "relative difference to the direct solution %.2e, ||B u||/||u|| %.2e\n", (double)(err / norm), (double)(gluing / unorm)));
  /* the CG tolerance (-feti_ksp_rtol 1e-12 in the tests) leaves about 1e-10 */
  PetscCheck(err <= 1e-8 * norm, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "FETI and direct solutions differ by %g relative", (double)(err / norm));
  PetscCheck(gluing <= 1e-8 * unorm, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Constraints violated in the primal: ||B u||/||u|| = %g", (double)(gluing / unorm));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "FETI equals direct solve\n"));

  PetscCall(VecDestroy(&Bu));
  PetscCall(KSPDestroy(&direct));
  PetscCall(VecDestroy(&udirect));
  PetscCall(VecDestroy(&ufeti));
  PetscCall(VecDestroy(&f));
  PetscCall(MatDestroy(&K));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&lambda));
  PetscCall(FETIDestroy(&feti));
  PetscCall(FEMDestroy(&fem));
  PetscCall(PetscFinalize());
  return 0;
}
