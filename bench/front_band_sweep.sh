#!/usr/bin/env bash
# The front on the PDE problems' bands (issue 9): bvp:points=30 and bratu2d:N=8, steps 0.15 to
# 0.7, default region. Prints one line per run: exit code, whether the mesh is valid, the run
# completed, χ, the vertex count, and the first words of the failure. Every run must be valid
# (completed or a clean, reported failure).
# Usage: bench/front_band_sweep.sh [TESSERA]   (default build/tessera)
set -uo pipefail
cd "$(dirname "$0")/.."
tessera=${1:-build/tessera}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for problem in bvp:points=30 bratu2d:N=8; do
  for step in 0.15 0.2 0.25 0.3 0.35 0.4 0.45 0.5 0.55 0.6 0.7; do
    output=$(timeout 300 "$tessera" mesh "$problem" --method front --step "$step" \
      -o "$work/mesh.ply" --summary "$work/summary.json" 2>&1)
    code=$?
    facts=$(/usr/bin/python3 -c "import json; d = json.load(open('$work/summary.json')); \
print(d['valid'], d['run']['completed'], d['topology']['euler_characteristic'], d['counts']['vertices'])" 2>/dev/null)
    failure=$(echo "$output" | grep -o "stopped early ([a-z ]*)" | head -1)
    echo "$problem step $step: exit $code, valid/completed/χ/vertices $facts ${failure}"
    rm -f "$work/summary.json"
  done
done
