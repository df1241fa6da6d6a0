/* Rewrites a FETI interchange file of version 2 object by object (docs/feti-interchange.md), for the tests of the
   reader: as version 1 (the pairing dropped: the files older codes wrote), with another version number, with a
   contact pairing index out of range, or with the first node's normal and first tangential row swapped (rows of
   the wrong kind). Runs on one rank. */
#pragma once

#include <conefeti.h>

#include <string>
#include <utility>
#include <vector>

static inline PetscErrorCode FETIFileRewrite(const char *in, const char *out, const std::string &how)
{
  PetscViewer     vin, vout;
  IS              is[5], kinds;
  Vec             coef, f, c, coords = NULL;
  Mat             K, B, R;
  const PetscInt *hd;
  PetscInt        n, header[6];

  PetscFunctionBeginUser;
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_SELF, in, FILE_MODE_READ, &vin));
  for (int i = 0; i < 5; i++) { /* header, sizes, kernels, Dirichlet dofs, pairing */
    PetscCall(ISCreate(PETSC_COMM_SELF, &is[i]));
    PetscCall(ISLoad(is[i], vin));
  }
  PetscCall(ISGetLocalSize(is[0], &n));
  PetscCheck(n == 6, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: not a version 2 file (header of %d entries)", in, (int)n);
  PetscCall(ISGetIndices(is[0], &hd));
  for (int i = 0; i < 6; i++) header[i] = hd[i];
  PetscCall(ISRestoreIndices(is[0], &hd));
  PetscCheck(header[1] == 2, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: not a version 2 file", in);
  PetscCall(VecCreate(PETSC_COMM_SELF, &coef));
  PetscCall(VecLoad(coef, vin));
  PetscCall(MatCreate(PETSC_COMM_SELF, &K));
  PetscCall(MatSetType(K, MATAIJ));
  PetscCall(MatLoad(K, vin));
  PetscCall(VecCreate(PETSC_COMM_SELF, &f));
  PetscCall(VecLoad(f, vin));
  PetscCall(MatCreate(PETSC_COMM_SELF, &B));
  PetscCall(MatSetType(B, MATAIJ));
  PetscCall(MatLoad(B, vin));
  PetscCall(VecCreate(PETSC_COMM_SELF, &c));
  PetscCall(VecLoad(c, vin));
  PetscCall(ISCreate(PETSC_COMM_SELF, &kinds));
  PetscCall(ISLoad(kinds, vin));
  PetscCall(MatCreate(PETSC_COMM_SELF, &R));
  PetscCall(MatSetType(R, MATAIJ));
  PetscCall(MatLoad(R, vin));
  if (header[3]) {
    PetscCall(VecCreate(PETSC_COMM_SELF, &coords));
    PetscCall(VecLoad(coords, vin));
  }
  PetscCall(PetscViewerDestroy(&vin));

  if (how == "v1" || how == "version3") {
    const PetscInt v1[4] = {header[0], how == "v1" ? 1 : 3, header[2], header[3]};
    if (how == "version3") header[1] = 3;
    PetscCall(ISDestroy(&is[0]));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, how == "v1" ? 4 : 6, how == "v1" ? v1 : header, PETSC_COPY_VALUES, &is[0]));
  } else if (how == "out_of_range" || how == "swap_rows") { /* the first node's normal row beyond the last row of B, or swapped with its first tangential row */
    std::vector<PetscInt> p;
    const PetscInt       *pa;
    PetscCall(ISGetLocalSize(is[4], &n));
    PetscCheck(n >= 4, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s has no contact pairing to break", in);
    PetscCall(ISGetIndices(is[4], &pa));
    p.assign(pa, pa + n);
    PetscCall(ISRestoreIndices(is[4], &pa));
    if (how == "out_of_range") p[0] = header[4] + 5;
    else std::swap(p[0], p[1]);
    PetscCall(ISDestroy(&is[4]));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, n, p.data(), PETSC_COPY_VALUES, &is[4]));
  } else SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "unknown rewrite %s (v1, version3, out_of_range, swap_rows)", how.c_str());

  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_SELF, out, FILE_MODE_WRITE, &vout));
  for (int i = 0; i < 4; i++) PetscCall(ISView(is[i], vout));
  if (how != "v1") {
    PetscCall(ISView(is[4], vout));
    PetscCall(VecView(coef, vout));
  }
  PetscCall(MatView(K, vout));
  PetscCall(VecView(f, vout));
  PetscCall(MatView(B, vout));
  PetscCall(VecView(c, vout));
  PetscCall(ISView(kinds, vout));
  PetscCall(MatView(R, vout));
  if (coords) PetscCall(VecView(coords, vout));
  PetscCall(PetscViewerDestroy(&vout));
  for (int i = 0; i < 5; i++) PetscCall(ISDestroy(&is[i]));
  PetscCall(ISDestroy(&kinds));
  PetscCall(VecDestroy(&coef));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&c));
  PetscCall(VecDestroy(&coords));
  PetscCall(MatDestroy(&K));
  PetscCall(MatDestroy(&B));
  PetscCall(MatDestroy(&R));
  PetscFunctionReturn(PETSC_SUCCESS);
}
