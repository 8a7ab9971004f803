#!/usr/bin/env bash
# The README's test command: install packages, build, run every test (headless GL
# included: Mesa llvmpipe through EGL on CPU-only machines).
#
#   tools/test.sh [CTEST ARGS]             Release build in build/
#   tools/test.sh --sanitize [CTEST ARGS]  AddressSanitizer + UndefinedBehaviorSanitizer build in
#                                          build-sanitize/, the whole suite but the two tests that
#                                          install the package and build consumers without the
#                                          sanitizer runtime (shadowkit_package, shadowkit_minimal_gl),
#                                          the case that limits the address space to make the driver
#                                          run out of memory (shadowkit_cli.gl-environment: ASan's
#                                          shadow memory needs more) and the Python module (python3
#                                          would need libasan preloaded). Leak checking covers the
#                                          tests without GL; the GL tests (label gl) run with ASan and
#                                          UBSan but without it, because Mesa unloads its driver before
#                                          LeakSanitizer reports, so its allocations arrive from an
#                                          "<unknown module>" no suppression can name (measured: 49 GL
#                                          tests, every report of that kind). tools/lsan.supp holds the
#                                          driver's libraries for the allocations it can name.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--sanitize" ]; then
  shift
  tools/install-deps.sh
  flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
  # -g1: line tables only. Reports keep their file:line stacks; the build is about a quarter
  # shorter than with full debug information.
  optimise="-O2 -g1 -DNDEBUG"
  # clang, as the fuzz targets: it compiles the instrumented code 2.3 times as fast as GCC 12
  # (apps/shadowkit/configs.cpp, CLI11 and nlohmann::json instantiated under ASan and UBSan:
  # 41 s against 94 s here), and the build was most of CI's longest stage. A tree configured
  # with another compiler is started afresh (CMake cannot change a tree's compiler).
  if [ -f build-sanitize/CMakeCache.txt ] && ! grep -q '^CMAKE_CXX_COMPILER:[A-Z]*=.*clang++' build-sanitize/CMakeCache.txt; then
    rm -rf build-sanitize
  fi
  cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHADOWKIT_BUILD_PYTHON=OFF \
        -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
        "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=$optimise" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=$optimise" \
        -DSHADOWKIT_BUILD_BENCHMARKS=OFF "-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_C_FLAGS=$flags" \
        "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined" "-DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=address,undefined" >/dev/null
  cmake --build build-sanitize --parallel "$(nproc)"
  cd build-sanitize
  export LSAN_OPTIONS="suppressions=$PWD/../tools/lsan.supp:print_suppressions=0"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  excluded="^(shadowkit_package|shadowkit_minimal_gl|shadowkit_cli.gl-environment)$"
  ASAN_OPTIONS="detect_leaks=1:halt_on_error=1" ctest --output-on-failure --parallel "$(nproc)" -LE gl -E "$excluded" "$@"
  ASAN_OPTIONS="detect_leaks=0:halt_on_error=1" exec ctest --output-on-failure --parallel "$(nproc)" -L gl -E "$excluded" "$@"
fi
tools/build.sh
cd build
ctest --output-on-failure --parallel "$(nproc)" "$@"
