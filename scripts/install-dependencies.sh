#!/usr/bin/env bash
# Installs the Debian packages tessera needs, only those that are missing. Arguments name more
# packages that a script needs besides (scripts/run-fuzzers.sh: clang and its libFuzzer runtime).
set -euo pipefail
# python3-meshio: tests/io/meshio_test.cpp checks that meshio reads the PLY files tessera writes.
# libsuitesparse-dev (UMFPACK, KLU) and libsuperlu-dev: sparse LU solvers for large n
# (core/sparse_lu.h); without them the build falls back to Eigen's SparseLU. libmetis-dev: the
# nested-dissection ordering of Eigen's SparseLU (half the fill of COLAMD on 2-D PDEs).
# python3-numpy: tests/io/npy_test.cpp and tests/app/view_cli_test.cpp check that numpy.load reads
# the .npy states tessera writes (meshio depends on it too).
# libspectra-dev: shift-invert Lanczos/Arnoldi (header-only) for the stability of steady states
# at large n (src/tessera/methods/stability).
# libcairo2-dev: pictures (`tessera render`, `mesh --picture`), PNG and SVG from one drawing.
# petsc-dev (with Open MPI, MUMPS, SuperLU_dist, hypre): the PETSc backend for problems beyond one
# machine (src/tessera/petsc, docs/cluster.md); about 100 packages, 90 s to install.
# slepc-dev (3.18, built on petsc-dev 3.18): the eigenvalues of `mesh --stability` on the PETSc
# backend (shift-invert Krylov-Schur on the ranks, src/tessera/petsc/petsc_stability.cpp).
# python3-dev, python3-pybind11, python3-pytest, python3-scipy: the Python module (python/,
# docs/python.md) for Debian's /usr/bin/python3, and its tests.
packages=(cmake ninja-build g++ libeigen3-dev libcli11-dev nlohmann-json3-dev libgtest-dev
          libbenchmark-dev ccache libcgal-dev python3-meshio python3-numpy libsuitesparse-dev
          libsuperlu-dev libmetis-dev libspectra-dev python3-dev python3-pybind11 python3-pytest python3-scipy libcairo2-dev petsc-dev slepc-dev
          "$@")
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
    missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "tessera: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi
