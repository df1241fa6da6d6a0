/* Product-based tests of an operator after a failed solve (include/conefeti/private/operatortest.h). */
#include <conefeti/private/operatortest.h>

/* random vectors of a fixed seed: the diagnosis of a run is the same when it is repeated */
static PetscErrorCode RandomVecs(Mat A, PetscInt n, Vec v[])
{
  PetscRandom rnd;

  PetscFunctionBegin;
  PetscCall(PetscRandomCreate(PetscObjectComm((PetscObject)A), &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -1.0, 1.0));
  PetscCall(PetscRandomSetSeed(rnd, 0x5eed));
  PetscCall(PetscRandomSeed(rnd));
  for (PetscInt i = 0; i < n; i++) {
    PetscCall(MatCreateVecs(A, &v[i], NULL));
    PetscCall(VecSetRandom(v[i], rnd));
  }
  PetscCall(PetscRandomDestroy(&rnd));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MatTestSymmetry_Private(Mat A, PetscReal normA, MatSymmetryTest *t)
{
  Vec       v[2], Ax, Ay;
  PetscReal xAy, yAx, nx, ny, nAx, nAy;

  PetscFunctionBegin;
  PetscCall(RandomVecs(A, 2, v));
  PetscCall(VecDuplicate(v[0], &Ax));
  PetscCall(VecDuplicate(v[0], &Ay));
  PetscCall(MatMult(A, v[0], Ax));
  PetscCall(MatMult(A, v[1], Ay));
  PetscCall(VecDot(Ay, v[0], &xAy));
  PetscCall(VecDot(Ax, v[1], &yAx));
  PetscCall(VecNorm(v[0], NORM_2, &nx));
  PetscCall(VecNorm(v[1], NORM_2, &ny));
  PetscCall(VecNorm(Ax, NORM_2, &nAx));
  PetscCall(VecNorm(Ay, NORM_2, &nAy));
  /* the estimate of ||A|| may be the culprit of the failure itself (too small): the products bound it from below */
  t->asymmetry = xAy - yAx;
  t->scale     = PetscMax(PetscMax(normA, nx > 0 ? nAx / nx : 0), ny > 0 ? nAy / ny : 0) * nx * ny;
  /* a NaN fails neither test: the solver reports it as such */
  t->symmetric = PetscAbsReal(t->asymmetry) > 1e-8 * t->scale ? PETSC_FALSE : PETSC_TRUE;
  PetscCall(VecDestroy(&v[0]));
  PetscCall(VecDestroy(&v[1]));
  PetscCall(VecDestroy(&Ax));
  PetscCall(VecDestroy(&Ay));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MatTestProjector_Private(Mat Q, MatProjectorTest *t)
{
  Vec x, Qx, QQx;

  PetscFunctionBegin;
  PetscCall(RandomVecs(Q, 1, &x));
  PetscCall(VecDuplicate(x, &Qx));
  PetscCall(VecDuplicate(x, &QQx));
  PetscCall(MatMult(Q, x, Qx));
  PetscCall(MatMult(Q, Qx, QQx));
  PetscCall(VecAXPY(QQx, -1.0, Qx));
  PetscCall(VecNorm(QQx, NORM_2, &t->defect));
  PetscCall(VecNorm(Qx, NORM_2, &t->scale));
  t->projector = t->defect > 1e-8 * t->scale ? PETSC_FALSE : PETSC_TRUE;
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&Qx));
  PetscCall(VecDestroy(&QQx));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode MatDiagnoseOperators_Private(Mat A, PetscReal normA, const char Aname[], char Aletter, Mat Q, const char Qname[], char why[], size_t len)
{
  MatSymmetryTest sym;

  PetscFunctionBegin;
  why[0] = 0;
  PetscCall(MatTestSymmetry_Private(A, normA, &sym));
  if (!sym.symmetric) {
    PetscCall(
        PetscSNPrintf(why, len, "%s is not symmetric (x'%cy - y'%cx = %g for random x, y, against ||%c|| |x| |y| = %g)", Aname, Aletter, Aletter, (double)sym.asymmetry, Aletter, (double)sym.scale));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  if (!Q) PetscFunctionReturn(PETSC_SUCCESS);
  MatProjectorTest proj;
  PetscCall(MatTestProjector_Private(Q, &proj));
  if (!proj.projector) {
    PetscCall(PetscSNPrintf(why, len, "%s is not a projector (|Q(Qx) - Qx| = %g for a random x, |Qx| = %g)", Qname, (double)proj.defect, (double)proj.scale));
    PetscFunctionReturn(PETSC_SUCCESS);
  }
  PetscCall(MatTestSymmetry_Private(Q, 1.0, &sym)); /* an orthogonal projector is symmetric, of norm 1 */
  if (!sym.symmetric)
    PetscCall(PetscSNPrintf(why, len, "%s is not symmetric, as an orthogonal projector is (x'Qy - y'Qx = %g for random x, y, against |x| |y| = %g)", Qname, (double)sym.asymmetry, (double)sym.scale));
  PetscFunctionReturn(PETSC_SUCCESS);
}
