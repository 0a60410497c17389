#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the benchmarks in build-bench (Release), runs them all and writes bench/results/:
#   front.json       BM_Front_* (median of 3 repetitions)      Google Benchmark JSON
#   corrector.json   BM_Factor_*, BM_Chord_*, BM_GaussNewton_*   Google Benchmark JSON
#   memory.json      tessera_front_memory, one fresh process per run
# and prints the tables of bench/RESULTS.md. Run it on a quiet machine: the load average is
# printed first and recorded in each JSON file's "context".
#
#     bench/run.sh                 everything (about two minutes on 2 cores)
#     bench/run.sh --quick         one repetition, shorter minimum times (a smoke test)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build-bench"
results="$root/bench/results"
repetitions=3
min_time=0.5
if [[ "${1:-}" == "--quick" ]]; then
  repetitions=1
  min_time=0.05
fi

cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DTESSERA_BUILD_BENCHMARKS=ON -DTESSERA_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" --target tessera_bench tessera_front_memory
mkdir -p "$results"

echo "== machine: $(nproc) cores; $(uptime)"
echo "== tree: $(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet -- src || echo ' + uncommitted changes in src/')"

bench="$build/bench/tessera_bench"
"$bench" --benchmark_filter='^BM_Front_' \
  --benchmark_repetitions="$repetitions" --benchmark_report_aggregates_only=true \
  --benchmark_min_time="$min_time" \
  --benchmark_out="$results/front.json" --benchmark_out_format=json
"$bench" --benchmark_filter='^BM_(Factor|Chord|GaussNewton)_' \
  --benchmark_min_time="$min_time" \
  --benchmark_out="$results/corrector.json" --benchmark_out_format=json

# Peak memory: one fresh process per (problem, step), since VmHWM never decreases.
memory_runs=()
for problem in sphere sphere_cut; do
  for step in 0.05 0.025 0.0125; do
    memory_runs+=("$("$build/bench/tessera_front_memory" "$problem" "$step")")
  done
done
printf '%s\n---\n' "${memory_runs[@]}" | python3 -c '
import json, sys
runs = []
for block in sys.stdin.read().split("---"):
    fields = dict(line.split(None, 1) for line in block.strip().splitlines() if line.strip())
    if fields:
        runs.append(fields)
json.dump({"runs": runs}, sys.stdout, indent=1)
' >"$results/memory.json"

python3 - "$results" <<'PYTHON'
import json, sys, os
results = sys.argv[1]

def load(name):
    with open(os.path.join(results, name)) as f:
        return json.load(f)

print("\n## Front: vertices per second (median of repetitions; CPU time)\n")
print("| benchmark | h | vertices | time (ms) | vertices/s | F evals/vertex | DF evals/vertex | mesh bytes/vertex |")
print("|---|---|---|---|---|---|---|---|")
for b in load("front.json")["benchmarks"]:
    if b.get("aggregate_name", "median") != "median" or "error_occurred" in b:
        if "error_occurred" in b:
            print(f"| {b['run_name']} | | | | ERROR: {b.get('error_message', '')} | | | |")
        continue
    name, arg = b["run_name"].split("/")
    h = int(arg.split(":")[1]) / 1000
    print(f"| {name} | {h:g} | {b['vertices']:.0f} | {b['cpu_time']:.2f} | "
          f"{b['vertices_per_second']:,.0f} | {b['F_evals_per_vertex']:.2f} | "
          f"{b['DF_evals_per_vertex']:.2f} | {b['bytes_per_vertex']:.1f} |")

print("\n## Correctors (CPU time; exponent p of time ∝ N^p against the previous N)\n")
print("| benchmark | N | time | time / n | p | corrector iterations | per factorisation |")
print("|---|---|---|---|---|---|---|")
import math
previous = {}
scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
for b in load("corrector.json")["benchmarks"]:
    family, _, arg = b["name"].partition("/")
    if "error_occurred" in b:
        print(f"| {family} | {arg.partition(':')[2]} | ERROR: {b.get('error_message', '')} | | | | |")
        continue
    seconds = b["cpu_time"] * scale[b["time_unit"]]
    size = int(arg.split(":")[1]) if arg.startswith("N:") else None
    per_unknown = f"{1e9 * seconds / (size + 2):.0f} ns" if size else ""
    exponent = ""
    if size and family in previous:
        previous_size, previous_seconds = previous[family]
        exponent = f"{math.log(seconds / previous_seconds) / math.log(size / previous_size):.2f}"
    if size:
        previous[family] = (size, seconds)
    per_factorisation = b.get("seconds_per_factorisation")
    iterations = b.get("corrector_iterations")
    print(f"| {family} | {size or arg} | {b['cpu_time']:.3g} {b['time_unit']} | {per_unknown} | "
          f"{exponent} | {'' if iterations is None else f'{iterations:.0f}'} | "
          + (f"{1e3 * per_factorisation:.3g} ms" if per_factorisation else "") + " |")

print("\n## Front: peak memory (fresh process per row)\n")
print("| problem | h | vertices | wall (s) | vertices/s | peak bytes/vertex | mesh bytes/vertex |")
print("|---|---|---|---|---|---|---|")
for r in load("memory.json")["runs"]:
    print(f"| {r['problem']} | {r['step']} | {r['vertices']} | {r['wall_seconds']} | "
          f"{float(r['vertices_per_second']):,.0f} | {r['peak_bytes_per_vertex']} | "
          f"{r['mesh_bytes_per_vertex']} |")
PYTHON
