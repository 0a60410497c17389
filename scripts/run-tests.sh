#!/usr/bin/env bash
# Builds tessera with its tests and runs the whole suite with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh -DTESSERA_BUILD_TESTS=ON
cd build
ctest --output-on-failure --parallel "$(nproc)" --timeout 900
