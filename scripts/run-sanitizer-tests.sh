#!/usr/bin/env bash
# Builds tessera, its CLI and its tests with AddressSanitizer (with LeakSanitizer) and
# UndefinedBehaviorSanitizer in build-asan/ and runs the whole suite with ctest. Any sanitizer
# report fails the test that caused it, also when it comes from a CLI run that a test spawned.
# Extra arguments go to cmake configure. See docs/testing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-dependencies.sh
# -O1: about half the test time of -O0 (Debug) and no optimisation that hides an error from the
# sanitizers; -g1: line tables for the stack traces at a fraction of -g's compile time. NDEBUG
# stays off, so Eigen's index and shape assertions are checked too.
# SuperLU 5 (Debian) leaks in sp_preorder and calls BLAS with invalid arguments when a matrix
# is singular (found by this build); it is an optional solver that is never the default, so the
# sanitizer build leaves it out rather than suppress a library's leak. The Python module is left
# out too: an ASan-instrumented extension cannot load into Debian's uninstrumented python3. So is
# the PETSc backend: Open MPI's start-up keeps its allocations to the end by design, and PETSc and
# MUMPS are not instrumented; its tests run in the normal build, on 1 and 2 ranks.
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DTESSERA_SANITIZE=address,undefined \
  -DTESSERA_BUILD_TESTS=ON -DTESSERA_USE_SUPERLU=OFF -DTESSERA_BUILD_PYTHON=OFF -DTESSERA_USE_PETSC=OFF "$@" >/dev/null
cmake --build build-asan --parallel "$(nproc)"

# Exported, so that the CLI processes the tests spawn run with the same options. exitcode 86 sets
# a sanitizer's exit apart from tessera's own 0, 1 and 2. The caller's options come last and win.
sanitizer_exit=86
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:exitcode=${sanitizer_exit}:print_stacktrace=1:\
check_initialization_order=1:strict_init_order=1:detect_stack_use_after_return=1\
${ASAN_OPTIONS:+:${ASAN_OPTIONS}}"
# fontconfig's process-lifetime cache (cairo's text) is the one leak suppressed: see the file.
export LSAN_OPTIONS="suppressions=$(pwd)/tests/sanitizers/lsan.supp:print_suppressions=0\
${LSAN_OPTIONS:+:${LSAN_OPTIONS}}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:exitcode=${sanitizer_exit}\
${UBSAN_OPTIONS:+:${UBSAN_OPTIONS}}"
# The longest tests repeat at a larger size what faster ones exercise: they run in the normal
# build only (tests/sanitizers/long_tests.txt says which and why), unless TESSERA_SANITIZE_ALL=1.
exclude=()
if [ "${TESSERA_SANITIZE_ALL:-0}" != 1 ]; then
  names=$(grep -v -E '^(#|$)' tests/sanitizers/long_tests.txt | sed 's/[.]/[.]/g' | paste -sd'|')
  exclude=(-E "^(${names})\$")
fi
cd build-asan
# One thread per test, as in scripts/run-tests.sh (tests that set their own count keep it).
TESSERA_THREADS=1 ctest --output-on-failure --parallel "$(nproc)" --timeout 1800 "${exclude[@]}"
