#!/usr/bin/env bash
# tools/fuzz.sh TARGET SECONDS [RUNS]: builds the libFuzzer target fuzz_TARGET (gltf, obj, views,
# paths, camera, configs, image, state, npy; fuzz/CMakeLists.txt) in build-sanitize/, the clang tree with AddressSanitizer and
# UndefinedBehaviorSanitizer that `tools/test.sh --sanitize` also builds (tools/sanitize-tree.sh),
# and runs it for SECONDS (and at most RUNS executions when given) over a copy of its seed corpus
# fuzz/corpus/TARGET, keeping what it learns in build-sanitize/fuzz/corpus/TARGET. `all` runs every
# target, as many at once as the machine has cores (each fuzzer is one process on one core, so
# each still gets SECONDS of its own). A crash leaves its input in build-sanitize/fuzz/ (crash-*)
# and exits non-zero.
set -euo pipefail
cd "$(dirname "$0")/.."
target=${1:?usage: tools/fuzz.sh TARGET|all SECONDS [RUNS]}
seconds=${2:?usage: tools/fuzz.sh TARGET|all SECONDS [RUNS]}
runs=${3:--1}
targets=(gltf obj views paths camera configs image state npy)
[ "$target" = all ] || targets=("$target")

tools/install-deps.sh
tools/sanitize-tree.sh
cmake --build build-sanitize --parallel "$(nproc)" --target "${targets[@]/#/fuzz_}"

export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
dir=build-sanitize/fuzz
fuzz() { # fuzz TARGET: one run, its log in build-sanitize/fuzz/fuzz_TARGET.log
  mkdir -p "$dir/corpus/$1"
  (cd "$dir" && "./fuzz_$1" -max_total_time="$seconds" -runs="$runs" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
                 -print_final_stats=1 "corpus/$1" "../../fuzz/corpus/$1") > "$dir/fuzz_$1.log" 2>&1
}
failed=0
at_once=$(nproc)
for ((first = 0; first < ${#targets[@]}; first += at_once)); do
  batch=("${targets[@]:first:at_once}")
  pids=()
  for t in "${batch[@]}"; do
    echo "fuzz_$t: ${seconds} s${3:+, at most $runs runs}, corpus $dir/corpus/$t (seeds fuzz/corpus/$t)" >&2
    fuzz "$t" &
    pids+=($!)
  done
  for i in "${!batch[@]}"; do
    t=${batch[$i]}
    status=0
    wait "${pids[$i]}" || status=$?
    grep -E "^(stat::number_of_executed_units|stat::average_exec_per_sec|==[0-9]+==ERROR|SUMMARY)|runtime error|Test unit written" \
         "$dir/fuzz_$t.log" | sed "s/^/fuzz_$t: /" || true
    if [ "$status" -ne 0 ]; then
      echo "fuzz_$t: failed (exit $status): $dir/fuzz_$t.log, the input in $dir/" >&2
      failed=$status
    fi
  done
done
exit "$failed"
