/* The quadratic q(x) = 1/2 x'Ax - b'x as TAO callbacks, and the tridiagonal A most tests take, shared by the test
   programs (tests/host's unmodified PETSc programs, which include only PETSc, and tests/qp); tests/CMakeLists.txt
   puts this folder on every test's include path. */
#ifndef CONEFETI_TESTS_TOOLS_QUADRATIC_H
#define CONEFETI_TESTS_TOOLS_QUADRATIC_H
#include <petsctao.h>

typedef struct {
  Mat A;
  Vec b;
} Quadratic;

/* f = 1/2 x'Ax - b'x, g = Ax - b */
static inline PetscErrorCode QuadraticObjectiveGradient(Tao tao, Vec x, PetscReal *f, Vec g, void *ctx)
{
  Quadratic  *q = (Quadratic *)ctx;
  PetscScalar xg, xb;

  PetscFunctionBeginUser;
  (void)tao;
  PetscCall(MatMult(q->A, x, g));
  PetscCall(VecDot(x, g, &xg));
  PetscCall(VecDot(x, q->b, &xb));
  *f = 0.5 * PetscRealPart(xg) - PetscRealPart(xb);
  PetscCall(VecAXPY(g, -1.0, q->b));
  PetscFunctionReturn(0);
}

/* The n x n tridiagonal AIJ matrix (-1, diag, -1), rows split by PETSc: the 1D Laplacian for diag = 2 */
static inline PetscErrorCode CreateTridiagonal(MPI_Comm comm, PetscInt n, PetscScalar diag, Mat *A)
{
  PetscInt rs, re;

  PetscFunctionBeginUser;
  PetscCall(MatCreateAIJ(comm, PETSC_DECIDE, PETSC_DECIDE, n, n, 3, NULL, 1, NULL, A));
  PetscCall(MatGetOwnershipRange(*A, &rs, &re));
  for (PetscInt i = rs; i < re; i++) {
    if (i > 0) PetscCall(MatSetValue(*A, i, i - 1, -1.0, INSERT_VALUES));
    if (i < n - 1) PetscCall(MatSetValue(*A, i, i + 1, -1.0, INSERT_VALUES));
    PetscCall(MatSetValue(*A, i, i, diag, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* the Hessian is the constant A, set once with TaoSetHessian() */
static inline PetscErrorCode QuadraticHessian(Tao tao, Vec x, Mat H, Mat Hpre, void *ctx)
{
  (void)tao;
  (void)x;
  (void)H;
  (void)Hpre;
  (void)ctx;
  return 0;
}
#endif
