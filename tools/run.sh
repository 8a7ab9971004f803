#!/usr/bin/env bash
# The README's main job: build, then render the default 10,000-tree forest from the
# standard views with the default technique into out/ (image + shadow map per view).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
mkdir -p out
for view in paper perpendicular into-sun sun-behind noon aerial; do
  echo "== view $view" >&2
  build/apps/shadowkit/shadowkit render --view "$view" --out "out/$view.png" --shadow-map-out "out/$view-shadowmap.png"
done
echo "images in out/" >&2
