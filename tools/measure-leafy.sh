#!/usr/bin/env bash
# Measures the technique table on the leafy forest (issue 33): one sweep, data/sweeps/leafy.json
# (8 set-ups × the six sunlit views, `shadowkit eval --forest leafy`: 10,000 trees of branches
# and alpha-tested leaf cards), and the blob forest's for the same set-ups (data/sweeps/readme.json,
# as tools/measure-readme.sh runs it), then writes the tables from the two results.csv with
# tools/readme_tables.py: the README's leafy summary and docs/materials.md's comparison of the two
# forests. Resumable; results in out/leafy/ and out/readme/.
set -euo pipefail
cd "$(dirname "$0")/.."
# SHADOWKIT=PATH: the binary to run (a copy keeps a rebuild from changing it mid-run).
[[ -n ${SHADOWKIT:-} ]] || tools/build.sh
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit}
$B sweep data/sweeps/leafy.json --out out/leafy --discard-stale
$B sweep data/sweeps/readme.json --out out/readme --discard-stale
l="out/leafy/results.csv#set-up="
b="out/readme/results.csv#set-up="
tables="python3 tools/readme_tables.py --into"
$tables README.md:leafy-summary summary --first-column 'set-up (texel memory)' \
    '`standard` 2048²='${l}standard '`focused` 2048²='${l}focused '`psm` 2048²='${l}psm \
    '`tsm` 2048²='${l}tsm '`lispsm` 2048²='${l}lispsm '`csm` 4 × 1024²='${l}csm-1024 \
    '`csm` 4 × 2048², per-split LiSPSM='${l}csm-2048-lispsm '`virtual` 16k² clipmap='${l}virtual
$tables docs/materials.md:forests forests \
    '`standard` 2048²='"${b}standard|${l}standard" '`focused` 2048²='"${b}focused|${l}focused" \
    '`psm` 2048²='"${b}psm|${l}psm" '`tsm` 2048²='"${b}tsm|${l}tsm" '`lispsm` 2048²='"${b}lispsm|${l}lispsm" \
    '`csm` 4 × 1024²='"${b}csm-1024|${l}csm-1024" \
    '`csm` 4 × 2048², per-split LiSPSM='"${b}csm-2048-lispsm|${l}csm-2048-lispsm" \
    '`virtual` 16k² clipmap='"${b}virtual|${l}virtual"
git diff --stat -- README.md docs/materials.md
