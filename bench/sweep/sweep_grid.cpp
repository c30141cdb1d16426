#include "bench/sweep/sweep_grid.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <tuple>

namespace lgh::bench {
namespace {

void appendUnique(std::vector<PointSpec>& to, const std::vector<PointSpec>& from) {
  for (const PointSpec& p : from)
    if (std::find(to.begin(), to.end(), p) == to.end()) to.push_back(p);
}

}  // namespace

bool PointSpec::operator<(const PointSpec& o) const {
  return std::tie(lightcuts, block, startLevel, alpha, interleave, k, filter, frames) <
         std::tie(o.lightcuts, o.block, o.startLevel, o.alpha, o.interleave, o.k, o.filter, o.frames);
}

RenderSettings PointSpec::applied(const RenderSettings& base) const {
  RenderSettings s = base;
  if (lightcuts) {
    s.indirectMethod = IndirectMethod::Rtslc;
    s.rtslc.samples = k;
    s.rtslc.blockSize = block;
    s.rtslc.interleave = interleave;
  } else {
    s.lightPass.alpha = alpha;
    s.lightPass.startLevel = startLevel;
    s.lightPass.interleave = interleave;
    s.shadows.samples = k;
  }
  s.filter.passes = filter ? base.filter.passes : 0;
  // More than one frame is an accumulation, whatever the base says.
  if (frames > 1) s.accumulation.enabled = true;
  return s;
}

std::vector<PointSpec> grid(const std::vector<float>& alphas, const std::vector<int>& starts,
                            const std::vector<int>& ns, const std::vector<int>& ks, const std::vector<bool>& filters,
                            const std::vector<int>& frames) {
  std::vector<PointSpec> points;
  for (int s : starts)
    for (float a : alphas)
      for (int n : ns)
        for (int k : ks)
          for (bool f : filters)
            for (int count : frames) points.push_back({a, s, n, k, f, count});
  return points;
}

std::vector<PointSpec> readmePoints() {
  std::vector<PointSpec> points = grid({0.5f, 1.0f, 2.0f, 4.0f}, {0, 1}, {1, 4}, {0, 4}, {true});
  appendUnique(points, grid({1.0f}, {1}, {1}, {1, 2, 8}, {true}));  // k
  appendUnique(points, grid({1.0f}, {1}, {1}, {4}, {false}));       // the raw ratio
  appendUnique(points, grid({2.0f}, {0}, {1}, {4}, {false}));
  appendUnique(points, grid({1.0f}, {1}, {2}, {4}, {true}));  // 2x2 interleaving
  appendUnique(points, grid({2.0f}, {0}, {2}, {4}, {true}));
  return points;
}

std::vector<PointSpec> lightcutPoints(const std::vector<int>& samples, const std::vector<int>& blocks,
                                      const std::vector<int>& interleaves, const std::vector<bool>& filters,
                                      const std::vector<int>& frames) {
  std::vector<PointSpec> points;
  for (int b : blocks)
    for (int m : interleaves)
      for (int n : samples)
        for (bool f : filters)
          for (int count : frames) {
            // The cut holds n m^2 nodes, at most gpu::kMaxCutNodes, and an m x m group lies in one block.
            if (n * m * m > int(gpu::kMaxCutNodes) || b % m != 0) continue;
            PointSpec p;
            p.lightcuts = true;
            p.block = b;
            p.interleave = m;
            p.k = n;
            p.filter = f;
            p.frames = count;
            points.push_back(p);
          }
  return points;
}

std::string settingsLabel(const PointSpec& p) {
  char buffer[96];
  if (p.lightcuts) {
    std::snprintf(buffer, sizeof buffer, "n=%d B%d %dx%d%s", p.k, p.block, p.interleave, p.interleave,
                  p.filter ? "" : " raw");
    return p.frames > 1 ? std::string(buffer) + " " + std::to_string(p.frames) + " frames" : std::string(buffer);
  }
  std::snprintf(buffer, sizeof buffer, "a=%g S%d %dx%d k=%d%s", double(p.alpha), p.startLevel, p.interleave,
                p.interleave, p.k, p.filter || p.k == 0 ? "" : " raw");
  return p.frames > 1 ? std::string(buffer) + " " + std::to_string(p.frames) + " frames" : std::string(buffer);
}

std::string fileLabel(const PointSpec& p) {
  char buffer[96];
  if (p.lightcuts) {
    std::snprintf(buffer, sizeof buffer, "rtslc_n%d_b%d_m%d_%s", p.k, p.block, p.interleave,
                  p.filter ? "filter" : "raw");
    return p.frames > 1 ? std::string(buffer) + "_f" + std::to_string(p.frames) : std::string(buffer);
  }
  std::snprintf(buffer, sizeof buffer, "a%g_s%d_n%d_k%d_%s", double(p.alpha), p.startLevel, p.interleave, p.k,
                p.filter ? "filter" : "raw");
  return p.frames > 1 ? std::string(buffer) + "_f" + std::to_string(p.frames) : std::string(buffer);
}

SceneSpec parseSceneSpec(const std::string& text) {
  namespace fs = std::filesystem;
  SceneSpec spec;
  const size_t at = text.rfind('@');
  if (at != std::string::npos && !fs::exists(text)) {
    spec.path = text.substr(0, at);
    spec.camera = text.substr(at + 1);
  } else {
    spec.path = text;
  }
  if (!fs::is_regular_file(spec.path)) throw std::runtime_error(spec.path.string() + ": no such scene file");
  spec.path = fs::absolute(spec.path).lexically_normal();
  spec.name = spec.path.stem().string();
  return spec;
}

}  // namespace lgh::bench
