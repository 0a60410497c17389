#!/usr/bin/env bash
# Issue 35: the atlas's work at both ends, two binaries side by side in one run. For each problem
# and binary: evaluations of F, of DF and factorisations per vertex (deterministic), vertices,
# the covering's wall time and its build step (the summary's timing), interleaved so that both
# binaries see the same load. Small n: sphere, torus, equipotential at --tolerance 1e-3; large n:
# bvp:points=1000 and bratu2d:N=32 at the command line's defaults.
# Usage: bench/atlas_both_ends.sh BEFORE AFTER [REPEATS]   (binaries of tessera; REPEATS of the
#        small-n runs, default 3, the smallest time kept). Prints a Markdown table.
#        SMALL="…" and LARGE="…" replace the problem lists (LARGE="" leaves large n out).
set -euo pipefail
before=$1
after=$2
repeats=${3:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
row() {  # problem, label, binary, repeats, extra arguments...
  local problem=$1 label=$2 binary=$3 count=$4
  shift 4
  local best=""
  for ((k = 0; k < count; ++k)); do
    "$binary" mesh "$problem" "$@" -o "$work/m.ply" --summary "$work/$label.json" >/dev/null 2>&1
    best=$(/usr/bin/python3 - "$work/$label.json" "$best" <<'PY'
import json, sys
run = json.load(open(sys.argv[1]))["run"]
build = sum(p["wall_seconds"] for p in run["work_by_phase"] if p["phase"] == "build")
now = (run["wall_seconds"], build)
best = sys.argv[2]
if best:
    old = tuple(float(v) for v in best.split())
    now = min(now, old)
print(f"{now[0]:.3f} {now[1]:.3f}")
PY
)
  done
  /usr/bin/python3 - "$work/$label.json" "$problem $*" "$label" "$best" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
run = d["run"]
v = run["per_vertex"]
vertices = round(run["function_evaluations"] / v["function_evaluations"])
covering, build = sys.argv[4].split()
print(f"| {sys.argv[2]} | {sys.argv[3]} | {v['function_evaluations']:.1f} | "
      f"{v['jacobian_evaluations']:.2f} | {v['factorisations']:.2f} | {vertices} | "
      f"{covering} | {build} |")
PY
}
echo "\`bench/atlas_both_ends.sh\`, $(date -u +%Y-%m-%dT%H:%MZ), load $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| problem | binary | F/vertex | DF/vertex | factorisations/vertex | vertices | covering s | build s |"
echo "|---|---|---|---|---|---|---|---|"
for problem in ${SMALL:-sphere torus equipotential}; do
  for label in before after; do
    binary=$before
    [ "$label" = after ] && binary=$after
    row "$problem" "$label" "$binary" "$repeats" --tolerance 1e-3
  done
done
for problem in ${LARGE-bvp:points=1000 bratu2d:N=32}; do
  for label in before after; do
    binary=$before
    [ "$label" = after ] && binary=$after
    row "$problem" "$label" "$binary" 1
  done
done
