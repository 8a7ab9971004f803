#!/usr/bin/env bash
# tools/gpu-tables.sh RESULTS.tgz: writes docs/performance.md's real-GPU tables ("On a real GPU")
# from the gpu-results.tgz tools/measure-gpu.sh leaves on the GPU machine (copied back here),
# beside llvmpipe's eval of the same five set-ups, measured here first (a few minutes on the
# project's 2-core machine; KEEP_LLVMPIPE=1 keeps the last ones).
set -euo pipefail
[[ $# -eq 1 && -f $1 ]] || { echo "usage: tools/gpu-tables.sh RESULTS.tgz (from tools/measure-gpu.sh)" >&2; exit 2; }
results=$(realpath "$1")
cd "$(dirname "$0")/.."
[ -x build/apps/shadowkit/shadowkit ] || tools/build.sh
gpu=out/gpu/results
cpu=out/gpu/llvmpipe
rm -rf "$gpu" && mkdir -p "$gpu" "$cpu"
tar -xzf "$results" -C "$gpu"
# A GPU family's golden figures, where the run re-recorded them (measure-gpu.sh's golden section).
if [[ -d $gpu/golden ]]; then
  for family in "$gpu"/golden/*/; do
    name=$(basename "$family")
    mkdir -p "data/golden/$name" && cp "$family"*.json "data/golden/$name/" && echo "golden figures of $name updated" >&2
  done
fi
# The set-ups tools/measure-gpu.sh's eval section measures, with the same options.
for setup in "tsm|--technique tsm" "csm4x2048-lispsm|--technique csm --cascades 4 --map-size 2048 --cascade-warp lispsm" \
  "virtual|--technique virtual" "tsm-hyperbolic|--technique tsm --depth-layout hyperbolic" \
  "psm-receiver-plane|--technique psm --receiver-plane-bias on --filter pcf:3"; do
  name=${setup%%|*}
  if [[ -z ${KEEP_LLVMPIPE:-} || ! -f $cpu/eval-$name.json ]]; then
    echo "== llvmpipe: eval --views all ${setup#*|}" >&2
    # shellcheck disable=SC2086
    build/apps/shadowkit/shadowkit eval --views all ${setup#*|} --json "$cpu/eval-$name.json" >/dev/null
  fi
done
python3 tools/gpu_tables.py "$gpu" "$cpu"
head -4 "$gpu/summary.txt" >&2
