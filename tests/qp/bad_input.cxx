/* Bad arguments give a clear PETSc error (never a crash or a silent wrong answer).

   -case selects one misuse; the program makes the call and ends with PETSc's error report, whose
   message a test checks (conefeti_error_test); a misuse that is not caught ends with status 0 and fails it. */
#include <conefeti.h>
#include <conefeti/compat.h>
#include <limits>
#include <string>

static PetscErrorCode MakeVec(PetscInt n, PetscReal v, Vec *x)
{
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, n, PETSC_DETERMINE, x));
  PetscCall(VecSet(*x, v));
  PetscFunctionReturn(PETSC_SUCCESS);
}

/* the misuse; returns the error code of the failing call */
static PetscErrorCode Misuse(const std::string &c)
{
  Tao          tao;
  Vec          x, l, u;
  Mat          A;
  SeparableSet set;
  PetscInt     idx[3] = {0, 1, 2};
  PetscReal    r[1] = {-1.0}, mu[1] = {-0.5};

  PetscFunctionBeginUser;
  if (c == "negative_radius") {
    PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, 4, PETSC_DETERMINE, &set));
    PetscCall(SeparableSetAddDisks(set, 1, idx, NULL, r));
  } else if (c == "huge_radius" || c == "huge_radius_set" || c == "nan_radius_set") { /* its square overflowed: the solve ended DIVERGED_NAN */
    PetscReal rr[1] = {1.0}, huge[1] = {c == "nan_radius_set" ? std::numeric_limits<PetscReal>::quiet_NaN() : 1e200};
    PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, 4, PETSC_DETERMINE, &set));
    PetscCall(SeparableSetAddDisks(set, 1, idx, NULL, c == "huge_radius" ? huge : rr));
    PetscCall(SeparableSetSetDiskRadii(set, huge));
  } else if (c == "disk_center_nan") {
    PetscReal rr[1] = {1.0}, center[2] = {std::numeric_limits<PetscReal>::quiet_NaN(), 0.0};
    PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, 4, PETSC_DETERMINE, &set));
    PetscCall(SeparableSetAddDisks(set, 1, idx, center, rr));
  } else if (c == "negative_mu") {
    PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, 4, PETSC_DETERMINE, &set));
    PetscCall(SeparableSetAddCones(set, 1, idx, mu));
  } else if (c == "lower_above_upper") {
    PetscCall(MakeVec(4, 1.0, &l));
    PetscCall(MakeVec(4, 0.0, &u));
    PetscCall(MakeVec(4, 0.5, &x));
    PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, 4, PETSC_DETERMINE, &set));
    PetscCall(SeparableSetSetBounds(set, l, u));
    PetscCall(SeparableSetProject(set, x));
  } else if (c == "bounds_wrong_layout") {
    PetscCall(MakeVec(5, 0.0, &l));
    PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, 4, PETSC_DETERMINE, &set));
    PetscCall(SeparableSetSetBounds(set, l, NULL));
  } else if (c == "disk_index_not_owned") {
    PetscInt  far[2] = {1000000, 1000001};
    PetscReal rr[1]  = {1.0};
    PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, 4, PETSC_DETERMINE, &set));
    PetscCall(SeparableSetAddDisks(set, 1, far, NULL, rr));
  } else if (c == "hessian_not_square" || c == "disk_block_odd_length" || c == "mprgp_with_disks" || c == "hessian_nan" || c == "hessian_zero" || c == "initial_guess_nan") {
    PetscInt n = c == "disk_block_odd_length" ? 5 : 4;
    PetscCall(MakeVec(n, 0.0, &x));
    PetscCall(MatCreateDense(PETSC_COMM_WORLD, n, c == "hessian_not_square" ? n + 1 : n, PETSC_DETERMINE, PETSC_DETERMINE, NULL, &A));
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
    if (c != "hessian_zero") PetscCall(MatShift(A, 1.0));
    if (c == "hessian_nan") {
      PetscCall(MatSetValue(A, 0, 1, std::numeric_limits<PetscReal>::quiet_NaN(), INSERT_VALUES));
      PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
    }
    if (c == "initial_guess_nan") {
      PetscCall(VecSetValue(x, 0, std::numeric_limits<PetscReal>::quiet_NaN(), INSERT_VALUES));
      PetscCall(VecAssemblyBegin(x));
      PetscCall(VecAssemblyEnd(x));
    }
    if (c == "hessian_zero") { /* a linear program in the box [-1, 1]^n */
      PetscCall(MakeVec(n, -1.0, &l));
      PetscCall(MakeVec(n, 1.0, &u));
    }
    PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
    if (c == "hessian_zero") PetscCall(TaoSetVariableBounds(tao, l, u));
    PetscCall(TaoSetType(tao, c == "mprgp_with_disks" || c == "hessian_zero" ? TAOMPRGP : TAOMPGP));
    PetscCall(TaoSetSolution(tao, x));
    PetscCall(TaoSetHessian(tao, A, A, NULL, NULL));
    PetscCall(TaoQPSetLinearTerm(tao, x));
    if (c == "disk_block_odd_length") {
      PetscCall(MakeVec(n, -1.0, &l));
      PetscCall(MakeVec(n, 1.0, &u));
      PetscCall(TaoSetVariableBounds(tao, l, u));
      PetscCall(PetscOptionsSetValue(NULL, "-tao_mpgp_block_type", "disk"));
      PetscCall(TaoSetFromOptions(tao));
    }
    if (c == "mprgp_with_disks") {
      PetscReal rr[1] = {1.0};
      PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, n, PETSC_DETERMINE, &set));
      PetscCall(SeparableSetAddDisks(set, 1, idx, NULL, rr));
      PetscCall(TaoQPSetConstraints(tao, set));
    }
    PetscCall(TaoSolve(tao));
  } else if (c == "alpha_out_of_range") {
    PetscCall(TaoCreate(PETSC_COMM_WORLD, &tao));
    PetscCall(TaoSetType(tao, TAOMPGP));
    PetscCall(PetscOptionsSetValue(NULL, "-tao_mpgp_alpha", "2.5"));
    PetscCall(TaoSetFromOptions(tao));
  } else SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "unknown -case %s", c.c_str());
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  char c[64] = "";

  PetscCall(PetscInitialize(&argc, &argv, NULL, "Bad input gives clear errors"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetString(NULL, NULL, "-case", c, sizeof(c), NULL));
  PetscCall(Misuse(c)); /* the error ends the program here */
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "NOT CAUGHT\n"));
  PetscCall(PetscFinalize());
  return 0;
}
