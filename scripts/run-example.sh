#!/usr/bin/env bash
# Covers the cut sphere of Brodzik & Rheinboldt's figure 5.1 with the default method (atlas) to
# within 1e-3 of M: writes out/sphere_cut.ply and out/sphere_cut.json and prints the report.
#
# The shortest way to a first mesh: it installs only the Debian packages the command-line tool
# needs (scripts/install-dependencies.sh --minimal) and builds only the tool, build/tessera,
# without the tests, the Python module or the PETSc backend. It uses build/, the folder of
# scripts/build.sh and scripts/run-tests.sh, so that the README's `build/tessera` commands work
# next: a fresh build/ is configured without the tests, an existing one is left as it is
# (`--target tessera_cli` builds no test either way). scripts/run-tests.sh later installs the
# rest and configures build/ with the tests; CMake then finds what was missing (PETSc, pybind11,
# the sparse solvers), so the two share the folder without undoing each other.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-dependencies.sh --minimal
if [ ! -f build/CMakeCache.txt ]; then
  echo "tessera: configuring build/ (Release, without the tests)…"
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DTESSERA_BUILD_TESTS=OFF >/dev/null
fi
# 439 CPU-seconds with an empty ccache (bench/cold-build-cpu.sh), about 225 s on 2 cores. The
# terminal shows Ninja's progress only; the compiler's output goes to a log (GCC 12 warns falsely
# about some std::string code, GCC bug 105651, which would be a first user's only sight of the
# build).
echo "tessera: building the command-line tool build/tessera (the first time about 4 minutes on" \
     "2 cores, then seconds)…"
log=build/run-example-build.log
if ! cmake --build build --target tessera_cli --parallel "$(nproc)" 2>&1 | tee "$log" |
     awk '/^\[[0-9]+\/[0-9]+\]/ { printf "\r  %s", $1; fflush() } END { print "" }'; then
  tail -n 40 "$log" >&2
  echo "tessera: the build failed; its whole output is in $log" >&2
  exit 1
fi
mkdir -p out
echo "tessera: covering the cut sphere (about a second)…"
build/tessera mesh sphere_cut --tolerance 1e-3 -o out/sphere_cut.ply \
  --summary out/sphere_cut.json
