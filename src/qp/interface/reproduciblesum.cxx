/* Rank-count independent sums (see reproduciblesum.h). */
#include <conefeti/private/reproduciblesum.h>
#include <conefeti/private/mpgpcore.h>
#include <conefeti/compat.h>
#include <petscvec.h>
#include <vector>

static MPI_Datatype dd_type = MPI_DATATYPE_NULL;
static MPI_Op       dd_sum  = MPI_OP_NULL;
static PetscBool    use_fma = PETSC_FALSE;

PetscBool ReproducibleSumUseFMA(void) { return use_fma; }

/* Reads -qp_reproducible_fma once per PetscInitialize (from the QP package initialization). */
PetscErrorCode ReproducibleSumSetFromOptions(void)
{
  PetscBool cpu = PETSC_FALSE, want = PETSC_TRUE;

  PetscFunctionBegin;
#if CONEFETI_FMA_DISPATCH
  cpu = (__builtin_cpu_supports("avx") && __builtin_cpu_supports("fma")) ? PETSC_TRUE : PETSC_FALSE;
#endif
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "conefeti QP kernels", "TAOMPRGP");
  PetscCall(
      PetscOptionsBool("-qp_reproducible_fma", "Exact products of the rank-independent sums by the CPU's FMA instead of Dekker's product (the same sums, faster)", "TAOMPRGP", want, &want, NULL));
  PetscOptionsEnd();
  use_fma = (cpu && want) ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscInfo(NULL, "rank-independent sums: exact products by %s\n", use_fma ? "FMA (run-time dispatch)" : (CONEFETI_FMA_BASELINE ? "FMA (build baseline)" : "Dekker's product")));
  PetscFunctionReturn(PETSC_SUCCESS);
}

static void DoubleDoubleSum(void *in, void *inout, int *len, MPI_Datatype *)
{
  const DoubleDouble *a = static_cast<const DoubleDouble *>(in);
  DoubleDouble       *b = static_cast<DoubleDouble *>(inout);
  for (int i = 0; i < *len; i++) b[i].add(a[i]);
}

PetscErrorCode ReproducibleSumInitialize(void)
{
  PetscFunctionBegin;
  if (dd_type == MPI_DATATYPE_NULL) {
    PetscCallMPI(MPI_Type_contiguous(2, MPI_DOUBLE, &dd_type));
    PetscCallMPI(MPI_Type_commit(&dd_type));
    /* not commutative: MPI then combines in rank order, the same in every run (a commutative op may
       be combined in arrival order) */
    PetscCallMPI(MPI_Op_create(DoubleDoubleSum, 0, &dd_sum));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ReproducibleSumFinalize(void)
{
  PetscFunctionBegin;
  if (dd_type != MPI_DATATYPE_NULL) {
    PetscCallMPI(MPI_Op_free(&dd_sum));
    PetscCallMPI(MPI_Type_free(&dd_type));
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ReproducibleAllreduce(DoubleDouble *v, PetscInt count, MPI_Comm comm)
{
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size > 1) {
    std::vector<DoubleDouble> out(count);
    PetscCall(ReproducibleSumInitialize());
    PetscCallMPI(MPI_Allreduce(v, out.data(), (PetscMPIInt)count, dd_type, dd_sum, comm));
    for (PetscInt i = 0; i < count; i++) v[i] = out[i];
  }
  /* round once, the same way on every rank whatever the split: renormalize */
  for (PetscInt i = 0; i < count; i++) {
    const double s = v[i].hi + v[i].lo;
    v[i].lo        = v[i].lo - (s - v[i].hi);
    v[i].hi        = s;
  }
  PetscFunctionReturn(PETSC_SUCCESS);
}

namespace {
#pragma GCC diagnostic                            push
#pragma GCC diagnostic                            ignored "-Wpsabi" /* lanes are passed only between inlined functions */
template <bool Fused> CONEFETI_INLINE_KERNEL void DotKernel(PetscInt n, const PetscScalar *a, const PetscScalar *b, const PetscScalar *c, const PetscScalar *e, DoubleDouble s[2])
{
  DoubleDouble4 s0, s1; /* locals: kept in registers, not stored back after every term */
  for (PetscInt i = 0; i < n; i += 4) s0.addProductT<Fused>(LoadLanes(a, i, n), LoadLanes(b, i, n));
  if (c)
    for (PetscInt i = 0; i < n; i += 4) s1.addProductT<Fused>(LoadLanes(c, i, n), LoadLanes(e, i, n));
  s[0] = s0.total();
  s[1] = s1.total();
}
#pragma GCC diagnostic pop
#if CONEFETI_FMA_DISPATCH
CONEFETI_TARGET_FMA void DotKernelFMA(PetscInt n, const PetscScalar *a, const PetscScalar *b, const PetscScalar *c, const PetscScalar *e, DoubleDouble s[2]) { DotKernel<true>(n, a, b, c, e, s); }
#endif
} // namespace

PetscErrorCode ReproducibleDot2(Vec x1, Vec y1, Vec x2, Vec y2, PetscReal *d1, PetscReal *d2)
{
  const PetscScalar *a, *b, *c = NULL, *e = NULL;
  PetscInt           n;
  DoubleDouble       s[2];

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(QP_VecReproducible, 0, 0, 0, 0));
  PetscCall(VecGetLocalSize(x1, &n));
  PetscCall(VecGetArrayRead(x1, &a));
  PetscCall(VecGetArrayRead(y1, &b));
  if (x2) {
    PetscCall(VecGetArrayRead(x2, &c));
    PetscCall(VecGetArrayRead(y2, &e));
  }
#if CONEFETI_FMA_DISPATCH
  if (use_fma) DotKernelFMA(n, a, b, c, e, s);
  else
#endif
    DotKernel<CONEFETI_FMA_BASELINE>(n, a, b, c, e, s);
  PetscCall(VecRestoreArrayRead(x1, &a));
  PetscCall(VecRestoreArrayRead(y1, &b));
  if (x2) {
    PetscCall(VecRestoreArrayRead(x2, &c));
    PetscCall(VecRestoreArrayRead(y2, &e));
  }
  PetscCall(ReproducibleAllreduce(s, x2 ? 2 : 1, PetscObjectComm((PetscObject)x1)));
  *d1 = s[0].value();
  if (x2) *d2 = s[1].value();
  PetscCall(PetscLogEventEnd(QP_VecReproducible, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ReproducibleDot(Vec x, Vec y, PetscReal *d)
{
  PetscFunctionBegin;
  PetscCall(ReproducibleDot2(x, y, NULL, NULL, d, NULL));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ReproducibleAXPY(Vec y, PetscReal a, Vec x)
{
  PetscScalar       *ya;
  const PetscScalar *xa;
  PetscInt           n;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(QP_VecReproducible, 0, 0, 0, 0));
  PetscCall(VecGetLocalSize(y, &n));
  PetscCall(VecGetArray(y, &ya));
  PetscCall(VecGetArrayRead(x, &xa));
  for (PetscInt i = 0; i < n; i++) ya[i] += a * xa[i];
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(PetscLogFlops(2.0 * n));
  PetscCall(PetscLogEventEnd(QP_VecReproducible, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}

PetscErrorCode ReproducibleAYPX(Vec y, PetscReal a, Vec x)
{
  PetscScalar       *ya;
  const PetscScalar *xa;
  PetscInt           n;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(QP_VecReproducible, 0, 0, 0, 0));
  PetscCall(VecGetLocalSize(y, &n));
  PetscCall(VecGetArray(y, &ya));
  PetscCall(VecGetArrayRead(x, &xa));
  for (PetscInt i = 0; i < n; i++) ya[i] = xa[i] + a * ya[i];
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(VecRestoreArray(y, &ya));
  PetscCall(PetscLogFlops(2.0 * n));
  PetscCall(PetscLogEventEnd(QP_VecReproducible, 0, 0, 0, 0));
  PetscFunctionReturn(PETSC_SUCCESS);
}
