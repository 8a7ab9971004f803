#!/usr/bin/env bash
# tools/measure-gpu.sh [SECTION ...]: the real-GPU figures of docs/performance.md "On a real GPU",
# run on any machine with an NVIDIA driver and EGL and none of this project's libraries, over the
# bundle tools/gpu-bundle.sh packs on a machine that builds the project. From the repository root:
#
#   tools/gpu-bundle.sh      # on the build machine: .gpu/bundle.tar.xz (programs + libraries, ~12 MB)
#   # copy the checkout with .gpu/ (and .gl/, the GL loader's .deb files, if the GPU machine lacks
#   # them) to the GPU machine, then there:
#   for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig   # only with .gl/
#   tools/measure-gpu.sh     # then tools/gpu-tables.sh on its gpu-results.tgz, back on the build machine
#
# Sections (default: all, in this order, most wanted first): tests (the GL test programs on the
# real driver), frame (a default frame, 1,000-100,000 trees, three views, CHC++ and GPU culling;
# then the flythrough's moving camera at 10,000 and 100,000 trees),
# techniques (every set-up at 10,000 trees), filters (each filter's passes under the real sun and
# the lamps), leafy (the leafy forest's frame: with its levels, crossing into them, without, and at 100,000 trees), eval (the standard views' figures against the truth,
# to compare with llvmpipe's: the same program on another rasteriser; TSM's two depth layouts; PSM
# with the receiver-plane bias), alpha (tools/measure-alpha.sh), scaling (what the shadow pass's
# time follows at 100,000 trees: culling, levels, the depth layout), opacity (what the leaves'
# opacity layers cost), local (the lamps' depth pass drawn each of its three ways: render's local
# pass line, docs/local-lights.md), foliage (the leafy forest's soft sweep, about four minutes). Not in the
# default, named when wanted: golden (re-records this GPU family's golden figures after a change
# meant to move them; tools/gpu-tables.sh puts them in data/golden/<family>/ back here).
# Every step has its own time limit and the whole run a deadline (DEADLINE seconds, default 540,
# nine minutes): steps past it are skipped and say so. Results, logs and
# bench JSON go to $OUT/gpu-results.tgz (re-packed after every step, so a killed run still returns
# what it measured) and a summary is printed last. Nothing here asserts a time: it prints figures.
#
# DRY=1 tools/measure-gpu.sh [SECTION ...] runs every step on tiny inputs (20 trees, two frames,
# 64 × 36 pixels, the test programs listing their tests) on any GL, llvmpipe included, in a few
# minutes: a command an option's rename broke fails here, not in a GPU machine's few minutes. Its
# figures mean nothing; its summary's return codes do (every step 0; `foliage` and `golden`, which
# write results the next GPU run would use, are skipped).
set -uo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
deadline=${DEADLINE:-540}
out=${OUT:-$PWD/out/gpu}
res=$(mktemp -d)
mkdir -p "$out"

# The bundle: programs in bin/, libraries in lib/. Tests and the CLI find data/ through the source
# path compiled into them (/work/main here), so that path is made to lead to this checkout.
root=/tmp/shadowkit-gpu
mkdir -p "$root" && tar -C "$root" -xJf .gpu/bundle.tar.xz || { echo "measure-gpu: .gpu/bundle.tar.xz: cannot unpack (run tools/gpu-bundle.sh here first)"; exit 1; }
export LD_LIBRARY_PATH=$root/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
# NVIDIA's EGL vendor file, where NVIDIA's container and desktop installs put it.
for f in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json /usr/share/glvnd/egl_vendor.d/10_nvidia.json; do
  [[ -f $f && -z ${__EGL_VENDOR_LIBRARY_FILENAMES:-} ]] && export __EGL_VENDOR_LIBRARY_FILENAMES=$f
done
[[ -e /work/main ]] || { mkdir -p /work && ln -s "$PWD" /work/main; }
# Where tools/measure-alpha.sh looks for the CLI (a build here is used as it is).
[[ -e build/apps/shadowkit/shadowkit ]] || { mkdir -p build/apps/shadowkit && ln -s "$root/bin/shadowkit" build/apps/shadowkit/shadowkit; }
B=build/apps/shadowkit/shadowkit

summary=$res/summary.txt
note() { echo "$*" | tee -a "$summary"; }
pack() { tar -C "$res" -czf "$out/gpu-results.tgz" . 2>/dev/null; }
dry=${DRY:-0}
# With DRY=1, a step's command on tiny inputs (above): --trees 20, --frames 2 (a path's first two), 64 × 36 pixels for
# the CLI's drawing commands, 200 cards once for measure-alpha.sh, and a test program's list.
tiny() {
  local prev="" a
  tinyArgs=()
  for a in "$@"; do
    case $prev in
    --trees) a=20 ;;
    --frames) a=2 ;;
    esac
    tinyArgs+=("$a")
    prev=$a
  done
  case " ${tinyArgs[*]} " in
  *" --path "*" --frames "*) ;;
  *" --path "*) tinyArgs+=(--frames 2) ;; # a path's frames: all of them unless named
  esac
  case " ${tinyArgs[*]} " in
  *" $B bench "* | *" $B eval "* | *" $B render "*) tinyArgs+=(--size 64x36) ;;
  *"measure-alpha.sh "*) tinyArgs=(tools/measure-alpha.sh 200 1 "${tinyArgs[-1]}") ;;
  *" --gtest_brief=1 "*) tinyArgs+=(--gtest_list_tests) ;;
  esac
}
# step NAME SECONDS COMMAND...: runs one measurement into NAME.log unless the deadline is near.
step() {
  local name=$1 limit=$2 left=$((deadline - (SECONDS - start)))
  shift 2
  if ((dry)); then
    tiny "$@"
    set -- "${tinyArgs[@]}"
  fi
  if ((left < 20)); then note "skipped $name: ${left}s left of the deadline"; return; fi
  ((limit > left)) && limit=$left
  local t0=$SECONDS
  timeout "$limit" "$@" >"$res/$name.log" 2>&1
  local rc=$?
  note "$(printf '%-34s rc %3d  %4ds' "$name" "$rc" $((SECONDS - t0)))"
  pack
}

note "commit $(cat .gpu/commit 2>/dev/null || echo '?'), $(nproc) CPU cores, $(date -u +%Y-%m-%dT%H:%MZ)"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm,memory.total --format=csv,noheader 2>&1 |
  tee -a "$summary"
step context 60 "$B" bench --trees 1000 --views perpendicular --frames 2
note "context: $(grep -o '^4\.[0-9].*via EGL[^|]*' "$res/context.log" | head -1)"
grep -q 'via EGL' "$res/context.log" || { note "no OpenGL context: $(tail -3 "$res/context.log")"; pack; exit 1; }

sections=("$@")
((${#sections[@]})) || sections=(tests frame techniques filters leafy eval alpha scaling opacity local foliage)
bench=("$B" bench --frames 11)
for section in "${sections[@]}"; do
  case $section in
  tests)
    for t in gl_tests frame_tests integration_tests golden_tests; do
      step "test-$t" 150 "$root/bin/shadowkit_$t" --gtest_brief=1
      note "  $(grep -E '^\[  (PASSED|FAILED) ' "$res/test-$t.log" | tr '\n' ' ')"
    done
    ;;
  frame)
    step frame-chc 150 "${bench[@]}" --trees 1000,10000,100000 --views perpendicular,aerial,paper --limits \
      --visibility chc --json "$res/frame-chc.json"
    step frame-gpu 120 "${bench[@]}" --trees 1000,10000,100000 --views perpendicular,aerial,paper --visibility gpu \
      --json "$res/frame-gpu.json"
    # A moving camera: the flythrough's 240 frames in order, the whole CPU side of each frame.
    for v in gpu chc; do
      step "path-$v" 120 "$B" bench --trees 10000,100000 --path flythrough --visibility "$v" --json "$res/path-$v.json"
    done
    # Technique virtual along it with the sun held: page requests read late (bench's default)
    # against a frame that waits for its own (one stall a frame).
    for r in late wait; do
      step "path-virtual-$r" 120 "$B" bench --trees 10000 --path flythrough --sun-path off --technique virtual \
        --virtual-requests "$r" --json "$res/path-virtual-$r.json"
    done
    # Its pages' casters culled on the GPU against the CPU's lists, the sun moving: pages every frame.
    for v in gpu chc; do
      step "path-virtual-pages-$v" 120 "$B" bench --trees 10000,100000 --path flythrough --frames 60 \
        --technique virtual --visibility "$v" --json "$res/path-virtual-pages-$v.json"
    done
    step frame-frustum 60 "${bench[@]}" --trees 10000 --views perpendicular --visibility frustum --caster-culling volume \
      --json "$res/frame-frustum.json"
    ;;
  techniques)
    # name|options: the README's set-ups.
    for setup in "standard|--technique standard" "focused|--technique focused" "psm|--technique psm" \
      "tsm|--technique tsm" "lispsm|--technique lispsm" "csm4x1024|--technique csm --cascades 4 --map-size 1024" \
      "csm4x2048-lispsm|--technique csm --cascades 4 --map-size 2048 --cascade-warp lispsm" \
      "virtual|--technique virtual"; do
      # shellcheck disable=SC2086
      step "tech-${setup%%|*}" 60 "${bench[@]}" --trees 10000 --views perpendicular,aerial --limits ${setup#*|} \
        --json "$res/tech-${setup%%|*}.json"
    done
    ;;
  filters)
    for f in hard pcf2 pcf:3 pcf:5 poisson:16 pcss pcss:32 msm; do
      step "filter-${f/:/}" 60 "${bench[@]}" --trees 10000 --views perpendicular,noon --sun-angle 0.53 --technique csm \
        --cascades 4 --cascade-warp lispsm --map-size 2048 --filter "$f" --json "$res/filter-${f/:/}.json"
    done
    for f in hard pcf2 pcss; do
      step "lamp-$f" 60 "${bench[@]}" --trees 10000 --views lamp,torch --filter "$f" --json "$res/lamp-$f.json"
    done
    ;;
  leafy)
    # The leafy forest's frame with its levels down to billboard clouds (the default), crossing into
    # them over a quarter of their bound (--lod-fade 0.25: the finer level's triangles kept in half
    # the band), with the full trees everywhere, and at 100,000 trees on 3.2 km.
    step leafy 120 "${bench[@]}" --forest leafy --trees 10000 --views perpendicular,aerial --json "$res/leafy.json"
    step leafy-fade 120 "${bench[@]}" --forest leafy --trees 10000 --views perpendicular,aerial --lod-fade 0.25 \
      --json "$res/leafy-fade.json"
    step leafy-no-lod 120 "${bench[@]}" --forest leafy --trees 10000 --views perpendicular,aerial --no-lod \
      --json "$res/leafy-no-lod.json"
    step leafy-100k 150 "${bench[@]}" --forest leafy --trees 100000 --same-density --views perpendicular,aerial \
      --json "$res/leafy-100k.json"
    ;;
  eval)
    for setup in "tsm|--technique tsm" "csm4x2048-lispsm|--technique csm --cascades 4 --map-size 2048 --cascade-warp lispsm" \
      "virtual|--technique virtual" "tsm-hyperbolic|--technique tsm --depth-layout hyperbolic" \
      "psm-receiver-plane|--technique psm --receiver-plane-bias on --filter pcf:3"; do
      # shellcheck disable=SC2086
      step "eval-${setup%%|*}" 120 "$B" eval --views all ${setup#*|} --json "$res/eval-${setup%%|*}.json"
    done
    ;;
  scaling)
    # What the shadow pass's time follows at 100,000 trees: the default, without culling by
    # receivers, without levels of detail, with every instance drawn.
    for variant in "default|" "volume|--visibility frustum --caster-culling volume" "no-lod|--no-lod" "all|--visibility off" \
      "hyperbolic|--depth-layout hyperbolic" "chc|--visibility chc"; do
      # shellcheck disable=SC2086
      step "scaling-${variant%%|*}" 60 "${bench[@]}" --trees 100000 --views perpendicular ${variant#*|} \
        --json "$res/scaling-${variant%%|*}.json"
    done
    # And the driver's own performance warnings for that frame.
    step scaling-driver-messages 60 env SHADOWKIT_GL_DEBUG=1 "$B" bench --frames 3 --trees 100000 --views perpendicular
    ;;
  alpha)
    step alpha-tsm 90 tools/measure-alpha.sh 20000 5 tsm
    ;;
  opacity)
    # What partial occlusion by leaves costs (issue 52): the leafy forest under the real sun, the
    # hard test, PCSS, and PCSS with the opacity layers (their two leaf draws are in the shadow
    # pass's time, their lookup in the camera pass's), for TSM and four LiSPSM cascades.
    for setup in "tsm|--technique tsm" "csm4x2048-lispsm|--technique csm --cascades 4 --map-size 2048 --cascade-warp lispsm"; do
      for f in "hard|--filter hard" "pcss|--filter pcss" "layers|--filter pcss --foliage-opacity"; do
        # shellcheck disable=SC2086
        step "opacity-${setup%%|*}-${f%%|*}" 60 "${bench[@]}" --forest leafy --trees 10000 --views perpendicular,aerial \
          --sun-angle 0.53 ${setup#*|} ${f#*|} --json "$res/opacity-${setup%%|*}-${f%%|*}.json"
      done
    done
    ;;
  local)
    # A point light's cube drawn in one layered pass by the vertex stage or a geometry stage, or in
    # six passes culled per face; `render` times the local pass (bench does not), 1280 × 720.
    for view in lamp village; do
      for pass in vertex-layer geometry per-face; do
        step "local-$view-$pass" 60 "$B" render --view "$view" --local-pass "$pass" --out "$root/local-$view-$pass.png"
      done
    done
    ;;
  foliage)
    ((dry)) && { note "skipped foliage: DRY=1 (its sweep's results would stand as the next GPU run's)"; continue; }
    # The leafy forest against both truths (tools/measure-foliage.sh's sweep, 1280 × 720): its
    # results.csv is what LEAFY_RESULTS= writes the foliage tables from.
    # The bundle has no compiled Python module, and `shadowkit sweep` needs it: the package runs
    # from a copy of the checkout's, without the module's import, its data directory named (the
    # sweep asks the module only when SHADOWKIT_DATA_DIR is unset).
    py=$root/python
    mkdir -p "$py" && cp -r libs/python/shadowkit "$py/" && : >"$py/shadowkit/__init__.py"
    step foliage-soft 330 env PYTHONPATH="$py" SHADOWKIT="$root/bin/shadowkit" SHADOWKIT_DATA_DIR="$PWD/data" \
      python3 -m shadowkit.sweep data/sweeps/leafy-soft.json --out "$root/leafy-soft" --discard-stale
    cp "$root/leafy-soft/results.csv" "$res/leafy-soft.csv" 2>/dev/null
    pack
    ;;
  golden)
    ((dry)) && { note "skipped golden: DRY=1 (it re-records the golden figures)"; continue; }
    # The test writes the figures into data/golden/<family>/ of this checkout (the compiled-in
    # source path leads here); they travel back in the results, then the tests are run once more
    # against them.
    step golden-record 150 env SHADOWKIT_UPDATE_GOLDEN=1 "$root/bin/shadowkit_golden_tests" --gtest_brief=1
    note "  $(grep -h '^re-recorded' "$res/golden-record.log" | tr '\n' ' ')"
    for family in data/golden/*/; do
      mkdir -p "$res/golden/$(basename "$family")" && cp "$family"*.json "$res/golden/$(basename "$family")/"
    done
    step golden-check 150 "$root/bin/shadowkit_golden_tests" --gtest_brief=1
    note "  $(grep -E '^\[  (PASSED|FAILED) ' "$res/golden-check.log" | tr '\n' ' ')"
    pack
    ;;
  *) note "unknown section $section" ;;
  esac
done
note "done in $((SECONDS - start)) s"
pack
echo "== summary"
cat "$summary"
