#!/usr/bin/env bash
# LGH or light tree? The LGH and the stochastic lightcuts (Lin & Yuksel 2020, --indirect-method rtslc) on the
# same lights, rays, filter and Embree reference: sponza_sun@atrium and cornell_emissive at 10K and 100K
# VPLs, 320x180. LGH grid: alpha 0.5/1/2, S1, interleave 1/2/4, k 1/4/16, filter on/off; lightcuts grid:
# n 1/2/4/8/16/32 samples per pixel, blocks 1/8, interleave 1/2/4 (the combinations the method takes: a cut
# of n m^2 <= 32 nodes, the block a multiple of m), filter on/off; the uniform baselines kept. One sweep per
# accumulated-frame count (FRAMES, default "1 16"), each into OUT/frames_N (sweep.csv, front.png, summary.md
# with the equal-time tables "LGH / lightcuts", points and curves, relative RMSE and MAE) through
# bench/sweep/plot_sweep.py.
# Accumulated frames (FRAMES > 1) run filtered only, over LGH alpha 0.5/1/2, interleave 1/2/4, k 1/4/16
# and lightcuts n 1-32, B8, interleave 1/2/4 (QUICK=1: the reduced grid of earlier runs, LGH interleave
# 1/4, k 1/4, lightcuts n 1/4/16, interleave 1/2). SCENES (default "sponza cornell") splits a long run by scene:
# each scene's sweep goes to OUT/frames_N/SCENE.
# Usage: bench/scripts/lightcuts.sh [BUILD_DIR] [OUT]   (OUT default: bench/results/lightcuts). REPEATS (default 3):
# timed frames per point (errors: the median over them, each with its own random numbers).
set -euo pipefail
here="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$here/build}"
out="${2:-$here/bench/results/lightcuts}"
scenes="$here/../shared/scenes"
if [ ! -d "$scenes" ]; then
  echo "bench/scripts/lightcuts.sh: $scenes is missing (the test scenes live beside the repository); nothing measured" >&2
  exit 1
fi
python=/usr/bin/python3
[ -x "$python" ] || python=python3
status=0
declare -A scene_paths=([sponza]="$scenes/sponza_sun/sponza_sun.gltf@atrium"
                        [cornell]="$scenes/cornell_emissive/cornell_emissive.gltf")
for frames in ${FRAMES:-1 16}; do
  grid=(--interleave 1,2,4 --shadow-samples 1,4,16 --filter on,off --rtslc-samples 1,2,4,8,16,32 --rtslc-block 1,8
        --rtslc-interleave 1,2,4 --uniform-lights 64,256,1024 --uniform-shadowed-lights 4,16,64)
  if [ "$frames" -gt 1 ]; then
    grid=(--interleave 1,2,4 --shadow-samples 1,4,16 --filter on --rtslc-samples 1,2,4,8,16,32 --rtslc-block 8
          --rtslc-interleave 1,2,4 --uniform-lights 256 --uniform-shadowed-lights 16)
    [ -n "${QUICK:-}" ] && grid=(--interleave 1,4 --shadow-samples 1,4 --filter on --rtslc-samples 1,4,16
                                 --rtslc-block 8 --rtslc-interleave 1,2 --uniform-lights 256 --uniform-shadowed-lights 16)
  fi
  # One sweep over both scenes, or with SCENES one per scene.
  parts=("sponza cornell")
  [ -n "${SCENES:-}" ] && read -r -a parts <<< "$SCENES"
  for part in "${parts[@]}"; do
    dir="$out/frames_$frames"
    [ -n "${SCENES:-}" ] && dir="$dir/$part"
    scene_args=()
    for scene in $part; do scene_args+=(--scene "${scene_paths[$scene]}"); done
    start=$(date +%s)
    "$build/lgh-bench" sweep "${scene_args[@]}" --vpls 10000,100000 \
      --alpha 0.5,1,2 --start-level 1 "${grid[@]}" --frames "$frames" --brute-force-limit 0 \
      --repeats "${REPEATS:-3}" --images false --cache-dir "$here/build-sweep/reference-cache" --out "$dir" ||
      status=1  # a failed check (NaN pixels, ...) is reported above; the tables are still made
    "$python" "$here/bench/sweep/plot_sweep.py" "$dir/sweep.csv" > /dev/null
    echo "wrote $dir ($(( ($(date +%s) - start) / 60 )) min)"
  done
done
exit $status
