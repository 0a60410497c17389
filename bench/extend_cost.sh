#!/usr/bin/env bash
# What `tessera extend` saves (issue 32): a covering of a small box with --checkpoint, its
# extension to a larger box, and a fresh covering of the larger box, side by side: charts,
# vertices, area and each step's factorisations (docs/checkpoints.md, "Extending").
#
# Usage: bench/extend_cost.sh PROBLEM SMALL_BOX LARGE_BOX [-- MESH OPTIONS ...]
# Example: bench/extend_cost.sh bvp:points=200 lambda=2:6 lambda=0:6
# Prints a Markdown table.
set -euo pipefail
cd "$(dirname "$0")/.."
problem=$1 small=$2 large=$3
shift 3
[ "${1:-}" = "--" ] && shift
tessera=${TESSERA:-build/tessera}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$tessera" mesh "$problem" --box "$small" "$@" --checkpoint "$work/run.tsc" -q \
  -o "$work/small.ply" --summary "$work/small.json" || true
/usr/bin/time -f %e -o "$work/extend.time" "$tessera" extend "$work/run.tsc" --box "$large" -q \
  -o "$work/extended.ply" --summary "$work/extended.json" || true
/usr/bin/time -f %e -o "$work/fresh.time" "$tessera" mesh "$problem" --box "$large" "$@" \
  --checkpoint "$work/fresh.tsc" -q -o "$work/fresh.ply" --summary "$work/fresh.json" || true
echo "\`bench/extend_cost.sh $problem $small $large -- $*\`, $(date -u +%Y-%m-%d), $(git rev-parse --short HEAD)"
echo
python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
print("| run | valid | χ | charts | vertices | area | factorisations: build / clip / refine / validate | wall s |")
print("|---|---|---|---|---|---|---|---|")
for name, label in (("small", "small box"), ("extended", "extended"), ("fresh", "fresh, large box")):
    s = json.load(open(f"{work}/{name}.json"))
    r = s["run"]
    phases = {p["phase"]: p["factorisations"] for p in r["work_by_phase"]}
    try:
        wall = open(f"{work}/{'extend' if name == 'extended' else name}.time").read().strip()
    except OSError:
        wall = ""
    print(f"| {label} | {s['valid']} | {s['topology']['euler_characteristic']} | "
          f"{r['atlas']['charts']} | {s['counts']['vertices']} | {s['shape']['area']:.5g} | "
          f"{' / '.join(str(phases.get(p, 0)) for p in ('build', 'clip', 'refine', 'validate'))} | "
          f"{wall} |")
PY
