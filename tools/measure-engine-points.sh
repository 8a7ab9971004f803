#!/usr/bin/env bash
# What the engine adapters' point-light maps gain over the engines' own, end to end
# (docs/engine-integration.md, "Point lights in the engines"). Neither engine's pipeline here
# draws cube maps: OpenSceneGraph's ViewDependentShadowMap aims a point light's one map along the
# light's direction attribute (−Z unless set) and widens it to the view frustum's corners, at
# most 160°; OGRE 1.12 gives it 120°, aimed from the lamp at a point ahead of the camera. The
# adapters give the core's one map (core::computePointSingleMapSetup): the narrowest cone over
# what the camera sees within the lamp's reach, where that spans at most 170°, and where it does
# not (the `among` lamps, standing in what the camera sees) a 170° cone aimed at the middle of it.
#
# Seven point lamps over a 300-tree patch seen from 40 m up (`--sun off --light point:...`), drawn
# by OpenSceneGraph and by OGRE (their samples, under Xvfb) with each engine's own camera and with
# the adapter's, and in OGRE the adapter's cube faces too (six shadow textures of that size,
# setPointLightCubeFaces), at 512² and 2048², each mask scored against the ray-traced truth by
# `shadowkit score --light`; shadowkit's own renderer (`eval`: a cube of up to six faces of that size) beside
# them. OSG's lights fade rather than end: the OSG sample gives each lamp the fall-off that
# reaches its range (osgadapter::setReach), which the adapter's map spans, as OGRE's spans its
# range (the truth's). Each mask is drawn by a process of its own (tools/engine-lamp-masks.sh).
# Then the `ahead` lamp's four masks at 2048² side by side (out/engine-points/ahead-2048.png; the
# picture in the docs). About a minute on this project's 2-core machine.
set -euo pipefail
cd "$(dirname "$0")/.."
SK=${SK:-build/apps/shadowkit/shadowkit}
OSG=build/adapters/osg/shadowkit-osg-sample
OGRE=build/adapters/ogre/shadowkit-ogre-sample
[ -x "$SK" ] || tools/build.sh
if [ ! -x "$OSG" ] || [ ! -x "$OGRE" ] || ! command -v xvfb-run > /dev/null; then
  echo "measure-engine-points: no engine samples or no xvfb-run: nothing to measure" >&2
  exit 0
fi
out=out/engine-points
mkdir -p "$out"
forest=(--trees 300 --terrain-size 256)
view=(--view aerial --eye 0,40,0 --dir 0,-0.7,-1 --sun off --size 640x360)
lamps=("ahead:point:0,50,-45,60" "behind:point:0,50,15,80" "left:point:-30,45,-20,60" "right:point:30,45,-10,60"
       "among-a:point:0,5,-40,30" "among-b:point:10,8,-25,40" "among-c:point:-20,12,-60,50")
[ -s "$out/patch.obj" ] || "$SK" export "${forest[@]}" --out "$out/patch.obj" > /dev/null 2>&1
. tools/engine-lamp-masks.sh
echo "| lamp | map | OSG's own | adapter in OSG | OGRE's own | adapter in OGRE | adapter in OGRE, cube faces | shadowkit's renderer (\`eval\`, a cube) |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|"
for entry in "${lamps[@]}"; do
  name=${entry%%:*} light=${entry#*:}
  "$SK" setup "${forest[@]}" "${view[@]}" --light "$light" > "$out/$name.json"
  for n in 512 2048; do
    row="| $name | $n² |$(lamp_masks "$name" "$light" "$n" osg osg-adapter ogre ogre-adapter ogre-cube)"
    "$SK" eval "${forest[@]}" "${view[@]}" --light "$light" --local-map-size "$n" --json "$out/$name-$n-eval.json" > /dev/null 2>&1
    echo "$row $(wrong "$out/$name-$n-eval.json") |"
  done
done

# The ahead lamp's masks, the engines' own cameras on the left, the adapters' on the right.
/usr/bin/python3 - "$out" <<'PY' || echo "measure-engine-points: no picture (Pillow missing?)" >&2
import sys
from PIL import Image, ImageDraw
out = sys.argv[1]
panels = [("osg", "OpenSceneGraph's own camera"), ("osg-adapter", "the adapter in OpenSceneGraph"),
          ("ogre", "OGRE's own camera"), ("ogre-adapter", "the adapter in OGRE")]
first = Image.open(f"{out}/ahead-2048-osg.png")
w, h = first.size[0] // 2, first.size[1] // 2
sheet = Image.new("RGB", (2 * w, 2 * h), "white")
for i, (name, label) in enumerate(panels):
    mask = Image.open(f"{out}/ahead-2048-{name}.png").convert("RGB").resize((w, h), Image.LANCZOS)
    draw = ImageDraw.Draw(mask)
    draw.rectangle([0, 0, 6 * len(label) + 8, 14], fill="black")
    draw.text((4, 2), label, fill="white")
    sheet.paste(mask, ((i % 2) * w, (i // 2) * h))
sheet.save(f"{out}/ahead-2048.png")
print(f"wrote {out}/ahead-2048.png")
PY
