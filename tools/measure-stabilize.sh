#!/bin/sh
# The README's trade of held texel lattices (--stabilize for warped maps): LiSPSM at one
# 4096² map along the whole flythrough, sun held, for texel-growth bounds G beyond the
# default 1.25 (whose row tools/measure-dynamics.sh writes), then the still-view price on
# perpendicular, where a fresh refit pays only the margin. Rows go to build/dynamics-held/;
# compare them with tools/readme_tables.py dynamics. About 7 minutes a path row.
set -eu
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit}
OUT=${OUT:-build/dynamics-held}
mkdir -p "$OUT"
for growth in ${GROWTHS:-1.5 2}; do
  echo "== lispsm --stabilize --stabilize-growth $growth" >&2
  "$B" eval --path flythrough --frames 0:240 --technique lispsm --map-size 4096 --stabilize --stabilize-growth "$growth" \
    --sun-path off --csv "$OUT/lispsm-g$growth.csv" --json "$OUT/lispsm-g$growth.json" > "$OUT/lispsm-g$growth.txt"
  tail -n 2 "$OUT/lispsm-g$growth.txt" >&2
done
echo "== perpendicular, equal memory" >&2
{
  "$B" eval --view perpendicular --technique csm --cascades 4 --map-size 2048 --stabilize
  for t in lispsm tsm; do
    "$B" eval --view perpendicular --technique $t --map-size 4096
    "$B" eval --view perpendicular --technique $t --map-size 4096 --stabilize
  done
  "$B" eval --view perpendicular --technique csm --cascades 4 --map-size 2048 --cascade-warp lispsm
  "$B" eval --view perpendicular --technique csm --cascades 4 --map-size 2048 --cascade-warp lispsm --stabilize
} 2>/dev/null | grep -v '^view' > "$OUT/perpendicular.txt"
cat "$OUT/perpendicular.txt" >&2
