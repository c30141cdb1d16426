#!/usr/bin/env bash
# The paper's scale on a Slurm cluster: exact references of both README scenes at 1M VPLs and 1280x720,
# every pixel (sponza_sun@atrium: ~4.6e11 pixel-light pairs; cornell_emissive: ~1.1e12), then a short
# sweep against them (alpha 1 and 2, 1x1 and 4x4, k 4, filtered). docs/cluster.md says what it costs.
#   sbatch bench/scripts/slurm_1m.sh                       (from the checkout, built: ./setup.sh build)
#   sbatch --nodes=32 bench/scripts/slurm_1m.sh            (more nodes: the time falls as 1/nodes)
# Killed (time limit, a node lost)? Submit it again: a finished reference is read from CACHE and an
# unfinished one resumes from its tiles there (the sweep's points, minutes against the references'
# hours, are measured again). CACHE must be on storage every node sees.
#SBATCH --job-name=lgh-1m
#SBATCH --nodes=8
#SBATCH --ntasks-per-node=1
#SBATCH --cpus-per-task=32
#SBATCH --time=04:00:00
#SBATCH --output=lgh-1m-%j.log
set -euo pipefail
here="${SLURM_SUBMIT_DIR:-$(cd "$(dirname "$0")/../.." && pwd)}"
scenes="${SCENES:-$here/../shared/scenes}"
cache="${CACHE:-$here/build-sweep/reference-cache}"
out="${OUT:-$here/bench/results/scale_1m}"
width="${WIDTH:-1280}" height="${HEIGHT:-720}"
# Inside the allocation MPICH's mpiexec starts one rank per task through srun itself (its Slurm
# launcher); with an MPI built for Slurm's PMI, `srun --mpi=pmi2` does the same (MPI_LAUNCH=...).
launch=(${MPI_LAUNCH:-mpiexec -n "${SLURM_NTASKS:-1}"})
threads="${SLURM_CPUS_PER_TASK:-0}"
for scene in "$scenes/sponza_sun/sponza_sun.gltf@atrium" "$scenes/cornell_emissive/cornell_emissive.gltf"; do
  name=$(basename "${scene%@*}" .gltf)
  "${launch[@]}" "$here/build/lgh-bench" reference --scene "$scene" --vpls 1M --width "$width" --height "$height" \
    --pixels 1 --threads "$threads" --cache-dir "$cache" --out "$out/${name}_1m_reference.exr"
done
"${launch[@]}" "$here/build/lgh-bench" sweep --scene "$scenes/sponza_sun/sponza_sun.gltf@atrium" \
  --scene "$scenes/cornell_emissive/cornell_emissive.gltf" --vpls 1M --width "$width" --height "$height" \
  --reference-pixels 1 --alpha 1,2 --start-level 1 --interleave 1,4 --shadow-samples 4 --filter on \
  --uniform-lights 4096 --uniform-shadowed-lights 64 --brute-force-limit 0 --repeats 3 --images false \
  --threads "$threads" --cache-dir "$cache" --out "$out"
