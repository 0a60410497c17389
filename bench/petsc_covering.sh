#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The whole covering on the PETSc backend (`mpiexec -n R tessera mesh bratu2d:N=… --backend petsc`)
# against the serial backend: strong scaling (one N, 1 … RANKS ranks) and weak scaling (about
# the same n per rank), time per vertex against one factorisation, factorisations per vertex and
# peak memory per rank. Writes bench/results/petsc_covering.jsonl and prints the table of
# bench/RESULTS.md, "PETSc / MPI backend" (history: bench/history/RESULTS-log.md sections 13b, 13c).
#
#     bench/petsc_covering.sh                       strong N = 50, weak N = 50 → 71 on 1, 2 ranks
#     STRONG=100 RANKS="1 2 4 8" bench/petsc_covering.sh   on a bigger machine
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tessera="$root/build/tessera"
results="$root/bench/results"
ranks_list=${RANKS:-"1 2"}
strong=${STRONG:-50}
weak_per_rank=${WEAK_PER_RANK:-2500}  # grid values per rank
[[ -x "$tessera" ]] || "$root/scripts/build.sh"
mkdir -p "$results"
out="$results/petsc_covering.jsonl"
: >"$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
run() {  # kind N ranks|serial
  local kind=$1 N=$2 ranks=$3
  local launcher=() backend=(--backend petsc) count=$ranks
  if [[ $ranks == serial ]]; then
    backend=()
    count=1
  else
    launcher=(mpiexec -n "$ranks" --oversubscribe)
  fi
  # /usr/bin/time inside mpiexec: one peak resident set per rank.
  "${launcher[@]}" /usr/bin/time -f "peak_kb %M" -a -o "$work/peak" \
    "$tessera" mesh "bratu2d:N=$N" "${backend[@]}" -o "$work/mesh.ply" \
    --summary "$work/summary.json" -q
  python3 - "$kind" "$N" "$ranks" "$count" "$work" >>"$out" <<'PYTHON'
import json, sys
kind, N, ranks, count, work = sys.argv[1], int(sys.argv[2]), sys.argv[3], int(sys.argv[4]), sys.argv[5]
summary = json.load(open(f"{work}/summary.json"))
peaks = [int(line.split()[1]) for line in open(f"{work}/peak") if line.startswith("peak_kb")]
run = summary["run"]
print(json.dumps({"kind": kind, "N": N, "n": summary["ambient_dimension"], "backend": ranks,
                  "ranks": count, "vertices": summary["counts"]["vertices"],
                  "seconds": run["wall_seconds"], "factorisations": run["factorisations"],
                  "factorisation_seconds": run["factorisation_seconds"],
                  "jacobians": run["jacobian_evaluations"], "valid": summary["valid"],
                  "peak_mb_per_rank": max(peaks) / 1024.0}))
PYTHON
  rm -f "$work/peak"
}
echo "== machine: $(nproc) cores; $(uptime)"
run strong "$strong" serial
for r in $ranks_list; do run strong "$strong" "$r"; done
for r in $ranks_list; do
  run weak "$(python3 -c "import math; print(round(math.sqrt($weak_per_rank * $r)))")" "$r"
done
echo "== after: $(uptime)"
python3 - "$out" <<'PYTHON'
import json, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
print("| scaling | N | n | backend | vertices | s | ms per vertex | one factorisation ms | ms per vertex ÷ one factorisation | factorisations per vertex | Jacobians per vertex | peak MB per rank | valid |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    V = r["vertices"]
    one = 1000 * r["factorisation_seconds"] / r["factorisations"]
    per_vertex = 1000 * r["seconds"] / V
    backend = "serial" if r["backend"] == "serial" else f"petsc, {r['ranks']} rank{'s' if r['ranks'] > 1 else ''}"
    print(f"| {r['kind']} | {r['N']} | {r['n']} | {backend} | {V} | {r['seconds']:.1f} | {per_vertex:.2f} | {one:.2f} | "
          f"{per_vertex / one:.1f} | {r['factorisations'] / V:.2f} | {r['jacobians'] / V:.2f} | {r['peak_mb_per_rank']:.0f} | {r['valid']} |")
PYTHON
