#!/bin/sh
# The figures of docs/dynamics.md: shadowkit eval along the flythrough
# path (240 frames, 1280x720, movers on) for every technique at equal memory (one 4096² map,
# or 4 cascades of 2048²), with the sun moving as the path says and, for cascades, held
# still (--sun-path off) so that only the camera moves. Rows go to build/dynamics/NAME.json
# and .csv; tools/readme_tables.py dynamics prints the table, tools/plot_flicker.py the plot.
# About 7 minutes a row on this project's 2-core machine.
set -eu
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit}
OUT=${OUT:-build/dynamics}
FRAMES=${FRAMES:-0:240}
mkdir -p "$OUT"
run() {
  name=$1
  shift
  [ -n "${ONLY:-}" ] && case " $ONLY " in *" $name "*) ;; *) return 0 ;; esac
  echo "== $name: $*" >&2
  "$B" eval --path flythrough --frames "$FRAMES" "$@" --csv "$OUT/$name.csv" --json "$OUT/$name.json" > "$OUT/$name.txt"
  tail -n 1 "$OUT/$name.txt" >&2
}
run csm-stabilize-sun-held --technique csm --cascades 4 --map-size 2048 --stabilize --sun-path off
run csm-sun-held           --technique csm --cascades 4 --map-size 2048 --sun-path off
run tsm-sun-held           --technique tsm --map-size 4096 --sun-path off
run lispsm-sun-held        --technique lispsm --map-size 4096 --sun-path off
run csm-lispsm-sun-held    --technique csm --cascades 4 --map-size 2048 --cascade-warp lispsm --sun-path off
# Held texel lattices (core::SetupHysteresis): the stable warped maps.
run lispsm-stabilize-sun-held     --technique lispsm --map-size 4096 --stabilize --sun-path off
run tsm-stabilize-sun-held        --technique tsm --map-size 4096 --stabilize --sun-path off
run csm-lispsm-stabilize-sun-held --technique csm --cascades 4 --map-size 2048 --cascade-warp lispsm --stabilize --sun-path off
# Error-driven parameters at the same memory (core::AutoChooser): one map, and any split count.
run auto-single-sun-held --technique auto --cascades 1 --texel-budget 16M --sun-path off
run auto-any-sun-held    --technique auto --texel-budget 16M --sun-path off
run auto-single-stabilize-sun-held --technique auto --cascades 1 --texel-budget 16M --stabilize --sun-path off
run standard               --technique standard --map-size 4096
run focused                --technique focused --map-size 4096
run psm                    --technique psm --map-size 4096
run tsm                    --technique tsm --map-size 4096
run lispsm                 --technique lispsm --map-size 4096
run csm                    --technique csm --cascades 4 --map-size 2048
run csm-stabilize          --technique csm --cascades 4 --map-size 2048 --stabilize
run csm-lispsm             --technique csm --cascades 4 --map-size 2048 --cascade-warp lispsm
run lispsm-stabilize       --technique lispsm --map-size 4096 --stabilize
