#!/usr/bin/env bash
# Fold curves and cusps (`tessera mesh --folds`, docs/algorithms/folds.md) of the Gelfand–Bratu
# problems as the grid is refined: the cusp's (λ, ε, max u), the fold points and their cost.
# Usage: bench/folds.sh [tessera binary] [problem ...]
#   default problems: bvp:points=100 bvp:points=1000 bvp:points=10000 bratu2d:N=32
# Prints a Markdown table (bench/RESULTS.md, "Fold curves and cusps"); the runs' files stay in a
# temporary folder.
set -euo pipefail
cd "$(dirname "$0")/.."
tessera="${1:-build/tessera}"
shift || true
problems=("$@")
[ ${#problems[@]} -gt 0 ] || problems=(bvp:points=100 bvp:points=1000 bvp:points=10000 bratu2d:N=32)
work="$(mktemp -d)"
echo "| problem | n | vertices | fold points | unrefined | cusp λ | cusp ε | cusp max u | largest \|F\| | factorisations / fold point | Jacobians / fold point | folds s | covering s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for problem in "${problems[@]}"; do
  name="$(echo "$problem" | tr ':=' '__')"
  "$tessera" mesh "$problem" --folds lambda,epsilon -q -o "$work/$name.ply" \
    --summary "$work/$name.json" --report-samples 50 || true
  /usr/bin/python3 - "$problem" "$work/$name.json" <<'PY'
import json, sys
problem, path = sys.argv[1], sys.argv[2]
d = json.load(open(path))
f, run = d["folds"], d["run"]
cusp = f["cusps"][0] if f["cusps"] else None
cell = lambda key, fmt: fmt % cusp["point"][key] if cusp else "–"
points = max(f["point_count"], 1)
print(f"| {problem} | {d['ambient_dimension']} | {d['counts']['vertices']} | {f['point_count']} | "
      f"{f['unrefined_points']} | {cell('lambda', '%.7f')} | {cell('epsilon', '%.7f')} | "
      f"{cell('max_u', '%.5f')} | {f['max_residual']:.1e} | "
      f"{f['work']['factorisations'] / points:.1f} | {f['work']['jacobian_evaluations'] / points:.1f} | "
      f"{f['seconds']:.2f} | {run['wall_seconds']:.1f} |")
PY
done
rm -rf "$work"
