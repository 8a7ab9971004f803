# Sourced by tools/measure-engine-spots.sh and tools/measure-engine-points.sh: one lamp's four
# masks — OpenSceneGraph's and OGRE's own shadow cameras and the adapters' — drawn by the engine
# samples under Xvfb and scored against the ray-traced truth by `shadowkit score --light`.
#
# Each mask is drawn by a process of its own. Drawn one after another in one process, under
# llvmpipe with two threads (Mesa 22.3.6, this project's 2-core machine), a shot of OSG's own
# camera left the next shot of the same lamp reading its map wrongly: the `behind` spot's adapter
# mask 46.9 % wrong, acne over the whole ground, where alone, or with 1, 3 or 4 threads, it is
# 0.08 %. A figure must not depend on what was drawn before it.
#
# Needs SK, OSG, OGRE, out and the arrays forest and view set by the caller.

# The wrong_pct of a `score` or `eval` JSON file.
wrong() {
  python3 -c 'import json, sys
d = json.load(open(sys.argv[1]))
print("%.2f" % (d.get("scores") or d["views"])[0]["wrong_pct"])' "$1"
}

# lamp_masks NAME LIGHT MAPSIZE [MASK...]: draws and scores the masks of $out/NAME.json (a
# `shadowkit setup` camera file with the lamp) at MAPSIZE² and prints " osg | osg-adapter | ogre |
# ogre-adapter |", each the mask's wrong_pct; MASK... names others, in order (ogre-cube: the OGRE
# adapter's cube faces, six textures, for a point light).
lamp_masks() {
  local name=$1 light=$2 n=$3 mask sample technique row=""
  shift 3
  local masks=("$@")
  [ ${#masks[@]} -gt 0 ] || masks=(osg osg-adapter ogre ogre-adapter)
  for mask in "${masks[@]}"; do
    case $mask in
      osg) sample=$OSG technique=osg ;;
      osg-adapter) sample=$OSG technique=tsm ;;
      ogre) sample=$OGRE technique=ogre ;;
      ogre-adapter) sample=$OGRE technique=tsm ;;
      ogre-cube) sample=$OGRE technique=cube ;;
    esac
    echo "$out/$name.json $technique $out/$name-$n-$mask.png" > "$out/shots.txt"
    xvfb-run -a "$sample" "$out/patch.obj" --shots "$out/shots.txt" --size 640x360 --map-size "$n" > /dev/null 2>&1
    "$SK" score "$out/$name-$n-$mask.png" "${forest[@]}" "${view[@]}" --light "$light" \
      --json "$out/$name-$n-$mask.json" > /dev/null 2>&1
    row+=" $(wrong "$out/$name-$n-$mask.json") |"
  done
  echo "$row"
}
