#!/usr/bin/env bash
# Measures every figure of the technique tables with `shadowkit eval` on the default forest
# (about a minute on the project's 2-core CPU machine once built) and writes the tables, generated
# from the JSON reports by tools/readme_tables.py, where they live: the README's summary,
# docs/techniques.md (techniques, all figures, visible depth) and docs/cascades.md. `git diff`
# then shows what a change moved. Reports are kept in out/readme/.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
shadowkit=build/apps/shadowkit/shadowkit
out=out/readme
mkdir -p "$out"
eval_to() { # eval_to NAME ARGS...: one report per technique / set-up, progress on stderr
    local name=$1; shift
    echo "== eval $name" >&2
    "$shadowkit" eval --views all "$@" --json "$out/$name.json" >/dev/null
}
for t in standard focused psm tsm lispsm; do eval_to "$t" --technique "$t" --map-size 2048; done
eval_to csm-1024 --technique csm --cascades 4 --map-size 1024
eval_to csm-1024-lispsm --technique csm --cascades 4 --map-size 1024 --cascade-warp lispsm
eval_to csm-2048 --technique csm --cascades 4 --map-size 2048
eval_to csm-2048-lispsm --technique csm --cascades 4 --map-size 2048 --cascade-warp lispsm
eval_to virtual --technique virtual
# Visible depth (a GPU min/max reduction of the camera's depth pre-pass) for n and splits.
eval_to lispsm-visible --technique lispsm --map-size 2048 --visible-depth auto
eval_to lispsm-visible-near --technique lispsm --map-size 2048 --visible-depth auto --lispsm-visible-near
eval_to csm-1024-visible --technique csm --cascades 4 --map-size 1024 --visible-depth auto

tables="python3 tools/readme_tables.py --into"
$tables README.md:readme-summary summary --first-column 'set-up (texel memory)' \
    '`standard` 2048² (4 M texels)='$out/standard.json '`focused` 2048²='$out/focused.json '`psm` 2048²='$out/psm.json \
    '`tsm` 2048²='$out/tsm.json '`lispsm` 2048²='$out/lispsm.json '`csm` 4 × 1024² (4 M texels)='$out/csm-1024.json \
    '`csm` 4 × 2048², per-split LiSPSM (16 M texels)='$out/csm-2048-lispsm.json \
    '`virtual` 16k² clipmap (pool of 16 M texels)='$out/virtual.json
$tables docs/techniques.md:techniques summary '`standard`='$out/standard.json '`focused`='$out/focused.json \
    '`psm`='$out/psm.json '`tsm`='$out/tsm.json '`lispsm`='$out/lispsm.json
$tables docs/techniques.md:details details '`standard`='$out/standard.json '`focused`='$out/focused.json \
    '`psm`='$out/psm.json '`tsm`='$out/tsm.json '`lispsm`='$out/lispsm.json
$tables docs/cascades.md:cascades summary --first-column 'set-up (texel memory)' \
    '`tsm` 1 × 2048² (4 M texels)='$out/tsm.json '`lispsm` 1 × 2048²='$out/lispsm.json \
    '`csm` 4 × 1024² (4 M texels)='$out/csm-1024.json '`csm` 4 × 1024², per-split LiSPSM='$out/csm-1024-lispsm.json \
    '`csm` 4 × 2048² (16 M texels)='$out/csm-2048.json '`csm` 4 × 2048², per-split LiSPSM='$out/csm-2048-lispsm.json \
    '`virtual` (pool of 16 M texels)='$out/virtual.json
$tables docs/techniques.md:visible-depth summary --first-column 'set-up' \
    '`lispsm`='$out/lispsm.json '`lispsm --visible-depth auto`='$out/lispsm-visible.json \
    '`lispsm --visible-depth auto --lispsm-visible-near`='$out/lispsm-visible-near.json \
    '`csm` 4 × 1024²='$out/csm-1024.json '`csm` 4 × 1024² `--visible-depth auto`='$out/csm-1024-visible.json
git diff --stat -- README.md docs/techniques.md docs/cascades.md
