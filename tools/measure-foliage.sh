#!/usr/bin/env bash
# The foliage tables under the real sun (issue 52): the leafy forest's soft sweep,
# data/sweeps/leafy-soft.json (the cells of data/sweeps/soft-filters.json on --forest leafy),
# beside the blob forest's soft sweep (as tools/measure-soft.sh runs it), written into
# docs/materials.md: each set-up and filter against both truths, the point sun's (wrong_pct) and
# the sun disk's (soft_mae, penumbra_mae, soft_wrong_pct). (The README's leafy section leads with
# tools/measure-foliage-opacity.sh's table: PCSS with and without the opacity layers.)
#
# The leafy sweep evaluates 138 views of 56 M triangles at 1280 × 720 under a 0.53° sun: about
# 4 minutes on an NVIDIA H200 (16 CPU cores for the truth), 26 minutes on this project's 2-core
# llvmpipe machine (2026-12-06). LEAFY_RESULTS=FILE writes the tables from a results.csv measured elsewhere:
# the H200's is kept, data/gpu/h200-2026-11-29-leafy-soft.csv (tools/measure-gpu.sh foliage). SKIP_SWEEP=1 keeps the blob
# forest's last results (out/sweeps/soft-filters).
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/apps/shadowkit/shadowkit ] || tools/build.sh
B=build/apps/shadowkit/shadowkit
blob=out/sweeps/soft-filters/results.csv
if [[ -z "${SKIP_SWEEP:-}" || ! -f $blob ]]; then
  "$B" sweep data/sweeps/soft-filters.json --out out/sweeps/soft-filters --discard-stale
fi
leafy=${LEAFY_RESULTS:-}
if [[ -z $leafy ]]; then
  "$B" sweep data/sweeps/leafy-soft.json --out out/sweeps/leafy-soft --discard-stale
  leafy=out/sweeps/leafy-soft/results.csv
fi
python3 tools/readme_tables.py --into docs/materials.md:foliage-soft soft-forests "$blob" "$leafy"
python3 tools/readme_tables.py --into docs/materials.md:foliage-soft-views soft "$leafy"
git diff --stat -- docs/materials.md
