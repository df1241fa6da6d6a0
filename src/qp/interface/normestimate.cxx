/* Estimate of ||A|| for the fixed step length alpha = a/||A|| of MPRGP/MPGP.

   An underestimate breaks the monotonicity the convergence proofs rely on, an overestimate only
   shortens the steps a little, so the estimate is deliberately pushed up:
   - SLEPc: Krylov-Schur (Lanczos) for the largest eigenvalue theta with a loose tolerance (1e-2
     relative residual, 8 basis vectors: a small fraction of the products of a solve); the
     result is (theta + |A v - theta v|)(1 + margin). For symmetric A an eigenvalue lies within the
     residual norm of theta, and the Lanczos theta approaches lambda_max from below.
   - power iteration (no SLEPc): |A v| for the last normalized iterate v, times (1 + margin).
   The value is cached on the Mat (composed object) together with the Mat's state, so repeated
   solves with one operator pay once; a new value is computed when the Mat changes state. */
#include <string>
#include <conefeti/private/mpgpcore.h>
#include <conefeti/sys.h>
#include <slepceps.h>
#include <cstdint>

const char *const QPNormMethods[] = {"slepc", "power", "user", "QPNormMethod", "QP_NORM_", NULL};

namespace {

struct CountingContext {
  Mat       A;
  PetscInt *count;
};

PetscErrorCode CountingMult(Mat M, Vec x, Vec y)
{
  CountingContext *ctx;

  PetscFunctionBegin;
  PetscCall(MatShellGetContext(M, &ctx));
  PetscCall(MatMult(ctx->A, x, y));
  (*ctx->count)++;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A shell that forwards products to A and counts them (SLEPc's products are reported apart). */
PetscErrorCode CreateCountingShell(Mat A, CountingContext *ctx, Mat *M)
{
  PetscInt m, n, Mg, Ng;

  PetscFunctionBegin;
  PetscCall(MatGetLocalSize(A, &m, &n));
  PetscCall(MatGetSize(A, &Mg, &Ng));
  PetscCall(MatCreateShell(PetscObjectComm((PetscObject)A), m, n, Mg, Ng, ctx, M));
  PetscCall(MatShellSetOperation(*M, MATOP_MULT, (void (*)(void))CountingMult));
  PetscCall(MatShellSetOperation(*M, MATOP_MULT_TRANSPOSE, (void (*)(void))CountingMult));
  PetscCall(MatSetOption(*M, MAT_SYMMETRIC, PETSC_TRUE));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* A start vector that depends only on the global index (a hash), so that the estimate, and with it
   every iteration count, is the same on any number of ranks. */
PetscErrorCode SetStartVector(Vec v)
{
  PetscInt     rstart, n;
  PetscScalar *a;

  PetscFunctionBegin;
  PetscCall(VecGetOwnershipRange(v, &rstart, NULL));
  PetscCall(VecGetLocalSize(v, &n));
  PetscCall(VecGetArrayWrite(v, &a));
  for (PetscInt i = 0; i < n; i++) {
    uint64_t z = (uint64_t)(rstart + i) * 0x9e3779b97f4a7c15ULL + 0x2545f4914f6cdd1dULL;
    z          = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z          = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    a[i] = 2.0 * ((double)(z >> 11) / 9007199254740992.0) - 1.0;
  }
  PetscCall(VecRestoreArrayWrite(v, &a));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode EstimateSLEPc(Mat M, const char prefix[], PetscReal *theta_upper, PetscBool *ok)
{
  EPS         eps;
  PetscInt    nconv;
  PetscScalar kr, ki;
  Vec         v, w;
  PetscReal   res;

  PetscFunctionBegin;
  PetscCall(ConeFETISlepcInitializeIfNeeded());
  PetscCall(EPSCreate(PetscObjectComm((PetscObject)M), &eps));
  PetscCall(EPSSetOperators(eps, M, NULL));
  PetscCall(MatCreateVecs(M, &v, NULL));
  PetscCall(SetStartVector(v));
  PetscCall(EPSSetInitialSpace(eps, 1, &v));
  PetscCall(VecDestroy(&v));
  PetscCall(EPSSetProblemType(eps, EPS_HEP));
  PetscCall(EPSSetWhichEigenpairs(eps, EPS_LARGEST_REAL));
  PetscCall(EPSSetDimensions(eps, 1, 8, PETSC_DEFAULT));
  PetscCall(EPSSetTolerances(eps, 1e-2, 50));
  if (prefix) PetscCall(EPSSetOptionsPrefix(eps, prefix));
  PetscCall(EPSSetFromOptions(eps));
  PetscCall(EPSSolve(eps));
  PetscCall(EPSGetConverged(eps, &nconv));
  *ok = nconv > 0 ? PETSC_TRUE : PETSC_FALSE;
  if (*ok) {
    PetscCall(MatCreateVecs(M, &v, &w));
    PetscCall(EPSGetEigenpair(eps, 0, &kr, &ki, v, NULL));
    /* residual of the normalized Ritz pair; computed here so its product is counted too */
    PetscCall(VecNormalize(v, NULL));
    PetscCall(MatMult(M, v, w));
    PetscCall(VecAXPY(w, -kr, v));
    PetscCall(VecNorm(w, NORM_2, &res));
    *theta_upper = PetscAbsReal(PetscRealPart(kr)) + res;
    PetscCall(VecDestroy(&v));
    PetscCall(VecDestroy(&w));
  }
  PetscCall(EPSDestroy(&eps));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode EstimatePower(Mat M, PetscInt maxit, PetscReal *theta)
{
  Vec       v, w;
  PetscReal nrm = 0, prev = 0;

  PetscFunctionBegin;
  PetscCall(MatCreateVecs(M, &v, &w));
  PetscCall(SetStartVector(v));
  PetscCall(VecNormalize(v, NULL));
  for (PetscInt k = 0; k < maxit; k++) {
    PetscCall(MatMult(M, v, w));
    PetscCall(VecNorm(w, NORM_2, &nrm));
    if (nrm == 0) break;
    PetscCall(VecScale(w, 1.0 / nrm));
    PetscCall(VecSwap(v, w));
    if (k > 2 && PetscAbsReal(nrm - prev) <= 1e-3 * nrm) break;
    prev = nrm;
  }
  *theta = nrm;
  PetscCall(VecDestroy(&v));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(PETSC_SUCCESS);
}

struct CachedNorm {
  PetscObjectState state;
  QPNormMethod     method;
  PetscReal        margin;
  PetscReal        value;
};

PetscErrorCode CachedNormDestroy(void *ctx)
{
  PetscFunctionBegin;
  delete (CachedNorm *)ctx;
  PetscFunctionReturn(PETSC_SUCCESS);
}

constexpr const char *kCacheKey = "ConeFETI_NormEstimate";

} // namespace

/*@C
  MatQPEstimateNorm - Estimate ||A||_2 of a symmetric positive semidefinite operator from above,
  for the fixed step length of MPRGP/MPGP; cached on the Mat.

  Collective

  Input Parameters:
+ A      - the operator (any Mat with MatMult, MATSHELL included)
. method - `QP_NORM_SLEPC` (default of the solvers) or `QP_NORM_POWER`
. margin - relative safety margin added on top (e.g. 0.01 for SLEPc, 0.05 for the power method)
- prefix - options prefix for the SLEPc EPS (e.g. "tao_mpgp_norm_" gives -tao_mpgp_norm_eps_monitor), or NULL

  Output Parameters:
+ norm     - the estimate
- products - number of products with A spent (0 when the cached value was reused); may be NULL

  Notes:
  SLEPc is initialized lazily if the host program only called `PetscInitialize()`. If the EPS
  does not converge, the power method is used instead. The cache is invalidated when the Mat's
  object state changes; a MATSHELL whose action changes behind PETSc's back needs
  `MatQPClearNormEstimate()` or `PetscObjectStateIncrease()`.

  Level: advanced

.seealso: `MatQPClearNormEstimate()`, `TaoQPSetNormEstimate()`, `QPNormMethod`
@*/
PetscErrorCode MatQPEstimateNorm(Mat A, QPNormMethod method, PetscReal margin, const char prefix[], PetscReal *norm, PetscInt *products)
{
  PetscContainer   container;
  CachedNorm      *cache = nullptr;
  PetscObjectState state;
  PetscInt         count = 0;
  CountingContext  ctx;
  Mat              M;
  PetscReal        theta = 0;
  PetscBool        ok    = PETSC_FALSE;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(A, MAT_CLASSID, 1);
  PetscCheck(method == QP_NORM_SLEPC || method == QP_NORM_POWER, PetscObjectComm((PetscObject)A), PETSC_ERR_ARG_WRONG, "MatQPEstimateNorm: method must be slepc or power");
  PetscCheck(margin >= 0 && !PetscIsInfOrNanReal(margin), PetscObjectComm((PetscObject)A), PETSC_ERR_ARG_OUTOFRANGE, "MatQPEstimateNorm: the safety margin must be finite and >= 0, got %g",
             (double)margin);
  PetscCall(PetscObjectStateGet((PetscObject)A, &state));
  PetscCall(PetscObjectQuery((PetscObject)A, kCacheKey, (PetscObject *)&container));
  if (container) {
    PetscCall(PetscContainerGetPointer(container, (void **)&cache));
    if (cache->state == state && cache->method == method && cache->margin == margin) {
      *norm = cache->value;
      if (products) *products = 0;
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  {
    PetscInt N;
    PetscCall(MatGetSize(A, &N, NULL));
    if (N == 0) { /* an empty problem: any positive value; no step will use it */
      *norm = 1;
      if (products) *products = 0;
      PetscFunctionReturn(PETSC_SUCCESS);
    }
  }
  {
    /* an assembled operator with a NaN or an infinity: SLEPc's failure would name neither (its entries cost less
       to read than one product; a MATSHELL without a norm is left to the estimate's own check below) */
    PetscBool hasnorm, assembled;
    PetscReal fro;
    PetscCall(MatHasOperation(A, MATOP_NORM, &hasnorm));
    PetscCall(MatAssembled(A, &assembled));
    if (hasnorm && assembled) {
      PetscCall(MatNorm(A, NORM_FROBENIUS, &fro));
      PetscCheck(!PetscIsInfOrNanReal(fro), PetscObjectComm((PetscObject)A), PETSC_ERR_FP, "MatQPEstimateNorm: the operator (the Hessian) has an entry that is not a finite number (Frobenius norm %g)",
                 (double)fro);
    }
  }
  PetscCall(PetscLogEventBegin(QP_NormEstimate, A, 0, 0, 0));
  ctx.A     = A;
  ctx.count = &count;
  PetscCall(CreateCountingShell(A, &ctx, &M));
  if (method == QP_NORM_SLEPC) PetscCall(EstimateSLEPc(M, prefix, &theta, &ok));
  if (!ok) PetscCall(EstimatePower(M, 100, &theta));
  PetscCall(MatDestroy(&M));
  PetscCall(PetscLogEventEnd(QP_NormEstimate, A, 0, 0, 0));
  if (theta == 0 && prefix) { /* a zero Hessian (a linear program in a box): its solver takes the norm as an option */
    std::string option(prefix);
    if (option.size() > 1 && option.back() == '_') option.pop_back();
    SETERRQ(PetscObjectComm((PetscObject)A), PETSC_ERR_NOT_CONVERGED,
            "MatQPEstimateNorm: the norm estimate is 0: a zero operator has no norm to estimate; give the step length's scale with -%s <positive value>", option.c_str());
  }
  PetscCheck(theta > 0 && !PetscIsInfOrNanReal(theta), PetscObjectComm((PetscObject)A), PETSC_ERR_NOT_CONVERGED, "MatQPEstimateNorm: the norm estimate is %g; the operator must be nonzero and finite",
             (double)theta);
  /* rounded up to 4 significant digits: rounding noise of the reductions (which differs with the
     number of ranks) must not change the step length and with it the iteration counts */
  {
    const PetscReal v = theta * (1 + margin), e = PetscPowReal(10.0, PetscFloorReal(PetscLog10Real(v)) - 3);
    *norm = PetscCeilReal(v / e) * e;
  }
  if (products) *products = count;

  if (!container) {
    PetscCallCXX(cache = new CachedNorm);
    PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)A), &container));
    PetscCall(PetscContainerSetPointer(container, cache));
    PetscCall(PetscContainerSetUserDestroy(container, CachedNormDestroy));
    PetscCall(PetscObjectCompose((PetscObject)A, kCacheKey, (PetscObject)container));
    PetscCall(PetscContainerDestroy(&container));
  }
  /* composing changes no state of A, so the state read above still identifies the operator */
  cache->state  = state;
  cache->method = method;
  cache->margin = margin;
  cache->value  = *norm;
  PetscFunctionReturn(PETSC_SUCCESS);
}

/*@C
  MatQPClearNormEstimate - Forget the cached norm estimate of a Mat.

  Not Collective

  Input Parameter:
. A - the operator

  Level: advanced

.seealso: `MatQPEstimateNorm()`
@*/
PetscErrorCode MatQPClearNormEstimate(Mat A)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(A, MAT_CLASSID, 1);
  PetscCall(PetscObjectCompose((PetscObject)A, kCacheKey, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}
