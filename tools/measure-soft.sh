#!/usr/bin/env bash
# docs/soft-shadows.md's figures, all on this machine:
#   1. the filters × set-ups table against the soft truth of the real sun: the sweep
#      data/sweeps/soft-filters.json (18 cells, about 5 minutes), written into the page and its
#      means into the README;
#   2. each filter's cost: the frame's ms (the median of 5 frames after the first) of
#      `shadowkit bench` on the default forest, four 2048² cascades with per-split LiSPSM, on two
#      views at 1280 × 720, printed as a table;
#   3. the lamps (data/sweeps/soft-lamps.json: lamp and torch, 5 cm) against their spheres' truth,
#      written into the page, and their filters' cost on the same two views;
#   4. the picture of penumbrae beside the truth, docs/soft-penumbrae.png (tools/soft_figure.py).
# SKIP_SWEEP=1 keeps the sweep's last results.
set -euo pipefail
cd "$(dirname "$0")/.."
B=build/apps/shadowkit/shadowkit
out=out/sweeps/soft-filters
if [[ -z "${SKIP_SWEEP:-}" ]]; then
  "$B" sweep data/sweeps/soft-filters.json --out "$out" --discard-stale
fi
python3 tools/readme_tables.py --into docs/soft-shadows.md:soft-filters soft "$out/results.csv"
python3 tools/readme_tables.py --into README.md:soft-summary soft-summary "$out/results.csv"
python3 tools/readme_tables.py --into docs/soft-shadows.md:soft-widths soft-widths "$out/results.csv"

# A cost table: the frame's ms per filter on two views (bench's frame_cpu_ms, the median of the 5
# frames after the first: on llvmpipe the whole frame, the drawing too), and the mean's change over
# the first filter. cost VIEW1 VIEW2 "FILTERS" [bench options...]
# The frame, not the camera pass: llvmpipe rasterises binned draws when a later read or flush
# needs them, so a pass's GPU time can hold another's drawing (most likely the sun's maps in the
# camera pass, or with MSM in the shadow pass, whose moments read them).
cost() {
  local v1=$1 v2=$2 filters=$3 base="" f v ms mean json
  shift 3
  json=$(mktemp --suffix=.json) # bench refuses a --json name without .json
  echo "| filter | $v1 | $v2 | over ${filters%% *} |"
  echo "|---|---:|---:|---:|"
  for f in $filters; do
    ms=()
    for v in "$v1" "$v2"; do
      "$B" bench --trees 10000 --views "$v" --filter "$f" --frames 5 "$@" --json "$json" > /dev/null 2>&1
      ms+=("$(python3 -c 'import json, sys; print("%.1f" % json.load(open(sys.argv[1]))["runs"][0]["frame_cpu_ms"]["median"])' "$json")")
    done
    mean=$(echo "(${ms[0]} + ${ms[1]}) / 2" | bc -l)
    [[ -z "$base" ]] && base=$mean
    printf '| `%s` | %s | %s | %+.0f %% |\n' "$f" "${ms[0]}" "${ms[1]}" "$(echo "100 * ($mean / $base - 1)" | bc -l)"
  done
  rm -f "$json"
}
cost perpendicular noon "hard pcf2 pcf:3 pcf:5 poisson:16 pcss pcss:32 msm" --sun-angle 0.53 --technique csm --cascades 4 \
  --cascade-warp lispsm --map-size 2048
"$B" sweep data/sweeps/soft-lamps.json --out out/sweeps/soft-lamps --discard-stale
python3 tools/readme_tables.py --into docs/soft-shadows.md:soft-lamps soft-lamps out/sweeps/soft-lamps/results.csv
cost lamp torch "hard pcf2 pcss"
/usr/bin/python3 tools/soft_figure.py
