#!/usr/bin/env bash
# Measures every figure of the technique tables with one sweep, data/sweeps/readme.json (13 set-ups ×
# the six sunlit views, `shadowkit eval` on the default forest; a few minutes on the project's 2-core
# CPU machine once built, resumable: an interrupted run goes on where it stopped), and writes the tables,
# generated from the sweep's results.csv by tools/readme_tables.py, where they live: the README's
# summary, docs/techniques.md (techniques, all figures, visible depth) and docs/cascades.md. `git diff`
# then shows what a change moved. Results are kept in out/readme/ (results.csv, summary.md, pareto.png).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
out=out/readme
build/apps/shadowkit/shadowkit sweep data/sweeps/readme.json --out "$out" --discard-stale
r="$out/results.csv#set-up="

tables="python3 tools/readme_tables.py --into"
$tables README.md:readme-summary summary --first-column 'set-up (texel memory)' \
    '`standard` 2048² (4 M texels)='${r}standard '`focused` 2048²='${r}focused '`psm` 2048²='${r}psm \
    '`tsm` 2048²='${r}tsm '`lispsm` 2048²='${r}lispsm '`csm` 4 × 1024² (4 M texels)='${r}csm-1024 \
    '`csm` 4 × 2048², per-split LiSPSM (16 M texels)='${r}csm-2048-lispsm \
    '`virtual` 16k² clipmap (pool of 16 M texels)='${r}virtual
$tables docs/techniques.md:techniques summary '`standard`='${r}standard '`focused`='${r}focused \
    '`psm`='${r}psm '`tsm`='${r}tsm '`lispsm`='${r}lispsm
$tables docs/techniques.md:details details '`standard`='${r}standard '`focused`='${r}focused \
    '`psm`='${r}psm '`tsm`='${r}tsm '`lispsm`='${r}lispsm
$tables docs/cascades.md:cascades summary --first-column 'set-up (texel memory)' \
    '`tsm` 1 × 2048² (4 M texels)='${r}tsm '`lispsm` 1 × 2048²='${r}lispsm \
    '`csm` 4 × 1024² (4 M texels)='${r}csm-1024 '`csm` 4 × 1024², per-split LiSPSM='${r}csm-1024-lispsm \
    '`csm` 4 × 2048² (16 M texels)='${r}csm-2048 '`csm` 4 × 2048², per-split LiSPSM='${r}csm-2048-lispsm \
    '`virtual` (pool of 16 M texels)='${r}virtual
$tables docs/techniques.md:visible-depth summary --first-column 'set-up' \
    '`lispsm`='${r}lispsm '`lispsm --visible-depth auto`='${r}lispsm-visible \
    '`lispsm --visible-depth auto --lispsm-visible-near`='${r}lispsm-visible-near \
    '`csm` 4 × 1024²='${r}csm-1024 '`csm` 4 × 1024² `--visible-depth auto`='${r}csm-1024-visible
git diff --stat -- README.md docs/techniques.md docs/cascades.md
