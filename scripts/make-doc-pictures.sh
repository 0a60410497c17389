#!/usr/bin/env bash
# Makes the pictures in README.md and docs/ (docs/images/*.png) with the commands the docs show
# beside them. Usage: scripts/make-doc-pictures.sh [tessera binary, default build/tessera]
set -euo pipefail
cd "$(dirname "$0")/.."
tessera="${1:-build/tessera}"
out=docs/images
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
size=(--size 600x450)
# Fine meshes drawn with their edges are mostly antialiased lines, which PNG compresses badly:
# these are drawn smaller (or coarser) to stay under ~150 KB each.
small=(--size 480x360)
# Each method on catalogue surfaces.
"$tessera" mesh sphere --tolerance 5e-3 -q -o "$work/sphere.ply"
"$tessera" render "$work/sphere.ply" "${small[@]}" --title "sphere, atlas (tolerance 5e-3)" \
  -o "$out/sphere_atlas.png"
"$tessera" mesh torus --method front --step 0.1 -q -o "$work/torus_front.ply"
"$tessera" render "$work/torus_front.ply" --colour min-angle --elevation 40 "${size[@]}" \
  --title "torus, front (step 0.1): smallest angle per triangle" -o "$out/torus_front.png"
"$tessera" mesh torus --method bezier --tolerance 0.01 -q -o "$work/torus_bezier.ply"
"$tessera" render "$work/torus_bezier.ply" --colour curvature --elevation 40 "${size[@]}" \
  --title "torus, bezier (tolerance 0.01): Gauss curvature" -o "$out/torus_bezier.png"
"$tessera" mesh flat_torus --tolerance 5e-3 -q -o "$work/flat_torus.vtu"
# The flat torus of R^4 drawn through the embedding ((2 + x3) x1, (2 + x3) x2, x4) in R^3.
"$tessera" render "$work/flat_torus.vtu" --problem flat_torus \
  --view 'a = (2 + x3)*x1, b = (2 + x3)*x2, c = x4' --colour min-angle "${small[@]}" \
  --title "flat torus in R^4, atlas: smallest angles (in R^4)" -o "$out/flat_torus_atlas.png"
# A continuation surface in its default view (lambda, epsilon, max:u): the axes scaled apart,
# ticked and named, seen from where its folds show (no --azimuth/--elevation: chosen).
"$tessera" mesh bvp:points=100 -q -o "$work/bvp100.ply"
"$tessera" render "$work/bvp100.ply" "${size[@]}" --edges off \
  --title "bvp:points=100 in (lambda, epsilon, max u), coloured by max u" -o "$out/bvp100_view.png"
# Fold curves and cusps.
"$tessera" mesh whitney_pleat --folds lambda,mu -q -o "$work/pleat.ply" --picture "$out/pleat_folds.png"
"$tessera" mesh cstr --folds Da,B --view Da,B,x1 -q -o "$work/cstr.ply" --folds-output "$work/cstr.json"
"$tessera" render "$work/cstr.ply" --curves "$work/cstr.json" "${size[@]}" --edges off \
  --title "cstr: fold curves over (Da, B) and the cusp" -o "$out/cstr_folds.png"
"$tessera" mesh bvp:points=1000 --folds lambda,epsilon -q -o "$work/bvp.ply" --folds-output "$work/bvp.json"
"$tessera" render "$work/bvp.ply" --curves "$work/bvp.json" "${size[@]}" --edges off \
  --title "bvp:points=1000 in (lambda, epsilon, max u): folds and cusp" -o "$out/bvp_folds.png"
# Stability: the CSTR coloured by the number of unstable eigenvalues with its fold, Hopf and
# neutral saddle curves, and its two-parameter bifurcation diagram over (Da, B).
"$tessera" mesh cstr --hopf --tolerance 5e-3 -q -o "$work/cstr_stability.ply" \
  --folds-output "$work/cstr.folds.json" --hopf-output "$work/cstr.hopf.json" \
  --diagram "$out/cstr_diagram.png"
"$tessera" render "$work/cstr_stability.ply" --colour stability --curves "$work/cstr.folds.json" \
  --curves "$work/cstr.hopf.json" --curves "$work/cstr.neutral_saddles.json" "${size[@]}" \
  --title "cstr in (x1, x2, Da): stable, index 1, index 2; fold, Hopf (dashed)" \
  -o "$out/cstr_stability.png"
# Data-dependent triangulations beside Delaunay (Franke's F2 on 33 points).
for criterion in delaunay abn; do
  "$tessera" ddt examples/data/franke33.csv --function F2 --criterion "$criterion" \
    -o "$work/ddt_$criterion.ply" >/dev/null
  "$tessera" render "$work/ddt_$criterion.ply" --top --colour z --size 480x400 \
    --title "F2 on 33 points: $criterion" -o "$out/ddt_$criterion.png"
done
ls -la "$out"
