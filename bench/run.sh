#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the benchmarks in build-bench (Release), runs them all and writes bench/results/:
#   front.json       BM_Front_* (5 repetitions: mean, median, stddev, cv)   Google Benchmark JSON
#   corrector.json   BM_Factor_*, BM_FirstFactor_*, BM_Chord_*, BM_GaussNewton_* (3 repetitions)
#   memory.json      tessera_front_memory, one fresh process per run
#   tables.md        the tables printed at the end (bench/history/RESULTS-log.md sections 1–3)
# Run it on a quiet machine: the load average is printed before and after, and recorded in each
# JSON file's "context"; the CV column (stddev/mean of the repetitions) shows how noisy a row was.
#
#     bench/run.sh                 everything (about two minutes on 2 cores)
#     bench/run.sh --quick         one repetition, shorter minimum times (a smoke test; it
#                                  overwrites bench/results too)
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build-bench"
results="$root/bench/results"
front_repetitions=5
corrector_repetitions=3
min_time=0.5
if [[ "${1:-}" == "--quick" ]]; then
  front_repetitions=1
  corrector_repetitions=1
  min_time=0.05
fi

cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DTESSERA_BUILD_BENCHMARKS=ON -DTESSERA_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" --target tessera_bench tessera_front_memory tessera_atlas_scaling
mkdir -p "$results"

echo "== machine: $(nproc) cores; $(uptime)"
tree="$(git -C "$root" rev-parse --short HEAD)"
if ! git -C "$root" diff --quiet -- src; then
  tree="$tree + uncommitted src/ changes (git diff -- src | sha1sum: $(git -C "$root" diff -- src | sha1sum | cut -c1-12))"
fi
echo "== tree: $tree"

bench="$build/bench/tessera_bench"
"$bench" --benchmark_filter='^BM_Front_' \
  --benchmark_repetitions="$front_repetitions" --benchmark_report_aggregates_only=true \
  --benchmark_min_time="$min_time" \
  --benchmark_out="$results/front.json" --benchmark_out_format=json
# Correctors: one process per sparse size, so that a run that exhausts memory (Eigen's SparseLU
# can crash rather than throw when an allocation fails) loses only its own row.
corrector_parts="$results/corrector_parts"
rm -rf "$corrector_parts"
mkdir -p "$corrector_parts"
corrector_filters=('^BM_(Factor|Chord)_Dense')
for family in Factor FirstFactor GaussNewton Chord; do
  for size in 100 1000 10000 100000; do
    corrector_filters+=("^BM_${family}_Sparse_Bvp/N:${size}\$")
  done
done
part=0
for filter in "${corrector_filters[@]}"; do
  part=$((part + 1))
  output="$corrector_parts/$(printf '%02d' "$part").json"
  status=0
  "$bench" --benchmark_filter="$filter" \
    --benchmark_repetitions="$corrector_repetitions" --benchmark_report_aggregates_only=true \
    --benchmark_min_time="$min_time" \
    --benchmark_out="$output" --benchmark_out_format=json || status=$?
  if [[ $status -ne 0 ]]; then
    echo "$filter $status" >"$output.failed"
  fi
done
python3 - "$corrector_parts" >"$results/corrector.json" <<'PYTHON'
import glob, json, os, re, signal, sys
merged = {"context": None, "benchmarks": []}
parts = glob.glob(os.path.join(sys.argv[1], "*.json*"))
for path in sorted({p.removesuffix(".failed") for p in parts}):
    if os.path.exists(path + ".failed"):
        pattern, status = open(path + ".failed").read().rsplit(None, 1)
        status = int(status)
        why = (f"signal {signal.Signals(status - 128).name}" if status > 128 else f"exit {status}")
        name = re.sub(r"[\^$\\]", "", pattern)
        merged["benchmarks"].append({"name": name, "run_name": name, "error_occurred": True,
                                     "error_message": f"the benchmark process died ({why})"})
        continue
    with open(path) as f:
        part = json.load(f)
    merged["context"] = merged["context"] or part["context"]
    merged["benchmarks"].extend(part["benchmarks"])
json.dump(merged, sys.stdout, indent=1)
PYTHON
rm -rf "$corrector_parts"

# Peak memory: one fresh process per (problem, step), since VmHWM never decreases.
memory_runs=()
# h = 0.00625 (about 4·10⁵ vertices) also shows whether the cost per vertex grows with the mesh.
for run in "sphere 0.05" "sphere 0.025" "sphere 0.0125" "sphere 0.00625" \
  "sphere_cut 0.05" "sphere_cut 0.025" "sphere_cut 0.0125"; do
  read -r problem step <<<"$run"
  memory_runs+=("$("$build/bench/tessera_front_memory" "$problem" "$step")")
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

echo "== after: $(uptime)"

python3 - "$results" <<'PYTHON' | tee "$results/tables.md"
import json, math, sys, os
results = sys.argv[1]

def load(name):
    with open(os.path.join(results, name)) as f:
        return json.load(f)

def by_aggregate(benchmarks):
    """{run_name: {aggregate_name: entry}}; a run without repetitions counts as its own median."""
    table = {}
    for b in benchmarks:
        table.setdefault(b["run_name"], {})[b.get("aggregate_name", "median")] = b
    return table

def is_error(entry):
    return entry.get("error_occurred", False)

print("\n## Front: vertices per second (median of repetitions, CPU time; CV = stddev/mean of time)\n")
print("| benchmark | h | vertices | time (ms) | CV | vertices/s | F evals/vertex | DF evals/vertex | mesh bytes/vertex |")
print("|---|---|---|---|---|---|---|---|---|")
for run_name, entries in by_aggregate(load("front.json")["benchmarks"]).items():
    name, arg = run_name.split("/")
    h = int(arg.split(":")[1]) / 1000
    b = entries.get("median") or next(iter(entries.values()))
    if is_error(b):
        print(f"| {name} | {h:g} | ERROR: {b.get('error_message', '')} | | | | | | |")
        continue
    cv = entries.get("cv")
    cv_text = f"{100 * cv['cpu_time']:.0f} %" if cv else ""
    print(f"| {name} | {h:g} | {b['vertices']:.0f} | {b['cpu_time']:.2f} | {cv_text} | "
          f"{b['vertices_per_second']:,.0f} | {b['F_evals_per_vertex']:.2f} | "
          f"{b['DF_evals_per_vertex']:.2f} | {b['bytes_per_vertex']:.1f} |")

print("\n## Correctors (median CPU time; p: exponent of time ∝ N^p against the previous N)\n")
print("| benchmark | N or h | time | CV | time / n | p | corrector iterations | per factorisation |")
print("|---|---|---|---|---|---|---|---|")
previous = {}
scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
for run_name, entries in by_aggregate(load("corrector.json")["benchmarks"]).items():
    family, _, arg = run_name.partition("/")
    b = entries.get("median") or next(iter(entries.values()))
    size = int(arg.split(":")[1]) if arg.startswith("N:") else None
    label = size if size else (f"{int(arg.split(':')[1]) / 1000:g}" if arg else "")
    if is_error(b):
        print(f"| {family} | {label} | ERROR: {b.get('error_message', '')} | | | | | |")
        continue
    seconds = b["cpu_time"] * scale[b["time_unit"]]
    cv = entries.get("cv")
    cv_text = f"{100 * cv['cpu_time']:.0f} %" if cv else ""
    per_unknown = f"{1e9 * seconds / (size + 2):.0f} ns" if size else ""
    exponent = ""
    if size and family in previous:
        previous_size, previous_seconds = previous[family]
        exponent = f"{math.log(seconds / previous_seconds) / math.log(size / previous_size):.2f}"
    if size:
        previous[family] = (size, seconds)
    per_factorisation = b.get("seconds_per_factorisation")
    iterations = b.get("corrector_iterations")
    time_text = f"{seconds * 1e3:.3g} ms" if seconds >= 1e-3 else f"{seconds * 1e6:.3g} µs"
    print(f"| {family} | {label} | {time_text} | {cv_text} | {per_unknown} | {exponent} | "
          f"{'' if iterations is None else f'{iterations:.0f}'} | "
          + (f"{1e3 * per_factorisation:.3g} ms" if per_factorisation else "") + " |")

print("\n## Front: peak memory (fresh process per row)\n")
print("| problem | h | vertices | wall (s) | vertices/s | peak bytes/vertex | mesh bytes/vertex |")
print("|---|---|---|---|---|---|---|")
for r in load("memory.json")["runs"]:
    print(f"| {r['problem']} | {r['step']} | {r['vertices']} | {r['wall_seconds']} | "
          f"{float(r['vertices_per_second']):,.0f} | {r['peak_bytes_per_vertex']} | "
          f"{r['mesh_bytes_per_vertex']} |")
PYTHON

echo
echo "== atlas scaling (one process per row): problem | tolerance | vertices | termination | s | vertices/s | µs/vertex | peak B/vertex"
for problem in sphere torus; do
  for tolerance in 1e-2 1e-3 1e-4 1e-5 2.5e-6; do
    "$build/bench/tessera_atlas_scaling" "$problem" "$tolerance" | tee -a "$results/atlas_scaling.md"
  done
done
