/* The quadratic q(x) = 1/2 x'Ax - b'x as TAO callbacks, shared by the unmodified host programs
   (plain_tao.c, obstacle_tao.c, equality_tao.c); they include only PETSc, not conefeti. */
#ifndef CONEFETI_TESTS_HOST_QUADRATIC_H
#define CONEFETI_TESTS_HOST_QUADRATIC_H
#include <petsctao.h>

typedef struct {
  Mat A;
  Vec b;
} Quadratic;

/* f = 1/2 x'Ax - b'x, g = Ax - b */
static PetscErrorCode QuadraticObjectiveGradient(Tao tao, Vec x, PetscReal *f, Vec g, void *ctx)
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
static PetscErrorCode QuadraticHessian(Tao tao, Vec x, Mat H, Mat Hpre, void *ctx)
{
  (void)tao;
  (void)x;
  (void)H;
  (void)Hpre;
  (void)ctx;
  return 0;
}
#endif
