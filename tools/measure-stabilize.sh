#!/bin/sh
# docs/dynamics.md's trade of held texel lattices (--stabilize for warped maps): LiSPSM at one
# 4096² map along the whole flythrough, sun held, without the lookahead (the defaults' row,
# margin 0.05 and lookahead 60, is tools/measure-dynamics.sh's),
# then the still views on perpendicular (a still camera's refit is the fresh fit itself).
# Rows go to build/dynamics-held/; compare them with tools/readme_tables.py stable.
# About 7 minutes a path row on this project's 2-core machine.
set -eu
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit}
OUT=${OUT:-build/dynamics-held}
mkdir -p "$OUT"
row() {
  name=$1
  shift
  echo "== lispsm --stabilize $*" >&2
  "$B" eval --path flythrough --frames 0:240 --technique lispsm --map-size 4096 --stabilize "$@" --sun-path off \
    --csv "$OUT/$name.csv" --json "$OUT/$name.json" > "$OUT/$name.txt"
  tail -n 2 "$OUT/$name.txt" >&2
}
row lispsm-no-lookahead --stabilize-lookahead 0
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
