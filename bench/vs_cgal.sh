#!/usr/bin/env bash
# Issue 35: tessera against CGAL's surface mesher at n = 3, side by side in one run. For each
# surface: tessera's atlas (Henderson's disk placement and the hexagonal one) at --tolerance EPS
# and CGAL's make_surface_mesh with distance bound EPS (angle bound 30°), interleaved so that all
# see the same load. Both meshes are measured by `tessera check` against M: vertices V, the
# largest sampled distance H (centroids and edge midpoints), the vertex economy V·H (which does
# not depend on the resolution for flat triangles; the isotropic ideal is 2.42 on the unit
# sphere), and the whole process's user CPU seconds (tessera: covering, report and files; CGAL:
# the mesher and writing its OBJ; tessera on one thread, as CGAL runs), the smallest of REPEATS.
# CGAL's distance bound is not a bound on the mesh's distance to M (its H came out 1.7 times EPS
# on the torus), so it is also run at the bound that gives tessera's H ("CGAL, same H": EPS
# scaled by tessera's H over CGAL's, once): the comparison at the same accuracy.
# Usage: bench/vs_cgal.sh [REPEATS] [EPS]   (default 3, 1e-3). Needs a build with
#        -DTESSERA_BUILD_BENCHMARKS=ON (build/bench/tessera_cgal_surface_mesher).
#        SURFACES="…" replaces the list (default: sphere torus equipotential).
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-3}
eps=${2:-1e-3}
surfaces=${SURFACES:-sphere torus equipotential}
tessera=build/tessera
cgal=build/bench/tessera_cgal_surface_mesher
[ -x "$cgal" ] || { echo "build $cgal first: scripts/build.sh -DTESSERA_BUILD_BENCHMARKS=ON" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cpu() {  # user CPU seconds of a command
  /usr/bin/time -f "%U" -o "$work/time" "$@" >/dev/null 2>&1
  cat "$work/time"
}
measure() {  # mesh file, surface: "V H" from tessera check --json
  "$tessera" check "$1" --problem "$2" --json 2>/dev/null | /usr/bin/python3 -c '
import json, sys
d = json.load(sys.stdin)
m = d["distance_to_manifold"]
print(d["counts"]["vertices"], max(m["centroids"]["max"], m["edge_midpoints"]["max"]))'
}
echo "| surface | mesher | V | H | V·H | V·H / CGAL's | user CPU s | / CGAL's |"
echo "|---|---|---|---|---|---|---|---|"
for s in $surfaces; do
  declare -A best=()
  for ((k = 0; k < repeats; ++k)); do
    for who in disk hexagonal cgal; do
      if [ "$who" = cgal ]; then
        t=$(cpu "$cgal" "$s" "$eps" "$work/$who.obj")
      else
        t=$(cpu "$tessera" mesh "$s" --tolerance "$eps" --placement "$who" --threads 1 -o "$work/$who.ply")
      fi
      if [ -z "${best[$who]:-}" ] || /usr/bin/python3 -c "import sys; sys.exit(not $t < ${best[$who]})"; then
        best[$who]=$t
      fi
    done
  done
  read -r cv ch < <(measure "$work/cgal.obj" "$s")
  read -r hv hh < <(measure "$work/hexagonal.ply" "$s")
  same_eps=$(/usr/bin/python3 -c "print($eps * $hh / $ch)")
  for ((k = 0; k < repeats; ++k)); do
    t=$(cpu "$cgal" "$s" "$same_eps" "$work/cgal_same.obj")
    if [ -z "${best[cgal_same]:-}" ] || /usr/bin/python3 -c "import sys; sys.exit(not $t < ${best[cgal_same]})"; then
      best[cgal_same]=$t
    fi
  done
  for who in disk hexagonal cgal cgal_same; do
    file=$work/$who.ply
    [ "$who" = cgal ] && file=$work/cgal.obj
    [ "$who" = cgal_same ] && file=$work/cgal_same.obj
    read -r v h < <(measure "$file" "$s")
    /usr/bin/python3 -c "
v, h, cv, ch, t, ct = $v, $h, $cv, $ch, ${best[$who]}, ${best[cgal]}
name = {'disk': 'tessera atlas (disk)', 'hexagonal': 'tessera atlas (hexagonal)', 'cgal': 'CGAL',
        'cgal_same': 'CGAL, same H (bound %.3g)' % $same_eps}['$who']
print(f'| $s | {name} | {v} | {h:.3g} | {v*h:.2f} | {v*h/(cv*ch):.2f} | {t:.2f} | {t/ct:.2f} |')"
  done
  unset best
done
