#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds tessera_sparse_lu_bench (Release, build-bench/), runs it over every available sparse LU
# solver and the bordered Jacobians of bvp (N = 10²…10⁵) and bratu2d (N = 10…316), writes
# bench/results/sparse_lu.json and prints the table of bench/history/RESULTS-log.md section 9.
#
#     bench/sparse_lu.sh              3 repetitions (about 15 minutes on 2 cores)
#     bench/sparse_lu.sh --table      only the table, from an existing bench/results/sparse_lu.json
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build-bench"
results="$root/bench/results"
if [[ "${1:-}" != "--table" ]]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DTESSERA_BUILD_BENCHMARKS=ON -DTESSERA_BUILD_TESTS=OFF >/dev/null
  cmake --build "$build" --target tessera_sparse_lu_bench
  mkdir -p "$results"
  echo "== machine: $(nproc) cores; $(uptime)"
  "$build/bench/tessera_sparse_lu_bench" --benchmark_min_time=0.2 --benchmark_repetitions=3 \
    --benchmark_report_aggregates_only=true \
    --benchmark_out="$results/sparse_lu.json" --benchmark_out_format=json
  echo "== after: $(uptime)"
fi

python3 - "$results/sparse_lu.json" <<'PYTHON'
import json, sys
SOLVES_PER_VERTEX = 30
rows = {}
for b in json.load(open(sys.argv[1]))["benchmarks"]:
    if b.get("aggregate_name", "median") != "median":
        continue
    family, solver, matrix = b["run_name"].split("/", 2)
    entry = rows.setdefault(matrix, {}).setdefault(solver, {})
    if b.get("error_occurred"):
        entry[family] = None
        continue
    entry[family] = b["cpu_time"] * {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
    for counter in ("n", "nnz_A", "fill"):
        if counter in b:
            entry[counter] = b[counter]

def time(seconds):
    if seconds is None:
        return "failed"
    if seconds >= 1.0:
        return f"{seconds:.2f} s"
    if seconds >= 1e-3:
        return f"{seconds * 1e3:.3g} ms"
    return f"{seconds * 1e6:.3g} µs"

def count(value):
    return f"{value / 1e6:.3g} M" if value >= 1e6 else f"{value / 1e3:.3g} k"

def vertex_costs(solvers, factorisation):
    costs = {}
    for solver, e in solvers.items():
        if e.get(factorisation) is not None and e.get("BM_Solve") is not None:
            costs[solver] = e[factorisation] + SOLVES_PER_VERTEX * e["BM_Solve"]
    return costs

def marked(costs, solver):
    text = time(costs.get(solver))
    return f"**{text}**" if costs and solver == min(costs, key=costs.get) else text

print(f"| matrix | n | nnz(A) | solver | analyse | analyse + factorise | factorise | solve | "
      f"fill nnz(L+U) | vertex: factorise + {SOLVES_PER_VERTEX} solves | "
      f"vertex with a new border: analyse + factorise + {SOLVES_PER_VERTEX} solves |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for matrix, solvers in rows.items():
    same_pattern = vertex_costs(solvers, "BM_Factorize")
    new_pattern = vertex_costs(solvers, "BM_AnalyzeFactorize")
    for solver, e in solvers.items():
        fill = count(e["fill"]) if "fill" in e else ""
        print(f"| {matrix} | {e.get('n', 0):.0f} | {count(e.get('nnz_A', 0))} | {solver} | "
              f"{time(e.get('BM_Analyze'))} | {time(e.get('BM_AnalyzeFactorize'))} | "
              f"{time(e.get('BM_Factorize'))} | {time(e.get('BM_Solve'))} | {fill} | "
              f"{marked(same_pattern, solver)} | {marked(new_pattern, solver)} |")
PYTHON
