#!/usr/bin/env bash
# tools/measure-foliage-setups.sh: every set-up on the leafy forest under the real sun (issue 52,
# item 1), into docs/materials.md ("Every set-up under the real sun"): the sweep
# data/sweeps/leafy-soft-setups.json — the four single maps the H200's leafy soft sweep
# (tools/measure-foliage.sh) leaves out, beside the three it has, each with the hard test, a 3 × 3
# PCF and PCSS, at 640 × 360, against the point sun's truth and the 0.53° disk's. About 15 minutes
# on this project's 2-core llvmpipe machine. SKIP_SWEEP=1 writes the tables from the last results
# (out/sweeps/leafy-soft-setups).
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/apps/shadowkit/shadowkit ] || tools/build.sh
out=out/sweeps/leafy-soft-setups
if [[ -z "${SKIP_SWEEP:-}" || ! -f $out/results.csv ]]; then
  build/apps/shadowkit/shadowkit sweep data/sweeps/leafy-soft-setups.json --out "$out" --discard-stale
fi
python3 tools/readme_tables.py --into docs/materials.md:foliage-setups soft-table "$out/results.csv"
python3 tools/readme_tables.py --into docs/materials.md:foliage-setups-widths soft-widths "$out/results.csv"
git diff --stat -- docs/materials.md
