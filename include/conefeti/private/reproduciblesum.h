/* Sums whose result does not depend on how the terms are split over MPI ranks (to rounding far
   below double precision): each rank accumulates in double-double arithmetic (error-free
   transformations), ranks combine with a double-double MPI operation, and the result is rounded
   once. The QP solvers use them for every scalar that steers a decision, so iteration counts are
   the same on 1, 2 or 3 ranks. */
#pragma once

#include <petscvec.h>
#include <cmath>
#include <type_traits>

/* FMA in every function (the build's baseline has it) or only in run-time dispatched clones: an
   x86-64 baseline build has no FMA, but nearly every x86-64 CPU in use does. The library is compiled
   with -ffp-contract=off, so an FMA clone fuses nothing but the explicit __builtin_fma calls and
   computes bitwise what the baseline code computes. */
#if defined(__FMA__) || defined(__aarch64__)
#  define CONEFETI_FMA_BASELINE true
#else
#  define CONEFETI_FMA_BASELINE false
#endif
#if !defined(__FMA__) && defined(__x86_64__) && defined(__GNUC__)
#  define CONEFETI_FMA_DISPATCH 1
#  define CONEFETI_TARGET_FMA   __attribute__((target("avx,fma")))
/* a kernel template must be inlined into its FMA clone: compiled on its own it has the baseline
   target, where __builtin_fma is a libm call */
#  define CONEFETI_INLINE_KERNEL inline __attribute__((always_inline))
#else
#  define CONEFETI_FMA_DISPATCH  0
#  define CONEFETI_INLINE_KERNEL inline
#endif

/* Four double-double accumulators side by side: lane k takes the terms k, k + 4, k + 8, ... of a
   local array and the lanes are added at the end. One accumulator is a chain of dependent
   additions (about ten operations per term, one term at a time); four independent ones run as one
   SIMD chain whose latencies overlap. The grouping of the terms is another one than with a single
   accumulator, which changes the sum only far below double precision, like the split over ranks. */
typedef double DoubleDoubleLanes __attribute__((vector_size(4 * sizeof(double))));
/* every function taking or returning lanes is inline: no call passes them, so no ABI to warn about */
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

/* A double-double accumulator of T = double (one sum) or DoubleDoubleLanes (four sums, lane-wise):
   the same operations either way. */
template <class T> struct DoubleDoubleT {
  T hi{}, lo{};

  /* add a value exactly (Knuth's TwoSum), keeping the error in lo */
  inline void add(const T &a)
  {
    const T s  = hi + a;
    const T bb = s - hi;
    const T e  = (hi - (s - bb)) + (a - bb);
    hi         = s;
    lo += e;
  }
  /* add the exact product a*b (TwoProd): the rounded product plus its exact error term. With a
     fused multiply-add the error is one instruction; without it, Dekker's product (Veltkamp
     splitting, exact barring overflow) gives the same error term in about 17 operations. Both are
     exact, so the two variants return bitwise the same sums; which one runs is chosen at compile
     time (addProduct) or, for the kernels that have an FMA clone, at run time (see
     ReproducibleSumUseFMA()). Fused = true only inside code compiled for FMA (CONEFETI_TARGET_FMA
     or an FMA baseline): elsewhere __builtin_fma is a call into libm. */
  template <bool Fused> inline void addProductT(const T &a, const T &b)
  {
    const T p = a * b;
    T       e;
    if constexpr (!Fused) {
      constexpr double split = 134217729.0; /* 2^27 + 1 */
      const T          ta = split * a, ah = ta - (ta - a), al = a - ah;
      const T          tb = split * b, bh = tb - (tb - b), bl = b - bh;
      e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    } else if constexpr (std::is_same_v<T, double>) e = __builtin_fma(a, b, -p);
    else
      for (int k = 0; k < 4; k++) e[k] = __builtin_fma(a[k], b[k], -p[k]);
    add(p);
    lo += e;
  }
};

struct DoubleDouble : DoubleDoubleT<double> {
  using DoubleDoubleT<double>::add;
  inline void addProduct(double a, double b) { addProductT<CONEFETI_FMA_BASELINE>(a, b); }
  inline void add(const DoubleDouble &o)
  {
    add(o.hi);
    lo += o.lo;
  }
  inline double value() const { return hi + lo; }
};

struct DoubleDouble4 : DoubleDoubleT<DoubleDoubleLanes> {
  /* the lanes added into one DoubleDouble, lane 0 first */
  inline DoubleDouble total() const
  {
    DoubleDouble t;
    for (int k = 0; k < 4; k++) {
      t.add(hi[k]);
      t.lo += lo[k];
    }
    return t;
  }
};

/* entries [i, i + 4) of a, the ones at or past n as zero (a zero term leaves a sum exactly as it was) */
inline DoubleDoubleLanes LoadLanes(const PetscScalar *a, PetscInt i, PetscInt n)
{
  DoubleDoubleLanes v = {0, 0, 0, 0};
  if (PetscLikely(i + 4 <= n)) {
    static_assert(sizeof(PetscScalar) == sizeof(double), "real scalars");
    __builtin_memcpy(&v, a + i, sizeof v);
  } else
    for (int k = 0; i + k < n; k++) v[k] = a[i + k];
  return v;
}
#pragma GCC diagnostic pop

/* In-place MPI_SUM over `count` DoubleDouble values, result on every rank. */
PETSC_INTERN PetscErrorCode ReproducibleAllreduce(DoubleDouble *, PetscInt, MPI_Comm);
/* x'y over the local entries then all ranks */
PETSC_INTERN PetscErrorCode ReproducibleDot(Vec, Vec, PetscReal *);
PETSC_INTERN PetscErrorCode ReproducibleDot2(Vec, Vec, Vec, Vec, PetscReal *, PetscReal *);
PETSC_INTERN PetscErrorCode ReproducibleSumInitialize(void);
/* Whether the dispatched kernels run their FMA clones: the CPU has FMA and -qp_reproducible_fma was
   not turned off (ReproducibleSumSetFromOptions(), called by the QP package initialization). */
PETSC_INTERN PetscBool      ReproducibleSumUseFMA(void);
PETSC_INTERN PetscErrorCode ReproducibleSumSetFromOptions(void);
PETSC_INTERN PetscErrorCode ReproducibleSumFinalize(void);

/* y += a x and y = x + a y with the same rounding for every entry. BLAS kernels use FMA in their
   vector bodies but not in their remainder loops, so which entries get fused depends on where a
   rank's local part starts, and the results then differ in the last bit with the number of ranks. */
PETSC_INTERN PetscErrorCode ReproducibleAXPY(Vec, PetscReal, Vec);
PETSC_INTERN PetscErrorCode ReproducibleAYPX(Vec, PetscReal, Vec);
