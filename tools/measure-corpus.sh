#!/usr/bin/env bash
# The default set-up on every model of the corpus (issue 49's bound, docs/reliability.md "Models
# we did not make"): each glTF 2.0 and OBJ file of Debian's assimp-testmodels, as
# CorpusTest loads them, evaluated on the six sunlit views at 640 × 360 with the default set-up
# and with `--technique focused`; tools/corpus_tables.py then writes the table of the models on
# which the default is more than 1.5 × `focused` + 0.1 points wrong on some view into
# docs/reliability.md, and the count of those on which it is not. The project's own scenes for the
# corpus follow (the pillar on its plate, tools/authored_shapes.py's shapes). Files the loader
# refuses (exit 1 and a one-line reason, kept in out/corpus/refused.txt) are counted, not
# evaluated; any other failure stops the script. About 5 minutes on this project's 2-core machine.
#
# CANDIDATE="FLAGS" holds a would-be default to the bound instead: the default set-up with FLAGS
# added (e.g. CANDIDATE="--offset-guard on"), into out/corpus-candidate and the table
# corpus-bound-candidate, counted against the default's last run (out/corpus) where there is one.
set -euo pipefail
cd "$(dirname "$0")/.."
B=build/apps/shadowkit/shadowkit
[ -x "$B" ] || tools/build.sh
corpus=/usr/share/assimp/models
[ -d "$corpus" ] || { echo "measure-corpus: $corpus is missing: install assimp-testmodels (tools/install-deps.sh)" >&2; exit 1; }
out=out/corpus table=corpus-bound candidate=()
if [ -n "${CANDIDATE:-}" ]; then
  read -ra candidate <<< "$CANDIDATE"
  out=out/corpus-candidate table=corpus-bound-candidate
fi
rm -rf "$out" && mkdir -p "$out"
{
  find "$corpus/glTF2" "$corpus/OBJ" -type f \( -iname '*.gltf' -o -iname '*.glb' -o -iname '*.obj' \) | sort
  echo tests/data/pillar_on_plate.gltf
  ls tests/data/shapes/*
} | while read -r file; do
    relative=${file#"$corpus"/}
    name=$(printf '%s' "$relative" | md5sum | cut -c1-12) # file names may hold spaces
    printf '%s\t%s\n' "$name" "$relative" >> "$out/names.tsv"
    for technique in default focused; do
      args=("${candidate[@]}")
      [ "$technique" = focused ] && args=(--technique focused)
      status=0
      "$B" eval --scene "$file" --views all --size 640x360 "${args[@]}" --json "$out/$name.$technique.json" \
        > /dev/null 2> "$out/$name.$technique.err" || status=$?
      if [ "$status" = 1 ]; then # refused with its one-line reason
        printf '%s\t%s\n' "$relative" "$(tail -n 1 "$out/$name.$technique.err")" >> "$out/refused.txt"
        break
      elif [ "$status" != 0 ]; then # a crash or a kill is a fault, never a refusal
        echo "measure-corpus: $relative: shadowkit eval exited with $status (see $out/$name.$technique.err)" >&2
        exit 1
      fi
    done
    echo "measure-corpus: $relative" >&2
  done
python3 tools/corpus_tables.py "$out" "$table" "${CANDIDATE:-}" out/corpus
