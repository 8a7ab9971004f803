#!/usr/bin/env bash
# What the engine adapters' spot maps gain over the engines' own spot cameras
# (docs/engine-integration.md): street lamps — spot lights 6 m up, shining straight down, a 90°
# cone reaching 20 m — placed round the `torch` view's eye at three distances and five bearings.
# OpenSceneGraph's ViewDependentShadowMap gives a spot the whole cone (a field of view of twice
# its cutoff), OGRE 1.12's default camera 1.2 times the cone; the adapters give the core's map
# (shadowkit setup's), narrowed to what the camera sees of the cone. Same map size, so the
# texels per metre gained along each axis is the ratio of the tangent spans, and the texels
# spent on what the camera sees, their product. No GL needed.
#
# Then the same switch end to end, scored against the ray-traced truth: four lamps over a
# 300-tree patch seen from 40 m up (`--sun off --light spot:...`), drawn by OpenSceneGraph and
# by OGRE (their samples, under Xvfb) with each engine's own spot camera and with the adapter's,
# at 512² and 2048², each mask scored by `shadowkit score --light`; shadowkit's own renderer
# (`eval`, its biases in metres) beside them, each mask drawn by a process of its own
# (tools/engine-lamp-masks.sh). About a minute on this project's 2-core machine.
set -euo pipefail
cd "$(dirname "$0")/.."
SK=${SK:-build/apps/shadowkit/shadowkit}
[ -x "$SK" ] || tools/build.sh
python3 - "$SK" <<'PY'
import json, math, subprocess, sys
sk = sys.argv[1]
camera = json.loads(subprocess.run([sk, "setup", "--view", "torch"], check=True, capture_output=True,
                                   text=True).stdout)["inputs"]["camera"]
eye, forward = camera["eye"], camera["direction"]
heading = math.atan2(forward[0], -forward[2])  # azimuth of the view, from -Z towards +X
cone = 90.0
whole = 2.0 * math.tan(math.radians(cone / 2))                # OSG: the whole cone
ogre = 2.0 * math.tan(math.radians(min(1.2 * cone, 175) / 2))  # OGRE 1.12: 1.2 x the cone
print(f"{'distance':>8} {'bearing':>7}  {'map span (x, y)':>16}  {'vs OSG: axis, area':>19}  {'vs OGRE: axis, area':>20}")
gains = {"osg": [], "ogre": []}
for distance in (4, 8, 15):
    for bearing in (0, 30, 60, 90, 135, 180):
        b = heading + math.radians(bearing)
        x, z = eye[0] + distance * math.sin(b), eye[2] - distance * math.cos(b)
        # The lamp 6 m above the ground under it: the torch view's eye stands 1.6 m above it.
        y = eye[1] - 1.6 + 6.0
        light = f"spot:{x:.3f},{y:.3f},{z:.3f},0,-1,0,{cone:g},20"
        out = json.loads(subprocess.run([sk, "setup", "--view", "torch", "--light", light], check=True,
                                        capture_output=True, text=True).stdout)
        spot = out["local_lights"][-1]
        if not spot["views"]:
            print(f"{distance:>8} {bearing:>7}  no map: the cone misses the view")
            continue
        m = spot["views"][0]["clip_from_light"]  # column-major: m[0] = [0][0], m[5] = [1][1]
        sx, sy = 2.0 / m[0], 2.0 / m[5]
        row = f"{distance:>8} {bearing:>7}  {sx:>7.3f}, {sy:>7.3f}"
        for name, span in (("osg", whole), ("ogre", ogre)):
            axis = span / max(sx, sy)
            area = span * span / (sx * sy)
            gains[name].append(area)
            row += f"  {axis:>8.2f}x, {area:>7.2f}x"
        print(row)
for name, label in (("osg", "OpenSceneGraph's"), ("ogre", "OGRE's")):
    g = gains[name]
    geo = math.exp(sum(map(math.log, g)) / len(g))
    print(f"texels on what the camera sees against {label} own camera: geometric mean {geo:.2f}x, "
          f"least {min(g):.2f}x, most {max(g):.2f}x over {len(g)} lamps")
PY

OSG=build/adapters/osg/shadowkit-osg-sample
OGRE=build/adapters/ogre/shadowkit-ogre-sample
if [ ! -x "$OSG" ] || [ ! -x "$OGRE" ] || ! command -v xvfb-run > /dev/null; then
  echo "measure-engine-spots: no engine samples or no xvfb-run: the end-to-end table is left out" >&2
  exit 0
fi
out=out/engine-spots
mkdir -p "$out"
forest=(--trees 300 --terrain-size 256)
view=(--view aerial --eye 0,40,0 --dir 0,-0.7,-1 --sun off --size 640x360)
lamps=("ahead:spot:0,50,-45,0,-1,0,120,60" "behind:spot:0,50,15,0,-1,-0.6,100,80"
       "left:spot:-30,45,-20,0,-1,0,120,60" "right:spot:30,45,-10,-0.3,-1,-0.3,120,60")
[ -s "$out/patch.obj" ] || "$SK" export "${forest[@]}" --out "$out/patch.obj" 2> /dev/null
. tools/engine-lamp-masks.sh
echo
echo "| lamp | map | OSG's own | adapter in OSG | OGRE's own | adapter in OGRE | shadowkit's renderer (\`eval\`) | the same, 2 × 2 PCF as OSG samples |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|"
for entry in "${lamps[@]}"; do
  name=${entry%%:*} light=${entry#*:}
  "$SK" setup "${forest[@]}" "${view[@]}" --light "$light" > "$out/$name.json"
  for n in 512 2048; do
    row="| $name | $n² |$(lamp_masks "$name" "$light" "$n")"
    "$SK" eval "${forest[@]}" "${view[@]}" --light "$light" --local-map-size "$n" --json "$out/$name-$n-eval.json" > /dev/null 2>&1
    "$SK" eval "${forest[@]}" "${view[@]}" --light "$light" --local-map-size "$n" --filter pcf2 \
      --json "$out/$name-$n-eval-pcf2.json" > /dev/null 2>&1
    echo "$row $(wrong "$out/$name-$n-eval.json") | $(wrong "$out/$name-$n-eval-pcf2.json") |"
  done
done
