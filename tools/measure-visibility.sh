#!/bin/sh
# docs/scale-and-visibility.md's visibility table: shadowkit bench on the perpendicular view at 10,000 and
# 100,000 trees for every visibility mode (GPU-driven culling included), with caster culling by volume and
# by visible receivers, 10 frames each (CHC++'s counts are medians of the 9 after the camera cut).
# Rows go to build/visibility/*.json; tools/readme_tables.py visibility prints the table. (100,000 trees without any culling is 29 M triangles a pass: left out.)
set -eu
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit}
OUT=${OUT:-build/visibility}
mkdir -p "$OUT"
for trees in 10000 100000; do
  for vis in off frustum chc gpu; do
    [ "$trees" = 100000 ] && [ "$vis" = off ] && continue
    for casters in volume receivers; do
      [ "$vis" = off ] && [ "$casters" = receivers ] && continue # without culling nothing is masked
      echo "== $trees trees, --visibility $vis --caster-culling $casters" >&2
      "$B" bench --trees "$trees" --views perpendicular --frames 10 --visibility "$vis" --caster-culling "$casters" \
        --json "$OUT/$trees-$vis-$casters.json"
    done
  done
done
