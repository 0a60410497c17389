#!/usr/bin/env bash
# The cost of `tessera mesh --stability` (docs/algorithms/stability.md) beside the covering's:
# factorisations and solves per vertex, and the time against the covering's wall time (issue 31:
# at most half of it on bratu2d:N=100 and bvp:points=10000). cstr adds --hopf (dense).
# Usage: bench/stability.sh [tessera binary] [problem ...]
#   default problems: cstr bvp:points=1000 bvp:points=10000 bratu2d:N=100
# Prints a Markdown table (bench/RESULTS.md, "Stability"); the runs' files stay in a temporary
# folder.
set -euo pipefail
cd "$(dirname "$0")/.."
tessera="${1:-build/tessera}"
shift || true
problems=("$@")
[ ${#problems[@]} -gt 0 ] || problems=(cstr bvp:points=1000 bvp:points=10000 bratu2d:N=100)
work="$(mktemp -d)"
echo "| problem | n | vertices | method | vertices by index | factorisations / vertex | solves / vertex | stability s | covering s | stability / covering | Hopf curves s |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for problem in "${problems[@]}"; do
  name="$(echo "$problem" | tr ':=' '__')"
  extra=(--stability)
  [ "$problem" = cstr ] && extra=(--hopf)
  "$tessera" mesh "$problem" "${extra[@]}" -q -o "$work/$name.ply" \
    --summary "$work/$name.json" --report-samples 50 || true
  /usr/bin/python3 - "$problem" "$work/$name.json" <<'PY'
import json, sys
problem, path = sys.argv[1], sys.argv[2]
d = json.load(open(path))
s, run = d["stability"], d["run"]
v = max(s["vertices"], 1)
hopf = f"{d['hopf']['seconds']:.3f}" if "hopf" in d else "–"
print(f"| {problem} | {d['ambient_dimension']} | {s['vertices']} | {s['method']} | "
      f"{s['vertices_by_index']} | {s['factorisations'] / v:.2f} | {s['solves'] / v:.1f} | "
      f"{s['seconds']:.2f} | {run['wall_seconds']:.1f} | {s['seconds'] / run['wall_seconds']:.2f} | {hopf} |")
PY
done
rm -rf "$work"
