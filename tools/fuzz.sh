#!/usr/bin/env bash
# tools/fuzz.sh TARGET SECONDS [RUNS]: builds the libFuzzer target fuzz_TARGET (gltf, obj, views,
# configs, image; fuzz/CMakeLists.txt) with clang, AddressSanitizer and UndefinedBehaviorSanitizer into
# build-fuzz/, and runs it for SECONDS (and at most RUNS executions when given) over a copy of its
# seed corpus fuzz/corpus/TARGET, keeping what it learns in build-fuzz/corpus/TARGET. A crash
# leaves its input in build-fuzz/ (crash-*) and exits non-zero. `all` runs every target in turn.
set -euo pipefail
cd "$(dirname "$0")/.."
target=${1:?usage: tools/fuzz.sh TARGET|all SECONDS [RUNS]}
seconds=${2:?usage: tools/fuzz.sh TARGET|all SECONDS [RUNS]}
runs=${3:--1}
targets=(gltf obj views configs image)
[ "$target" = all ] || targets=("$target")

tools/install-deps.sh
flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
      -DSHADOWKIT_FUZZ=ON -DSHADOWKIT_BUILD_TESTS=OFF -DSHADOWKIT_BUILD_BENCHMARKS=OFF -DSHADOWKIT_BUILD_PYTHON=OFF \
      -DSHADOWKIT_INSTALL=OFF "-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_C_FLAGS=$flags" \
      "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined" >/dev/null
cmake --build build-fuzz --parallel "$(nproc)" --target "${targets[@]/#/fuzz_}"

export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
for t in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$t
  mkdir -p "$corpus"
  echo "fuzz_$t: ${seconds} s${3:+, at most $runs runs}, corpus $corpus (seeds fuzz/corpus/$t)" >&2
  status=0
  (cd build-fuzz && "./fuzz/fuzz_$t" -max_total_time="$seconds" -runs="$runs" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
                      -print_final_stats=1 "corpus/$t" "../fuzz/corpus/$t") > "build-fuzz/fuzz_$t.log" 2>&1 || status=$?
  grep -E "^(stat::number_of_executed_units|stat::average_exec_per_sec|==[0-9]+==ERROR|SUMMARY)|runtime error|Test unit written" \
       "build-fuzz/fuzz_$t.log" || true
  [ "$status" -eq 0 ] || { echo "fuzz_$t: failed (exit $status): build-fuzz/fuzz_$t.log, the input in build-fuzz/" >&2; exit "$status"; }
done
