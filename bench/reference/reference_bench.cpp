#include "bench/reference/reference_bench.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>

#include "bench/common/bench_setup.h"
#include "bench/common/ranks.h"
#include "bench/common/table.h"
#include "bench/sweep/sweep_grid.h"
#include "bench/sweep/sweep_reference.h"
#include "render/image_io.h"
#include "render/passes/lgh_build_pass.h"

namespace lgh::bench {
namespace {

namespace fs = std::filesystem;

// The reference as an image: `sums` at the computed pixels, alpha 1 there and 0 elsewhere.
ImageRGBA referenceImage(const reference::ReferenceImage& ref, const std::vector<glm::dvec3>& sums) {
  ImageRGBA image{ref.width, ref.height, std::vector<glm::vec4>(size_t(ref.width) * size_t(ref.height), glm::vec4(0))};
  for (size_t i = 0; i < ref.pixels.size(); ++i) image.pixels[ref.pixels[i]] = glm::vec4(glm::vec3(sums[i]), 1.0f);
  return image;
}

fs::path unshadowedPath(const fs::path& out) {
  return out.parent_path() / (out.stem().string() + "_unshadowed" + out.extension().string());
}

}  // namespace

CLI::App* addReferenceCommand(CLI::App& app, ReferenceBenchOptions& options) {
  CLI::App* command = app.add_subcommand(
      "reference",
      "the exact reference (Embree: every light, every pixel, true visibility) of one scene, by every MPI rank, "
      "resumable (tiles kept in the cache as they complete)");
  command->add_option("--scene", options.scene, "glTF scene, PATH or PATH@CAMERA")->required();
  options.settings.image.width = 320;  // the sweep's default image, so that defaults make the sweep's references
  options.settings.image.height = 180;
  addRenderSettingsOptions(*command, options.settings, {"camera", "vpls"});
  command->add_option("--vpls", options.vpls, "VPL target (1K, 1M allowed); the budget is raised until it is met")
      ->transform(CLI::AsNumberWithUnit(std::map<std::string, size_t>{{"K", 1000}, {"M", 1000000}}))
      ->check(CLI::Range(size_t(1), size_t(16000000)))
      ->capture_default_str();
  command
      ->add_option("--pixels", options.pixels,
                   "fraction of the pixels to compute (0: all, unless that exceeds --budget pairs; as the sweep)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command->add_option("--budget", options.budget, "pixel-light pairs above which a random pixel subset is taken")
      ->check(CLI::Range(1e3, 1e13))
      ->capture_default_str();
  command->add_option("--tile", options.tileSize, "tile side in pixels")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  command->add_option("--threads", options.threads, "Embree threads per rank (0: the host's, shared by its ranks)")
      ->capture_default_str();
  command->add_option("--cache-dir", options.cacheDir,
                      "reference cache, seen by every rank (default: reference-cache beside lgh-bench; none: off)");
  command->add_option(
      "--out", options.out,
      "EXR of the shadowed irradiance (alpha 1 where computed); the unshadowed beside it as *_unshadowed");
  addBackendOption(*command, options.backend);
  // Test hooks: kill this process (SIGKILL) once it has stored N tiles; make tile T fail.
  command->add_option("--kill-after-tiles", options.killAfterTiles)->group("");
  command->add_option("--fail-tile", options.failTile)->group("");
  return command;
}

int runReferenceBench(const ReferenceBenchOptions& options) {
  const Ranks& ranks = Ranks::world();
  const SceneSpec spec = parseSceneSpec(options.scene);
  if (!options.out.empty() && ranks.root()) {
    checkImagePath(options.out);
    if (!isHdrFormat(options.out)) throw std::runtime_error(options.out + ": the reference is written as HDR (.exr)");
  }
  const fs::path cacheDir = options.cacheDir == "none" ? fs::path()
                            : options.cacheDir.empty() ? defaultReferenceCache()
                                                       : fs::path(options.cacheDir);
  const Scene scene = loadScene(spec.path);  // every rank: its own occluders
  RenderSettings settings = options.settings;
  settings.image.camera = spec.camera;
  resolveCamera(scene, settings);
  const reference::OcclusionScene occlusion(scene.positions, scene.indices);

  // Rank 0 renders the frame (G-buffer, S0) the reference is of; the other ranks need no GL.
  reference::ReferenceInput input;
  std::string lightsLine;
  std::unique_ptr<gl::Context> context;
  if (ranks.root()) {
    context = createContext(options.backend);
    const SceneGpu gpu(scene, settings.bvhLayout);
    BenchRenderer bench(gpu, settings);
    const FrameStats first = bench.renderToVplTarget(settings, options.vpls);
    const Renderer& renderer = bench.renderer();
    const std::vector<gpu::GpuLight> lights =
        renderer.inputLights().lights.download<gpu::GpuLight>(renderer.inputLights().count);
    input = referenceInput(renderer, fromGpuLights(lights));
    lightsLine = std::to_string(first.lights.vpls) + " VPLs (budget " + std::to_string(settings.inputLights.vpls) +
                 "), " + std::to_string(first.lights.inputLights) + " lights in S0";
    std::fprintf(stderr, "lgh-bench reference: %s, %d x %d, %s; %s; cache %s\n", spec.name.c_str(),
                 settings.image.width, settings.image.height, lightsLine.c_str(), context->description().c_str(),
                 cacheDir.empty() ? "none" : cacheDir.string().c_str());
  }

  ReferenceRequest request;
  request.pixels = options.pixels;
  request.budget = options.budget;
  request.run.tileSize = options.tileSize;
  request.run.threads = options.threads;
  request.run.cacheDir = cacheDir;
  request.run.label = "reference " + spec.name + " " + shortCount(options.vpls) + " VPLs";
  request.run.killAfterTiles = options.killAfterTiles;
  request.run.failTile = options.failTile;
  ReferenceInfo info;
  TileCounts tiles;
  const reference::ReferenceImage ref = obtainReference(ranks, occlusion, spec, settings, input, request, info, &tiles);
  if (!ranks.root()) return 0;

  if (info.cached && tiles.computed == 0 && tiles.cached == 0)
    std::printf("reference: from the cache (%s)\n", info.cacheFile.c_str());
  else
    std::printf(
        "reference: %d tiles of %d px: %d computed (%d of them again: truncated, corrupt or another's), %d from the "
        "cache; %d rank%s x %u threads, %.1f s\n",
        tiles.tiles, options.tileSize, tiles.computed, int(tiles.redoneWhy.size()), tiles.cached, tiles.ranks,
        tiles.ranks == 1 ? "" : "s", tiles.threadsPerRank, tiles.seconds);
  for (const std::string& why : tiles.redoneWhy) std::printf("  computed again: %s\n", why.c_str());
  // Seconds: the tiles' thread time over the threads (a resumed reference's earlier tiles included).
  const double raysPerSecond = ref.seconds > 0 ? double(ref.rays) / ref.seconds : 0.0;
  std::printf(
      "reference: %zu of %zu pixels (fraction %.4g), %s, %llu pairs, %llu shadow rays in %.1f s on %u "
      "threads (%.2f M rays/s, %.2f M rays/s per thread)\n",
      info.pixels, info.imagePixels, info.fraction, lightsLine.c_str(), static_cast<unsigned long long>(ref.pairs),
      static_cast<unsigned long long>(ref.rays), ref.seconds, ref.threads, raysPerSecond * 1e-6,
      raysPerSecond * 1e-6 / std::max(1u, ref.threads));
  if (!info.cacheFile.empty()) std::printf("cache: %s\n", info.cacheFile.c_str());
  if (!options.out.empty()) {
    writeImage(options.out, referenceImage(ref, ref.shadowed));
    writeImage(unshadowedPath(options.out), referenceImage(ref, ref.unshadowed));
    std::printf("wrote %s and %s\n", options.out.c_str(), unshadowedPath(options.out).string().c_str());
  }
  return 0;
}

}  // namespace lgh::bench
