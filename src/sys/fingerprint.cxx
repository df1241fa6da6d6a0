/* A fingerprint of a vector's bits: a regression check that a solve gave exactly the same result
   (on another number of ranks, after a refactoring) without storing the vector. */
#include <conefeti.h>
#include <conefeti/compat.h>
#include <petsc/private/petscimpl.h>

#include <cstdint>
#include <cstring>

/*@C
  ConeFETIVecFingerprint - A 64-bit FNV-1a hash of the bits of a vector's entries in global order.

  Collective

  Input Parameter:
. v - the vector

  Output Parameter:
. hex - 16 hexadecimal digits and a terminating zero (the same string on every rank)

  Notes:
  Two vectors have the same fingerprint when their entries are bitwise equal (up to the rare hash
  collision). The FETI operators and the QP solvers of conefeti sum in an order that does not depend on
  the distribution, so a solve on 1 rank and on 4 ranks gives the same multipliers and the same
  fingerprint; the driver prints it in its JSON summary. Positive and negative zero hash alike.
  The vector is gathered on rank 0: meant for checks, not for the inner loop of a solver.

  Level: intermediate

.seealso: `FETICreateVecs()`
@*/
PetscErrorCode ConeFETIVecFingerprint(Vec v, char hex[17])
{
  VecScatter  scatter;
  Vec         all;
  PetscMPIInt rank;
  uint64_t    h = 1469598103934665603ull;

  PetscFunctionBegin;
  PetscValidHeaderSpecific(v, VEC_CLASSID, 1);
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)v), &rank));
  PetscCall(VecScatterCreateToZero(v, &scatter, &all));
  PetscCall(VecScatterBegin(scatter, v, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(scatter, v, all, INSERT_VALUES, SCATTER_FORWARD));
  if (rank == 0) {
    const PetscScalar *a;
    PetscInt           n;
    PetscCall(VecGetLocalSize(all, &n));
    PetscCall(VecGetArrayRead(all, &a));
    for (PetscInt i = 0; i < n; i++) {
      double        x = (double)PetscRealPart(a[i]);
      unsigned char b[sizeof(double)];
      if (x == 0) x = 0; /* -0 == 0 */
      std::memcpy(b, &x, sizeof(double));
      for (unsigned char c : b) h = (h ^ c) * 1099511628211ull;
    }
    PetscCall(VecRestoreArrayRead(all, &a));
  }
  PetscCall(VecScatterDestroy(&scatter));
  PetscCall(VecDestroy(&all));
  PetscCallMPI(MPI_Bcast(&h, 1, MPI_UINT64_T, 0, PetscObjectComm((PetscObject)v)));
  PetscCall(PetscSNPrintf(hex, 17, "%016llx", (unsigned long long)h));
  PetscFunctionReturn(PETSC_SUCCESS);
}
