#!/usr/bin/env bash
# The full randomized stress campaign (issue 10): every surface × method of tessera_stress with
# random starts, steps and tolerances; writes bench/results/stress.md.
# Usage: bench/stress.sh [CASES [SEED]]   (defaults: 1120 cases, seed 2026)
# Needs a build with -DTESSERA_BUILD_TESTS=ON (build/tests/tessera_stress).
set -uo pipefail
cd "$(dirname "$0")/.."
cases=${1:-1120}
seed=${2:-2026}
mkdir -p bench/results
command="nice build/tests/tessera_stress --cases $cases --seed $seed --max-seconds-per-case 300"
{
  echo "# Randomized stress campaign"
  echo
  echo "Command: \`$command\` ($(date -u +%Y-%m-%d), $(git rev-parse --short HEAD))"
  echo
  $command
  status=$?
  echo
  echo "exit code $status"
} > bench/results/stress.md 2>&1
tail -1 bench/results/stress.md
