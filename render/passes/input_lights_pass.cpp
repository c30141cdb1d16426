#include "render/passes/input_lights_pass.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/lgh_types.h"

namespace lgh {

InputLightsPass::InputLightsPass(const SceneGpu& scene) : scene_(scene), vplPass_(scene) {}

void InputLightsPass::execute(const InputLightSettings& s, bool pointLightsToS0, InputLights& out) {
  // glTF point lights as omni S0 lights: intensity in W/sr, the same I cos / d^2 the direct pass uses
  // (without glTF's range window, which the LGH cannot express per light).
  std::vector<gpu::GpuLight> points;
  if (pointLightsToS0)
    for (const gpu::GpuPunctualLight& l : scene_.punctualLights())
      if (l.type == gpu::kLightPoint) points.push_back(gpu::GpuLight{l.position, 0u, l.intensity, 0u});

  const size_t emitterSamples = vplPass_.emissiveTriangles().empty() ? 0 : size_t(s.emitterSamples);
  const size_t vplBudget = size_t(s.vpls);
  const std::uint32_t seed = std::uint32_t(s.seed);
  const size_t vplCapacity = vplBudget > 0 ? VplPass::maxVplCount(vplBudget, s.bounces) : 0;
  const size_t capacity = points.size() + emitterSamples + vplCapacity;
  gl::fitSize(out.lights, {passes::kInputLights, "S0", "vpls and the scene's lights"},
              std::max<size_t>(capacity, 1) * sizeof(gpu::GpuLight));

  if (!points.empty()) out.lights.update(points);
  out.pointLights = points.size();
  out.emitterSamples = vplPass_.sampleEmissiveTriangles(out.lights, out.pointLights, emitterSamples, seed);
  const size_t vplOffset = out.pointLights + out.emitterSamples;
  // A different seed stream from the emitter samples', so the two sets are independent.
  out.vpls = vplBudget > 0 ? vplPass_.tracePaths(out.lights, vplOffset, vplBudget, s.bounces, seed ^ 0x9e3779b9u) : 0;
  // VPLs are appended where the GPU's atomic counter put them: compact, from vplOffset on.
  out.count = vplOffset + out.vpls;
  // Paths that leave the scene deposit nothing (half of them in Sponza): S0 keeps the lights made, not
  // the budget's room.
  if (out.count < capacity) {
    gl::Buffer made(out.lights.label(), std::max<size_t>(out.count, 1) * sizeof(gpu::GpuLight));
    glCopyNamedBufferSubData(out.lights.id(), made.id(), 0, 0, GLsizeiptr(out.count * sizeof(gpu::GpuLight)));
    out.lights = std::move(made);
  }
  gl::checkErrors("input lights");
}

}  // namespace lgh
