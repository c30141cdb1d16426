#!/usr/bin/env bash
# The lightcuts' denoiser tuned as the LGH's filter was (docs/measurements.md, "The lightcuts' denoiser"):
# one frame, 10K VPLs, 320x180, 8x8 cuts, 1x1, n = 4 and 8, filtered and raw, against the Embree reference,
# over SVGF's luminance stop sigma_l, the normal power, the plane sigma and the pass count, one at a time
# around the defaults, on sponza_sun@atrium and cornell_emissive. Prints one table (filtered / raw error).
# Usage: bench/scripts/lightcuts_filter.sh [BUILD_DIR] [OUT]   (OUT default: build-sweep/lightcuts-filter). About
# 15 min on 2 cores (the errors are deterministic: the same seeds at every point).
set -euo pipefail
here="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$here/build}"
out="${2:-$here/build-sweep/lightcuts-filter}"
scenes="$here/../shared/scenes"
if [ ! -d "$scenes" ]; then
  echo "bench/scripts/lightcuts_filter.sh: $scenes is missing (the test scenes live beside the repository); nothing measured" >&2
  exit 1
fi
configs=("rtslc-filter-sigma=4" "rtslc-filter-sigma=8" "" "rtslc-filter-sigma=32" "rtslc-filter-sigma=64"
         "rtslc-filter-normal-power=1" "rtslc-filter-normal-power=16" "rtslc-filter-normal-power=64"
         "rtslc-filter-plane-sigma=0.5" "rtslc-filter-plane-sigma=2" "rtslc-filter-plane-sigma=4"
         "filter-passes=4" "filter-passes=6")
mkdir -p "$out"
for scene in "sponza_sun/sponza_sun.gltf@atrium" "cornell_emissive/cornell_emissive.gltf"; do
  for config in "${configs[@]}"; do
    name="$(basename "${scene%%.gltf*}")_${config:-defaults}"
    sets=()
    [ -n "$config" ] && sets=(--set "$config")
    "$build/lgh-bench" sweep --scene "$scenes/$scene" --vpls 10000 --alpha 1 --start-level 1 --interleave 1 \
      --shadow-samples 4 --filter on,off --rtslc-samples 4,8 --rtslc-block 8 --rtslc-interleave 1 --uniform-lights 16 \
      --uniform-shadowed-lights 2 --repeats 1 --brute-force-limit 0 --images false "${sets[@]}" \
      --cache-dir "$here/build-sweep/reference-cache" --out "$out/$name" > "$out/$name.log"
  done
done
python3 - "$out" <<'PY'
import csv, glob, os, sys
print("| scene | setting (else the defaults) | n = 4 filtered / raw | n = 8 filtered / raw | n = 4 filtered | n = 8 filtered |")
print("|---|---|---|---|---|---|")
for path in sorted(glob.glob(os.path.join(sys.argv[1], "*", "sweep.csv"))):
    scene, config = os.path.basename(os.path.dirname(path)).rsplit("_", 1)
    error = {}
    for r in csv.DictReader(open(path)):
        if r["method"] == "rtslc" and r["series"] == "grid":
            error[(r["shadow_samples"], r["filter"])] = float(r["rmse_shadowed"])
    cells = [f"{error[(n, 'on')] / error[(n, 'off')]:.3f}" for n in ("4", "8")]
    cells += [f"{error[(n, 'on')]:.3f}" for n in ("4", "8")]
    print(f"| {scene} | {config} | " + " | ".join(cells) + " |")
PY
