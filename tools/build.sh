#!/usr/bin/env bash
# Configures and builds shadowkit into build/ (Release, Ninja), installing missing
# Debian packages first. SHADOWKIT_UNITY_BUILD=ON compiles each target's files in batches of
# eight (CMake's unity build): a build from nothing takes less time, one edit recompiles its
# batch; .ci/run sets it, a desk need not. Unset, a build folder keeps the choice it was made
# with (a measuring script that builds first must not turn a unity build into a full rebuild).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release ${SHADOWKIT_UNITY_BUILD:+"-DCMAKE_UNITY_BUILD=$SHADOWKIT_UNITY_BUILD"} >/dev/null
cmake --build build --parallel "$(nproc)"
