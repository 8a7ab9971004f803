#!/usr/bin/env bash
# tools/measure-virtual-late.sh: technique virtual's page requests read late against a frame that
# waits for its own — docs/virtual-shadow-maps.md "Requests read late".
#
# 1. Synchronisations a frame (counts: the same on any GL): `bench --path flythrough` at 1,000
#    trees with the sun held, with the path's own moving sun, and with that sun under page
#    budgets of 256 and 64, each with --virtual-requests late and wait.
# 2. What reading late costs in the image: `eval --path flythrough --frames 0:60 --sun-path off`
#    (the default forest, 1280 × 720) with each, frame by frame against the ray-traced truth.
# Results in out/virtual-late/; the tables on stdout. About 6 minutes on this project's 2-core
# llvmpipe machine.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/apps/shadowkit/shadowkit ] || tools/build.sh
B=build/apps/shadowkit/shadowkit
out=out/virtual-late
mkdir -p "$out"
echo "commit $(git rev-parse --short HEAD), $(nproc) CPU cores, $(date -u +%Y-%m-%dT%H:%MZ)" >"$out/summary.txt"
for sun in "held|--sun-path off" "moving|" "moving-256|--virtual-page-budget 256" "moving-64|--virtual-page-budget 64"; do
  for r in late wait; do
    echo "== bench, sun ${sun%%|*}, requests $r" >&2
    # shellcheck disable=SC2086
    $B bench --trees 1000 --path flythrough --frames 24 --size 320x180 --technique virtual --virtual-requests "$r" \
      ${sun#*|} --json "$out/sync-${sun%%|*}-$r.json" >"$out/sync-${sun%%|*}-$r.log" 2>&1
  done
done
for r in late wait; do
  echo "== eval along the flythrough, sun held, requests $r" >&2
  $B eval --path flythrough --frames 0:60 --sun-path off --technique virtual --virtual-requests "$r" \
    --json "$out/path-$r.json" >"$out/path-$r.log" 2>&1
done
python3 - "$out" <<'EOF' | tee -a "$out/summary.txt"
import json, sys
out = sys.argv[1]
print("| sun | requests late: synchronisations a frame, median / max | waited for: median / max |")
print("|---|---|---|")
names = {"held": "held", "moving": "the path's own (moving)", "moving-256": "moving, page budget 256",
         "moving-64": "moving, page budget 64"}
for sun, label in names.items():
    cells = []
    for r in ("late", "wait"):
        rb = json.load(open(f"{out}/sync-{sun}-{r}.json"))["runs"][0]["read_backs"]
        cells.append(f"{rb['median']:g} / {rb['max']:g}")
    print(f"| {label} | {cells[0]} | {cells[1]} |")
print()
runs = {r: json.load(open(f"{out}/path-{r}.json")) for r in ("late", "wait")}
frames = {r: runs[r]["frames"] for r in runs}
print("| requests | `wrong_pct` mean | `flicker_pct` mean / p95 | requests' age (frames), after the first |")
print("|---|---|---|---|")
for r in ("late", "wait"):
    s = runs[r]["summary"]
    ages = sorted({x["virtual"]["requests_age"] for x in frames[r][1:]})
    print(f"| {r} | {s['wrong_pct']['mean']:.3f} | {s['flicker_pct']['mean']:.3f} / {s['flicker_pct']['p95']:.3f} | "
          f"{', '.join(map(str, ages))} |")
diff = [abs(a["wrong_pct"] - b["wrong_pct"]) for a, b in zip(frames["late"], frames["wait"])]
print()
print(f"frames whose wrong_pct differs: {sum(d > 1e-9 for d in diff)} of {len(diff)}, "
      f"by at most {max(diff):.4f} points")
EOF
