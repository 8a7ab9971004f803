#!/usr/bin/env bash
# The project's C and C++ sources in the committed .clang-format (clang-format 14, Debian 12).
#
#   tools/format.sh           reformat every tracked .cpp / .h / .c file in place
#   tools/format.sh --check   change nothing; list the files that differ and exit 1 if any do (CI)
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
mapfile -t files < <(git ls-files '*.cpp' '*.h' '*.c')
if [ "${1:-}" = "--check" ]; then
  differ=()
  for f in "${files[@]}"; do
    clang-format-14 --style=file "$f" | cmp -s - "$f" || differ+=("$f")
  done
  if [ ${#differ[@]} -gt 0 ]; then
    printf 'format: %s differs from .clang-format (tools/format.sh fixes it)\n' "${differ[@]}" >&2
    echo "format: ${#differ[@]} of ${#files[@]} files differ" >&2
    exit 1
  fi
  echo "format: ${#files[@]} files as .clang-format says"
  exit 0
fi
clang-format-14 --style=file -i "${files[@]}"
