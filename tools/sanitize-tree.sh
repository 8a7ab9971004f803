#!/usr/bin/env bash
# tools/sanitize-tree.sh: configures build-sanitize/, the one clang 14 tree with AddressSanitizer and
# UndefinedBehaviorSanitizer that both `tools/test.sh --sanitize` (the suite) and `tools/fuzz.sh`
# (the libFuzzer targets, -DSHADOWKIT_FUZZ=ON) build in, so CI compiles the instrumented libraries
# once. fuzz/CMakeLists.txt adds libFuzzer's coverage (-fsanitize=fuzzer-no-link) to the libraries
# the fuzz targets feed only (core, scene, frame, the command line's options); the tests link
# those with the sanitizer runtime, whose coverage callbacks do nothing outside a fuzzer.
# SHADOWKIT_UNITY_BUILD as for tools/build.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
# -g1: line tables only. Reports keep their file:line stacks; the build is about a quarter
# shorter than with full debug information.
optimise="-O2 -g1 -DNDEBUG"
# clang: it compiles the instrumented code 2.3 times as fast as GCC 12 (apps/shadowkit/configs.cpp,
# CLI11 and nlohmann::json instantiated under ASan and UBSan: 41 s against 94 s here), and libFuzzer
# is clang's. A tree configured with another compiler is started afresh (CMake cannot change a
# tree's compiler).
if [ -f build-sanitize/CMakeCache.txt ] && ! grep -q '^CMAKE_CXX_COMPILER:[A-Z]*=.*clang++' build-sanitize/CMakeCache.txt; then
  rm -rf build-sanitize
fi
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHADOWKIT_BUILD_PYTHON=OFF \
      -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DSHADOWKIT_FUZZ=ON \
      "-DCMAKE_UNITY_BUILD=${SHADOWKIT_UNITY_BUILD:-OFF}" \
      "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$optimise" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=$optimise" \
      -DSHADOWKIT_BUILD_BENCHMARKS=OFF "-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_C_FLAGS=$flags" \
      "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined" "-DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=address,undefined" >/dev/null
