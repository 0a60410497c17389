#!/usr/bin/env bash
# Builds tessera and covers the cut sphere of Brodzik & Rheinboldt's figure 5.1 with the default
# method (atlas) to within 1e-3 of M:
# writes out/sphere_cut.ply and out/sphere_cut.json and prints the report.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out
build/tessera mesh sphere_cut --tolerance 1e-3 -o out/sphere_cut.ply \
  --summary out/sphere_cut.json
