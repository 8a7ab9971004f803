#!/usr/bin/env bash
# tools/measure-lod-fade.sh: the levels of detail's cross-fade (--lod-fade) on the leafy forest
# against switching at the bound — docs/materials.md "Crossing between levels".
#
# For each band (0: a switch, the default levels; 0.25 and 0.5: a cross-fade over that fraction of
# each coverage level's bound): `eval --forest leafy --views all` hard and under the real sun
# (--sun-angle 0.53 --filter pcss), `eval --path flythrough` over its first 48 frames with the sun
# held (flicker_pct, frame to frame), and `bench --forest leafy` at 10,000 trees with GPU-driven
# culling (triangles: a crossing tree is drawn at both levels), all at SIZE (default 640x360), into
# out/lod-fade/; then writes the table. About 25 minutes on this project's 2-core llvmpipe machine.
#   LOD_FADE_RESULTS=DIR  writes the table from a kept run instead
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ -n ${LOD_FADE_RESULTS:-} ]]; then exec python3 tools/lod_fade_tables.py "$LOD_FADE_RESULTS"; fi
[ -x build/apps/shadowkit/shadowkit ] || tools/build.sh
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit} # a copy keeps a rebuild from changing it mid-run
SIZE=${SIZE:-640x360}
out=out/lod-fade
mkdir -p "$out"
echo "commit $(git rev-parse --short HEAD), $(nproc) CPU cores, $(date -u +%Y-%m-%dT%H:%MZ), $SIZE" >"$out/summary.txt"
for band in 0 0.25 0.5; do
  echo "== --lod-fade $band: eval, hard and under the real sun" >&2
  $B eval --forest leafy --views all --size "$SIZE" --lod-fade "$band" --json "$out/eval-$band.json" >/dev/null
  $B eval --forest leafy --views all --size "$SIZE" --sun-angle 0.53 --filter pcss --lod-fade "$band" \
    --json "$out/soft-$band.json" >/dev/null
  echo "== --lod-fade $band: the flythrough's first 48 frames, sun held" >&2
  $B eval --forest leafy --path flythrough --frames 0:48 --sun-path off --size "$SIZE" --lod-fade "$band" \
    --json "$out/fly-$band.json" >"$out/fly-$band.log"
  echo "== --lod-fade $band: bench, 10,000 trees" >&2
  $B bench --forest leafy --trees 10000 --views perpendicular,aerial --frames 3 --visibility gpu --size "$SIZE" \
    --lod-fade "$band" --json "$out/bench-$band.json" >"$out/bench-$band.log"
done
grep -m1 " via " "$out/bench-0.log" | cut -d"|" -f1 >>"$out/summary.txt"
python3 tools/lod_fade_tables.py "$out"
