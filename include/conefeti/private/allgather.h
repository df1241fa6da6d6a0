/* Every rank's array, concatenated in rank order, on every rank (MPI_Allgatherv with the counts gathered first): for
   the small tables that each rank builds of its own subdomains and all ranks need whole */
#pragma once

#include <petscsys.h>
#include <vector>

template <class T> struct ConeFETIMPIType;
template <> struct ConeFETIMPIType<PetscInt> {
  static MPI_Datatype get() { return MPIU_INT; }
};
template <> struct ConeFETIMPIType<double> {
  static MPI_Datatype get() { return MPI_DOUBLE; }
};

template <class T> static inline PetscErrorCode ConeFETIAllgather(MPI_Comm comm, const std::vector<T> &mine, std::vector<T> &all)
{
  PetscMPIInt size, n;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMPIIntCast((PetscInt)mine.size(), &n));
  std::vector<PetscMPIInt> counts(size), displs(size + 1, 0);
  PetscCallMPI(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm));
  for (PetscMPIInt r = 0; r < size; r++) displs[r + 1] = displs[r] + counts[r];
  PetscCallCXX(all.resize(displs[size]));
  PetscCallMPI(MPI_Allgatherv(mine.data(), n, ConeFETIMPIType<T>::get(), all.data(), counts.data(), displs.data(), ConeFETIMPIType<T>::get(), comm));
  PetscFunctionReturn(PETSC_SUCCESS);
}
