#pragma once
// lgh-bench rays: the BVH's pace on its own, against Embree's on the same machine in one run, on three
// sets of rays over one scene: the frame's own shadow rays (recorded by the shadow-ray pass from a frame
// rendered with the render settings: Sponza's camera, 640 x 360, 100K VPLs, k = 4 by default), segments
// between random points of the scene's surfaces (area-weighted; from the surface offset as the frame's
// rays are, to 0.1% short of the other point: incoherent, 20-90% blocked), and camera rays (one a pixel
// of the frame's size, through its centre: coherent). Each set is traced any-hit by each GPU
// BVH layout (glsl/trace_occlusion.comp) and by Embree (rtcOccluded1 on every hardware thread): rays per
// second (Embree's also per thread), the layouts' work per ray (inner nodes, box tests, triangle tests:
// device-independent counts, from a second trace with counters), their bytes per scene triangle, how many
// answers differ from Embree's, and the summary lines: the default layout's pace over the binary BVH's
// and over Embree's.

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

#include "bench/common/bench_setup.h"

namespace lgh::bench {

struct RaysBenchOptions {
  // --scene, --backend, and the settings of the frame whose shadow rays are traced (--vpls is the VPL
  // count to reach; its default, set by addRaysCommand: 100K, one bounce).
  RenderBenchOptions render;
  bool frameRays = true;  // also the frame's own shadow rays
  size_t rays = 1000000;  // random segments
  int repeats = 3;        // timed traces per tracer; the median is reported
  unsigned seed = 1;
  std::string bvhQuality = "high";  // the GPU layouts' build (kBvhQualityChoices; a scene's load: high)
  // The exit code is 1 when a layout answers otherwise than Embree on more than this share of a set's rays
  // (edges: Embree is watertight, Moller-Trumbore is not; alpha-masked triangles: only the GPU tests them).
  double maxDiffering = 1e-3;
};

CLI::App* addRaysCommand(CLI::App& app, RaysBenchOptions& options);
int runRaysBench(const RaysBenchOptions& options);

}  // namespace lgh::bench
