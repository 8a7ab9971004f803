#!/usr/bin/env bash
# tools/measure-foliage-lod.sh: the leafy forest's levels of detail down to billboard clouds,
# against the full geometry's truth and in work — docs/materials.md "Foliage levels of detail".
#
# Runs, for the default levels (--lod-foliage-scale 6), a stricter scale (4), the shadow passes'
# farthest level an octahedral impostor (--impostors) and none (--no-lod):
# `eval --forest leafy --views all` hard and under the real sun (--sun-angle 0.53 --filter pcss),
# `bench --forest leafy` at 10,000 trees and at 100,000 (--same-density) with GPU-driven
# culling (every machine's default on a GPU; named so that a software rasteriser's triangle
# counts are the same work), and `eval --path flythrough` over its first 48 frames with the sun
# held (flicker_pct), into out/foliage-lod/; then writes the tables. On this project's 2-core
# llvmpipe machine about an hour (the flythroughs and the frames without levels are the slow
# part); on a GPU machine a few.
#   FOLIAGE_LOD_RESULTS=DIR_OR_TGZ  writes the tables from a kept run instead (the H200's of the
#                                   single cloud, data/gpu/h200-2026-11-28-foliage-lod.tgz, were
#                                   written by this script at 66186b9, whose variant was scale 8)
#   SHADOWKIT=PATH                  the binary to run (a copy keeps a rebuild from changing it mid-run)
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ -n ${FOLIAGE_LOD_RESULTS:-} ]]; then
  dir=$FOLIAGE_LOD_RESULTS
  if [[ -f $dir ]]; then
    mkdir -p out/foliage-lod-kept && tar -xzf "$dir" -C out/foliage-lod-kept && dir=out/foliage-lod-kept
  fi
  exec python3 tools/foliage_lod_tables.py "$dir"
fi
[[ -n ${SHADOWKIT:-} ]] || [ -x build/apps/shadowkit/shadowkit ] || tools/build.sh
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit}
out=out/foliage-lod
mkdir -p "$out"
{ echo "commit $(git rev-parse --short HEAD), $(nproc) CPU cores, $(date -u +%Y-%m-%dT%H:%MZ)"; } >"$out/summary.txt"
for set in "lod|" "no-lod|--no-lod" "s4|--lod-foliage-scale 4" "imp|--impostors"; do
  name=${set%%|*} options=${set#*|}
  echo "== $name: eval, hard and under the real sun" >&2
  # shellcheck disable=SC2086
  $B eval --forest leafy --views all $options --json "$out/eval-$name.json" >/dev/null
  # shellcheck disable=SC2086
  $B eval --forest leafy --views all --sun-angle 0.53 --filter pcss $options --json "$out/soft-$name.json" >/dev/null
  suffix=$([[ $name == lod ]] && echo "" || echo "-$name")
  echo "== $name: bench, 10,000 trees" >&2
  # shellcheck disable=SC2086
  $B bench --forest leafy --trees 10000 --views perpendicular,aerial --frames 3 --visibility gpu $options \
    --json "$out/leafy$suffix.json" >"$out/leafy$suffix.log"
  echo "== $name: bench, 100,000 trees" >&2
  # shellcheck disable=SC2086
  $B bench --forest leafy --trees 100000 --same-density --views perpendicular,aerial --frames 3 --visibility gpu \
    $options --json "$out/leafy-100k$suffix.json" >"$out/leafy-100k$suffix.log"
  echo "== $name: the flythrough's first 48 frames, sun held" >&2
  # shellcheck disable=SC2086
  $B eval --forest leafy --path flythrough --frames 0:48 --sun-path off $options --csv "$out/fly-$name.csv" \
    >"$out/fly-$name.log"
done
# The rasteriser that drew the frames (named by the bench's line with " via ").
grep -m1 " via " "$out/leafy.log" | cut -d"|" -f1 >>"$out/summary.txt"
python3 tools/foliage_lod_tables.py "$out"
