#!/usr/bin/env bash
# docs/soft-shadows.md's figures, all on this machine:
#   1. the filters × set-ups table against the soft truth of the real sun: the sweep
#      data/sweeps/soft-filters.json (18 cells, about 5 minutes), written into the page and its
#      means into the README;
#   2. each filter's cost: the camera pass's GPU ms (median of 5 frames after the first) of
#      `shadowkit bench` on the default forest, four 2048² cascades with per-split LiSPSM, on two
#      views at 1280 × 720, printed as a table;
#   3. the picture of penumbrae beside the truth, docs/soft-penumbrae.png (tools/soft_figure.py).
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

echo "| filter | perpendicular | noon | over hard |"
echo "|---|---:|---:|---:|"
hard=""
for f in hard pcf2 pcf:3 pcf:5 poisson:16 pcss pcss:32; do
  ms=()
  for v in perpendicular noon; do
    # The bench's row for the camera pass: "... main INSTANCES MTRIS DRAWS MIN MED MAX ...".
    ms+=("$("$B" bench --trees 10000 --views "$v" --filter "$f" --sun-angle 0.53 --frames 5 --technique csm \
      --cascades 4 --cascade-warp lispsm --map-size 2048 2>/dev/null | awk '$0 ~ / main / {print $(NF-5)}')")
  done
  mean=$(echo "(${ms[0]} + ${ms[1]}) / 2" | bc -l)
  [[ -z "$hard" ]] && hard=$mean
  printf '| `%s` | %s | %s | %+.0f %% |\n' "$f" "${ms[0]}" "${ms[1]}" "$(echo "100 * ($mean / $hard - 1)" | bc -l)"
done
/usr/bin/python3 tools/soft_figure.py
