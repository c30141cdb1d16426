#!/usr/bin/env bash
# Error of the shadowed indirect light against k (1, 4, 16; one frame, filtered and raw) and against
# accumulated still frames (1, 4, 16, 64 at k = 4, filtered), for five shadow modes, each an estimator plus
# ablations (docs/settings.md): `lights`: the converging estimator, the default; `uncorrected`: without the
# irradiance correction; `unshrunk`: the correction trusted whatever its variance (prior spread 10); `centres`:
# uncorrected, blended by their grid light's centre; `paper`: the paper's estimator), on
# sponza_sun@atrium and cornell_emissive at 10K and 100K VPLs, 320x180, alpha 2, S1; plus interleaved
# frames (2x2 and 4x4, k = 1, 4, 16, 1 / 4 / 16 frames, filtered and raw, the default estimator and the
# uncorrected one) and the unshadowed error of 4x4 interleaving accumulated over 16 frames against 1x1.
# Writes the sweeps under OUT (default build-convergence/) and the tables bench/results/convergence.md and
# convergence_interleave.md (bench/scripts/convergence_table.py).
# Usage: bench/scripts/convergence.sh [BUILD_DIR] [OUT]   (over an hour on 2 cores, most of it the 64-frame points at
# 100K VPLs; the Embree references are cached in build-sweep/reference-cache). A part of it: MODES (default
# "lights uncorrected unshrunk centres paper"), SCENES (default "sponza_sun cornell_emissive"), VPLS (default "10000 100000"), PARTS
# (default "k frames"; none: neither) and INTERLEAVE=0 (no interleaving rows; INTERLEAVE_MODES, default
# "lights uncorrected", the shadowed ones, written to bench/results/convergence_interleave.md). The tables
# are made from whatever OUT holds.
set -euo pipefail
here="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$here/build}"
out="${2:-$here/build-convergence}"
scenes="$here/../shared/scenes"
if [ ! -d "$scenes" ]; then
  echo "bench/scripts/convergence.sh: $scenes is missing (the test scenes live beside the repository); nothing measured" >&2
  exit 1
fi
common=(--alpha 2 --start-level 1 --retries 0 --uniform-lights 16 --uniform-shadowed-lights 2
        --brute-force-limit 0 --images false --cache-dir "$here/build-sweep/reference-cache")
# Each mode is an estimator (--shadow-estimator, resolved by render/shadow_estimator.h) plus ablations.
declare -A modes=([lights]="--set shadow-estimator=converging"
                  [uncorrected]="--set shadow-estimator=converging --set shadow-correct-irradiance=false"
                  [unshrunk]="--set shadow-estimator=converging --set shadow-correction-lgh-error=10"
                  [centres]="--set shadow-estimator=converging --set shadow-blend-targets=false --set shadow-correct-irradiance=false"
                  [paper]="--set shadow-estimator=paper")
declare -A paths=([sponza_sun]="sponza_sun/sponza_sun.gltf@atrium"
                  [cornell_emissive]="cornell_emissive/cornell_emissive.gltf")
for name in ${SCENES:-sponza_sun cornell_emissive}; do
  scene="${paths[$name]}"
  for vpls in ${VPLS:-10000 100000}; do
    for mode in ${MODES:-lights uncorrected unshrunk centres paper}; do
      dir="$out/${name}_${vpls}_${mode}"
      read -ra flags <<< "${modes[$mode]}"  # the mode's --set pairs, as separate arguments
      if [[ " ${PARTS:-k frames} " == *" k "* ]]; then
        "$build/lgh-bench" sweep --scene "$scenes/$scene" --vpls "$vpls" "${common[@]}" "${flags[@]}" --repeats 1 \
          --interleave 1 --shadow-samples 1,4,16 --filter on,off --frames 1 --out "$dir/k"
      fi
      if [[ " ${PARTS:-k frames} " == *" frames "* ]]; then
        "$build/lgh-bench" sweep --scene "$scenes/$scene" --vpls "$vpls" "${common[@]}" "${flags[@]}" --repeats 1 \
          --interleave 1 --shadow-samples 4 --filter on --frames 4,16,64 --out "$dir/frames"
      fi
    done
    [ "${INTERLEAVE:-1}" = 0 ] && continue
    "$build/lgh-bench" sweep --scene "$scenes/$scene" --vpls "$vpls" "${common[@]}" --repeats 1 \
      --interleave 1,4 --shadow-samples 0 --frames 1,16 --out "$out/${name}_${vpls}_interleave"
    # Shadowed interleaving: one frame (median of 3, single frames vary) and accumulated frames, for the
    # default estimator and without its correction.
    for mode in ${INTERLEAVE_MODES:-lights uncorrected}; do
      dir="$out/${name}_${vpls}_${mode}"
      read -ra flags <<< "${modes[$mode]}"
      "$build/lgh-bench" sweep --scene "$scenes/$scene" --vpls "$vpls" "${common[@]}" "${flags[@]}" --repeats 3 \
        --interleave 2,4 --shadow-samples 1,4,16 --filter on,off --frames 1 --out "$dir/interleave_one"
      "$build/lgh-bench" sweep --scene "$scenes/$scene" --vpls "$vpls" "${common[@]}" "${flags[@]}" --repeats 1 \
        --interleave 2,4 --shadow-samples 1,4,16 --filter on,off --frames 4,16 --out "$dir/interleave_frames"
    done
  done
done
if [ "${PARTS:-k frames}" != none ]; then
  python3 "$here/bench/scripts/convergence_table.py" "$out" > "$here/bench/results/convergence.md"
  echo "wrote bench/results/convergence.md"
fi
if [ "${INTERLEAVE:-1}" != 0 ]; then
  python3 "$here/bench/scripts/convergence_table.py" --interleave "$out" > "$here/bench/results/convergence_interleave.md"
  echo "wrote bench/results/convergence_interleave.md"
fi
