#!/bin/sh
# The README's first measurement of --stabilize for warped maps (set-up hysteresis): LiSPSM
# at one 4096² map along frames 100-159 of flythrough (the climb), sun held, for two reaches.
# Compared with tools/measure-dynamics.sh's full runs on the same frames by
#   tools/readme_tables.py segment 101 159 LABEL=RUN.csv ...
set -eu
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit}
OUT=${OUT:-build/dynamics-hyst}
mkdir -p "$OUT"
for reach in "1 2" "4 5"; do
  set -- $reach
  echo "== lispsm --stabilize --stabilize-radius $1 --stabilize-turn $2" >&2
  "$B" eval --path flythrough --frames 100:160 --technique lispsm --map-size 4096 --stabilize --stabilize-radius "$1" \
    --stabilize-turn "$2" --sun-path off --csv "$OUT/lispsm-r$1.csv" --json "$OUT/lispsm-r$1.json" > "$OUT/lispsm-r$1.txt"
  tail -n 2 "$OUT/lispsm-r$1.txt" >&2
done
