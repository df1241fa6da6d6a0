#!/usr/bin/env bash
# Install the Debian 12 packages conefeti needs, and only those that are missing.
# Idempotent: when everything is present it changes nothing and needs no network.
# Runs as root, or through sudo when it is available.
set -euo pipefail

packages=(
  g++ make cmake pkg-config git         # toolchain
  petsc-dev slepc-dev                   # PETSc 3.18 (OpenMPI, HDF5, MUMPS, SuiteSparse) and SLEPc
  libopenblas0-serial                   # optimized BLAS for CHOLMOD/MUMPS (8x faster factorizations than the reference BLAS)
  libmetis-dev                          # graph partitioning of meshes (and of the coarse problem)
  libsuitesparse-dev                    # CHOLMOD's headers (PETSc's dependency; the split coarse solve calls it directly)
  libhdf5-openmpi-dev                   # hdf5.h for PETSc's HDF5 viewer (the HDF5 + XDMF output); PETSc links this HDF5
  openmpi-bin                           # mpiexec for the parallel tests
  clang-format                          # style check (a test)
  python3 python3-numpy python3-h5py    # result checks and benchmark tables
  gmsh python3-gmsh                     # meshes of your own geometry (meshes/*.geo); the mesh-file tests make theirs at test time
  python3-matplotlib                    # the figures of docs/ (scripts/figures.sh, scripts/bench-hertz.py, scripts/bench-peers.py)
)

missing=()
for p in "${packages[@]}"; do
  [[ "$p" == \#* ]] && continue
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then missing+=("$p"); fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} Debian packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
  run() { "$@"; }
elif command -v sudo >/dev/null 2>&1; then
  run() { sudo "$@"; }
else
  echo "setup: missing packages (${missing[*]}) and not root; install them as root with apt-get" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
run apt-get update -q
run apt-get install -y -q --no-install-recommends "${missing[@]}"
