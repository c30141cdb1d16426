#include "render/passes/light_tree_pass.h"

#include <optional>
#include <stdexcept>
#include <string>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"
#include "shared/lgh_types.h"

namespace lgh {
namespace {
constexpr unsigned kLocalSize = 256;  // lgh_bounds.comp and light_tree.comp
// light_tree.comp's stages.
constexpr unsigned kStageMorton = 0, kStageLeaves = 1, kStageLevel = 2;
// 2^21 leaves: 2^22 nodes of 32 bytes, one 128 MiB storage block (llvmpipe's limit, and common on GPUs).
constexpr int kMaxTreeLevels = 22;
}  // namespace

int lightTreeLevelsFor(size_t lightCount) {
  if (lightCount == 0) return 0;
  int levels = 1;
  while ((size_t(1) << (levels - 1)) < lightCount) ++levels;
  return levels;
}

std::vector<gpu::GpuLightTreeNode> GpuLightTree::download() const {
  return leafCount ? nodes.download<gpu::GpuLightTreeNode>(2 * size_t(leafCount))
                   : std::vector<gpu::GpuLightTreeNode>{};
}

LightTreePass::LightTreePass()
    : bounds_(gl::Program::compute("lgh_bounds.comp")), build_(gl::Program::compute("light_tree.comp")) {}

void LightTreePass::execute(const gl::Buffer& lights, size_t lightCount, GpuLightTree& out, gl::Profiler* profiler) {
  auto scope = [&](const char* name) {
    return profiler ? std::optional<gl::Profiler::Scope>(std::in_place, *profiler, name) : std::nullopt;
  };
  const int levels = lightTreeLevelsFor(lightCount);
  if (levels > kMaxTreeLevels)
    throw std::runtime_error("light tree: " + std::to_string(lightCount) + " input lights need " +
                             std::to_string(levels) + " levels; at most " + std::to_string(kMaxTreeLevels) + " (2^" +
                             std::to_string(kMaxTreeLevels - 1) + " leaves) fit one storage block");
  out.levels = levels;
  out.lightCount = lightCount;
  out.leafCount = levels ? 1u << (levels - 1) : 0u;
  if (lightCount == 0) return;
  const size_t nodeBytes = 2 * size_t(out.leafCount) * sizeof(gpu::GpuLightTreeNode);
  if (out.nodes.size() != nodeBytes)
    out.nodes = gl::Buffer({passes::kLightTreeBuild, "nodes", "the input lights"}, nodeBytes);
  if (!out.bounds) out.bounds = gl::Buffer({passes::kLightTreeBuild, "bounds"}, sizeof(gpu::LghBoundsResult));
  gl::ensureSize(keys_, {passes::kLightTreeBuild, "Morton codes", "the input lights"}, lightCount * sizeof(GLuint));
  gl::ensureSize(values_, {passes::kLightTreeBuild, "light indices", "the input lights"}, lightCount * sizeof(GLuint));

  lights.bindRange(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0, 0, lightCount * sizeof(gpu::GpuLight));
  keys_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  values_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  out.bounds.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS3);
  out.nodes.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS4);
  build_.set("lightCount", GLuint(lightCount));
  build_.set("leafCount", GLuint(out.leafCount));
  {
    auto s = scope("bounds");
    // Lower bounds start at the largest ordered bits, upper bounds and counts at 0 (lgh_bounds.comp).
    gpu::LghBoundsResult init{};
    for (int a = 0; a < 3; ++a) init.litLower[a] = init.allLower[a] = 0xffffffffu;
    out.bounds.update(&init, sizeof init);
    bounds_.set("lightCount", GLuint(lightCount));
    bounds_.dispatch1D(lightCount, kLocalSize);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  {
    auto s = scope("Morton codes");
    build_.set("stage", kStageMorton);
    build_.dispatch1D(lightCount, kLocalSize);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  {
    auto s = scope("sort");
    sort_.sort(keys_, values_, lightCount, 30);
  }
  // The sort bound its own buffers.
  lights.bindRange(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0, 0, lightCount * sizeof(gpu::GpuLight));
  keys_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  values_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  out.bounds.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS3);
  out.nodes.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS4);
  {
    auto s = scope("leaves");
    build_.set("stage", kStageLeaves);
    build_.dispatch1D(out.leafCount, kLocalSize);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  {
    auto s = scope("internal levels");
    build_.set("stage", kStageLevel);
    for (unsigned first = out.leafCount / 2; first >= 1; first /= 2) {
      build_.set("levelFirst", GLuint(first));
      build_.dispatch1D(first, kLocalSize);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  }
  // The codes and the sort's scratch are the build's alone: the frame holds the tree.
  keys_ = {};
  values_ = {};
  sort_.release();
  gl::checkErrors("light tree build");
}

}  // namespace lgh
