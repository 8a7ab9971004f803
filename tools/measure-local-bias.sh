#!/usr/bin/env bash
# The local lights' normal offset, applied where the light grazes a receiver (docs/local-lights.md,
# "Bias in metres"): `wrong_pct` of shadowkit's own renderer at 640 × 360 for
# --local-normal-offset K on the local views (`lamp`,
# `torch`, `village` and the village's grazing lamp `point[4]`, at 1024² and 256², and `village`
# at 2048²) and on the four lamps of tools/measure-engine-spots.sh (a 300-tree patch seen from
# 40 m up, at 512² and 2048², their mean). The other biases at their defaults. About 8 minutes
# on this project's 2-core machine. OFFSETS="1.0 0.5" measures those alone.
set -euo pipefail
cd "$(dirname "$0")/.."
SK=${SK:-build/apps/shadowkit/shadowkit}
[ -x "$SK" ] || tools/build.sh
offsets=${OFFSETS:-1.0 0.75 0.5 0.25 0.15 0.1 0}
# wrong V N K [LIGHT...]: the view's wrong_pct and, for village, point[4]'s.
row() { # the eval table's wrong% for a line starting with $1
  awk -v key="$1" '$1 == key { print ($1 ~ /\[/) ? $3 : $6; exit }'
}
patch=(--trees 300 --terrain-size 256 --view aerial --eye 0,40,0 --dir 0,-0.7,-1 --sun off --size 640x360)
lamps=(spot:0,50,-45,0,-1,0,120,60 spot:0,50,15,0,-1,-0.6,100,80 spot:-30,45,-20,0,-1,0,120,60
       spot:30,45,-10,-0.3,-1,-0.3,120,60)
echo "| normal offset (texels) | lamp 1024² / 256² | torch 1024² / 256² | village 1024² / 256² / 2048² | village's point[4] 1024² / 256² / 2048² | four lamps over the patch, mean, 512² / 2048² |"
echo "|---:|---|---|---|---|---|"
for k in $offsets; do
  cells=()
  for v in lamp torch; do
    a=$("$SK" eval --view $v --size 640x360 --local-map-size 1024 --local-normal-offset "$k" 2> /dev/null | row $v)
    b=$("$SK" eval --view $v --size 640x360 --local-map-size 256 --local-normal-offset "$k" 2> /dev/null | row $v)
    cells+=("$a / $b")
  done
  v=() p=()
  for n in 1024 256 2048; do
    table=$("$SK" eval --view village --size 640x360 --local-map-size $n --local-normal-offset "$k" 2> /dev/null)
    v+=("$(row village <<< "$table")") p+=("$(row 'point[4]' <<< "$table")")
  done
  cells+=("${v[0]} / ${v[1]} / ${v[2]}" "${p[0]} / ${p[1]} / ${p[2]}")
  means=()
  for n in 512 2048; do
    sum=0
    for light in "${lamps[@]}"; do
      w=$("$SK" eval "${patch[@]}" --light "$light" --local-map-size $n --local-normal-offset "$k" 2> /dev/null | row aerial)
      sum=$(python3 -c "print($sum + $w)")
    done
    means+=("$(python3 -c "print('%.2f' % ($sum / ${#lamps[@]}))")")
  done
  cells+=("${means[0]} / ${means[1]}")
  line="| $k |"
  for c in "${cells[@]}"; do line+=" $c |"; done
  echo "$line"
done
