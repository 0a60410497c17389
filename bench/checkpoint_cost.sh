#!/usr/bin/env bash
# The cost of the checkpoints of the atlas or the front (issue 32, docs/checkpoints.md): one run without
# checkpoints and one with `--checkpoint-every EVERY`, their build and wall times, the size and
# time of each checkpoint (from --progress), and whether both meshes are the same file; then the
# second run killed (SIGKILL) after KILL_AFTER seconds and resumed, its mesh compared too.
#
# Usage: bench/checkpoint_cost.sh PROBLEM [-- MESH OPTIONS ...]
#   EVERY=S        seconds between checkpoints (default 10)
#   KILL_AFTER=S   when the killed run is killed (default: half the plain run's wall time)
#   METHOD=name    atlas (default) or front
#   TESSERA=path   another binary (default build/tessera)
# Example: bench/checkpoint_cost.sh bratu2d:N=100 -- --step 0.4 --tolerance 0.05
set -euo pipefail
cd "$(dirname "$0")/.."
problem=$1
shift
[ "${1:-}" = "--" ] && shift
options=("$@")
tessera=${TESSERA:-build/tessera}
method=${METHOD:-atlas}
every=${EVERY:-10}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
now() { date +%s.%N; }

start=$(now)
"$tessera" mesh "$problem" --method "$method" "${options[@]}" -q -o "$work/plain.ply" \
  --summary "$work/plain.json"
plain=$(echo "$(now) - $start" | bc -l)

start=$(now)
"$tessera" mesh "$problem" --method "$method" "${options[@]}" -o "$work/saved.ply" \
  --summary "$work/saved.json" --checkpoint "$work/run.tsc" --checkpoint-every "$every" \
  --progress 2> "$work/saved.log" > /dev/null
saved=$(echo "$(now) - $start" | bc -l)

build_of() {
  python3 -c "import json,sys; s=json.load(open(sys.argv[1])); print('%.1f' % sum(p['wall_seconds'] for p in s['run']['work_by_phase'] if p['phase'] in ('start', 'build')), s['run']['atlas']['charts'] if 'atlas' in s['run'] else s['counts']['vertices'])" "$1"
}
echo "plain:      wall $(printf %.1f "$plain") s, build s and charts: $(build_of "$work/plain.json")"
echo "checkpoint: wall $(printf %.1f "$saved") s, build s and charts: $(build_of "$work/saved.json")"
sed -n 's/^tessera: checkpoint: \([0-9]*\) bytes to .* in \([0-9.]*\) s\( (its state made in \([0-9.]*\) s before)\)\{0,1\}$/\1 \2 \4/p' \
  "$work/saved.log" | awk '{bytes+=$1; t+=$2; s+=$3; n++; if ($2>max) max=$2}
  END {printf "checkpoints: %d, mean %.0f MB, writing %.2f s in all (longest %.3f s), making the states %.2f s in all\n", n, bytes/n/1e6, t, max, s}'
cmp "$work/plain.ply" "$work/saved.ply" && echo "meshes: identical"

kill_after=${KILL_AFTER:-$(echo "$plain / 2" | bc -l)}
rm -f "$work/run.tsc" "$work/saved.ply"
"$tessera" mesh "$problem" --method "$method" "${options[@]}" -q -o "$work/saved.ply" \
  --checkpoint "$work/run.tsc" --checkpoint-every "$every" &
pid=$!
sleep "$kill_after"
kill -KILL $pid
wait $pid || true
start=$(now)
"$tessera" resume "$work/run.tsc" -q
echo "killed after $(printf %.1f "$kill_after") s, resumed in $(printf %.1f "$(echo "$(now) - $start" | bc -l)") s"
cmp "$work/plain.ply" "$work/saved.ply" && echo "resumed mesh: identical"
