#!/usr/bin/env bash
# CPU seconds (user+sys) of each translation unit of the command-line tool, built cold (no
# ccache) in a fresh build folder configured as scripts/run-example.sh configures build/ after
# `install-dependencies.sh --minimal` (no PETSc, no SuiteSparse, SuperLU or METIS). Wall time on
# a shared machine says little; CPU seconds / 2 estimates the wall time on a free 2-core machine.
# Prints "seconds file" per unit, largest first, then the total.
#
#   bench/cold-build-cpu.sh BUILD_DIR [CMAKE_ARGS…]    (BUILD_DIR is removed first; e.g.
#                                                       -DTESSERA_UNITY_BUILD=OFF)
set -euo pipefail
root=$(realpath "$(dirname "$0")/..")
build=$1
shift
rm -rf "$build"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DTESSERA_BUILD_TESTS=OFF \
  -DTESSERA_USE_PETSC=OFF -DTESSERA_USE_SUITESPARSE=OFF -DTESSERA_USE_SUPERLU=OFF \
  -DTESSERA_USE_METIS=OFF -DTESSERA_BUILD_PYTHON=OFF \
  -DCMAKE_CXX_COMPILER_LAUNCHER="$root/bench/cpu-time-launcher.sh" "$@" >/dev/null
log=$(realpath "$build")/cold-cpu.txt
: >"$log"
TESSERA_CPU_LOG=$log nice ninja -C "$build" -j 2 tessera_cli >/dev/null
sed -E "s@ $root/@ @; s@ $(realpath "$build")/@ @" "$log" | sort -rn
awk '{ s += $1 } END { printf "total %.0f CPU seconds, %d units\n", s, NR }' "$log"
