// Shadow rays to real input lights (render/passes/shadow_targets_pass, glsl/shadow_targets.comp):
// the input light drawn for a grid light follows its share of the grid light's importance (chi-square
// against lgh::ClusterSources, gathered and scattered levels), and a pixel whose lights are half
// behind a wall gets, averaged over frames, the exact share-weighted visibility of its selection; and
// the samples' estimate of the unshadowed sum counts the grid lights the selection cannot reach.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <numeric>
#include <random>

#include "gl_test_env.h"
#include "gltf_writer.h"
#include "lgh/blending.h"
#include "lgh/chi_square.h"
#include "lgh/cluster_shares.h"
#include "lgh/shading.h"
#include "render/passes/lgh_build_pass.h"
#include "render/passes/shadow_targets_pass.h"
#include "render/renderer.h"
#include "render/scene/scene_gpu.h"

namespace lgh::test {
namespace {

glm::ivec3 vertexOf(std::uint32_t key, const GridGeometry& grid, int level) {
  const std::uint32_t n = std::uint32_t(grid.cellsPerAxis(level)) + 1;
  return glm::ivec3(int(key % n), int((key / n) % n), int(key / (n * n)));
}

// CPU grid light index of every GPU grid light of `level` (matched by vertex).
std::vector<size_t> cpuIndexOfGpuLights(const GpuHierarchy& gpu, const Hierarchy& cpu, int level) {
  std::map<std::uint64_t, size_t> cpuByKey;
  for (size_t g = 0; g < cpu.levels[size_t(level)].size(); ++g)
    cpuByKey[packVertex(cpu.levels[size_t(level)][g].vertex)] = g;
  std::vector<size_t> out;
  for (const gpu::GpuGridLight& g : gpu.downloadLevel(level)) {
    const auto it = cpuByKey.find(packVertex(vertexOf(g.vertexKey, gpu.grid, level)));
    out.push_back(it == cpuByKey.end() ? SIZE_MAX : it->second);
  }
  return out;
}

class ShadowTargetsTest : public GLTest {};

TEST_F(ShadowTargetsTest, DrawsFollowImportanceShares) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), intensity(0.2f, 3.0f);
  std::vector<Light> lights(400);
  for (Light& l : lights) {
    l.position = 10.0f * glm::vec3(u(rng), u(rng), u(rng));
    l.intensity = glm::vec3(intensity(rng), intensity(rng), intensity(rng));
    if (u(rng) < 0.5f) l.normal = glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
  }
  const std::vector<gpu::GpuLight> gpuLights = toGpuLights(lights);
  const std::vector<Light> seen = fromGpuLights(gpuLights);
  const gl::Buffer buffer = gl::Buffer::fromVector({"test", "data"}, gpuLights);
  LghBuildPass build(glContext().hasExtension("GL_NV_shader_atomic_float"));
  ShadowTargetsPass targetsPass;
  constexpr unsigned kRaces = 16;
  constexpr int kFrames = 150;
  std::vector<ChiSquare> family;
  for (bool gathered : {true, false}) {
    LghBuildOptions options;
    options.levels = 4;
    options.eMin = 1e-4;
    options.gatherCoarseLevels = gathered;
    GpuHierarchy hierarchy;
    build.execute(buffer, lights.size(), options, hierarchy);
    const Hierarchy cpu = gathered ? buildGather(seen, hierarchy.grid) : buildScatter(seen, hierarchy.grid);
    const ClusterSources clusters(seen, cpu, gathered);
    // A few grid lights of every level with clusters of at least 12 lights.
    struct Tested {
      int level;
      size_t gpuIndex;  // merged
      std::vector<LightShare> shares;
      std::vector<double> counts;
    };
    std::vector<Tested> tested;
    for (int level = 1; level <= 4; ++level) {
      const std::vector<size_t> cpuIndex = cpuIndexOfGpuLights(hierarchy, cpu, level);
      int picked = 0;
      for (size_t g = 0; g < cpuIndex.size() && picked < 2; ++g) {
        if (cpuIndex[g] == SIZE_MAX) continue;
        std::vector<LightShare> shares = clusters.shares(level, cpuIndex[g]);
        if (shares.size() < 12) continue;
        tested.push_back(
            {level, hierarchy.levels[size_t(level)].offset + g, shares, std::vector<double>(shares.size())});
        ++picked;
      }
    }
    ASSERT_GE(tested.size(), 6u);
    ShadowTargets targets;
    for (int frame = 0; frame < kFrames; ++frame) {
      targetsPass.execute({buffer, lights.size(), hierarchy}, kRaces, 0x9e3779b9u * unsigned(frame + 1), targets);
      for (Tested& t : tested) {
        for (GLuint light : targets.targets.download<GLuint>(kRaces, t.gpuIndex * kRaces)) {
          const auto it = std::lower_bound(t.shares.begin(), t.shares.end(), size_t(light),
                                           [](const LightShare& s, size_t l) { return s.light < l; });
          ASSERT_TRUE(it != t.shares.end() && it->light == light)
              << "level " << t.level << ": drew light " << light << ", which is not in the cluster";
          t.counts[size_t(it - t.shares.begin())] += 1;
        }
      }
    }
    for (const Tested& t : tested) {
      std::vector<double> probabilities;
      for (const LightShare& s : t.shares) probabilities.push_back(s.share);
      const ChiSquare chi = chiSquare(t.counts, probabilities);
      std::printf("  %s, level %d, %zu lights: chi-square %.1f with %d dof\n", gathered ? "gather" : "scatter", t.level,
                  t.shares.size(), chi.statistic, chi.dof);
      family.push_back(chi);
    }
  }
  // One test at 1% over the family (pooled: the clusters' draws are independent), not 1% per cluster.
  const ChiSquare pooled = pooledChiSquare(family);
  std::printf("  pooled over %zu clusters: chi-square %.1f with %d dof (1%% critical %.1f)\n", family.size(),
              pooled.statistic, pooled.dof, pooled.critical01);
  EXPECT_TRUE(pooled.passes());
}

// A floor cut by a tall wall at x = 0 and a cloud of point lights (S0) around it, half on each side:
// seen from the floor at x > 0, the lights at x < 0 are hidden.
std::filesystem::path writeWallScene(const TempDir& dir, std::vector<glm::vec3>& lightPositions) {
  GltfWriter w;
  const int grey = w.addMaterial(MaterialDesc{}.withBaseColor({0.5f, 0.5f, 0.5f, 1}));
  w.addNode(NodeDesc{}.withMesh(w.addMesh({quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, grey)})));
  w.addNode(NodeDesc{}.withMesh(w.addMesh({quad({0, 0, -4}, {0, 4, 0}, {0, 0, 8}, grey)})));
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 48; ++i) {
    const float side = i % 2 ? 1.0f : -1.0f;
    const glm::vec3 p(side * (0.2f + 0.8f * u(rng)), 0.6f + 0.8f * u(rng), 1.4f * (u(rng) - 0.5f));
    lightPositions.push_back(p);
    w.addNode(NodeDesc{}.withLight(w.addLight(LightDesc{}.withIntensity(0.5 + u(rng)))).translated(p));
  }
  w.addNode(NodeDesc{}
                .withCamera(w.addCamera(CameraDesc{}.named("top").withYfov(1.0).withClip(0.1, 100)))
                .translated({0, 6, 0})
                .rotated(glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0))));
  return w.write(dir / "wall.gltf");
}

// The visibility ratios the shadow estimate converges to at surface point x, over the selectable grid
// lights g with f_g = lum(blend x contribution) (what the light pass selects by):
//   byShare:        sum_g f_g V_g / sum_g f_g with V_g = sum_i share_i(g) [input light i visible] (drawn
//                   lights as they are);
//   byContribution: the same with each share further weighted by the light's geometric factor
//                   G_i(x) = lum(f_i(x)) / a_i (the limit of resampled targets: shadow_rays.comp, pickTarget);
//   weighted:       sum_g c_g V_g / sum_g c_g with c_g = blend a_g sum_i share_i G_i(x), what g's input
//                   lights add (samples weighed by drawn over centre contribution);
//   blended:        the same with each input light blended by its own distance to x instead of its grid
//                   light's centre's, c_g = a_g sum_i share_i B_l(|x - p_i|) G_i(x) (shadow-blend-targets):
//                   since the levels' B_l sum to 1 at every distance, sum_g c_g = sum_i a_i G_i wherever
//                   every grid light holding a light i with B_l > 0 is selectable;
//   exact:          sum_i a_i G_i V_i / sum_i a_i G_i over the input lights (the reference's ratio).
// Input light i is visible from x when it is on x's side of the wall at x = wallX (taller than the lights).
struct ExpectedRatios {
  double byShare, byContribution, weighted, blended, exact;
  // Unshadowed luminance: what the selectable grid lights' input lights add (blend a_g sum_i share_i G_i,
  // and blended by their own distance), what all input lights add (sum_i a_i G_i), and the same two sums
  // over every grid light whose volume covers x, selectable or not: what the samples' T estimates when
  // the light pass counts the unselectable ones (shadow-count-unselectable).
  double weightedTotal, blendedTotal, exactTotal, reachableWeightedTotal, reachableBlendedTotal;
};
// What expectedRatios reads of a hierarchy, read once (the tests evaluate it at hundreds of pixels): the
// grid, each level's grid lights as the GPU built them, and the exact shares of their input lights (from a
// CPU build over the same lights).
struct HierarchyShares {
  HierarchyShares(const GpuHierarchy& gpu, const std::vector<Light>& lights) : grid(gpu.grid), lights(lights) {
    const Hierarchy cpu = buildGather(lights, gpu.grid);
    const ClusterSources clusters(lights, cpu);
    gridLights.resize(size_t(std::max(grid.levels, 0)) + 1);
    shares.resize(gridLights.size());
    for (int level = 1; level <= grid.levels; ++level) {
      const std::vector<size_t> cpuIndex = cpuIndexOfGpuLights(gpu, cpu, level);
      gridLights[size_t(level)] = gpu.downloadLevel(level);
      for (size_t g = 0; g < gridLights[size_t(level)].size(); ++g)
        shares[size_t(level)].push_back(clusters.shares(level, cpuIndex[g]));
    }
  }
  GridGeometry grid;
  std::vector<Light> lights;
  std::vector<std::vector<gpu::GpuGridLight>> gridLights;    // [level][GPU index]
  std::vector<std::vector<std::vector<LightShare>>> shares;  // [level][GPU index]: its input lights' shares
};

ExpectedRatios expectedRatios(const HierarchyShares& hierarchy, const glm::dvec3& x, const glm::dvec3& n, double wallX,
                              const RenderSettings& settings, float clampDistance) {
  const std::vector<Light>& lights = hierarchy.lights;
  const int levels = hierarchy.grid.levels, first = settings.lightPass.startLevel;
  const bool defensive = resolveShadowEstimator(settings.shadows, {}).estimator.defensive > 0;
  const auto geometric = [&](const Light& l) {
    return luminance(lightContribution(glm::dvec3(l.position), glm::dvec3(l.intensity), glm::dvec3(l.normal),
                                       omniFraction(l), x, &n, clampDistance)) /
           luminance(glm::dvec3(l.intensity));
  };
  const auto visibleFromX = [&](const Light& l) { return (l.position.x > wallX) == (x.x > wallX); };
  struct Sum {
    double visible = 0, total = 0;
    double ratio() const { return visible / total; }
  } byShare, byContribution, weighted, blended, exact;
  double reachableWeighted = 0, reachableBlended = 0;
  for (int level = std::max(first, 1) + (settings.shadows.skipFinest ? 1 : 0); level <= levels; ++level) {
    const std::vector<gpu::GpuGridLight>& gpuLevel = hierarchy.gridLights[size_t(level)];
    for (size_t g = 0; g < gpuLevel.size(); ++g) {
      const gpu::GpuGridLight& light = gpuLevel[g];
      const double d = glm::distance(glm::dvec3(light.position), x);
      const LevelRole role = levelRole(level, first, levels);
      const double radius = hierarchy.grid.radius(level, settings.lightPass.alpha);
      const double blend = blendWeight(role, d, radius);
      const double f =
          blend * luminance(lightContribution(glm::dvec3(light.position), glm::dvec3(light.intensity),
                                              glm::dvec3(light.meanNormal), light.omniFraction, x, &n, clampDistance));
      Sum shareSum, contributionSum, blendedSum;
      for (const LightShare& s : hierarchy.shares[size_t(level)][g]) {
        const Light& l = lights[s.light];
        const double v = visibleFromX(l) ? 1.0 : 0.0;
        shareSum.visible += s.share * v, shareSum.total += s.share;
        contributionSum.visible += s.share * geometric(l) * v, contributionSum.total += s.share * geometric(l);
        const double own = blendWeight(role, glm::distance(glm::dvec3(l.position), x), radius) * geometric(l);
        blendedSum.visible += s.share * own * v, blendedSum.total += s.share * own;
      }
      const double a = luminance(glm::dvec3(light.intensity));
      if (role == LevelRole::Top || role == LevelRole::Only || d < 2.0 * radius) {
        reachableWeighted += blend * a * contributionSum.total;
        reachableBlended += a * blendedSum.total;
      }
      // Selectable: a positive importance (with the defensive share, any grid light blended here).
      if (!(f > 0) && !(defensive && blend > 0)) continue;
      if (!(contributionSum.total > 0)) continue;
      byShare.visible += f * shareSum.ratio(), byShare.total += f;
      byContribution.visible += f * contributionSum.ratio(), byContribution.total += f;
      weighted.visible += blend * a * contributionSum.visible, weighted.total += blend * a * contributionSum.total;
      blended.visible += a * blendedSum.visible, blended.total += a * blendedSum.total;
    }
  }
  for (const Light& l : lights) {
    const double c = luminance(glm::dvec3(l.intensity)) * geometric(l);
    exact.visible += visibleFromX(l) ? c : 0.0, exact.total += c;
  }
  return {byShare.ratio(), byContribution.ratio(), weighted.ratio(), blended.ratio(),   exact.ratio(),
          weighted.total,  blended.total,          exact.total,      reachableWeighted, reachableBlended};
}

// 24 x 24, the scene's point lights as S0 (no VPLs, no emitters), 3 levels, alpha 2, the raw ratio.
RenderSettings pointLightSettings() {
  RenderSettings settings;
  settings.image.width = settings.image.height = 24;
  settings.inputLights.maxDirectLights = 0;
  settings.inputLights.vpls = 0;
  settings.inputLights.emitterSamples = 0;
  settings.hierarchy.levels = 3;
  settings.lightPass.alpha = 2.0f;
  settings.filter.passes = 0;
  return settings;
}

TEST_F(ShadowTargetsTest, HalfHiddenClusterGetsItsWeightedVisibility) {
  TempDir dir;
  std::vector<glm::vec3> placed;
  const Scene scene = loadScene(writeWallScene(dir, placed));
  const SceneGpu gpuScene(scene);
  RenderSettings settings = pointLightSettings();
  // Drawn lights as they are: the importance-weighted visibility, exactly; resampled at the pixel: the
  // contribution-weighted visibility, in the limit of many drawn lights (16 here; a bias for finite m);
  // resampled and weighed: the visibility weighted by what each grid light's input lights add, exactly
  // (a ratio of sums over the frames), which is the exact ratio but for the blending's approximation;
  // and then the mean weight D times the LGH's irradiance is what the input lights add (the irradiance
  // correction), with the defensive selection too.
  // Blended by each light's own distance: the same, but converging to the exact sum and ratio.
  enum class Target { byShare, byContribution, weighted, blended };
  struct Mode {
    bool skipFinest;
    Target target;
    float defensive = 0.0f;
  };
  const std::vector<Mode> modes{Mode{true, Target::byShare},         Mode{false, Target::byShare},
                                Mode{false, Target::byContribution}, Mode{false, Target::weighted},
                                Mode{false, Target::weighted, 0.5f}, Mode{false, Target::blended}};
  const auto limitOf = [](const Mode& mode, const ExpectedRatios& e) {
    return mode.target == Target::byShare          ? e.byShare
           : mode.target == Target::byContribution ? e.byContribution
           : mode.target == Target::weighted       ? e.weighted
                                                   : e.blended;
  };
  const auto modeSettings = [&](const Mode& mode) {
    RenderSettings s = settings;
    s.shadows.skipFinest = mode.skipFinest;
    s.shadows.resampleTargets = mode.target != Target::byShare;
    s.shadows.weighTargets = mode.target == Target::weighted || mode.target == Target::blended;
    s.shadows.blendTargets = mode.target == Target::blended;
    s.shadows.targets = 16;
    s.shadows.defensive = mode.defensive;
    return s;
  };
  // What each mode converges to differs by a few hundredths at a pixel, less than one pixel's error over
  // the frames; so the estimates are compared summed over the floor pixels (about half hidden: exact ratio
  // 0.3-0.75) where the limits of the modes that select or weigh otherwise lie farthest apart. Resampled
  // and weighed targets converge to nearly the same value here (within 0.01 at every pixel: the drawn
  // lights' contribution and what they add differ by the centre's blending alone), so they form one group.
  const auto group = [](const Mode& mode) {
    return mode.skipFinest ? 0 : mode.target == Target::byShare ? 1 : mode.target == Target::blended ? 3 : 2;
  };
  constexpr size_t kPixels = 12;
  std::vector<size_t> pixels;
  std::vector<double> limits(modes.size());  // the mean of the limits over the pixels
  {
    Renderer renderer(gpuScene, settings);
    renderer.render(makeCameraView(resolveCamera(scene, settings), 24, 24));
    const std::vector<Light> lights =
        fromGpuLights(renderer.inputLights().lights.download<gpu::GpuLight>(renderer.inputLights().count));
    const HierarchyShares shares(renderer.hierarchy(), lights);
    const ImageRGBA position = renderer.readImage(Aov::Position), normal = renderer.readImage(Aov::Normal);
    std::vector<std::pair<double, size_t>> byGap;  // (smallest gap between groups' limits, pixel)
    std::vector<std::vector<double>> pixelLimits(position.pixels.size());
    for (size_t i = 0; i < position.pixels.size(); ++i) {
      if (!(position.pixels[i].w > 0) || normal.pixels[i].y < 0.99f) continue;
      const glm::dvec3 x = glm::dvec3(glm::vec3(position.pixels[i]));
      const auto expectedFor = [&](const RenderSettings& s) {
        return expectedRatios(shares, x, glm::dvec3(0, 1, 0), -scene.origin.x, s, renderer.clampDistance());
      };
      const double exact = expectedFor(settings).exact;
      if (exact < 0.3 || exact > 0.75) continue;
      for (const Mode& mode : modes) pixelLimits[i].push_back(limitOf(mode, expectedFor(modeSettings(mode))));
      double gap = 1e30;
      for (size_t a = 0; a < modes.size(); ++a)
        for (size_t b = 0; b < a; ++b)
          if (group(modes[a]) != group(modes[b])) gap = std::min(gap, std::abs(pixelLimits[i][a] - pixelLimits[i][b]));
      byGap.push_back({gap, i});
    }
    ASSERT_GE(byGap.size(), kPixels) << "too few floor pixels are about half hidden";
    std::sort(byGap.rbegin(), byGap.rend());
    for (size_t j = 0; j < kPixels; ++j) {
      pixels.push_back(byGap[j].second);
      for (size_t m = 0; m < modes.size(); ++m) limits[m] += pixelLimits[byGap[j].second][m] / kPixels;
    }
  }
  const size_t pixel = pixels.front();  // the widest apart: where the irradiance correction is checked
  std::vector<double> tolerances(modes.size()), means(modes.size());
  for (size_t m = 0; m < modes.size(); ++m) {
    const Mode mode = modes[m];
    const std::string label = std::string(mode.skipFinest ? "skip S1" : "with S1") +
                              (mode.target == Target::byContribution ? ", resampled"
                               : mode.target == Target::weighted     ? ", resampled and weighed"
                               : mode.target == Target::blended      ? ", resampled, weighed and blended"
                                                                     : "") +
                              (mode.defensive > 0 ? ", defensive" : "");
    SCOPED_TRACE(label);
    settings = modeSettings(mode);
    const bool weighed = mode.target == Target::weighted || mode.target == Target::blended;
    Renderer renderer(gpuScene, settings);
    const CameraView view = makeCameraView(resolveCamera(scene, settings), 24, 24);
    renderer.render(view);
    const std::vector<Light> lights =
        fromGpuLights(renderer.inputLights().lights.download<gpu::GpuLight>(renderer.inputLights().count));
    ASSERT_EQ(lights.size(), placed.size());
    const ImageRGBA position = renderer.readImage(Aov::Position);
    const glm::dvec3 x = glm::dvec3(glm::vec3(position.pixels[pixel]));
    const ExpectedRatios expected =
        expectedRatios(HierarchyShares(renderer.hierarchy(), lights), x, glm::dvec3(0, 1, 0), -scene.origin.x, settings,
                       renderer.clampDistance());
    // The frames' ratios combined per pixel as the accumulation does: sum_f D_f r_f / sum_f D_f, D_f the
    // frame's mean weight (Aov::Ratio's blue is C D_f, C the LGH's irradiance; D_f = 1 unless weighed),
    // then averaged over the pixels; its standard error by the delta method over the frames (a frame's
    // drawn targets are shared by its pixels, so pixels are not independent within a frame).
    const ImageRGBA irradiance = renderer.readImage(Aov::Irradiance);
    const int frames = 400;
    std::vector<std::vector<glm::dvec2>> samples(kPixels);  // per pixel, (D r, D) per frame
    for (int f = 0; f < frames; ++f) {
      if (f > 0) renderer.render(view);
      const ImageRGBA raw = fromGLRows(24, 24, renderer.texture(Aov::Ratio).readRGBA());  // r ratio, b C D
      for (size_t j = 0; j < kPixels; ++j) {
        const glm::vec4 r = raw.pixels[pixels[j]];
        const double meanWeight = double(r.z) / luminance(glm::dvec3(glm::vec3(irradiance.pixels[pixels[j]])));
        samples[j].push_back({meanWeight * r.x, meanWeight});
      }
    }
    std::vector<double> pixelMean(kPixels), weightSum(kPixels);
    double mean = 0;
    for (size_t j = 0; j < kPixels; ++j) {
      glm::dvec2 sum(0.0);
      for (const glm::dvec2& v : samples[j]) sum += v;
      pixelMean[j] = sum.x / sum.y, weightSum[j] = sum.y;
      mean += pixelMean[j] / kPixels;
    }
    double residuals = 0;
    for (int f = 0; f < frames; ++f) {
      double frameResidual = 0;
      for (size_t j = 0; j < kPixels; ++j) {
        const glm::dvec2 v = samples[j][size_t(f)];
        frameResidual += (v.x - pixelMean[j] * v.y) / weightSum[j] / kPixels;
      }
      residuals += frameResidual * frameResidual;
    }
    const double standardError = std::sqrt(residuals);
    std::printf(
        "  %s: ratio over %zu pixels %.4f +- %.4f over %d frames (limit %.4f); at the widest pixel: "
        "share-weighted visibility %.4f, contribution-weighted %.4f, weighted by what the grid lights add "
        "%.4f (blended by the lights' own distance %.4f), exact %.4f\n",
        label.c_str(), kPixels, mean, standardError, frames, limits[m], expected.byShare, expected.byContribution,
        expected.weighted, expected.blended, expected.exact);
    EXPECT_GT(limits[m], 0.1);  // partly hidden: the test can tell a dark bias from the right answer
    EXPECT_LT(limits[m], 0.9);
    // Resampled targets are consistent, not unbiased: within a per cent or two of the contribution-weighted
    // value for m = 16.
    tolerances[m] = 4.0 * standardError + (mode.target == Target::byContribution ? 0.02 : 2e-3);
    means[m] = mean;
    EXPECT_NEAR(mean, limits[m], tolerances[m]);
    if (weighed) {  // the blending's approximation is all that is left, and blended by own distance, nothing
      const double pixelError = std::sqrt(std::accumulate(samples[0].begin(), samples[0].end(), 0.0,
                                                          [&](double sum, const glm::dvec2& v) {
                                                            const double r = v.x - pixelMean[0] * v.y;
                                                            return sum + r * r;
                                                          })) /
                                weightSum[0];
      EXPECT_NEAR(pixelMean[0], expected.exact, 4.0 * pixelError + (mode.target == Target::blended ? 2e-3 : 0.02));
      // The irradiance correction: D C estimates what the input lights add, where the LGH's irradiance
      // C is off (a test that the pixel can tell them apart, then that D C converges to the sum).
      const double lghIrradiance = luminance(glm::dvec3(glm::vec3(irradiance.pixels[pixel])));
      double meanWeight = 0, squares = 0;
      for (const glm::dvec2& v : samples[0]) meanWeight += v.y / frames, squares += v.y * v.y / frames;
      const double weightError = std::sqrt(std::max(squares - meanWeight * meanWeight, 0.0) / (frames - 1));
      std::printf(
          "  %s: LGH irradiance %.4f, x mean weight %.4f +- %.4f; what the input lights add %.4f "
          "(through the blending), %.4f (blended by their own distance; %.4f with the unselectable grid lights), "
          "%.4f (exact)\n",
          label.c_str(), lghIrradiance, lghIrradiance * meanWeight, lghIrradiance * weightError, expected.weightedTotal,
          expected.blendedTotal, expected.reachableBlendedTotal, expected.exactTotal);
      const bool blended = mode.target == Target::blended;
      // The light pass counts the unselectable grid lights (shadow-count-unselectable), so T estimates what
      // the lights of every grid light whose volume covers x add.
      const double total = blended ? expected.reachableBlendedTotal : expected.reachableWeightedTotal;
      const double tolerance = lghIrradiance * 4.0 * weightError + 2e-3 * total;
      if (!blended) {  // blended, the weights are heavier (B_l at a fringe light over B_l at its centre)
        EXPECT_GT(std::abs(lghIrradiance - total), tolerance);
      }
      EXPECT_NEAR(lghIrradiance * meanWeight, total, tolerance);
      // Blended by their own distance, the input lights add what they add exactly, but for the grid
      // lights that hold a light near x and whose volume does not reach it.
      EXPECT_LT(std::abs(expected.reachableBlendedTotal - expected.exactTotal),
                0.2 * std::abs(expected.weightedTotal - expected.exactTotal));
    }
  }
  // Each mode's estimate is told from the limits of the modes that select or weigh otherwise.
  for (size_t a = 0; a < modes.size(); ++a)
    for (size_t b = 0; b < modes.size(); ++b) {
      if (group(modes[a]) == group(modes[b])) continue;
      EXPECT_GT(std::abs(limits[b] - means[a]), tolerances[a])
          << "mode " << a << " (estimate " << means[a] << " +- " << tolerances[a] << ") cannot be told from mode " << b
          << "'s limit " << limits[b];
    }
}

// A floor at y = 0 seen from above, and point lights (S0) that straddle it: dim ones just above, bright
// ones below. Their clusters' centres lie below the floor, so grid lights whose lights above it light the
// floor cannot be selected there (their centre's cosine is 0).
std::filesystem::path writeStraddlingScene(const TempDir& dir) {
  GltfWriter w;
  const int grey = w.addMaterial(MaterialDesc{}.withBaseColor({0.5f, 0.5f, 0.5f, 1}));
  w.addNode(NodeDesc{}.withMesh(w.addMesh({quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, grey)})));
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < 40; ++i) {
    const bool above = i % 2 == 0;
    const glm::vec3 p(1.6f * (u(rng) - 0.5f), above ? 0.05f + 0.3f * u(rng) : -0.35f - 0.35f * u(rng),
                      1.6f * (u(rng) - 0.5f));
    w.addNode(NodeDesc{}.withLight(w.addLight(LightDesc{}.withIntensity(above ? 1.0 : 3.0))).translated(p));
  }
  w.addNode(NodeDesc{}
                .withCamera(w.addCamera(CameraDesc{}.named("top").withYfov(1.0).withClip(0.1, 100)))
                .translated({0, 4, 0})
                .rotated(glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0))));
  return w.write(dir / "straddling.gltf");
}

// The samples' estimate of the unshadowed sum, T = F' mean(w) + U (shadow_rays.comp), averaged over frames
// and summed over the floor pixels where a good part of the light comes from grid lights the selection
// cannot reach: with the light pass counting those (U), the CPU's sum over every grid light whose volume
// covers each pixel; without, only the selectable ones' sum. Summed over pixels (independent samples) the
// test's own error is a few per cent, so U counted at half its value fails too.
TEST_F(ShadowTargetsTest, UnselectableGridLightsCompleteTheUnshadowedSum) {
  TempDir dir;
  const Scene scene = loadScene(writeStraddlingScene(dir));
  const SceneGpu gpuScene(scene);
  RenderSettings settings = pointLightSettings();
  for (const bool counted : {true, false}) {
    SCOPED_TRACE(counted ? "counted" : "not counted");
    settings.shadows.countUnselectable = counted;
    Renderer renderer(gpuScene, settings);
    const CameraView view = makeCameraView(resolveCamera(scene, settings), 24, 24);
    renderer.render(view);
    const std::vector<Light> lights =
        fromGpuLights(renderer.inputLights().lights.download<gpu::GpuLight>(renderer.inputLights().count));
    // The floor pixels with at least a tenth of the brightest one's light of which the selectable grid
    // lights' lights add at most nine tenths (52 of them; T's sum over them has a 0.4% standard error).
    const ImageRGBA position = renderer.readImage(Aov::Position);
    const HierarchyShares shares(renderer.hierarchy(), lights);
    std::vector<ExpectedRatios> perPixel(position.pixels.size());
    double brightest = 0;
    for (size_t i = 0; i < position.pixels.size(); ++i) {
      if (!(position.pixels[i].w > 0)) continue;
      perPixel[i] = expectedRatios(shares, glm::dvec3(glm::vec3(position.pixels[i])), glm::dvec3(0, 1, 0), 1e9,
                                   settings, renderer.clampDistance());
      brightest = std::max(brightest, perPixel[i].reachableBlendedTotal);
    }
    std::vector<size_t> pixels;
    double selectable = 0, reachable = 0;
    for (size_t i = 0; i < position.pixels.size(); ++i) {
      const ExpectedRatios& e = perPixel[i];
      if (!(e.reachableBlendedTotal > 0.1 * brightest) || !(e.blendedTotal < 0.9 * e.reachableBlendedTotal)) continue;
      pixels.push_back(i);
      selectable += e.blendedTotal, reachable += e.reachableBlendedTotal;
    }
    // The scene does what it is for: many pixels get much of their light through unselectable grid lights.
    ASSERT_GE(pixels.size(), 20u);
    const int frames = 200;
    std::vector<double> sum(pixels.size()), squares(pixels.size());
    for (int f = 0; f < frames; ++f) {
      if (f > 0) renderer.render(view);
      const ImageRGBA raw = fromGLRows(24, 24, renderer.texture(Aov::Ratio).readRGBA());
      for (size_t j = 0; j < pixels.size(); ++j) {
        const double t = raw.pixels[pixels[j]].z;  // b: T
        sum[j] += t, squares[j] += t * t;
      }
    }
    // Sum over the pixels of T's mean over the frames, and its standard error (pixels and frames independent).
    double total = 0, variance = 0;
    for (size_t j = 0; j < pixels.size(); ++j) {
      const double mean = sum[j] / frames;
      total += mean;
      variance += std::max(squares[j] / frames - mean * mean, 0.0) / (frames - 1);
    }
    const double standardError = std::sqrt(variance);
    std::printf(
        "  %s: T summed over %zu pixels %.3f +- %.3f over %d frames; the selectable grid lights' lights add %.3f, "
        "every covering grid light's %.3f (U half counted: %.3f)\n",
        counted ? "counted" : "not counted", pixels.size(), total, standardError, frames, selectable, reachable,
        0.5 * (selectable + reachable));
    // 4 standard errors, and 1% for the lights the light pass skips as unable to light x (those within two
    // standard deviations of their centre all in the hole, behind the plane or facing away) while a few
    // farther out could.
    const double tolerance = 4.0 * standardError + 0.01 * reachable;
    EXPECT_LT(tolerance, 0.05 * reachable) << "the test's own error is too large to tell U from U / 2";
    EXPECT_NEAR(total, counted ? reachable : selectable, tolerance);
    // The other hypotheses lie outside the tolerance: not counted, and counted at half its value.
    EXPECT_GT(std::abs(reachable - selectable), tolerance);
    EXPECT_GT(0.5 * std::abs(reachable - selectable), tolerance);
  }
}

}  // namespace
}  // namespace lgh::test
