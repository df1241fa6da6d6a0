/* Algebraic properties of the FETI operators built from the test scene (tests/feti/scene.h):
     K R = 0                       (kernel, per subdomain, through the FETI's own K product)
     K K+ K = K                    (generalized inverse, random vectors)
     F symmetric positive semidefinite on random vectors; P^2 = P, P symmetric, G P = 0
     G' = B R                      (stored G' against B times R)
     G x = R'(B' x), G' c = B R c  (the shells against PETSc's products; on one rank G to the last bit)
     x'K_p y = (Ex)'K (Ey)         (subdomain matrices consistent with the assembled global matrix,
                                    E copies global nodal values to the subdomain copies)
     B B' = I                      (Helmert gluing and identity Dirichlet rows are orthonormal)
     F x = B (K+ (B' x))           (F's own product, e.g. with -feti_kplus_explicit, against the factor's K+)
   Each relative error must be below 1e-10 (roundoff of well-scaled products). */
#include "scene.h"

static PetscErrorCode Report(const char *what, PetscReal err, PetscReal tol, PetscBool *ok)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%-40s %.2e %s\n", what, (double)err, err <= tol ? "ok" : "FAILED"));
  if (!(err <= tol)) *ok = PETSC_FALSE;
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  FEM         fem;
  FETI        feti;
  Mat         F, G, P, Q, R, Gt, B, Kplus, BBt, Kglob;
  Vec         x, y, Fx, Fy, kx, w, kw, p1, p2, c1, c2, d1, d2, fglob, xg, yg, kxg;
  PetscRandom rnd;
  PetscReal   a, b, tol = 1e-10, ftol;
  PetscScalar s1, s2;
  PetscInt    ncoarse;
  PetscBool   ok = PETSC_TRUE;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "FETI operator properties"));
  PetscCall(ConeFETIInitializePackage());
  /* -feti_kplus_precision single: F products solve with the float factors as they are, K+ itself is refined to
     double, so F and B K+ B' differ by the factors' rounding to float (about cond(K_s) 6e-8): -f_kplus_tol */
  ftol = tol;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-f_kplus_tol", &ftol, NULL));
  PetscCall(CreateTestScene(PETSC_COMM_WORLD, &fem));
  PetscBool kernels = PETSC_FALSE;
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-test_kernels_without_coordinates", &kernels, NULL));
  if (kernels) PetscCall(PetscInfoDeactivateClass(FETI_CLASSID)); /* -info: only of the problem checked */
  PetscCall(FEMCreateFETI(fem, &feti));
  PetscCall(FETISetFromOptions(feti));
  PetscCall(FETISetUp(feti));
  {
    /* -test_kernels_without_coordinates: the same problem again, each subdomain given the kernel basis the first
       setup used (FETISetSubdomainKernel()) and no coordinates, as a user's own FEM code may do; G and G' then
       keep R's stored rows (fetirigidrows.cxx) */
    if (kernels) {
      FETI     again;
      PetscInt nlocal;
      PetscCall(PetscInfoActivateClass(FETI_CLASSID));
      PetscCall(FEMCreateFETI(fem, &again));
      PetscCall(FETIGetNumSubdomains(feti, NULL, &nlocal, NULL));
      for (PetscInt s = 0; s < nlocal; s++) {
        Mat Rs;
        PetscCall(FETIGetSubdomainKernel(feti, s, &Rs));
        PetscCall(FETISetSubdomainKernel(again, s, Rs));
        PetscCall(FETISetSubdomainCoordinates(again, s, NULL));
        PetscCall(MatDestroy(&Rs));
      }
      PetscCall(FETIDestroy(&feti));
      feti = again;
      PetscCall(FETISetFromOptions(feti));
      PetscCall(FETISetUp(feti));
    }
  }
  PetscCall(FETIGetOperators(feti, &F, &G, &P, &Q));
  PetscCall(FETIGetKernel(feti, &R));
  PetscCall(FETIGetGt(feti, &Gt));
  PetscCall(FETIGetGeneralizedInverse(feti, &Kplus));
  PetscCall(FETIGetConstraints(feti, &B, NULL, NULL));
  PetscCall(FETIGetSizes(feti, NULL, NULL, &ncoarse));
  PetscCall(FETICreateVecs(feti, &p1, &d1, &c1));
  PetscCall(VecDuplicate(p1, &p2));
  PetscCall(VecDuplicate(p1, &kx));
  PetscCall(VecDuplicate(p1, &w));
  PetscCall(VecDuplicate(p1, &kw));
  PetscCall(VecDuplicate(d1, &d2));
  PetscCall(VecDuplicate(d1, &x));
  PetscCall(VecDuplicate(d1, &y));
  PetscCall(VecDuplicate(d1, &Fx));
  PetscCall(VecDuplicate(d1, &Fy));
  PetscCall(VecDuplicate(c1, &c2));
  PetscCall(PetscRandomCreate(PETSC_COMM_WORLD, &rnd));
  PetscCall(PetscRandomSetFromOptions(rnd));

  /* K R = 0: ||K R alpha|| / (||K|| ||R alpha||), ||K|| estimated by ||K x|| / ||x|| for random x */
  PetscCall(VecSetRandom(p1, rnd));
  PetscCall(FETIApplyK(feti, p1, kx));
  PetscCall(VecNorm(kx, NORM_2, &a));
  PetscCall(VecNorm(p1, NORM_2, &b));
  const PetscReal knorm = a / b;
  if (ncoarse) {
    PetscCall(VecSetRandom(c1, rnd));
    PetscCall(MatMult(R, c1, p2));
    PetscCall(FETIApplyK(feti, p2, kx));
    PetscCall(VecNorm(kx, NORM_2, &a));
    PetscCall(VecNorm(p2, NORM_2, &b));
    PetscCall(Report("K R = 0", a / (knorm * b), tol, &ok));
  }
  /* K K+ K = K */
  PetscCall(FETIApplyK(feti, p1, kx));
  PetscCall(MatMult(Kplus, kx, w));
  PetscCall(FETIApplyK(feti, w, kw));
  PetscCall(VecAXPY(kw, -1.0, kx));
  PetscCall(VecNorm(kw, NORM_2, &a));
  PetscCall(VecNorm(kx, NORM_2, &b));
  PetscCall(Report("K K+ K = K", a / b, 1e-8, &ok));
  /* F symmetric and positive semidefinite */
  PetscCall(VecSetRandom(x, rnd));
  PetscCall(VecSetRandom(y, rnd));
  PetscCall(MatMult(F, x, Fx));
  PetscCall(MatMult(F, y, Fy));
  PetscCall(VecDot(Fx, y, &s1));
  PetscCall(VecDot(Fy, x, &s2));
  PetscCall(VecNorm(Fx, NORM_2, &a));
  PetscCall(VecNorm(y, NORM_2, &b));
  PetscCall(Report("F symmetric: |y'Fx - x'Fy| / ||Fx|| ||y||", PetscAbsScalar(s1 - s2) / (a * b), tol, &ok));
  PetscCall(VecDot(Fx, x, &s1));
  PetscCall(Report("F positive semidefinite: -min(x'Fx, 0)", PetscMax(0.0, -PetscRealPart(s1)), 0, &ok));
  /* F = B K+ B' with the factored K+ (the F product may use explicit blocks of K+ instead) */
  PetscCall(MatMultTranspose(B, x, p1));
  PetscCall(MatMult(Kplus, p1, p2));
  PetscCall(MatMult(B, p2, d1));
  PetscCall(VecAXPY(d1, -1.0, Fx));
  PetscCall(VecNorm(d1, NORM_2, &a));
  PetscCall(VecNorm(Fx, NORM_2, &b));
  PetscCall(Report("F x = B K+ B' x", a / b, ftol, &ok));
  /* P projector, symmetric, onto Ker G */
  PetscCall(MatMult(P, x, d1));
  PetscCall(MatMult(P, d1, d2));
  PetscCall(VecAXPY(d2, -1.0, d1));
  PetscCall(VecNorm(d2, NORM_2, &a));
  PetscCall(VecNorm(x, NORM_2, &b));
  PetscCall(Report("P^2 = P", a / b, tol, &ok));
  PetscCall(MatMult(P, y, d2));
  PetscCall(VecDot(d1, y, &s1));
  PetscCall(VecDot(d2, x, &s2));
  PetscCall(Report("P symmetric", PetscAbsScalar(s1 - s2) / (b * b), tol, &ok));
  if (ncoarse) {
    PetscCall(MatMult(G, d1, c1));
    PetscCall(VecNorm(c1, NORM_2, &a));
    PetscCall(MatMult(G, x, c2));
    PetscCall(VecNorm(c2, NORM_2, &b));
    PetscCall(Report("G P = 0", a / b, tol, &ok));
    /* G' = B R */
    PetscCall(VecSetRandom(c1, rnd));
    PetscCall(MatMult(Gt, c1, d1));
    PetscCall(MatMult(R, c1, p1));
    PetscCall(MatMult(B, p1, d2));
    PetscCall(VecAXPY(d2, -1.0, d1));
    PetscCall(VecNorm(d2, NORM_2, &a));
    PetscCall(VecNorm(d1, NORM_2, &b));
    PetscCall(Report("G' = B R", a / b, tol, &ok));
    /* the shell G (the rows of R where B' x lives, fetioperators.cxx) against PETSc's R'(B' x): with R's stored rows
       (-feti_rigid_rows 0), on one rank the same sums in the same order, so the same bits (FETI's B' sums each
       column of B in row order, as PETSc's MatMultTranspose() does); on more ranks PETSc adds the other ranks'
       parts in its own order. Through the rigid-body modes (the default, fetirigidrows.cxx) it agrees to rounding */
    PetscMPIInt size;
    PetscBool   rigid = PETSC_TRUE;
    PetscCall(PetscOptionsGetBool(NULL, NULL, "-feti_rigid_rows", &rigid, NULL));
    PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
    PetscCall(VecSetRandom(d1, rnd));
    PetscCall(MatMult(G, d1, c1));
    PetscCall(MatMultTranspose(B, d1, p1));
    PetscCall(MatMultTranspose(R, p1, c2));
    if (size == 1 && !rigid) {
      const PetscScalar *u, *v;
      PetscInt           n, differ = 0;
      PetscCall(VecGetLocalSize(c1, &n));
      PetscCall(VecGetArrayRead(c1, &u));
      PetscCall(VecGetArrayRead(c2, &v));
      for (PetscInt i = 0; i < n; i++) differ += u[i] != v[i];
      PetscCall(VecRestoreArrayRead(c2, &v));
      PetscCall(VecRestoreArrayRead(c1, &u));
      PetscCall(Report("G x = R'(B' x), entries not bitwise equal", (PetscReal)differ, 0, &ok));
    }
    PetscCall(VecAXPY(c2, -1.0, c1));
    PetscCall(VecNorm(c2, NORM_2, &a));
    PetscCall(VecNorm(c1, NORM_2, &b));
    PetscCall(Report("G x = R'(B' x)", a / b, tol, &ok));
    /* G' c through the same rows against B (R c) */
    PetscCall(VecSetRandom(c1, rnd));
    PetscCall(MatMultTranspose(G, c1, d1));
    PetscCall(MatMult(R, c1, p1));
    PetscCall(MatMult(B, p1, d2));
    PetscCall(VecAXPY(d2, -1.0, d1));
    PetscCall(VecNorm(d2, NORM_2, &a));
    PetscCall(VecNorm(d1, NORM_2, &b));
    PetscCall(Report("G' c = B (R c)", a / b, tol, &ok));
  }
  /* subdomain matrices against the assembled global matrix: y'K_g x = (E y)'K_p (E x) for global x, y vanishing
     at the Dirichlet dofs (E copies nodal values to every copy of the node) */
  PetscCall(FEMAssembleGlobal(fem, &Kglob, &fglob));
  PetscCall(VecDuplicate(fglob, &xg));
  PetscCall(VecDuplicate(fglob, &yg));
  PetscCall(VecDuplicate(fglob, &kxg));
  {
    IS              dirichlet;
    const PetscInt *idx;
    PetscInt        nd;
    PetscCall(VecSetRandom(xg, rnd));
    PetscCall(VecSetRandom(yg, rnd));
    PetscCall(FEMGetGlobalDirichletDofs(fem, &dirichlet));
    PetscCall(ISGetLocalSize(dirichlet, &nd));
    PetscCall(ISGetIndices(dirichlet, &idx));
    for (PetscInt i = 0; i < nd; i++) {
      PetscCall(VecSetValue(xg, idx[i], 0.0, INSERT_VALUES));
      PetscCall(VecSetValue(yg, idx[i], 0.0, INSERT_VALUES));
    }
    PetscCall(ISRestoreIndices(dirichlet, &idx));
    PetscCall(ISDestroy(&dirichlet));
    PetscCall(VecAssemblyBegin(xg));
    PetscCall(VecAssemblyEnd(xg));
    PetscCall(VecAssemblyBegin(yg));
    PetscCall(VecAssemblyEnd(yg));
  }
  PetscCall(FEMGlobalToPrimal(fem, xg, p1));
  PetscCall(FEMGlobalToPrimal(fem, yg, p2));
  PetscCall(FETIApplyK(feti, p1, kx));
  PetscCall(VecDot(kx, p2, &s1));
  PetscCall(MatMult(Kglob, xg, kxg));
  PetscCall(VecDot(kxg, yg, &s2));
  PetscCall(VecNorm(kxg, NORM_2, &a));
  PetscCall(VecNorm(yg, NORM_2, &b));
  PetscCall(Report("y'K_g x = (E y)'K_p (E x)", PetscAbsScalar(s1 - s2) / (a * b), tol, &ok));
  /* a global field copied to the subdomains satisfies the gluing rows */
  PetscCall(MatMult(B, p1, d1));
  {
    const FETIRowKind *kinds;
    PetscInt           m;
    PetscScalar       *v;
    PetscCall(FETIGetConstraints(feti, NULL, NULL, &kinds));
    PetscCall(VecGetLocalSize(d1, &m));
    PetscCall(VecGetArray(d1, &v));
    for (PetscInt i = 0; i < m; i++)
      if (kinds[i] != FETI_ROW_GLUING) v[i] = 0;
    PetscCall(VecRestoreArray(d1, &v));
  }
  PetscCall(VecNorm(d1, NORM_2, &a));
  PetscCall(VecNorm(p1, NORM_2, &b));
  PetscCall(Report("gluing rows vanish on continuous fields", a / b, tol, &ok));
  /* the kernel basis of a subdomain has orthonormal columns: R_s'R_s = I */
  {
    Mat       Rs, RtR;
    PetscInt  k;
    PetscReal e;
    PetscCall(FETIGetSubdomainKernel(feti, 0, &Rs));
    PetscCall(MatGetSize(Rs, NULL, &k));
    if (k) {
      PetscCall(MatTransposeMatMult(Rs, Rs, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &RtR));
      PetscCall(MatShift(RtR, -1.0));
      PetscCall(MatNorm(RtR, NORM_FROBENIUS, &e));
      PetscCall(Report("R_s' R_s = I (first local subdomain)", e, tol, &ok));
      PetscCall(MatDestroy(&RtR));
    }
    PetscCall(MatDestroy(&Rs));
  }
  /* BB' = I */
  PetscCall(MatMatTransposeMult(B, B, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &BBt));
  PetscCall(MatShift(BBt, -1.0));
  PetscCall(MatNorm(BBt, NORM_FROBENIUS, &a));
  PetscCall(Report("B B' = I", a, tol, &ok));
  PetscCall(MatDestroy(&BBt));
  PetscCheck(ok, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "A FETI operator property failed");
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&y));
  PetscCall(VecDestroy(&Fx));
  PetscCall(VecDestroy(&Fy));
  PetscCall(VecDestroy(&kx));
  PetscCall(VecDestroy(&w));
  PetscCall(VecDestroy(&kw));
  PetscCall(VecDestroy(&p1));
  PetscCall(VecDestroy(&p2));
  PetscCall(VecDestroy(&c1));
  PetscCall(VecDestroy(&c2));
  PetscCall(VecDestroy(&d1));
  PetscCall(VecDestroy(&d2));
  PetscCall(VecDestroy(&fglob));
  PetscCall(VecDestroy(&xg));
  PetscCall(VecDestroy(&yg));
  PetscCall(VecDestroy(&kxg));
  PetscCall(MatDestroy(&Kglob));
  PetscCall(FETIDestroy(&feti));
  PetscCall(FEMDestroy(&fem));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "all operator properties hold\n"));
  PetscCall(PetscFinalize());
  return 0;
}
