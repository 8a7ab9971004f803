#!/bin/sh
# How low --technique auto's mean wrong_pct could go at 4 M texels by choosing parameters at all
# (docs/error-driven.md): 40 fixed configurations within the budget - TSM's focus
# fraction, LiSPSM's weight on n on both warp axes, 2, 3 and 4 cascades over the visible depth
# at four values of lambda, unwarped and warped per split, and focused - each measured against
# the ray-traced truth on the six standard views; tools/readme_tables.py oracle then keeps the
# lowest wrong_pct per view, as an oracle that knew the truth would. About 10 minutes on this
# project's 2-core machine.
set -eu
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit}
OUT=${OUT:-build/auto-oracle}
mkdir -p "$OUT"
run() {
  name=$1
  shift
  echo "== $name: $*" >&2
  "$B" eval --views all "$@" --json "$OUT/$name.json" > "$OUT/$name.txt" 2>/dev/null
}
for f in 0.05 0.1 0.2 0.3 0.5; do run tsm-$f --technique tsm --map-size 2048 --tsm-focus $f; done
for w in 0.25 0.5 1 2 4; do
  for d in cross middle; do run lispsm-$w-$d --technique lispsm --map-size 2048 --lispsm-weight $w --lispsm-direction $d; done
done
# Map sides as --texel-budget 4M gives them: sqrt(4M / N) rounded down to a multiple of 16.
for n_size in 2:1440 3:1168 4:1024; do
  n=${n_size%:*} size=${n_size#*:}
  for l in 0.5 0.75 0.9 1; do
    for w in none lispsm; do
      run csm$n-$l-$w --technique csm --cascades "$n" --map-size "$size" --lambda $l --cascade-warp $w --visible-depth auto
    done
  done
done
run focused --technique focused --map-size 2048
tools/readme_tables.py oracle "$OUT"/*.json
