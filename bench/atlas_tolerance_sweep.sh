#!/usr/bin/env bash
# The atlas at every tolerance from 1e-4 to 3e-2 on every catalogue surface (issue 10's
# done-criterion): one row per run with the exit code, the vertex count, χ (and the expected
# one), the CLI's validity verdict, the area and the wall time.
#
#   bench/atlas_tolerance_sweep.sh [build/tessera] [--skip-fine-bvp]
#
# Extra surfaces: examples/problems/genus2_thin.tsr (a genus-2 tube of half-thickness 0.07).
# --skip-fine-bvp leaves out bvp at 1e-4 and 3e-4 (minutes each on a loaded machine).
# Runs are niced; each is limited to 20 minutes.
set -u
tessera=${1:-build/tessera}
skip_fine_bvp=0
[[ "${2:-}" == --skip-fine-bvp || "${1:-}" == --skip-fine-bvp ]] && skip_fine_bvp=1
[[ "$tessera" == --skip-fine-bvp ]] && tessera=build/tessera
problems="sphere sphere_cut torus equipotential whitney_pleat trough cstr plane flat_torus crossing bvp examples/problems/genus2_thin.tsr"
tolerances="1e-4 3e-4 1e-3 3e-3 1e-2 3e-2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '%-16s %-7s %-4s %-8s %-9s %-8s %-12s %s\n' problem tol exit vertices "χ (exp)" valid area seconds
failures=0
for problem in $problems; do
  for tolerance in $tolerances; do
    if [[ $skip_fine_bvp == 1 && $problem == bvp && ( $tolerance == 1e-4 || $tolerance == 3e-4 ) ]]; then
      printf '%-16s %-7s skipped\n' "$(basename "$problem" .tsr)" "$tolerance"
      continue
    fi
    start=$(date +%s.%N)
    timeout 1200 nice "$tessera" mesh "$problem" --tolerance "$tolerance" -o "$work/m.ply" \
      >"$work/out.txt" 2>&1
    code=$?
    seconds=$(echo "$(date +%s.%N) - $start" | bc)
    vertices=$(sed -n 's/^mesh *\([0-9]*\) vertices.*/\1/p' "$work/out.txt")
    chi=$(sed -n 's/^topology *Euler characteristic \(-\{0,1\}[0-9]*\).*/\1/p' "$work/out.txt")
    expected=$(sed -n 's/^topology.*(expected \(-\{0,1\}[0-9]*\)).*/\1/p' "$work/out.txt")
    valid=$(grep -q '^topology.*INVALID' "$work/out.txt" && echo INVALID || echo valid)
    area=$(sed -n 's/^area *\([0-9.e+-]*\).*/\1/p' "$work/out.txt")
    printf '%-16s %-7s %-4s %-8s %-9s %-8s %-12s %.1f\n' "$(basename "$problem" .tsr)" "$tolerance" \
      "$code" "${vertices:--}" "${chi:--} (${expected:-?})" "$valid" "${area:--}" "$seconds"
    if [[ $code != 0 ]]; then
      failures=$((failures + 1))
      grep '^tessera:' "$work/out.txt" | head -1 | cut -c1-200 | sed 's/^/    /'
    fi
    if [[ $code == 0 && ( $valid != valid || ( -n "$expected" && "$chi" != "$expected" ) ) ]]; then
      failures=$((failures + 1))
      echo "    completed with a wrong mesh"
    fi
  done
done
echo "failed cells: $failures"
[[ $failures == 0 ]]
