#!/usr/bin/env bash
# Configures and builds shadowkit into build/ (Release, Ninja), installing missing
# Debian packages first.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --parallel "$(nproc)"
