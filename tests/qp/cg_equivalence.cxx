/* Without constraints KSP mprgp and mpgp are CG: the same iterates as KSPCG up to rounding.

   Solves a 2D Laplacian (plus a small shift) with KSPCG and with KSP mprgp/mpgp, for a fixed number
   of iterations, with -pc_type none and with Jacobi preconditioning, and compares the residual
   histories (relative difference <= 1e-8 while the residual is above 1e-8 |b|) and the final
   iterates (|x_cg - x| <= 1e-10 |x_cg|). Option -type mprgp|mpgp. */
#include <conefeti.h>
#include <conefeti/compat.h>
#include <petsc/private/kspimpl.h>
#include <vector>

static PetscErrorCode Solve(Mat A, Vec b, KSPType type, PCType pctype, PetscInt its, Vec x, std::vector<PetscReal> &hist)
{
  KSP              ksp;
  PC               pc;
  PetscInt         n;
  const PetscReal *h;

  PetscFunctionBeginUser;
  hist.assign(its + 1, 0.0);
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetType(ksp, type));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, pctype));
  PetscCall(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
  PetscCall(KSPSetTolerances(ksp, 1e-30, 0.0, PETSC_DEFAULT, its));
  PetscCall(KSPSetConvergenceTest(ksp, KSPConvergedSkip, NULL, NULL));
  PetscCall(KSPSetResidualHistory(ksp, hist.data(), its + 1, PETSC_TRUE));
  PetscCall(KSPSolve(ksp, b, x));
  PetscCall(KSPGetResidualHistory(ksp, &h, &n));
  hist.resize(n);
  PetscCall(KSPDestroy(&ksp));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  Mat      A;
  Vec      b, xcg, x, e;
  PetscInt m = 30, its = 40, rstart, rend;
  char     type[32] = "mprgp";

  PetscCall(PetscInitialize(&argc, &argv, NULL, "KSP mprgp/mpgp without constraints equals KSPCG"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-type", type, sizeof(type), NULL));
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, m * m, m * m, 5, NULL, 2, NULL, &A));
  PetscCall(MatGetOwnershipRange(A, &rstart, &rend));
  for (PetscInt r = rstart; r < rend; r++) {
    PetscInt i = r / m, j = r % m;
    if (i > 0) PetscCall(MatSetValue(A, r, r - m, -1.0, INSERT_VALUES));
    if (i < m - 1) PetscCall(MatSetValue(A, r, r + m, -1.0, INSERT_VALUES));
    if (j > 0) PetscCall(MatSetValue(A, r, r - 1, -1.0, INSERT_VALUES));
    if (j < m - 1) PetscCall(MatSetValue(A, r, r + 1, -1.0, INSERT_VALUES));
    PetscCall(MatSetValue(A, r, r, 4.0 + 0.01 * (1 + (r % 7)), INSERT_VALUES)); /* varying diagonal: Jacobi does something */
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreateVecs(A, &x, &b));
  PetscCall(VecDuplicate(x, &xcg));
  PetscCall(VecDuplicate(x, &e));
  for (PetscInt r = rstart; r < rend; r++) PetscCall(VecSetValue(b, r, 1.0 + (r % 5), INSERT_VALUES));
  PetscCall(VecAssemblyBegin(b));
  PetscCall(VecAssemblyEnd(b));

  for (PCType pctype : {PCNONE, PCJACOBI}) {
    std::vector<PetscReal> hcg, h;
    PetscReal              bnorm, xn, en, worst = 0;
    PetscCall(Solve(A, b, KSPCG, pctype, its, xcg, hcg));
    PetscCall(Solve(A, b, type, pctype, its, x, h));
    PetscCheck(h.size() == hcg.size(), PETSC_COMM_WORLD, PETSC_ERR_PLIB, "PC %s: %zu residuals from CG, %zu from %s", pctype, hcg.size(), h.size(), type);
    PetscCall(VecNorm(b, NORM_2, &bnorm));
    for (size_t k = 0; k < h.size(); k++)
      if (hcg[k] > 1e-8 * bnorm) worst = PetscMax(worst, PetscAbsReal(h[k] - hcg[k]) / hcg[k]);
    PetscCall(VecWAXPY(e, -1.0, xcg, x));
    PetscCall(VecNorm(e, NORM_2, &en));
    PetscCall(VecNorm(xcg, NORM_2, &xn));
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "PC %s: %zu iterations, max relative residual difference %.2e, |x - x_cg|/|x_cg| = %.2e\n", pctype, h.size() - 1, (double)worst, (double)(en / xn)));
    PetscCheck(worst <= 1e-8, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "PC %s: residual histories differ by %g", pctype, (double)worst);
    PetscCheck(en <= 1e-10 * xn, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "PC %s: iterates differ by %g", pctype, (double)(en / xn));
  }
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&xcg));
  PetscCall(VecDestroy(&e));
  PetscCall(VecDestroy(&b));
  PetscCall(MatDestroy(&A));
  PetscCall(PetscFinalize());
  return 0;
}
