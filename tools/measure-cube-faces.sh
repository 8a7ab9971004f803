#!/usr/bin/env bash
# Cube faces a point light skips (they see nothing of the view) on the `lamp` view, for the
# lamp 10 m from the eye, 3 m up, at eight bearings round the view direction (0 = straight
# ahead, the view's own lamp). docs/local-lights.md. No GL needed: `shadowkit setup`.
set -euo pipefail
cd "$(dirname "$0")/.."
SK=${SK:-build/apps/shadowkit/shadowkit}
eye=$("$SK" setup --view lamp | python3 -c 'import json,sys; print(*json.load(sys.stdin)["inputs"]["camera"]["eye"])')
read -r ex ey ez <<<"$eye"
printf "%-8s %-26s %s\n" bearing "light (x, y, z)" skipped_faces
total=0
for bearing in 0 45 90 135 180 225 270 315; do
  # The lamp view looks along -Z (azimuth 0); bearing clockwise from it, seen from above.
  pos=$(python3 -c "import math; b=math.radians($bearing); print(f'{$ex+10*math.sin(b):.3f},{$ey-1.8+3:.3f},{$ez-10*math.cos(b):.3f}')")
  skipped=$("$SK" setup --view lamp --light "point:$pos,30" |
            python3 -c 'import json,sys; print(json.load(sys.stdin)["local_lights"][1]["skipped_faces"])')
  printf "%-8s %-26s %s\n" "$bearing" "$pos" "$skipped"
  total=$((total + skipped))
done
python3 -c "print(f'mean skipped faces over the eight bearings: {$total/8:.2f} of 6')"
