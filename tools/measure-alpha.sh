#!/usr/bin/env bash
# tools/measure-alpha.sh [CARDS] [RUNS] [TECHNIQUE]: what alpha testing costs. Writes two fields of CARDS leaf
# cards (tools/card_field.py, default 20000 cards = 40,000 triangles over a ground quad), one
# MASK and one OPAQUE, the same triangles and texture, and renders each RUNS times (default 5)
# with `shadowkit render` at its defaults (TSM 2048², 1280×720, the loaded scene framed), or
# --technique TECHNIQUE (focused: hyperbolic depth, where opaque casters keep early depth tests).
# Prints the median GPU ms of the shadow pass and the main pass, and the ratios (docs/materials.md).
set -euo pipefail
cd "$(dirname "$0")/.."
cards=${1:-20000}
runs=${2:-5}
technique=${3:-tsm}
python=/usr/bin/python3
[ -x "$python" ] || python=python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
[ -x build/apps/shadowkit/shadowkit ] || tools/build.sh
declare -A shadow main
for mode in MASK OPAQUE; do
  "$python" tools/card_field.py "$work/$mode.gltf" --cards "$cards" --mode "$mode" >/dev/null
  s=(); m=()
  for ((i = 0; i < runs; ++i)); do
    out=$(build/apps/shadowkit/shadowkit render --scene "$work/$mode.gltf" --technique "$technique" --out "$work/$mode.png" 2>&1)
    s+=("$(awk '/shadow pass/ {print $3}' <<<"$out")")
    m+=("$(awk '/main pass/ {print $3}' <<<"$out")")
  done
  shadow[$mode]=$(printf '%s\n' "${s[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
  main[$mode]=$(printf '%s\n' "${m[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
  echo "$mode ($technique): $cards cards, $((2 * cards)) triangles: shadow pass ${shadow[$mode]} ms, main pass ${main[$mode]} ms (median of $runs; ${s[*]} / ${m[*]})"
done
awk -v ms="${shadow[MASK]}" -v os="${shadow[OPAQUE]}" -v mm="${main[MASK]}" -v om="${main[OPAQUE]}" \
  'BEGIN { printf "alpha-tested / opaque: shadow pass %.2f×, main pass %.2f×\n", ms / os, mm / om }'
echo "machine: $(nproc) cores, $(build/apps/shadowkit/shadowkit render --scene "$work/MASK.gltf" --out "$work/x.png" 2>&1 | grep -o 'Mesa[^|]*' | head -1)"
