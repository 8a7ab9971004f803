#!/usr/bin/env bash
# Shadows inside engines against the truth (issue 53, item 4): the standard forest's six sunlit
# views drawn by OpenSceneGraph and by OGRE (below), first by OpenSceneGraph (adapters/osg's sample, under Xvfb) with OSG's own
# ViewDependentShadowMap — its box fit (`osg`), its light-space perspective warp
# (`osg-perspective`, OSG's default) and that warp over two maps (`osg-split`, each 1448², the
# same texels) — and with shadowkit's shadow camera in the same engine (the adapter: `tsm`,
# `lispsm`, `focused`, `psm`, and `auto` for the receivers the sample reads back), all at 2048²,
# each mask scored by `shadowkit score`; shadowkit's
# own renderer (`eval`) beside them. Written into docs/engine-integration.md. About 6 minutes
# on this project's 2-core llvmpipe machine (OSG's OBJ reader takes 4 of them).
# ENGINES="osg ogre" (the default) or either alone re-measures that engine's tables only.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/apps/shadowkit/shadowkit ] && [ -x build/adapters/osg/shadowkit-osg-sample ] &&
  [ -x build/adapters/ogre/shadowkit-ogre-sample ] || tools/build.sh
B=build/apps/shadowkit/shadowkit
OSG=build/adapters/osg/shadowkit-osg-sample
OGRE=build/adapters/ogre/shadowkit-ogre-sample
for sample in "$OSG" "$OGRE"; do
  [ -x "$sample" ] || { echo "measure-engines: no $sample: install the engines (tools/install-deps.sh)" >&2; exit 1; }
done
out=out/engines
mkdir -p "$out/along-sun" "$out/eval"
views=(paper perpendicular into-sun sun-behind noon aerial)
techniques=(osg osg-perspective osg-split tsm lispsm focused psm auto)
[ -s "$out/forest.obj" ] || "$B" export --out "$out/forest.obj"
: > "$out/shots.txt"
for v in "${views[@]}"; do
  "$B" setup --view "$v" > "$out/$v.json"
  for t in "${techniques[@]}"; do echo "$out/$v.json $t $out/$v-$t.png" >> "$out/shots.txt"; done
done
# The degenerate case of the engines' own warps: `perpendicular`'s eye looking along the sun.
python3 -c 'import json, sys
d = json.load(open(sys.argv[1]))
d["inputs"]["camera"]["direction"] = d["inputs"]["light"]["direction"]
json.dump({"inputs": d["inputs"]}, open(sys.argv[2], "w"))' "$out/perpendicular.json" "$out/along-sun.json"
for t in "${techniques[@]}"; do echo "$out/along-sun.json $t $out/along-sun-$t.png" >> "$out/shots.txt"; done
engines=${ENGINES:-osg ogre}
"$B" eval --views all --size 640x360 --technique tsm --json "$out/eval/tsm.json" > /dev/null
"$B" eval --views all --size 640x360 --technique csm --map-size 1024 --json "$out/eval/csm-1024.json" > /dev/null
if [[ " $engines " == *" osg "* ]]; then
  xvfb-run -a "$OSG" "$out/forest.obj" --shots "$out/shots.txt" --size 640x360 --map-size 2048 2> "$out/osg.log"
  for v in "${views[@]}"; do
    for t in "${techniques[@]}"; do
      "$B" score "$out/$v-$t.png" --view "$v" --size 640x360 --json "$out/$v-$t.json" > /dev/null
    done
  done
  for t in "${techniques[@]}"; do
    "$B" score "$out/along-sun-$t.png" --camera "$out/along-sun.json" --size 640x360 --json "$out/along-sun/$t.json" > /dev/null
  done
  python3 tools/readme_tables.py --into docs/engine-integration.md:engines-osg wrong \
    "OSG's own: box fit (\`osg\`)=$out/*-osg.json" \
    "OSG's own: perspective warp (\`osg-perspective\`, its default)=$out/*-osg-perspective.json" \
    "OSG's own: two maps of 1448² (\`osg-split\`)=$out/*-osg-split.json" \
    "shadowkit in OSG: \`tsm\`=$out/*-tsm.json" \
    "shadowkit in OSG: \`lispsm\`=$out/*-lispsm.json" \
    "shadowkit in OSG: \`focused\`=$out/*-focused.json" \
    "shadowkit in OSG: \`psm\`=$out/*-psm.json" \
    "shadowkit in OSG: \`auto\` over single maps=$out/*-auto.json" \
    "shadowkit's own renderer: \`tsm\` (\`eval\`)=$out/eval/tsm.json"
  python3 tools/readme_tables.py --into docs/engine-integration.md:engines-osg-along-sun scores \
    $(for t in "${techniques[@]}"; do echo "$out/along-sun/$t.json"; done)
fi

# OGRE: its own set-ups (default, focused, LiSPSM: one 2048² map each; PSSM: four 1024² maps)
# and the adapter's (the same; `csm`: four 1024² cascades through OGRE's shadow-texture
# iterations; `auto`: the core's choice of single map for the receivers OGRE's camera sees), drawn
# by the same depth-map shaders (adapters/ogre/sample).
[[ " $engines " == *" ogre "* ]] || exit 0
ogre_techniques=(ogre ogre-focused ogre-lispsm ogre-pssm tsm lispsm focused psm csm auto)
for t in "${ogre_techniques[@]}"; do mkdir -p "$out/ogre/$t"; done
: > "$out/ogre/shots.txt"
for v in "${views[@]}"; do
  for t in "${ogre_techniques[@]}"; do echo "$out/$v.json $t $out/ogre/$t/$v.png" >> "$out/ogre/shots.txt"; done
done
for t in "${ogre_techniques[@]}"; do echo "$out/along-sun.json $t $out/ogre/$t/along-sun.png" >> "$out/ogre/shots.txt"; done
xvfb-run -a "$OGRE" "$out/forest.obj" --shots "$out/ogre/shots.txt" --size 640x360 --map-size 2048
for v in "${views[@]}"; do
  for t in "${ogre_techniques[@]}"; do
    "$B" score "$out/ogre/$t/$v.png" --view "$v" --size 640x360 --json "$out/ogre/$t/$v.json" > /dev/null
  done
done
mkdir -p "$out/ogre/along-sun"
for t in "${ogre_techniques[@]}"; do
  "$B" score "$out/ogre/$t/along-sun.png" --camera "$out/along-sun.json" --size 640x360 --json "$out/ogre/along-sun/$t.json" > /dev/null
done
python3 tools/readme_tables.py --into docs/engine-integration.md:engines-ogre-along-sun scores \
  $(for t in "${ogre_techniques[@]}"; do echo "$out/ogre/along-sun/$t.json"; done)
python3 tools/readme_tables.py --into docs/engine-integration.md:engines-ogre wrong \
  "OGRE's own: \`DefaultShadowCameraSetup\` (\`ogre\`)=$out/ogre/ogre/*.json" \
  "OGRE's own: \`FocusedShadowCameraSetup\` (\`ogre-focused\`)=$out/ogre/ogre-focused/*.json" \
  "OGRE's own: \`LiSPSMShadowCameraSetup\` (\`ogre-lispsm\`)=$out/ogre/ogre-lispsm/*.json" \
  "OGRE's own: \`PSSMShadowCameraSetup\`, 4 × 1024² (\`ogre-pssm\`)=$out/ogre/ogre-pssm/*.json" \
  "shadowkit in OGRE: \`tsm\`=$out/ogre/tsm/*.json" \
  "shadowkit in OGRE: \`lispsm\`=$out/ogre/lispsm/*.json" \
  "shadowkit in OGRE: \`focused\`=$out/ogre/focused/*.json" \
  "shadowkit in OGRE: \`psm\`=$out/ogre/psm/*.json" \
  "shadowkit in OGRE: \`csm\`, 4 × 1024²=$out/ogre/csm/*.json" \
  "shadowkit in OGRE: \`auto\` over single maps=$out/ogre/auto/*.json" \
  "shadowkit's own renderer: \`tsm\` (\`eval\`)=$out/eval/tsm.json" \
  "shadowkit's own renderer: \`csm\`, 4 × 1024² (\`eval\`)=$out/eval/csm-1024.json"
git diff --stat -- docs/engine-integration.md
