#!/usr/bin/env bash
# Loaded models in motion (docs/reliability.md "Models in motion"): a standard path — the
# `flythrough`, or the one named as the argument (`orbit`) —, which frames a model without ground
# in every frame ("on_loaded_scene": "frame", docs/dynamics.md), evaluated on the project's own
# corpus scenes, on models whose own animations move a caster (turning_crane.gltf: its jib turns
# once in 8 s, the flythrough's length; bending_arm.gltf: its skinned forearm bends, once a
# second) and on the assimp-testmodels files on which the default
# missed issue 49's bound on a still view, with the default set-up, with `--technique focused`
# and with the default's texel lattice held (`--stabilize`): flicker and error along the path,
# frame by frame at 320 × 180 (240 frames). tools/readme_tables.py model-paths writes the table
# (corpus-paths, or corpus-paths-orbit) into docs/reliability.md.
# About 6 minutes (flythrough) and 10 (orbit) on this project's 2-core machine.
set -euo pipefail
cd "$(dirname "$0")/.."
B=build/apps/shadowkit/shadowkit
[ -x "$B" ] || tools/build.sh
corpus=/usr/share/assimp/models
[ -d "$corpus" ] || { echo "measure-corpus-paths: $corpus is missing: install assimp-testmodels (tools/install-deps.sh)" >&2; exit 1; }
path=${1:-flythrough}
table=corpus-paths
[ "$path" = flythrough ] || table=corpus-paths-$path
out=out/$table
rm -rf "$out" && mkdir -p "$out"
rows=()
for file in tests/data/pillar_on_plate.gltf tests/data/turning_crane.gltf tests/data/bending_arm.gltf \
            tests/data/shapes/ship.obj tests/data/shapes/town.obj \
            tests/data/shapes/tree.gltf "$corpus/OBJ/WusonOBJ.obj" "$corpus/OBJ/regr01.obj" \
            "$corpus/glTF2/ClearCoat-glTF/ClearCoatTest.gltf"; do
  name=$(basename "$file")
  for technique in default focused stabilize; do
    args=()
    [ "$technique" = focused ] && args=(--technique focused)
    [ "$technique" = stabilize ] && args=(--stabilize)
    "$B" eval --scene "$file" --path "$path" --size 320x180 "${args[@]}" \
      --json "$out/$name.$technique.json" > "$out/$name.$technique.txt" 2> "$out/$name.$technique.err"
  done
  echo "measure-corpus-paths: $name: $(tail -n 1 "$out/$name.default.txt")" >&2
  rows+=("\`$name\`=$out/$name.default.json,$out/$name.focused.json,$out/$name.stabilize.json")
done
python3 tools/readme_tables.py --into "docs/reliability.md:$table" model-paths "${rows[@]}"
