#!/usr/bin/env bash
# LGH or light tree? The LGH and the stochastic lightcuts (Lin & Yuksel 2020, --indirect-method rtslc) on the
# same lights, rays, filter and Embree reference: sponza_sun@atrium and cornell_emissive at 10K and 100K
# VPLs, 320x180. LGH grid: alpha 0.5/1/2, S1, interleave 1/2/4, k 1/4/16, filter on/off; lightcuts grid:
# n 1/2/4/8/16/32 samples per pixel, blocks 1/8, interleave 1/2/4 (the combinations the method takes: a cut
# of n m^2 <= 32 nodes, the block a multiple of m), filter on/off; the uniform baselines kept. One sweep per
# accumulated-frame count (FRAMES, default "1 16"), each into OUT/frames_N (sweep.csv, front.png, summary.md
# with the equal-time table "LGH / lightcuts") through bench/plot_sweep.py.
# Accumulated frames (FRAMES > 1) run a reduced grid unless FULL_GRID=1: LGH alpha 0.5/1/2, interleave 1/4,
# k 1/4, filtered; lightcuts n 1/4/16, B8, interleave 1/2, filtered; one uniform size each (at 16 frames
# the full grid would take about 16 x 25 min on 2 cores; the reduced one took 24 min).
# Usage: bench/lightcuts.sh [BUILD_DIR] [OUT]   (OUT default: bench/results/lightcuts). REPEATS (default 3):
# timed frames per point. One frame at 1 repeat takes about 20-25 min on 2 cores.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$here/build}"
out="${2:-$here/bench/results/lightcuts}"
scenes="$here/../shared/scenes"
if [ ! -d "$scenes" ]; then
  echo "bench/lightcuts.sh: $scenes is missing (the test scenes live beside the repository); nothing measured" >&2
  exit 1
fi
python=/usr/bin/python3
[ -x "$python" ] || python=python3
status=0
for frames in ${FRAMES:-1 16}; do
  grid=(--interleave 1,2,4 --shadow-samples 1,4,16 --filter on,off --rtslc-samples 1,2,4,8,16,32 --rtslc-block 1,8
        --rtslc-interleave 1,2,4 --uniform-lights 64,256,1024 --uniform-shadowed-lights 4,16,64)
  if [ "$frames" -gt 1 ] && [ -z "${FULL_GRID:-}" ]; then
    grid=(--interleave 1,4 --shadow-samples 1,4 --filter on --rtslc-samples 1,4,16 --rtslc-block 8
          --rtslc-interleave 1,2 --uniform-lights 256 --uniform-shadowed-lights 16)
  fi
  "$build/lgh-bench" sweep --scene "$scenes/sponza_sun/sponza_sun.gltf@atrium" \
    --scene "$scenes/cornell_emissive/cornell_emissive.gltf" --vpls 10000,100000 \
    --alpha 0.5,1,2 --start-level 1 "${grid[@]}" --frames "$frames" --brute-force-limit 0 \
    --repeats "${REPEATS:-3}" --images false --cache-dir "$here/build-sweep/reference-cache" --out "$out/frames_$frames" ||
    status=1  # a failed check (NaN pixels, ...) is reported above; the tables are still made
  "$python" "$here/bench/plot_sweep.py" "$out/frames_$frames/sweep.csv" > /dev/null
  echo "wrote $out/frames_$frames"
done
exit $status
