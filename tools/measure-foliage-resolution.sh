#!/usr/bin/env bash
# How much of the foliage error is resolution (issue 52): the leafy forest's six sunlit views
# under the real sun (0.53°) with PCSS, TSM and four LiSPSM cascades at a quarter of the default's
# texels up to sixteen times them, then without levels of detail and with raster and ray held to
# one leaf (--depth-tolerance 0.0005) — sweep data/sweeps/leafy-resolution.json at 640 × 360 —
# and where `aerial`'s error lies, ground or trees (tools/foliage_error_split.py over `eval
# --dump`), all written into docs/materials.md, and docs/foliage-one-leaf.png
# (tools/foliage_agreement_figure.py). About 20 minutes on this project's 2-core llvmpipe machine.
#   SHADOWKIT=PATH   the binary to run (a copy keeps a rebuild from changing it mid-run)
set -euo pipefail
cd "$(dirname "$0")/.."
[[ -n ${SHADOWKIT:-} ]] || [ -x build/apps/shadowkit/shadowkit ] || tools/build.sh
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit}
"$B" sweep data/sweeps/leafy-resolution.json --out out/sweeps/leafy-resolution --discard-stale
results=out/sweeps/leafy-resolution/results.csv
python3 tools/readme_tables.py --into docs/materials.md:foliage-resolution soft-table "$results"
python3 tools/readme_tables.py --into docs/materials.md:foliage-resolution-views soft "$results"

dumps=out/foliage-resolution
aerial=(eval --forest leafy --views aerial --size 640x360 --sun-angle 0.53 --filter pcss --technique tsm)
"$B" "${aerial[@]}" --map-size 2048 --dump "$dumps/2048" >/dev/null
"$B" "${aerial[@]}" --map-size 8192 --dump "$dumps/8192" >/dev/null
"$B" "${aerial[@]}" --map-size 8192 --no-lod --dump "$dumps/8192-no-lod" >/dev/null
"$B" "${aerial[@]}" --map-size 8192 --no-lod --depth-tolerance 0.0005 --dump "$dumps/8192-no-lod-one-leaf" >/dev/null
/usr/bin/python3 tools/foliage_error_split.py --into docs/materials.md:foliage-resolution-split \
  "tsm 2048²=$dumps/2048" "tsm 8192²=$dumps/8192" "tsm 8192², no levels=$dumps/8192-no-lod" \
  "tsm 8192², no levels, one leaf=$dumps/8192-no-lod-one-leaf"
/usr/bin/python3 tools/foliage_agreement_figure.py "$dumps/8192-no-lod" "$dumps/8192-no-lod-one-leaf"
git diff --stat -- docs/materials.md docs/foliage-one-leaf.png
