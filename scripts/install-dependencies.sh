#!/usr/bin/env bash
# Installs the Debian packages tessera needs, only those that are missing, with apt-get (as root,
# or with sudo when run as another user).
#
#   scripts/install-dependencies.sh [--minimal] [PACKAGE...]
#
# --minimal: only what the command-line tool needs (scripts/run-example.sh): on a fresh Debian 12
#            about 175 packages with their dependencies, 140 MB to download (the full set below
#            is about 500 and 460 MB). Without it: everything, for the library, the CLI, the
#            Python module, the PETSc backend, the tests and the benchmarks (scripts/build.sh,
#            scripts/run-tests.sh).
# PACKAGE:   more packages that a script needs besides (scripts/run-fuzzers.sh: clang and its
#            libFuzzer runtime).
set -euo pipefail
minimal=false
if [ "${1:-}" = "--minimal" ]; then
  minimal=true
  shift
fi

# The command-line tool (scripts/run-example.sh), all required by CMakeLists.txt:
# cmake, ninja-build, g++, pkg-config: the build (pkg-config finds cairo, PETSc and SLEPc).
# libeigen3-dev: all linear algebra. nlohmann-json3-dev: the JSON summary, problem files.
# libcli11-dev: the CLI's options. libspectra-dev: shift-invert Lanczos/Arnoldi (header-only)
# for the stability of steady states at large n (src/tessera/methods/stability).
# libcgal-dev: the Delaunay triangulation of `tessera ddt` (methods/planar/delaunay.cpp; it
# brings GMP, MPFR and Boost's headers).
# libcairo2-dev: pictures (`tessera render`, `mesh --picture`), PNG and SVG from one drawing.
# ccache: optional; rebuilds after a `git pull` or a switch of branch take seconds.
cli_packages=(cmake ninja-build g++ pkg-config libeigen3-dev nlohmann-json3-dev libcli11-dev
              libspectra-dev libcgal-dev libcairo2-dev ccache)

# Everything else, all optional to CMakeLists.txt (found when installed):
# libsuitesparse-dev (UMFPACK, KLU) and libsuperlu-dev: sparse LU solvers for large n
# (core/sparse_lu.h); without them the build falls back to Eigen's SparseLU. libmetis-dev: the
# nested-dissection ordering of Eigen's SparseLU (half the fill of COLAMD on 2-D PDEs).
# petsc-dev (with Open MPI, MUMPS, SuperLU_dist, hypre): the PETSc backend for problems beyond one
# machine (src/tessera/petsc, docs/cluster.md); about 100 packages, 90 s to install.
# slepc-dev (3.18, built on petsc-dev 3.18): the eigenvalues of `mesh --stability` on the PETSc
# backend (shift-invert Krylov-Schur on the ranks, src/tessera/petsc/petsc_stability.cpp).
# python3-dev, python3-pybind11, python3-numpy: the Python module (python/, docs/python.md) for
# Debian's /usr/bin/python3; python3-venv, python3-setuptools: `pip install .` into a virtual
# environment (docs/python.md).
# libgtest-dev, python3-pytest, python3-scipy: the tests (ctest, python/tests).
# python3-meshio: tests/io/meshio_test.cpp checks that meshio reads the PLY files tessera writes.
# python3-numpy: tests/io/npy_test.cpp and tests/app/view_cli_test.cpp check that numpy.load reads
# the .npy states tessera writes (meshio depends on it too).
# libbenchmark-dev: the benchmarks (bench/, -DTESSERA_BUILD_BENCHMARKS=ON).
other_packages=(libsuitesparse-dev libsuperlu-dev libmetis-dev petsc-dev slepc-dev python3-dev
                python3-pybind11 python3-numpy python3-venv python3-setuptools libgtest-dev
                python3-pytest python3-scipy python3-meshio libbenchmark-dev)

packages=("${cli_packages[@]}")
$minimal || packages+=("${other_packages[@]}")
packages+=("$@")

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
    missing+=("$package")
done
[ ${#missing[@]} -gt 0 ] || exit 0

if ! command -v apt-get >/dev/null; then
  echo "tessera: no apt-get (not Debian?); install these packages or their equivalents:" >&2
  echo "  ${missing[*]}" >&2
  exit 1
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  if ! command -v sudo >/dev/null; then
    echo "tessera: installing ${missing[*]} needs root: run this as root, or install sudo" >&2
    exit 1
  fi
  sudo="sudo"
fi
# The minimal set leaves out what the packages only recommend (a third fewer packages: no
# documentation tools, no X server fonts); the full set keeps the recommendations it was
# tested with.
apt_options=(-y -qq)
$minimal && apt_options+=(--no-install-recommends)
$sudo apt-get update -qq
total=$(apt-get install -s "${apt_options[@]}" "${missing[@]}" 2>/dev/null |
        grep -c '^Inst' || true)
echo "tessera: installing ${#missing[@]} missing package(s), ${total} with their dependencies" \
     "(${missing[*]})…"
DEBIAN_FRONTEND=noninteractive $sudo apt-get install "${apt_options[@]}" "${missing[@]}" >/dev/null
