/* Sums whose result does not depend on how the terms are split over MPI ranks (to rounding far
   below double precision): each rank accumulates in double-double arithmetic (error-free
   transformations), ranks combine with a double-double MPI operation, and the result is rounded
   once. The QP solvers use them for every scalar that steers a decision, so iteration counts are
   the same on 1, 2 or 3 ranks. */
#pragma once

#include <petscvec.h>
#include <cmath>

struct DoubleDouble {
  double hi = 0, lo = 0;

  /* add a double exactly (Knuth's TwoSum), keeping the error in lo */
  inline void add(double a)
  {
    const double s  = hi + a;
    const double bb = s - hi;
    const double e  = (hi - (s - bb)) + (a - bb);
    hi              = s;
    lo += e;
  }
  /* add the exact product a*b (TwoProd). With a hardware FMA known at compile time it is one
     instruction; otherwise std::fma is a call into libm for every term (x86-64 baseline builds), which
     made the solvers' reductions cost several matrix products per iteration, so Dekker's product
     (Veltkamp splitting, exact without FMA barring overflow) is used instead: the same error term. */
  inline void addProduct(double a, double b)
  {
    const double p = a * b;
#if defined(__FMA__) || defined(__aarch64__)
    const double e = __builtin_fma(a, b, -p);
#else
    constexpr double split = 134217729.0; /* 2^27 + 1 */
    const double     ta = split * a, ah = ta - (ta - a), al = a - ah;
    const double     tb = split * b, bh = tb - (tb - b), bl = b - bh;
    const double     e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
#endif
    add(p);
    lo += e;
  }
  inline void add(const DoubleDouble &o)
  {
    add(o.hi);
    lo += o.lo;
  }
  inline double value() const { return hi + lo; }
};

/* In-place MPI_SUM over `count` DoubleDouble values, result on every rank. */
PETSC_INTERN PetscErrorCode ReproducibleAllreduce(DoubleDouble *, PetscInt, MPI_Comm);
/* x'y over the local entries then all ranks */
PETSC_INTERN PetscErrorCode ReproducibleDot(Vec, Vec, PetscReal *);
PETSC_INTERN PetscErrorCode ReproducibleDot2(Vec, Vec, Vec, Vec, PetscReal *, PetscReal *);
PETSC_INTERN PetscErrorCode ReproducibleSumInitialize(void);
PETSC_INTERN PetscErrorCode ReproducibleSumFinalize(void);

/* y += a x and y = x + a y with the same rounding for every entry. BLAS kernels use FMA in their
   vector bodies but not in their remainder loops, so which entries get fused depends on where a
   rank's local part starts, and the results then differ in the last bit with the number of ranks. */
PETSC_INTERN PetscErrorCode ReproducibleAXPY(Vec, PetscReal, Vec);
PETSC_INTERN PetscErrorCode ReproducibleAYPX(Vec, PetscReal, Vec);
