#!/usr/bin/env bash
# Large n (issue 9): covers the discretised PDE problems of the catalogue and prints, per run,
# the work per vertex (factorisations, Jacobians, evaluations of F: deterministic), the time
# per vertex against the mean time of one factorisation in the same run (DF evaluation, border,
# analysis and factorisation, as the run measures it) and the peak memory (GNU time), also
# less the atlas's open boundary at its largest (kept factorisations and tangent bases, which
# issue 9's bound allows beside 1.5 × 8n bytes per vertex), and the run's own sample of that
# (run.memory: the resident memory less the boundary held at the same moment, the largest of
# the samples taken every 64 charts and between stages). Writes bench/results/large_n.md.
# Usage: bench/large_n.sh [PROBLEM ...]   (default: bvp at N = 10², 10³, 10⁴ and bratu2d at
#        N = 10, 32; add bvp:points=100000 bratu2d:N=100 bratu2d:N=316 for the full table)
# Needs build/tessera (scripts/build.sh; TESSERA=path runs another binary) and /usr/bin/time.
set -euo pipefail
cd "$(dirname "$0")/.."
problems=("$@")
if [ ${#problems[@]} -eq 0 ]; then
  problems=(bvp:points=100 bvp:points=1000 bvp:points=10000 bratu2d:N=10 bratu2d:N=32)
fi
methods=${METHODS:-atlas front bezier}
tessera=${TESSERA:-build/tessera}
mkdir -p bench/results
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
{
  echo "# Large n: work, time and memory per vertex"
  echo
  echo "\`bench/large_n.sh ${problems[*]}\` (METHODS=\"$methods\"), $(date -u +%Y-%m-%d), $(git rev-parse --short HEAD), load $(cut -d' ' -f1-3 /proc/loadavg)"
  echo
  echo "| problem | n | method | vertices | pipeline s | ms/vertex | one factorisation ms | ms/vertex ÷ one factorisation | factorisations/vertex | Jacobians/vertex | F/vertex | peak MB | peak bytes / (8n·vertices) | (peak − boundary) / (8n·vertices) | sampled resident beyond the boundary / (8n·vertices) | completed |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for problem in "${problems[@]}"; do
    for method in $methods; do
      /usr/bin/time -f "%M" -o "$work/time" "$tessera" mesh "$problem" --method "$method" \
        -q -o "$work/mesh.ply" --summary "$work/summary.json" || true
      peak_kb=$(tail -1 "$work/time")
      /usr/bin/python3 - "$problem" "$method" "$peak_kb" "$work/summary.json" <<'PY'
import json, sys
problem, method, peak_kb, path = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
s = json.load(open(path))
r = s["run"]
V = max(1, s["counts"]["vertices"])
n = s["ambient_dimension"]
per = r.get("per_vertex", {})
one = r["factorisation_seconds"] / max(1, r["factorisations"])
print(f"| {problem} | {n} | {method} | {V} | {r['wall_seconds']:.1f} | "
      f"{1000 * r['wall_seconds'] / V:.2f} | {1000 * one:.3f} | "
      f"{per.get('factorisations_worth', float('nan')):.1f} | {per.get('factorisations', 0):.2f} | "
      f"{per.get('jacobian_evaluations', 0):.2f} | {per.get('function_evaluations', 0):.1f} | "
      f"{peak_kb / 1024:.0f} | {peak_kb * 1024 / (8 * n * V):.1f} | "
      f"{(peak_kb * 1024 - r.get('atlas', {}).get('boundary_peak_bytes', 0.0)) / (8 * n * V):.1f} | "
      f"{r.get('memory', {}).get('beyond_boundary_per_state', float('nan')):.2f} | "
      f"{r['completed']} |")
PY
    done
  done
} | tee bench/results/large_n.md
