#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz (clang, with AddressSanitizer and
# UndefinedBehaviorSanitizer) in build-fuzz/ and runs each for a bounded time, starting from its
# seed corpus tests/fuzz/corpus/<target>/. Fails if any target finds a crash, a leak, a timeout,
# an out-of-memory or a sanitizer report; the input that did it is kept in
# build-fuzz/artifacts/<target>/ (reproduce: build-fuzz/tests/fuzz/<target>_fuzz <file>).
#
# Usage: scripts/run-fuzzers.sh [seconds per target, default 60] [target ...]
#   e.g. scripts/run-fuzzers.sh 300 ply problem_file
# New inputs that reach new code go to build-fuzz/corpus/<target>/, so a second run continues
# where the first stopped; the seeds in the repository are never changed. See docs/testing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
# clang-14 is Debian 12's clang; libclang-rt-dev holds its libFuzzer runtime (libclang_rt.fuzzer).
scripts/install-dependencies.sh clang libclang-rt-dev
# File by file (no unity build): the one build in CI that compiles each file on its own, so that a
# file that uses what only its batch-mates include fails here, not on a developer's machine.
cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DTESSERA_SANITIZE=address,undefined \
  -DTESSERA_UNITY_BUILD=OFF \
  -DTESSERA_BUILD_FUZZERS=ON -DTESSERA_BUILD_TESTS=OFF -DTESSERA_BUILD_PYTHON=OFF -DTESSERA_USE_PETSC=OFF >/dev/null
cmake --build build-fuzz --target fuzzers --parallel "$(nproc)"

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for source in tests/fuzz/*_fuzz.cpp; do
    name="$(basename "$source")"
    targets+=("${name%_fuzz.cpp}")
  done
fi

export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:print_stacktrace=1${ASAN_OPTIONS:+:${ASAN_OPTIONS}}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:${UBSAN_OPTIONS}}"

# One target: libFuzzer exits non-zero on a crash, leak, timeout (-timeout s for one input),
# out-of-memory (-rss_limit_mb, -malloc_limit_mb) or sanitizer report, and 0 when the time is up.
run_target() {
  local target="$1"
  local seeds="tests/fuzz/corpus/${target}"
  local corpus="build-fuzz/corpus/${target}"
  local artifacts="build-fuzz/artifacts/${target}/"
  local options=(-max_total_time="${seconds}" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024
                 -print_final_stats=1 -artifact_prefix="${artifacts}")
  [ -f "tests/fuzz/${target}.dict" ] && options+=(-dict="tests/fuzz/${target}.dict")
  [ -d "${seeds}" ] || { echo "fuzz ${target}: no seed corpus ${seeds}"; return 1; }
  mkdir -p "${corpus}" "${artifacts}"
  "build-fuzz/tests/fuzz/${target}_fuzz" "${options[@]}" "${corpus}" "${seeds}" \
    >"build-fuzz/${target}.log" 2>&1
}

# As many targets at a time as there are cores; each writes its own log and exit status.
for target in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do
    wait -n || true
  done
  rm -f "build-fuzz/${target}.status"
  (
    status=0
    run_target "${target}" || status=$?
    echo "${status}" >"build-fuzz/${target}.status"
  ) &
done
wait
failed=()
for target in "${targets[@]}"; do
  if [ "$(cat "build-fuzz/${target}.status" 2>/dev/null)" = "0" ]; then
    runs="$(grep -o 'stat::number_of_executed_units: [0-9]*' "build-fuzz/${target}.log" |
            grep -o '[0-9]*$' || echo '?')"
    echo "fuzz ${target}: ok, ${runs} inputs in ${seconds} s"
  else
    failed+=("${target}")
    echo "fuzz ${target}: FAILED (log build-fuzz/${target}.log, input in build-fuzz/artifacts/${target}/)"
    tail -n 60 "build-fuzz/${target}.log"
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzzers that found a bug: ${failed[*]}"
  exit 1
fi
