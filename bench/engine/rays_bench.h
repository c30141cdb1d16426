#pragma once
// lgh-bench rays: the BVH's pace on its own, against Embree's on the same machine in one run. Shadow-ray
// segments between random points of the scene's surfaces (area-weighted; from the surface offset as the
// frame's rays are, to 0.1% short of the other point: incoherent, 20-90% blocked), traced any-hit by each
// GPU BVH layout (glsl/trace_occlusion.comp) and by Embree (rtcOccluded1 on every hardware thread):
// rays per second (Embree's also per thread), the layouts' work per ray (inner nodes, box tests, triangle
// tests: device-independent counts, from a second trace with counters), their bytes per scene triangle,
// how many answers differ from Embree's, and the ratio lines wide4 / binary and each layout / Embree.
// (Not yet: the frame's own rays dumped, camera rays.)

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

namespace lgh::bench {

struct RaysBenchOptions {
  std::string scene;  // empty: ../shared/scenes/sponza_sun if present, else the project's Cornell box
  std::string backend = "auto";
  size_t rays = 1000000;
  int repeats = 3;  // timed traces per tracer; the median is reported
  unsigned seed = 1;
  // The exit code is 1 when a layout answers otherwise than Embree on more than this share of the rays
  // (edges: Embree is watertight, Moller-Trumbore is not; alpha-masked triangles: only the GPU tests them).
  double maxDiffering = 1e-3;
};

CLI::App* addRaysCommand(CLI::App& app, RaysBenchOptions& options);
int runRaysBench(const RaysBenchOptions& options);

}  // namespace lgh::bench
