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
#                                          would need libasan preloaded). Leaks inside the GL driver are suppressed
#                                          (tools/lsan.supp), ours are not.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--sanitize" ]; then
  shift
  tools/install-deps.sh
  flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
  cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHADOWKIT_BUILD_PYTHON=OFF \
        -DSHADOWKIT_BUILD_BENCHMARKS=OFF "-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_C_FLAGS=$flags" \
        "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined" "-DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=address,undefined" >/dev/null
  cmake --build build-sanitize --parallel "$(nproc)"
  cd build-sanitize
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:halt_on_error=1"
  export LSAN_OPTIONS="suppressions=$PWD/../tools/lsan.supp:print_suppressions=0"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  exec ctest --output-on-failure --parallel "$(nproc)" -E "^(shadowkit_package|shadowkit_minimal_gl|shadowkit_cli.gl-environment)$" "$@"
fi
tools/build.sh
cd build
ctest --output-on-failure --parallel "$(nproc)" "$@"
