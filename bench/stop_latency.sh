#!/usr/bin/env bash
# Stop latency (issue 32): how long after a SIGTERM the valid partial mesh and the summary that
# records the stop are on disk, and the process has exited, for a SIGTERM in each stage of a
# `tessera mesh` run (docs/stopping.md). Batch systems send SIGKILL a grace period after the
# SIGTERM (Slurm: 30 s); the goal is 10 s at n = 10⁵.
#
# Each stage is one run, watched through its --progress lines: the signal goes when the line of
# the stage appears (for `build`, the first build line after BUILD_SECONDS into the run). The
# files are polled every 50 ms: "mesh" is when the mesh file appears (it is removed before the
# run and replaced by a rename), "summary" when the summary file records the stop.
#
# Usage: bench/stop_latency.sh PROBLEM [STAGE ...] [-- MESH OPTIONS ...]
#   STAGE: build, clip, refine, validate, patches, report (default: all of them)
#   BUILD_SECONDS=S   the build is signalled after S seconds (default 60)
#   SECOND_SIGNAL=S   send a second SIGTERM S seconds after the first (default: none)
#   TESSERA=path      another binary (default build/tessera)
# Example: bench/stop_latency.sh bratu2d:N=100 -- --method front --step 0.6 --tolerance 0.3
# Prints one Markdown row per stage (and appends them to bench/results/stop_latency.md).
set -euo pipefail
cd "$(dirname "$0")/.."
problem=$1
shift
stages=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  stages+=("$1")
  shift
done
[ "${1:-}" = "--" ] && shift
options=("$@")
[ ${#stages[@]} -eq 0 ] && stages=(build clip refine validate patches report)
tessera=${TESSERA:-build/tessera}
build_seconds=${BUILD_SECONDS:-60}
work=$(mktemp -d)
pid=""
trap '[ -n "$pid" ] && kill -KILL "$pid" 2>/dev/null; rm -rf "$work"' EXIT
now() { date +%s.%N; }
since() { echo "$(now) - $1" | bc -l; }
mkdir -p bench/results
{
  echo
  echo "\`bench/stop_latency.sh $problem ${stages[*]} -- ${options[*]}\`" \
    "(BUILD_SECONDS=$build_seconds${SECOND_SIGNAL:+, SECOND_SIGNAL=$SECOND_SIGNAL})," \
    "$(date -u +%Y-%m-%d), $(git rev-parse --short HEAD), load $(cut -d' ' -f1-3 /proc/loadavg)"
  echo
  echo "| stage signalled | s into the run | stage in summary | mesh on disk s | summary on disk s | exited s | exit | signals | termination | vertices | checks cut short | checkpoint written s |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
} | tee -a bench/results/stop_latency.md
for stage in "${stages[@]}"; do
  rm -f "$work/mesh.ply" "$work/summary.json"
  : >"$work/progress"
  start=$(now)
  nice "$tessera" mesh "$problem" "${options[@]}" --progress -o "$work/mesh.ply" \
    --summary "$work/summary.json" 2>"$work/progress" >/dev/null &
  pid=$!
  reached=yes
  until grep -q "^tessera: $stage: " "$work/progress" &&
    { [ "$stage" != build ] || [ "$(echo "$(since "$start") > $build_seconds" | bc)" = 1 ]; }; do
    if ! kill -0 "$pid" 2>/dev/null; then
      reached=no
      break
    fi
    sleep 0.05
  done
  if [ "$reached" = no ]; then
    echo "| $stage | (the run ended before it) | | | | | | | | | | |" | tee -a bench/results/stop_latency.md
    wait "$pid" || true
    pid=""
    continue
  fi
  signalled=$(now)
  into=$(since "$start")
  kill -TERM "$pid"
  second_sent=no
  mesh_at=""
  summary_at=""
  while kill -0 "$pid" 2>/dev/null; do
    [ -z "$mesh_at" ] && [ -e "$work/mesh.ply" ] && mesh_at=$(since "$signalled")
    [ -z "$summary_at" ] && grep -q '"stop":' "$work/summary.json" 2>/dev/null &&
      summary_at=$(since "$signalled")
    if [ -n "${SECOND_SIGNAL:-}" ] && [ "$second_sent" = no ] &&
      [ "$(echo "$(since "$signalled") > $SECOND_SIGNAL" | bc)" = 1 ]; then
      kill -TERM "$pid" 2>/dev/null || true
      second_sent=yes
    fi
    sleep 0.05
  done
  code=0
  wait "$pid" || code=$?
  pid=""
  exited=$(since "$signalled")
  [ -z "$mesh_at" ] && [ -e "$work/mesh.ply" ] && mesh_at=$exited
  [ -z "$summary_at" ] && grep -q '"stop":' "$work/summary.json" 2>/dev/null && summary_at=$exited
  # With --checkpoint FILE: when FILE was last written, against the signal (a stop in the build
  # writes it before the mesh; after the build it was written when the build ended).
  checkpoint_at=none
  for ((k = 0; k + 1 < ${#options[@]}; ++k)); do
    if [ "${options[k]}" = --checkpoint ] && [ -e "${options[k + 1]}" ]; then
      checkpoint_at=$(echo "$(stat -c %.9Y "${options[k + 1]}") - $signalled" | bc -l)
    fi
  done
  /usr/bin/python3 - "$stage" "$into" "${mesh_at:-none}" "${summary_at:-none}" "$exited" "$code" \
    "$work/summary.json" "$checkpoint_at" <<'PY' | tee -a bench/results/stop_latency.md
import json, os, sys
stage, into, mesh, summary, exited, code, path, checkpoint = sys.argv[1:]
def seconds(text):
    return "not written" if text == "none" else f"{float(text):.1f}"
s = json.load(open(path)) if os.path.exists(path) else {}
stop = s.get("stop", {})
cut = s.get("geometry", {}).get("cut_short", [])
print(f"| {stage} | {float(into):.0f} | {stop.get('stage', '-')} | {seconds(mesh)} | "
      f"{seconds(summary)} | {float(exited):.1f} | {code} | {stop.get('signals', '-')} | "
      f"{s.get('run', {}).get('termination', '-')} | {s.get('counts', {}).get('vertices', '-')} | "
      f"{'; '.join(cut) if cut else 'none'} | "
      f"{'-' if checkpoint == 'none' else (f'{float(checkpoint):.1f}' if float(checkpoint) > 0 else 'before the signal')} |")
PY
done
