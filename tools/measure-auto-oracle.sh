#!/bin/sh
# How low --technique auto's mean wrong_pct could go at 4 M texels by choosing parameters at all
# (docs/error-driven.md): 40 fixed configurations within the budget - TSM's focus
# fraction, LiSPSM's weight on n on both warp axes, 2, 3 and 4 cascades over the visible depth
# at four values of lambda, unwarped and warped per split, and focused - each measured against
# the ray-traced truth on the six standard views: one sweep, data/sweeps/auto-oracle.json
# (resumable: run it again after an interruption); tools/readme_tables.py oracle then keeps the
# lowest wrong_pct per view, as an oracle that knew the truth would. About 5 minutes on this
# project's 2-core machine.
set -eu
B=${SHADOWKIT:-build/apps/shadowkit/shadowkit}
OUT=${OUT:-build/auto-oracle}
"$B" sweep data/sweeps/auto-oracle.json --out "$OUT" --discard-stale
tools/readme_tables.py oracle --name technique,tsm_focus,lispsm_weight,lispsm_direction,cascades,lambda,cascade_warp \
  "$OUT/results.csv"
