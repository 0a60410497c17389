#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Issue 10's done-criterion for the front at scale: `tessera mesh sphere --method front --step
# 0.003` must complete the sphere (χ = 2, about 1.8 million vertices, below the default vertex
# limit of 2 million). Before issue 10 it stopped with a front collision at 1.19 million vertices
# (see docs/algorithms/front.md, *Order*). Tens of seconds of CPU; run it niced on a shared machine.
#
#     bench/front_fine_sphere.sh [build-dir] [step]        defaults: build 0.003
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${1:-$root/build}"
step="${2:-0.003}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

status=0
"$build/tessera" mesh sphere --method front --step "$step" -o "$work/sphere.ply" \
  --summary "$work/sphere.json" >"$work/log" 2>&1 || status=$?
python3 - "$work/sphere.json" "$status" <<'PY'
import json, sys
summary = json.load(open(sys.argv[1]))
run, counts, topology = summary["run"], summary["counts"], summary["topology"]
print(f"sphere, front, step {run['step']}: {run['termination']}, {counts['vertices']} vertices, "
      f"χ {topology['euler_characteristic']}, {run['wall_seconds']:.1f} s, exit {sys.argv[2]}")
if run["message"]:
    print("message:", run["message"])
ok = run["completed"] and topology["euler_characteristic"] == 2 and summary["valid"]
sys.exit(0 if ok else 1)
PY
