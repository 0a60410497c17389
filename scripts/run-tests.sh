#!/usr/bin/env bash
# Builds tessera with its tests and runs the whole suite with ctest, then the Python tests
# (python/tests, pytest) against the module in build/python, then the docs check (every example
# of the README and docs/ that is not marked slow runs as written: scripts/check-docs.py).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh -DTESSERA_BUILD_TESTS=ON
# ctest runs one test per core: each on one thread (TESSERA_THREADS), unless a test sets its own
# count (the thread tests do), so that tests do not wait at each other's barriers.
(cd build && TESSERA_THREADS=1 ctest --output-on-failure --parallel "$(nproc)" --timeout 900)
# Debian's interpreter, for which the module is built: python3 on PATH may be another one.
if [ -d build/python/tessera ]; then
  PYTHONPATH="$PWD/build/python" /usr/bin/python3 -m pytest python/tests -q
  /usr/bin/python3 scripts/check-docs.py
else
  echo "tessera: the Python module was not built (no python3-dev or python3-pybind11)" >&2
  exit 1
fi
