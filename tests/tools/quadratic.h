/* The quadratic q(x) = 1/2 x'Ax - b'x as TAO callbacks, shared by the test programs (tests/host's
   unmodified PETSc programs, which include only PETSc, and tests/qp); tests/CMakeLists.txt puts this
   folder on every test's include path. */
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
