#!/usr/bin/env bash
# Builds tessera and covers the paper's cut sphere (Brodzik & Rheinboldt, figure 5.1):
# writes out/sphere_cut.ply and out/sphere_cut.json and prints the report.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out
build/tessera mesh sphere_cut --method front --step 0.3 -o out/sphere_cut.ply \
  --summary out/sphere_cut.json
