/* Diagnoses of a failed solve: is the operator symmetric, is Q a projector. MatIsSymmetric() cannot test a MATSHELL
   (FETI's F, a user's operator), so they test with products; the products are counted in the solvers' statistics,
   whose documented counts are those of successful solves, so the tests run only after a solve failed. */
#pragma once

#include <conefeti/compat.h>
#include <petscmat.h>

/* x'Ay - y'Ax for random x, y against scale = max(||A||, |Ax|/|x|, |Ay|/|y|) |x| |y|: symmetric when within
   1e-8 scale, far above the rounding of the two products (about 1e-16 n scale) and below any asymmetry that matters */
struct MatSymmetryTest {
  PetscReal asymmetry = 0; /* x'Ay - y'Ax */
  PetscReal scale     = 0;
  PetscBool symmetric = PETSC_TRUE;
};
/* |Q(Qx) - Qx| for a random x against |Qx|: a projector within 1e-8 |Qx| */
struct MatProjectorTest {
  PetscReal defect    = 0; /* |Q(Qx) - Qx| */
  PetscReal scale     = 0; /* |Qx| */
  PetscBool projector = PETSC_TRUE;
};
/* two products each; normA is an estimate of ||A|| (0: none) */
PETSC_INTERN PetscErrorCode MatTestSymmetry_Private(Mat, PetscReal, MatSymmetryTest *);
PETSC_INTERN PetscErrorCode MatTestProjector_Private(Mat, MatProjectorTest *);
/* why a failed solve's operators are to blame: A (named Aname, written Aletter in the formula) not symmetric, else Q (if
   any) not a projector or not symmetric; "" when they pass. Two products with A, up to four with Q (uncounted) */
PETSC_INTERN PetscErrorCode MatDiagnoseOperators_Private(Mat, PetscReal, const char[], char, Mat, const char[], char[], size_t);

#include <petsctao.h>
/* the names of smalxe's Hessian and projector in the errors of a failed solve ("the Hessian", "the projector Q") */
PETSC_INTERN PetscErrorCode TaoSMALXESetOperatorNames_Private(Tao, const char[], const char[]);
PETSC_INTERN PetscErrorCode TaoSMALXESetStartMultiplier_Private(Tao, Vec);
PETSC_INTERN PetscErrorCode TaoSMALXEGetSlowLoop_Private(Tao, PetscInt *, PetscInt *, PetscReal *);
