#pragma once
// The sweep's case runner: one scene at one VPL target rendered through the Renderer at every grid
// point, measured against the exact reference, beside the baselines (brute force over all S0 lights,
// uniform subsampling), and the time-vs-VPL-count series. The baselines that the Renderer cannot draw
// (a chosen subset of S0, the shadowed compute brute force) use the passes' public interfaces on the
// Renderer's G-buffer and S0.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bench/common/bench_setup.h"
#include "bench/common/progress.h"
#include "bench/reference/reference.h"
#include "bench/sweep/quiet_sampler.h"
#include "bench/sweep/sweep_bench.h"
#include "bench/sweep/sweep_case.h"
#include "render/exact/brute_force_pass.h"
#include "render/passes/lgh_build_pass.h"
#include "render/passes/light_tree_pass.h"
#include "render/passes/light_volume_pass.h"

namespace lgh::bench {

class Ranks;

// Under MPI (bench/common/ranks.h) every rank runs every case: the reference is computed by the ranks together,
// grid point i is measured by rank i mod N on its own GL context, the baselines and the scaling series by
// rank 0, which gathers the points' measurements and returns the cases in the order of one process (the
// other ranks return cases without measurements; with --images each rank writes its points' images into
// the output folder, one every host should see).
class SweepRunner {
 public:
  // imageDir: where .npy images go (options.images); cacheDir: the reference cache (empty: none).
  // Needs a current GL context.
  SweepRunner(const Ranks& ranks, const SweepOptions& options, std::vector<PointSpec> points,
              std::filesystem::path imageDir, std::filesystem::path cacheDir);

  // Units of work (progress ticks) of one scene.
  size_t workPerScene() const;
  void setProgress(ProgressBar* progress) { progress_ = progress; }

  // Every grid point and baseline at one VPL target; checks them (failures()).
  Case runCase(const SceneGpu& gpu, const reference::OcclusionScene& occlusion, const SceneSpec& spec,
               size_t vplTarget);
  // Time and overdraw at options.scalingVpls (alpha 1, S1, k 4, 1x1 and 4x4), brute force beside; no error.
  Case runScaling(const SceneGpu& gpu, const SceneSpec& spec);

  const std::vector<PointSpec>& points() const { return points_; }
  const std::vector<std::string>& failures() const { return failures_; }
  const QuietSampler& sampler() const { return sampler_; }

 private:
  struct CaseImages;  // where a case's .npy images go, if anywhere
  class Baselines;    // the baselines of one case

  RenderSettings baseSettings(const SceneSpec& spec) const;
  // The structure a method draws over the renderer's S0 (the LGH's hierarchy, the lightcuts' light tree),
  // built again `repeats` times.
  std::vector<double> measureStructureBuild(const Renderer& renderer, bool lightTree);
  void compileVariants(BenchRenderer& bench, const RenderSettings& base);
  // A grid point of either method: time = its structure's build + its indirect passes, error against `ref`.
  Measurement measurePoint(BenchRenderer& bench, const RenderSettings& base, const PointSpec& point, double structureMs,
                           const reference::ReferenceImage* ref, const CaseImages* images);
  Measurement measureBruteForce(BenchRenderer& bench, const RenderSettings& base, size_t lights,
                                const reference::ReferenceImage* ref, const char* series);
  // One timed frame with the renderer's settings, after frames - 1 untimed ones accumulated from a
  // fresh history; records the others' share of the machine in m.
  FrameStats timedFrame(BenchRenderer& bench, Measurement& m, int frames = 1);
  bool mine(size_t point) const;  // measured by this rank
  // Rank 0: the other ranks' grid points into c.measurements (in point order), their failures into failures_.
  void gatherPoints(Case& c, std::vector<std::pair<size_t, Measurement>> measured);
  void check(const Case& c);
  void fail(const std::string& message);
  void tick();

  const Ranks& ranks_;
  const SweepOptions& options_;
  std::vector<PointSpec> points_;
  std::filesystem::path imageDir_, cacheDir_;
  QuietSampler sampler_;
  std::vector<std::string> failures_;
  size_t failuresSent_ = 0;  // of failures_, those already gathered by rank 0
  ProgressBar* progress_ = nullptr;
  size_t done_ = 0;
  LghBuildPass buildPass_;
  LightVolumePass lightPass_;
  BruteForcePass bruteForce_;
  LightTreePass treePass_;
};

}  // namespace lgh::bench
