#!/usr/bin/env bash
# Issue 35, "every core is used": the same command on 1 and on 2 (or more) threads, interleaved
# so that both see the same load. For each problem and thread count: the whole process's wall
# time (the median of the repeats), the covering's steps as the summary times them (build,
# refine, validate), and the rest of the process (the report's distances and the writing), and
# the check that the mesh file is the same bytes on every thread count.
# Usage: bench/threads.sh [BINARY] [REPEATS]   (default build/tessera, 3 repeats)
#        CASES="problem --options;…" replaces the list; THREADS="1 2" the thread counts.
# Default cases: sphere and torus at 1e-3, and the torus of about 10⁶ vertices (1.6e-5: about
# 3 minutes a run on the build machine; CASES without it for a quick look).
set -euo pipefail
binary=${1:-build/tessera}
repeats=${2:-3}
threads=${THREADS:-1 2}
cases=${CASES:-"sphere --tolerance 1e-3;torus --tolerance 1e-3;torus --tolerance 1.6e-5"}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "| case | threads | vertices | whole s (median) | build s | refine s | validate s | rest s | speed-up | same mesh |"
echo "|---|---|---|---|---|---|---|---|---|---|"
IFS=';' read -ra list <<<"$cases"
for arguments in "${list[@]}"; do
  read -ra words <<<"$arguments"
  for ((k = 0; k < repeats; ++k)); do
    for t in $threads; do
      start=$(date +%s.%N)
      "$binary" mesh "${words[@]}" --threads "$t" -q -o "$work/t$t.ply" \
        --summary "$work/t$t.$k.json"
      end=$(date +%s.%N)
      echo "$start $end" >"$work/t$t.$k.wall"
    done
  done
  /usr/bin/python3 - "$work" "$arguments" "$repeats" $threads <<'PY'
import filecmp, json, statistics, sys
work, arguments, repeats, counts = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4:]
first = None
for t in counts:
    walls = []
    for k in range(repeats):
        start, end = (float(v) for v in open(f"{work}/t{t}.{k}.wall").read().split())
        walls.append(end - start)
    wall = statistics.median(walls)
    k = sorted(range(repeats), key=lambda i: walls[i])[repeats // 2]  # the median run's steps
    run = json.load(open(f"{work}/t{t}.{k}.json"))["run"]
    steps = {p["phase"]: p["wall_seconds"] for p in run["work_by_phase"]}
    vertices = round(run["function_evaluations"] / run["per_vertex"]["function_evaluations"])
    rest = walls[k] - run["wall_seconds"]
    if first is None:
        first = wall
    same = filecmp.cmp(f"{work}/t{counts[0]}.ply", f"{work}/t{t}.ply", shallow=False)
    print(f"| `{arguments}` | {t} | {vertices} | {wall:.2f} | {steps.get('build', 0):.2f} | "
          f"{steps.get('refine', 0):.2f} | {steps.get('validate', 0):.2f} | {rest:.2f} | "
          f"{first / wall:.2f}× | {'yes' if same else 'NO'} |")
PY
done
