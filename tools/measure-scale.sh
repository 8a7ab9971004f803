#!/bin/sh
# docs/scale-and-visibility.md's scale table: shadowkit bench with frustum culling and levels of
# detail (the CPU path before occlusion culling), the same density on a growing terrain
# (--same-density) and ten times denser, each again with --no-cull --no-lod right after, 3 frames
# of the paper, perpendicular and aerial views. Rows go to build/scale/*.json;
# tools/readme_tables.py scale prints the table from (culled, full) pairs. About 6 minutes.
set -eu
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit}
OUT=${OUT:-build/scale}
mkdir -p "$OUT"
F="--visibility frustum --caster-culling volume --views perpendicular,aerial,paper --frames 3"
for what in same-density denser; do
  if [ "$what" = same-density ]; then trees="--trees 1000,10000,100000 --same-density"; else trees="--trees 100000"; fi
  for mode in culled full; do
    extra=""
    [ "$mode" = full ] && extra="--no-cull --no-lod"
    echo "== $what, $mode" >&2
    # shellcheck disable=SC2086 # option lists
    "$B" bench $trees $F $extra --json "$OUT/$what-$mode.json"
  done
done
