#!/usr/bin/env bash
# The README's test command: install packages, build, run every test (headless GL
# included: Mesa llvmpipe through EGL on CPU-only machines).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
cd build
ctest --output-on-failure --parallel "$(nproc)" "$@"
