#include "bench/engine/rays_bench.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench/common/bench_setup.h"
#include "bench/common/light_source.h"
#include "bench/common/stats.h"
#include "bench/common/table.h"
#include "bench/reference/reference.h"
#include "render/gl/buffer.h"
#include "render/scene/scene_gpu.h"
#include "render/scene/tracing_program.h"
#include "shared/bindings.h"
#include "shared/bvh_types.h"
#include "shared/ray_offset.h"

namespace lgh::bench {
namespace {

using Ray = reference::OcclusionScene::Ray;
static_assert(sizeof(Ray) == sizeof(gpu::GpuRay), "the rays go to the GPU as they are");

std::string number(double value, const char* format) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// Segments between two random surface points (triangles drawn by area, points uniform on them): from the
// first point offset along its normal toward the second, to 0.1% short of the second, as the frame's
// shadow rays run from a surface to a light on another surface.
std::vector<Ray> surfaceSegments(const Scene& scene, size_t count, unsigned seed) {
  const size_t triangles = scene.indices.size() / 3;
  std::vector<double> cumulative(triangles);
  double total = 0;
  auto vertex = [&](size_t t, int k) { return scene.positions[scene.indices[3 * t + size_t(k)]]; };
  for (size_t t = 0; t < triangles; ++t) {
    total += 0.5 * double(glm::length(glm::cross(vertex(t, 1) - vertex(t, 0), vertex(t, 2) - vertex(t, 0))));
    cumulative[t] = total;
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto point = [&](glm::vec3& p, glm::vec3& n) {
    const size_t t =
        std::min(size_t(std::lower_bound(cumulative.begin(), cumulative.end(), unit(rng) * total) - cumulative.begin()),
                 triangles - 1);
    float a = float(unit(rng)), b = float(unit(rng));
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const glm::vec3 v0 = vertex(t, 0), e1 = vertex(t, 1) - v0, e2 = vertex(t, 2) - v0;
    p = v0 + a * e1 + b * e2;
    const glm::vec3 c = glm::cross(e1, e2);
    n = glm::length(c) > 0 ? glm::normalize(c) : glm::vec3(0, 1, 0);
  };
  std::vector<Ray> rays;
  rays.reserve(count);
  while (rays.size() < count) {
    glm::vec3 p, n, q, m;
    point(p, n);
    point(q, m);
    if (glm::dot(q - p, n) < 0) n = -n;  // leave from the side facing the other point
    const glm::vec3 origin = gpu::offsetRayOrigin(p, n), toQ = q - origin;
    const float length = glm::length(toQ);
    if (!(length > 0)) continue;
    rays.push_back({origin, 0.0f, toQ / length, length * (1.0f - 1e-3f)});
  }
  return rays;
}

struct Traced {
  std::string tracer;
  double ms = 0;  // median over the repeats
  std::vector<std::uint8_t> blocked;
  double bytesPerTriangle = 0;  // GPU layouts: nodes and triangle records per scene triangle
  // GPU layouts, per ray: inner nodes whose children were tested, box tests, triangle tests (a separate,
  // untimed trace with the traversal's counters compiled in)
  double innerNodes = 0, boxTests = 0, triangleTests = 0;
};

// A GPU layout's BVH and its tracing programs (timed, and counting its work), made once for every set.
struct GpuTracer {
  GpuTracer(const Scene& scene, BvhLayout layout, BvhQuality quality) : gpu(scene, layout, quality) {}
  SceneGpu gpu;
  TracingProgram trace{"trace_occlusion.comp"}, counting{"trace_occlusion.comp", {{"LGH_BVH_COUNTERS", "1"}}};
};

Traced traceOnGpu(const Scene& scene, GpuTracer& tracer, const gl::Buffer& rays, size_t count, int repeats) {
  const SceneGpu& gpu = tracer.gpu;
  const gl::Program& program = tracer.trace(gpu);
  gl::Buffer blocked({"rays bench", "blocked"}, count * sizeof(GLuint));
  gpu.bindForCompute();
  rays.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  blocked.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  program.set("rayCount", GLuint(count));
  std::vector<double> times;
  for (int r = 0; r <= repeats; ++r) {  // the first is a warm-up
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    program.dispatch1D(count, 64);
    glFinish();
    if (r > 0)
      times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::ostringstream name;
  name << "GPU " << gpu.bvh().layout;
  Traced out{name.str(), spreadOf(times).median, {}, 0};
  for (GLuint b : blocked.downloadAll<GLuint>()) out.blocked.push_back(std::uint8_t(b));
  // The same rays again with the counters: the work, not the time.
  gl::Buffer work({"rays bench", "work per ray"}, count * sizeof(glm::uvec4));
  work.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  const gl::Program& counting = tracer.counting(gpu);
  counting.set("rayCount", GLuint(count));
  counting.dispatch1D(count, 64);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  for (const glm::uvec4& w : work.downloadAll<glm::uvec4>()) {
    out.innerNodes += w.x;
    out.boxTests += w.y;
    out.triangleTests += w.z;
  }
  for (double* sum : {&out.innerNodes, &out.boxTests, &out.triangleTests}) *sum /= double(std::max<size_t>(count, 1));
  const Bvh& bvh = gpu.bvh();
  out.bytesPerTriangle = double(bvh.nodeBytes() + bvh.triangles.size() * sizeof(gpu::BvhTriangle)) /
                         double(std::max<size_t>(scene.indices.size() / 3, 1));
  return out;
}

// One rtcOccluded1 per ray on every hardware thread, timed alone. (OcclusionScene::occluded, the reference's,
// polls its workers every 100 ms for its progress bar: up to 100 ms more per call.)
std::vector<std::uint8_t> occludedByEmbree(const reference::OcclusionScene& scene, const std::vector<Ray>& rays,
                                           unsigned threads) {
  std::vector<std::uint8_t> result(rays.size(), 0);
  std::atomic<size_t> next{0};
  auto worker = [&] {
    for (;;) {
      const size_t first = next.fetch_add(4096);
      if (first >= rays.size()) return;
      for (size_t i = first; i < std::min(rays.size(), first + 4096); ++i) result[i] = scene.occluded(rays[i]) ? 1 : 0;
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  return result;
}

Traced traceWithEmbree(const reference::OcclusionScene& occlusion, const std::vector<Ray>& rays, unsigned threads,
                       int repeats) {
  Traced out{"Embree rtcOccluded1", 0, {}, 0};
  std::vector<double> times;
  for (int r = 0; r <= repeats; ++r) {  // the first is a warm-up
    const auto start = std::chrono::steady_clock::now();
    out.blocked = occludedByEmbree(occlusion, rays, threads);
    if (r > 0)
      times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  out.ms = spreadOf(times).median;
  return out;
}

// The shadow rays of one frame rendered with `settings` (the VPL budget raised to reach settings' VPL
// count), as the shadow-ray pass traced them, in its recording's order (image order, slot by slot).
std::vector<Ray> frameShadowRays(RenderBench& bench, RenderSettings settings, size_t& vpls) {
  if (settings.indirectMethod != IndirectMethod::Lgh || settings.shadows.samples < 1)
    throw std::invalid_argument(
        "lgh-bench rays: the frame traces no shadow rays (indirect-method lgh, shadow-samples >= 1)");
  const size_t slots = size_t(settings.image.width) * size_t(settings.image.height) * size_t(settings.shadows.samples);
  gl::Buffer recorded({"rays bench", "the frame's shadow rays"}, slots * sizeof(gpu::GpuRay));
  Renderer& renderer = bench.renderer().renderer();
  renderer.recordShadowRays(&recorded);  // every frame overwrites them: the last one's stay
  vpls = bench.renderer().renderToVplTarget(settings, size_t(settings.inputLights.vpls)).lights.vpls;
  renderer.recordShadowRays(nullptr);
  std::vector<Ray> rays;
  for (const gpu::GpuRay& r : recorded.downloadAll<gpu::GpuRay>())
    if (r.tMax > r.tMin) rays.push_back({r.origin, r.tMin, r.direction, r.tMax});
  if (rays.empty()) throw std::runtime_error("lgh-bench rays: the frame traced no shadow rays (no indirect light?)");
  return rays;
}

// One ray per pixel from the camera through the pixel's centre, to twice the scene's extent: coherent
// rays (the G-buffer's, were they traced), any-hit like the rest.
std::vector<Ray> cameraRays(const Scene& scene, const CameraView& view, int width, int height) {
  const glm::dmat4 unproject = glm::inverse(glm::dmat4(view.cameraRelativeViewProjection));
  const float reach = 2.0f * glm::length(scene.bounds.max - scene.bounds.min);
  std::vector<Ray> rays;
  rays.reserve(size_t(width) * size_t(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::dvec4 p = unproject * glm::dvec4((x + 0.5) / width * 2 - 1, (y + 0.5) / height * 2 - 1, 0.5, 1);
      rays.push_back({view.position, view.znear, glm::vec3(glm::normalize(glm::dvec3(p) / p.w)), reach});
    }
  return rays;
}

// Embree's scene and every GPU layout's tracer, made once for all the sets.
struct Tracers {
  Tracers(const Scene& scene, BvhQuality quality) : embree(scene.positions, scene.indices) {
    std::printf("BVH builds (Embree's builder, %s quality):", choiceName(quality, kBvhQualityChoices).c_str());
    for (BvhLayout layout : kBvhLayouts) {
      gpu.push_back(std::make_unique<GpuTracer>(scene, layout, quality));
      std::printf(" %s %.0f ms", choiceName(layout, kBvhLayoutChoices).c_str(), gpu.back()->gpu.bvhBuildMs());
    }
    std::printf("\n");
  }
  reference::OcclusionScene embree;
  std::vector<std::unique_ptr<GpuTracer>> gpu;  // by BvhLayout
};

std::vector<Traced> traceAll(const Scene& scene, Tracers& tracers, const std::vector<Ray>& rays, unsigned threads,
                             int repeats) {
  const gl::Buffer buffer = gl::Buffer::fromVector({"rays bench", "rays"}, rays, 0);
  std::vector<Traced> traced;
  traced.push_back(traceWithEmbree(tracers.embree, rays, threads, repeats));
  for (const auto& tracer : tracers.gpu) traced.push_back(traceOnGpu(scene, *tracer, buffer, rays.size(), repeats));
  return traced;
}

// The set's table and summary line; returns the most answers a layout gave otherwise than Embree.
size_t report(const char* set, const std::vector<Ray>& rays, const std::vector<Traced>& traced, unsigned threads,
              BvhLayout defaultLayout) {
  const Traced& embree = traced[0];
  std::printf("\n%s: %s rays\n", set, formatCount(rays.size()).c_str());
  TextTable table({"tracer", "ms", "M rays/s", "M rays/s per thread", "inner nodes/ray", "box tests/ray",
                   "triangle tests/ray", "BVH B/triangle", "blocked", "differ from Embree"});
  size_t mostDiffering = 0;
  for (const Traced& t : traced) {
    size_t blocked = 0, differ = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      blocked += t.blocked[i];
      differ += t.blocked[i] != embree.blocked[i];
    }
    const double perSecond = double(rays.size()) / (t.ms * 1e-3) * 1e-6;
    const bool counted = t.boxTests > 0;
    table.addRow({t.tracer, formatMs(t.ms), number(perSecond, "%.2f"), number(perSecond / threads, "%.2f"),
                  counted ? number(t.innerNodes, "%.1f") : "-", counted ? number(t.boxTests, "%.1f") : "-",
                  counted ? number(t.triangleTests, "%.1f") : "-",
                  t.bytesPerTriangle > 0 ? number(t.bytesPerTriangle, "%.0f") : "-",
                  number(100.0 * double(blocked) / double(std::max<size_t>(rays.size(), 1)), "%.1f%%"),
                  formatCount(differ)});
    mostDiffering = std::max(mostDiffering, differ);
  }
  table.print(stdout);
  const double binary = traced[1 + size_t(BvhLayout::Binary)].ms, chosen = traced[1 + size_t(defaultLayout)].ms;
  std::ostringstream name;
  name << defaultLayout;
  std::printf("%s: default (%s) / binary %.2fx, default / Embree %.2fx (pace: rays per second)\n", set,
              name.str().c_str(), binary / chosen, embree.ms / chosen);
  return mostDiffering;
}

}  // namespace

CLI::App* addRaysCommand(CLI::App& app, RaysBenchOptions& options) {
  CLI::App* command = app.add_subcommand(
      "rays", "shadow rays through each GPU BVH layout and through Embree, on the same rays and machine");
  options.render.settings.inputLights.vpls = 100000;  // the bench's defaults (RaysBenchOptions)
  options.render.settings.inputLights.bounces = 1;
  addRenderBenchOptions(*command, options.render, {});
  command->add_option("--frame-rays", options.frameRays, "also trace the frame's own shadow rays")
      ->capture_default_str();
  command->add_option("--rays", options.rays, "random surface-to-surface segments per tracer")
      ->check(CLI::Range(size_t(1), size_t(16000000)))
      ->capture_default_str();
  command->add_option("--repeats", options.repeats, "timed traces per tracer (the median is reported)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command->add_option("--ray-seed", options.seed, "random seed of the segments");
  command->add_option("--bvh-quality", options.bvhQuality, "Embree's build quality of the GPU layouts: high|medium|low")
      ->check(CLI::IsMember(choiceList(kBvhQualityChoices)))
      ->capture_default_str();
  command->add_option("--max-differ", options.maxDiffering,
                      "share of a set's rays a GPU layout may answer otherwise than Embree before the exit code is 1");
  return command;
}

int runRaysBench(const RaysBenchOptions& options) {
  RenderBench bench(options.render);
  const Scene& scene = bench.scene();
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  const RenderSettings& settings = options.render.settings;
  std::printf("lgh-bench rays: %s (%s), %zu triangles, %s, %u hardware threads; median of %d traces each\n",
              bench.scenePath().filename().string().c_str(), bench.sceneReason().c_str(), scene.indices.size() / 3,
              bench.context().description().c_str(), threads, options.repeats);

  struct Set {
    std::string name;
    std::vector<Ray> rays;
  };
  std::vector<Set> sets;
  if (options.frameRays) {
    size_t vpls = 0;
    std::vector<Ray> rays = frameShadowRays(bench, settings, vpls);
    char name[160];
    std::snprintf(name, sizeof name, "the frame's shadow rays (%d x %d, %s VPLs, k = %d)", settings.image.width,
                  settings.image.height, formatCount(vpls).c_str(), settings.shadows.samples);
    sets.push_back({name, std::move(rays)});
  }
  sets.push_back({"random surface-to-surface segments", surfaceSegments(scene, options.rays, options.seed)});
  sets.push_back({"camera rays (any hit, one a pixel)",
                  cameraRays(scene, bench.renderer().view(), settings.image.width, settings.image.height)});

  Tracers tracers(scene, choiceValue<BvhQuality>(options.bvhQuality, kBvhQualityChoices));
  bool differed = false;
  for (const Set& set : sets) {
    const size_t differ =
        report(set.name.c_str(), set.rays, traceAll(scene, tracers, set.rays, threads, options.repeats), threads,
               settings.bvhLayout);
    if (double(differ) > options.maxDiffering * double(set.rays.size())) {
      std::fprintf(stderr, "lgh-bench rays: %s: a GPU layout differs from Embree on %zu of %zu rays (more than %g)\n",
                   set.name.c_str(), differ, set.rays.size(), options.maxDiffering);
      differed = true;
    }
  }
  std::printf(
      "(Embree differs where alpha-masked triangles are cut out: the GPU tests them, this Embree scene "
      "does not; and on edges, where Embree is watertight and Moller-Trumbore is not.)\n");
  return differed ? 1 : 0;
}

}  // namespace lgh::bench
