#!/usr/bin/env bash
# The README's main job: build, then on the default 10,000-tree forest render every standard
# view with the default set-up — the six sunlit views and the night and dusk views with spot and
# point lights — measure each against ray-traced truth and write one page, out/index.html (per
# view the frame, the rendered and ray-traced shadows, the error and aliasing maps, the figures
# explained) with the figures as JSON beside it (out/figures.json); then the same for the six
# sunlit views of the leafy forest (--forest leafy: branches and alpha-tested leaf cards), in
# out/leafy/, also against the truth under the sun's real disk (0.53°: how much of it each
# pixel sees, which under a canopy is a fraction) — soft figures and pictures beside the hard.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
mkdir -p out
shadowkit=build/apps/shadowkit/shadowkit
echo "== eval, every standard view (sunlit, then with spot and point lights)" >&2
"$shadowkit" eval --views paper,perpendicular,into-sun,sun-behind,noon,aerial,lamp,torch,village \
    --json out/figures.json --report out/index.html
echo "== eval, the leafy forest's sunlit views, against the point sun and the sun's disk" >&2
mkdir -p out/leafy
"$shadowkit" eval --forest leafy --views paper,perpendicular,into-sun,sun-behind,noon,aerial --sun-angle 0.53 \
    --json out/leafy/figures.json --report out/leafy/index.html
echo "open $(pwd)/out/index.html (the leafy forest: $(pwd)/out/leafy/index.html)" >&2
