#!/usr/bin/env bash
# The README's main job: build, then on the default 10,000-tree forest render every
# standard view with the default technique (image + shadow map) and measure it against
# ray-traced truth (figures table, JSON, error and aliasing maps), then the night and dusk
# views with spot and point lights (image, their maps, figures per light), all into out/.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
mkdir -p out
shadowkit=build/apps/shadowkit/shadowkit
for view in paper perpendicular into-sun sun-behind noon aerial; do
  echo "== render $view" >&2
  "$shadowkit" render --view "$view" --out "out/$view.png" --shadow-map-out "out/$view-shadowmap.png"
done
echo "== eval, all views" >&2
"$shadowkit" eval --views all --json out/figures.json --error-map out/error.png --aliasing-map out/aliasing.png
for view in lamp torch village; do
  echo "== render $view (spot and point lights)" >&2
  "$shadowkit" render --view "$view" --out "out/$view.png" --local-map-out "out/$view-localmaps.png"
done
echo "== eval, local-light views" >&2
"$shadowkit" eval --views local --json out/figures-local.json --error-map out/error.png
echo "images, maps, out/figures.json and out/figures-local.json in out/" >&2
