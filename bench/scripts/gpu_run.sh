#!/usr/bin/env bash
# The prepared GPU run: one call on a machine with an NVIDIA GPU (EGL device platform, no display)
# builds the project, checks that EGL picked the device platform and a hardware renderer, runs the GL
# tests that exercise the device path, then measures the paper's Tables 1-3 at 1280x720 with 100K and
# 1M VPLs, the lightcuts' frame, the BVH layouts' shadow rays against Embree, and an equal-time sweep of the LGH against the lightcuts (Sponza 100K,
# 720p, against the Embree reference on a pixel subset), and writes CSV/JSON plus summary.md into the output
# folder. Planned to finish in under 10 minutes on a GPU machine with 8+ cores (--no-build skips the build).
#
# Without a hardware GPU (llvmpipe, or no EGL device at all) it says so loudly and runs a reduced
# version (160x90, 1K/10K VPLs on data/cornell_box, one frame per point, three tests) that checks the
# script end to end:
# ctest runs it that way (test GpuRunReduced, under a minute).
#
#   bench/scripts/gpu_run.sh [--out DIR] [--build-dir DIR] [--no-build] [--reduced] [--require-gpu] [--jobs N]
#                    [--check-filters]
#
#   --reduced        the reduced version even on a GPU
#   --require-gpu    exit 2 when no hardware GPU is found, instead of running the reduced version
#   --no-build       use the binaries already in --build-dir
#   --check-filters  only check that every pattern of both modes' test filters selects a test of
#                    render_tests (no GL, no device; ctest GpuRunFiltersListed), then exit
# The tests step fails when a filter pattern selects no test (a renamed test would otherwise drop out
# of the run silently: gtest passes a filter that matches nothing) or fewer tests ran than it selects.
# Exit status: 0 when every step passed, 1 when a test or a benchmark check failed, 2 no GPU with
# --require-gpu, 3 bad arguments or a failed build.
set -uo pipefail

source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=gpu_run_out
build_dir="$source_dir/build-gpu"
build=1
mode=auto
require_gpu=0
jobs=$(nproc 2>/dev/null || echo 4)
check_filters=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --out) out=$2; shift 2 ;;
    --build-dir) build_dir=$2; shift 2 ;;
    --no-build) build=0; shift ;;
    --reduced) mode=reduced; shift ;;
    --require-gpu) require_gpu=1; shift ;;
    --jobs) jobs=$2; shift 2 ;;
    --check-filters) check_filters=1; build=0; shift ;;
    -h|--help) sed -n '2,25p' "$0"; exit 0 ;;
    *) echo "gpu_run.sh: unknown argument '$1' (see --help)" >&2; exit 3 ;;
  esac
done
mkdir -p "$out" || exit 3
out=$(cd "$out" && pwd)
started=$(date +%s)
status=0
: > "$out/log.txt"
log() { echo "[gpu_run $(( $(date +%s) - started ))s] $*" | tee -a "$out/log.txt"; }
# Runs a step with its output in $out/NAME.txt; a failure is recorded, later steps still run.
step() {
  local name=$1; shift
  log "$name: $*"
  if "$@" > "$out/$name.txt" 2>&1; then
    log "$name: ok"
  else
    log "$name: FAILED (exit $?, see $name.txt)"
    tail -n 20 "$out/$name.txt" | sed 's/^/    /' | tee -a "$out/log.txt"
    status=1
  fi
}

# --- 1. Build.
if [[ $build == 1 ]]; then
  launcher=()
  command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  log "build: $build_dir with $jobs jobs"
  if ! { cmake -S "$source_dir" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" &&
         cmake --build "$build_dir" -j "$jobs" --target lgh-render lgh-bench render_tests; } > "$out/build.txt" 2>&1; then
    log "build: FAILED (see build.txt)"; tail -n 30 "$out/build.txt"; exit 3
  fi
  log "build: ok"
fi
render="$build_dir/lgh-render"
bench="$build_dir/lgh-bench"
tests="$build_dir/tests/render_tests"
exes=("$render" "$bench" "$tests")
[[ $check_filters == 1 ]] && exes=("$tests")
for exe in "${exes[@]}"; do
  [[ -x $exe ]] || { log "missing $exe (build first, or drop --no-build)"; exit 3; }
done

# The GL tests of step 3 that exercise the device path (context, build, light pass, shadows, pinned
# frames, the lightcuts), as gtest filters: the full run's and the reduced run's. (LightTreeGpuTest compares
# Morton cells bit for bit with the CPU's, which a GPU's inexact division may not give: not here.)
full_filter='ContextTest.*:Headless/BackendTest.*:LghBuild*:LightPassTest.*:ShadowTest.*:PinnedFramesTest.*:RadixSortTest.*:Lightcuts*:FinitePixelsTest.*'
reduced_filter='ContextTest.IsCore45WithComputeShaders:LightPassTest.CulledVolumesShadeWhatCubesShade:LightPassTest.CullingLeavesShadowSelectionUnchanged'
# render_tests' enabled tests, a full name (Suite.Test) a line: listed, not run (no GL context).
list_tests() {
  "$tests" --gtest_list_tests |
    awk '/^[^ ]/ { suite = $1; next }
         /^  [^ ]/ && suite !~ /(^|\/)DISABLED_/ && $1 !~ /^DISABLED_/ { print suite $1 }'
}
# Prints how many of the tests listed in $listed (list_tests) FILTER selects; fails, logging each, when
# one of its patterns (gtest's wildcards * and ?, which bash's [[ == ]] reads alike) selects none.
filter_test_count() {
  local pattern name n total=0 missing=0
  local -a patterns names
  IFS=: read -ra patterns <<< "${1%%-*}"  # the positive patterns (before any '-')
  mapfile -t names <<< "$listed"
  for pattern in "${patterns[@]}"; do
    n=0
    for name in "${names[@]}"; do [[ $name == $pattern ]] && n=$(( n + 1 )); done
    if [[ $n == 0 ]]; then
      log "filter: '$pattern' selects no test of $tests (renamed or removed? update the filter)" >&2
      missing=1
    fi
  done
  for name in "${names[@]}"; do  # each test once, however many patterns select it
    for pattern in "${patterns[@]}"; do
      if [[ $name == $pattern ]]; then total=$(( total + 1 )); break; fi
    done
  done
  echo "$total"
  return $missing
}
listed=$(list_tests) || { log "listing the tests of $tests failed"; exit 1; }
if [[ $check_filters == 1 ]]; then
  for name in full reduced; do
    filter_var=${name}_filter
    if count=$(filter_test_count "${!filter_var}"); then
      log "filter ($name): every pattern selects a test, $count in all"
    else
      log "filter ($name): FAILED"; status=1
    fi
  done
  exit $status
fi

# --- 2. Which device EGL gives us: the device platform and a hardware renderer, or not.
cornell="$source_dir/data/cornell_box.gltf"
device_line=$("$render" "$cornell" --backend egl-device --width 64 --height 36 --vpls 1000 -o "$out/device_check.png" 2> "$out/device_check.txt" | grep '^context' | sed 's/^context *//')
[[ -z $device_line ]] && device_line="(no EGL device context: $(tail -n 1 "$out/device_check.txt"))"
gpu=0
if [[ $device_line == "EGL device:"* ]] && ! grep -qiE 'llvmpipe|softpipe|swrast|software|lavapipe' <<< "$device_line"; then gpu=1; fi
if [[ $gpu == 1 ]]; then
  log "device: hardware GPU through the EGL device platform: $device_line"
  backend=egl-device
  [[ $mode == auto ]] && mode=full
else
  log "device: NO GPU PRESENT - EGL gives $device_line"
  if [[ $require_gpu == 1 ]]; then log "--require-gpu: stopping"; exit 2; fi
  log "running the REDUCED version (small sizes); its times say nothing about a GPU"
  backend=auto
  mode=reduced
fi

# --- 3. The GL tests that exercise the device path (context, build, light pass, shadows, pinned frames).
filter=$reduced_filter
[[ $mode == full ]] && filter=$full_filter
if ! selected=$(filter_test_count "$filter"); then
  log "tests: FAILED (the filter names a test that render_tests does not have)"
  status=1
fi
export LGH_TEST_BACKEND=$backend
step tests "$tests" --gtest_filter="$filter" --gtest_output="json:$out/tests.json"
# gtest's own count: "[==========] N tests from M test suites ran."
ran=$(sed -nE 's/^\[==========\] ([0-9]+) tests? from .* ran\..*/\1/p' "$out/tests.txt" | tail -n 1)
if (( ${ran:-0} < selected )); then
  log "tests: FAILED (${ran:-0} tests ran, the filter selects $selected)"
  status=1
else
  log "tests: $ran tests ran, as many as the filter selects"
fi

# --- 4. The paper's tables.
sponza="$source_dir/../shared/scenes/sponza_sun/sponza_sun.gltf"
[[ -f $sponza && $mode == full ]] || sponza="$cornell"  # reduced: the project's own small scene
camera=()
[[ $sponza == *sponza_sun* ]] && camera=(--camera atrium)
if [[ $mode == full ]]; then
  width=1280 height=720 vpls=100K,1M frame_vpls=(100000 1000000) repeats=5 build_lights=100K,1M table1=100K
else
  width=160 height=90 vpls=1K,10K frame_vpls=(10000) repeats=1 build_lights=1K,10K table1=10K
fi
# Tables 1 and 2 (construction): per-step times at one count, totals vs light count.
step table1_2_build "$bench" build --backend "$backend" --lights "$build_lights" --table1-lights "$table1" \
  --repeats "$repeats" --budget 20 --cpu-limit 5 --csv "$out/build.csv" --json "$out/build.json"
# Table 2 (render time vs VPLs) and the light pass's efficiency, cube and culled volumes, 1x1 and 4x4.
step table2_light "$bench" light --backend "$backend" --scene "$sponza" "${camera[@]}" --width "$width" \
  --height "$height" --vpls "$vpls" --tiles 1,4 --repeats "$repeats" --brute-force-limit 0 --interleave-vpls 0 \
  --csv "$out/light.csv" --json "$out/light.json"
# Table 3: the frame pass by pass, interleaving 1/2/4, at each VPL count.
for v in "${frame_vpls[@]}"; do
  step "table3_frame_$v" "$bench" frame --backend "$backend" --scene "$sponza" "${camera[@]}" --width "$width" \
    --height "$height" --vpls "$v" --repeats "$repeats" --csv "$out/frame_$v.csv"
done
# The stochastic lightcuts' frame at the paper's anchor: Sponza, 100K VPLs, 8 samples per pixel, 1920x1080
# ([LY20] Table 3: 27.4 ms a frame, 17.4 ms sampling, tree build 0.43 ms on an RTX 2080), beside the LGH's.
if [[ $mode == full ]]; then rtslc_size=(--width 1920 --height 1080 --vpls 100000); else rtslc_size=(--width "$width" --height "$height" --vpls 10000); fi
step rtslc_frame "$bench" frame --backend "$backend" --scene "$sponza" "${camera[@]}" "${rtslc_size[@]}" \
  --interleave 1 --lightcut-samples 8 --repeats "$repeats" --compare-cubes false --compare-targets false

# The BVH layouts' pace on this device against Embree on this machine's cores (lgh-bench rays): a frame's own
# shadow rays (640x360, 100K VPLs, k = 4; the reduced run: its size, 10K) and shadow-ray segments between
# random surface points (4M on Sponza, 20K on the reduced run's scene).
if [[ $mode == full ]]; then ray_count=4000000 ray_frame=(--vpls 100000); else ray_count=20000 ray_frame=(--width "$width" --height "$height" --vpls 10000); fi
step rays "$bench" rays --backend "$backend" --scene "$sponza" "${camera[@]}" "${ray_frame[@]}" --rays "$ray_count" \
  --repeats "$repeats"

# LGH or light tree on this device: a small equal-time sweep of both methods against the Embree reference
# (the reference on a pixel subset, on this machine's CPU), one frame: Sponza atrium, 100K VPLs, 720p; the
# fronts compared as curves by bench/sweep/plot_sweep.py (docs/measurements.md, "LGH or light tree?").
if [[ $mode == full ]]; then
  race=(--width 1280 --height 720 --vpls 100000 --alpha 0.5,1,2 --interleave 1,4 --shadow-samples 1,4,16
        --rtslc-samples 1,2,4,8,16,32)
else  # two points of each, 10K VPLs on the small scene; no waiting for a quiet machine (ctest runs it beside others)
  race=(--width "$width" --height "$height" --vpls 10000 --alpha 1 --interleave 1,4 --shadow-samples 4
        --rtslc-samples 4,16 --retries 0)
fi
step equal_time_sweep "$bench" sweep --backend "$backend" --scene "$sponza${camera[1]:+@${camera[1]}}" "${race[@]}" \
  --start-level 1 --filter on --rtslc-block 8 --rtslc-interleave 1 --uniform-lights 256 --uniform-shadowed-lights 16 \
  --brute-force-limit 0 --repeats "$repeats" --images false --cache-dir "$out/reference-cache" --out "$out/equal_time"
plot_python=/usr/bin/python3
[[ -x $plot_python ]] || plot_python=python3
"$plot_python" "$source_dir/bench/sweep/plot_sweep.py" "$out/equal_time/sweep.csv" > "$out/equal_time_summary.txt" 2>&1 ||
  log "equal_time_sweep: no plots (plot_sweep.py: see equal_time_summary.txt)"

# --- 5. Summary.
{
  echo "# GPU run ($mode)"
  echo
  echo "* date: $(date -u '+%Y-%m-%d %H:%M UTC'), commit $(git -C "$source_dir" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "* device: $device_line"
  [[ $gpu == 1 ]] || echo "* **NO GPU PRESENT**: the reduced version ran on the software renderer; times say nothing about a GPU"
  echo "* scene: $sponza ${camera[*]}"
  echo "* sizes: ${width}x${height}, VPLs $vpls (light pass), ${frame_vpls[*]} (frame), $repeats timed frames per point"
  echo "* wall time: $(( $(date +%s) - started )) s; status: $([[ $status == 0 ]] && echo 'all steps passed' || echo 'SOME STEPS FAILED (log.txt)')"
  echo
  echo "## Tests"
  echo
  grep -E '^\[  (PASSED|FAILED)|tests? ran' "$out/tests.txt" | sed 's/^/    /'
  for f in table1_2_build table2_light "${frame_vpls[@]/#/table3_frame_}" rtslc_frame rays equal_time_summary; do
    echo
    echo "## $f"
    echo
    sed 's/^/    /' "$out/$f.txt"
  done
} > "$out/summary.md"
log "wrote $out/summary.md (status $status)"
exit $status
