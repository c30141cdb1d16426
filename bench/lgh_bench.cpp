// lgh-bench: the project's benchmarks, one subcommand each.
//   lgh-bench build [--lights 1K,10K,100K,1M --repeats N --csv F --json F ...]   (paper Tables 1 and 2)
//   lgh-bench light [--vpls 1K,10K,100K,1M --interleave-vpls 100K ...]           (paper Fig. 5, interleaving)
//   lgh-bench frame [--vpls 100K --shadow-samples 4 --interleave 1,2,4 ...]        (paper Table 3)
//   lgh-bench memory [--vpls 1K,10K,100K,1M,4.5M --sizes 320x180,640x360 ...]      (GPU memory by owner)
//   lgh-bench rays [--scene S --vpls 100K --rays 1000000 --repeats 3]               (the BVH against Embree)
//   lgh-bench sweep [--preset readme|smoke --scene S@CAM --alpha ... --csv ...]      (docs/design.md §7: error vs time)
//   lgh-bench reference --scene S@CAM --vpls 1M [--out ref.exr ...]                 (docs/design.md §13: MPI,
//   resumable)
// Under mpiexec / srun (built with MPI: bench/common/ranks.h) the sweep and the reference share the work among the
// ranks.
#include <CLI/CLI.hpp>
#include <functional>
#include <iostream>
#include <vector>

#include "bench/common/ranks.h"
#include "bench/engine/build_bench.h"
#include "bench/engine/frame_bench.h"
#include "bench/engine/light_bench.h"
#include "bench/engine/memory_bench.h"
#include "bench/engine/motion_bench.h"
#include "bench/engine/rays_bench.h"
#ifdef LGH_HAVE_REFERENCE
#include "bench/reference/reference_bench.h"
#include "bench/sweep/sweep_bench.h"
#endif

namespace {

// A benchmark as main sees it: the subcommand it registered, and how to run it once chosen.
struct Benchmark {
  CLI::App* command;
  std::function<int()> run;
};

int run(int argc, char** argv) {
  CLI::App app{"lgh-bench: benchmarks of the lighting grid hierarchy renderer"};
  app.require_subcommand(1);

  // Options live here, for the whole run; a new benchmark adds its options and one Benchmark line.
  lgh::bench::BuildBenchOptions buildOptions;
  lgh::bench::LightBenchOptions lightOptions;
  lgh::bench::FrameBenchOptions frameOptions;
  lgh::bench::MemoryBenchOptions memoryOptions;
  std::vector<Benchmark> benchmarks = {
      {lgh::bench::addBuildCommand(app, buildOptions), [&] { return lgh::bench::runBuildBench(buildOptions); }},
      {lgh::bench::addLightCommand(app, lightOptions), [&] { return lgh::bench::runLightBench(lightOptions); }},
      {lgh::bench::addFrameCommand(app, frameOptions), [&] { return lgh::bench::runFrameBench(frameOptions); }},
      {lgh::bench::addMemoryCommand(app, memoryOptions), [&] { return lgh::bench::runMemoryBench(memoryOptions); }},
  };
#ifdef LGH_HAVE_REFERENCE  // the sweep needs the Embree reference (bench/reference/reference.h)
  lgh::bench::SweepOptions sweepOptions;
  benchmarks.push_back(
      {lgh::bench::addSweepCommand(app, sweepOptions), [&] { return lgh::bench::runSweepBench(sweepOptions); }});
  lgh::bench::RaysBenchOptions raysOptions;
  benchmarks.push_back(
      {lgh::bench::addRaysCommand(app, raysOptions), [&] { return lgh::bench::runRaysBench(raysOptions); }});
  lgh::bench::MotionBenchOptions motionOptions;
  benchmarks.push_back(
      {lgh::bench::addMotionCommand(app, motionOptions), [&] { return lgh::bench::runMotionBench(motionOptions); }});
  lgh::bench::ReferenceBenchOptions referenceOptions;
  benchmarks.push_back({lgh::bench::addReferenceCommand(app, referenceOptions),
                        [&] { return lgh::bench::runReferenceBench(referenceOptions); }});
#endif

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help prints and returns 0; every other parse error prints its message on stderr.
    return app.exit(e) == 0 ? 0 : 1;
  }
  for (const Benchmark& benchmark : benchmarks)
    if (benchmark.command->parsed()) return benchmark.run();
  return 1;  // unreachable: require_subcommand(1)
}

}  // namespace

int main(int argc, char** argv) {
  const lgh::bench::Ranks ranks(argc, argv);  // MPI_Init first, MPI_Finalize last
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    // Under MPI the other ranks may be waiting for this one: end them all (MPI_Abort), saying which rank.
    ranks.abort(std::string("lgh-bench: error: ") + e.what());
  }
}
