#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Strong and weak scaling of the PETSc backend's kernel (bench/petsc_kernel.cpp: one MUMPS
# factorisation and a chord projection per step along bratu2d's M) on 1 … RANKS ranks.
# Writes bench/results/petsc_scaling.jsonl and prints the tables of bench/RESULTS.md,
# "PETSc / MPI backend" (history: bench/history/RESULTS-log.md section 13).
#
#     bench/petsc_scaling.sh            ranks 1 2 (the 2-core machine)
#     RANKS="1 2 4 8" bench/petsc_scaling.sh
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="$root/build-bench"
results="$root/bench/results"
ranks_list=${RANKS:-"1 2"}
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DTESSERA_BUILD_BENCHMARKS=ON -DTESSERA_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" --target tessera_petsc_kernel >/dev/null
mkdir -p "$results"
out="$results/petsc_scaling.jsonl"
: >"$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
run() {  # ranks N kind
  echo "{\"kind\": \"$3\", \"run\": $(mpiexec -n "$1" --oversubscribe "$build/bench/tessera_petsc_kernel" 2 "$2" 10)}" >>"$out"
}
echo "== machine: $(nproc) cores; $(uptime)"
for N in 100 316; do
  for r in $ranks_list; do run "$r" "$N" strong; done
done
# Weak: about 20 000 grid values per rank (N = √(20 000 · ranks)).
for r in $ranks_list; do
  run "$r" "$(python3 -c "import math; print(round(math.sqrt(20000 * $r)))")" weak
done
echo "== after: $(uptime)"
python3 - "$out" <<'PYTHON'
import json, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
print("| scaling | N | n | ranks | first factorisation s (with the analysis) | s per later factorisation | s per chord step | chord step ÷ factorisation | peak MB per rank | MB per rank per 10⁴ unknowns | λ reached |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for row in rows:
    r = row["run"]
    print(f"| {row['kind']} | {r['N']} | {r['n']} | {r['ranks']} | {r['first_factorisation_seconds']:.2f} | {r['seconds_per_factorisation']:.3f} | "
          f"{r['seconds_per_chord_step']:.4f} | {r['seconds_per_chord_step'] / r['seconds_per_factorisation']:.3f} | "
          f"{r['peak_mb_per_rank']:.0f} | {r['peak_mb_per_rank'] / (r['n'] / r['ranks'] / 1e4):.0f} | {r['lambda_reached']:.6f} |")
PYTHON
