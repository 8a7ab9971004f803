#!/usr/bin/env bash
# Partial occlusion by leaves (issue 52, item 2): the leafy forest's six sunlit views under the
# real sun (0.53°) with PCSS, its leaves cast through the depth test and through opacity layers
# (--foliage-opacity), for the default TSM at 2048² and 4096², four LiSPSM cascades and virtual
# shadow maps — sweep data/sweeps/leafy-opacity.json at 640 × 360 — written into
# docs/materials.md (the means against both truths and the figures per view) and the README's
# leafy section, which leads with it (soft_mae / soft_wrong_pct per set-up, with and without).
# About 11 minutes on this project's 2-core llvmpipe machine (the leafy shadow passes dominate;
# the opacity layers draw the leaves twice more).
#   SHADOWKIT=PATH   the binary to run (a copy keeps a rebuild from changing it mid-run)
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -n ${SHADOWKIT:-} ]] || [ -x build/apps/shadowkit/shadowkit ] || tools/build.sh
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit}
"$B" sweep data/sweeps/leafy-opacity.json --out out/sweeps/leafy-opacity --discard-stale
results=out/sweeps/leafy-opacity/results.csv
python3 tools/readme_tables.py --into docs/materials.md:foliage-opacity soft-table "$results"
python3 tools/readme_tables.py --into docs/materials.md:foliage-opacity-views soft "$results"
python3 tools/readme_tables.py --into README.md:leafy-soft-lead soft-disk "$results"
git diff --stat -- README.md docs/materials.md
