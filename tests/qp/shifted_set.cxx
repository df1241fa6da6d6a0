/* SeparableSetSetShift(): the shifted set is { x : x + s in Omega }, so its projection must be
   P_s(x) = P(x + s) - s, P the projection onto Omega. It is the only way to give a cone an apex away
   from the origin (and to homogenize C x = d by a particular solution). Checked on scalar bounds, disks
   (with centers) and cones, for points mostly outside the set, on 1 and 2 ranks; then the shift vector
   is changed in place (the set must notice through its object state) and finally removed (NULL).
   Fails if the shift is ignored, applied with the wrong sign, or a stale value is used. */
#include <conefeti.h>
#include <conefeti/compat.h>
#include <vector>

static const PetscInt UNIT = 7; /* per unit: 2 scalars, a disk (2), a cone (3) */

/* |P_s(x) - (P(x + s) - s)|_inf, with the set's shift temporarily removed to evaluate P */
static PetscErrorCode CompareWithShiftedProjection(SeparableSet set, Vec s, Vec x, PetscReal *err)
{
  Vec y, z;

  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(x, &y));
  PetscCall(VecDuplicate(x, &z));
  PetscCall(SeparableSetSetShift(set, s));
  PetscCall(VecCopy(x, y));
  PetscCall(SeparableSetProject(set, y)); /* P_s(x) */
  PetscCall(SeparableSetSetShift(set, NULL));
  PetscCall(VecWAXPY(z, 1.0, x, s));
  PetscCall(SeparableSetProject(set, z));
  PetscCall(VecAXPY(z, -1.0, s)); /* P(x + s) - s */
  PetscCall(VecAXPY(y, -1.0, z));
  PetscCall(VecNorm(y, NORM_INFINITY, err));
  PetscCall(SeparableSetSetShift(set, s));
  PetscCall(VecDestroy(&y));
  PetscCall(VecDestroy(&z));
  PetscFunctionReturn(PETSC_SUCCESS);
}

int main(int argc, char **argv)
{
  SeparableSet set;
  Vec          x, s, lb, ub, px;
  PetscInt     units = 5, lo, hi;
  PetscRandom  rnd;
  PetscReal    err1, err2, moved;

  PetscCall(PetscInitialize(&argc, &argv, NULL, "SeparableSetSetShift: projection onto a translated set"));
  PetscCall(ConeFETIInitializePackage());
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-units", &units, NULL));
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, UNIT * units, PETSC_DETERMINE, &x));
  PetscCall(VecDuplicate(x, &s));
  PetscCall(VecDuplicate(x, &lb));
  PetscCall(VecDuplicate(x, &ub));
  PetscCall(VecDuplicate(x, &px));
  PetscCall(VecGetOwnershipRange(x, &lo, &hi));
  PetscCall(SeparableSetCreate(PETSC_COMM_WORLD, UNIT * units, PETSC_DETERMINE, &set));
  PetscCall(VecSet(lb, -0.5));
  PetscCall(VecSet(ub, 0.25));
  PetscCall(SeparableSetSetBounds(set, lb, ub));
  {
    std::vector<PetscInt>  didx, cidx;
    std::vector<PetscReal> center, radius, mu;
    for (PetscInt k = 0; k < units; k++) {
      PetscInt b = lo + UNIT * k;
      didx.push_back(b + 2);
      didx.push_back(b + 3);
      center.push_back(0.1 * (k + 1));
      center.push_back(-0.2);
      radius.push_back(0.3 + 0.1 * k);
      for (PetscInt j = 4; j < 7; j++) cidx.push_back(b + j);
      mu.push_back(0.2 + 0.2 * k);
    }
    PetscCall(SeparableSetAddDisks(set, units, didx.data(), center.data(), radius.data()));
    PetscCall(SeparableSetAddCones(set, units, cidx.data(), mu.data()));
  }
  PetscCall(PetscRandomCreate(PETSC_COMM_WORLD, &rnd));
  PetscCall(PetscRandomSetInterval(rnd, -2.0, 2.0));
  PetscCall(VecSetRandom(x, rnd));
  PetscCall(VecSetRandom(s, rnd));

  PetscCall(CompareWithShiftedProjection(set, s, x, &err1));
  /* the test can fail: the shift must move the projection */
  {
    Vec y;
    PetscCall(VecDuplicate(x, &y));
    PetscCall(SeparableSetSetShift(set, NULL));
    PetscCall(VecCopy(x, px));
    PetscCall(SeparableSetProject(set, px));
    PetscCall(SeparableSetSetShift(set, s));
    PetscCall(VecCopy(x, y));
    PetscCall(SeparableSetProject(set, y));
    PetscCall(VecAXPY(y, -1.0, px));
    PetscCall(VecNorm(y, NORM_INFINITY, &moved));
    PetscCall(VecDestroy(&y));
  }
  /* the shift's values changed in place, without a new SeparableSetSetShift() call */
  PetscCall(SeparableSetSetShift(set, s));
  {
    Vec y;
    PetscCall(VecDuplicate(x, &y));
    PetscCall(VecCopy(x, y));
    PetscCall(SeparableSetProject(set, y)); /* sets up with the current s */
    PetscCall(VecScale(s, -1.5));
    PetscCall(VecCopy(x, y));
    PetscCall(SeparableSetProject(set, y)); /* must use -1.5 s */
    PetscCall(SeparableSetSetShift(set, NULL));
    PetscCall(VecWAXPY(px, 1.0, x, s));
    PetscCall(SeparableSetProject(set, px));
    PetscCall(VecAXPY(px, -1.0, s));
    PetscCall(VecAXPY(y, -1.0, px));
    PetscCall(VecNorm(y, NORM_INFINITY, &err2));
    PetscCall(VecDestroy(&y));
  }
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "|P_s(x) - (P(x+s) - s)|_inf = %.3e, after changing s in place %.3e; the shift moved the projection by %.3e\n", (double)err1, (double)err2, (double)moved));
  PetscCheck(err1 <= 1e-12 && err2 <= 1e-12, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "Shifted projection wrong: %g (set once), %g (shift changed in place)", (double)err1, (double)err2);
  PetscCheck(moved > 1e-2, PETSC_COMM_WORLD, PETSC_ERR_PLIB, "The shift did not move the projection (%g): the test data cannot tell", (double)moved);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "shift check passed\n"));
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(SeparableSetDestroy(&set));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&s));
  PetscCall(VecDestroy(&lb));
  PetscCall(VecDestroy(&ub));
  PetscCall(VecDestroy(&px));
  PetscCall(PetscFinalize());
  return 0;
}
