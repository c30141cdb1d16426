#include "render/passes/rtslc_pass.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"

namespace lgh {

RtslcPass::RtslcPass() : program_("rtslc.comp"), uniforms_(passes::kLightcutSampling, sizeof(gpu::RtslcUniforms)) {}

void RtslcPass::bind(const RtslcInputs& in, const RtslcOptions& options, size_t dispatch, bool ratioOutputs) {
  const RtslcSettings& s = options.settings;
  if (s.samples < 1 || s.samples > int(gpu::kMaxCutNodes))
    throw std::invalid_argument("lightcuts: " + std::to_string(s.samples) + " samples (use 1.." +
                                std::to_string(gpu::kMaxCutNodes) + ")");
  if (s.blockSize < 1)
    throw std::invalid_argument("lightcuts: block size " + std::to_string(s.blockSize) + " (use 1 or more)");
  if (s.interleave != 1 && s.interleave != 2 && s.interleave != 4)
    throw std::invalid_argument("lightcuts: interleave " + std::to_string(s.interleave) + " (use 1, 2 or 4)");
  const int cutSize = s.samples * s.interleave * s.interleave;
  if (cutSize > int(gpu::kMaxCutNodes))
    throw std::invalid_argument("lightcuts: " + std::to_string(s.samples) + " samples per pixel at " +
                                std::to_string(s.interleave) + "x" + std::to_string(s.interleave) +
                                " interleaving need a cut of " + std::to_string(cutSize) + " nodes; at most " +
                                std::to_string(gpu::kMaxCutNodes));
  // An m x m group splits one cut: it must lie in one block.
  if (s.blockSize % s.interleave != 0)
    throw std::invalid_argument("lightcuts: block size " + std::to_string(s.blockSize) + " is not a multiple of the " +
                                std::to_string(s.interleave) + "x" + std::to_string(s.interleave) + " interleaving");
  const unsigned blocksPerRow = unsigned((in.gbuffer.width + s.blockSize - 1) / s.blockSize);
  const unsigned blockRows = unsigned((in.gbuffer.height + s.blockSize - 1) / s.blockSize);
  gl::fitSize(cuts_, {passes::kLightcutCuts, "cuts", "width x height / rtslc-block^2"},
              size_t(blocksPerRow) * blockRows * gpu::kMaxCutNodes * sizeof(GLuint));
  gpu::RtslcUniforms u{};
  u.stage = dispatch == 0 ? gpu::kRtslcCuts : gpu::kRtslcSampling;
  u.leafCount = in.tree.leafCount;
  u.cutSize = unsigned(cutSize);
  u.blockSize = unsigned(s.blockSize);
  u.blocksPerRow = blocksPerRow;
  u.interleave = unsigned(s.interleave);
  u.frameSeed = options.frameSeed;
  u.ratioOutputs = ratioOutputs ? 1u : 0u;
  u.errorLimit = s.errorLimit;
  u.clampDistance = options.clampDistance;
  uniforms_.upload(std::vector<gpu::RtslcUniforms>{u});
  uniforms_.bind(0, LGH_UBO_PASS);
  in.scene.bindForCompute();
  in.gbuffer.bindForReading();
  in.inputLights.bindRange(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0, 0, in.inputLightCount * sizeof(gpu::GpuLight));
  in.tree.nodes.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  in.tree.bounds.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  cuts_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS3);
}

void RtslcPass::release() {
  cuts_ = {};
  uniforms_.release();
}

void RtslcPass::selectCuts(const RtslcInputs& in, const RtslcOptions& options) {
  if (in.tree.leafCount == 0) return;  // no lights: no tree, no cuts
  bind(in, options, 0, false);
  const int block = options.settings.blockSize;
  program_(in.scene).dispatch2D((in.gbuffer.width + block - 1) / block, (in.gbuffer.height + block - 1) / block,
                                {8, 8});
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  gl::checkErrors("lightcut cuts");
}

void RtslcPass::sample(const RtslcInputs& in, const RtslcOptions& options, const RtslcTargets& out) {
  if (in.tree.leafCount == 0) {  // no lights: no indirect light
    out.shadowed.clear(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    if (out.ratio) {
      out.unshadowed->clear(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
      out.ratio->clear(glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
      out.sampledLuminance->clear(glm::vec4(0.0f));
    }
    return;
  }
  bind(in, options, 1, out.ratio != nullptr);
  out.shadowed.bindImage(LGH_IMAGE_RTSLC_SHADOWED, GL_WRITE_ONLY);
  if (out.ratio) {
    out.unshadowed->bindImage(LGH_IMAGE_RTSLC_UNSHADOWED, GL_WRITE_ONLY);
    out.ratio->bindImage(LGH_IMAGE_RTSLC_RATIO, GL_WRITE_ONLY);
    out.sampledLuminance->bindImage(LGH_IMAGE_RTSLC_SAMPLED, GL_WRITE_ONLY);
  }
  program_(in.scene).dispatch2D(in.gbuffer.width, in.gbuffer.height, {8, 8});
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  gl::checkErrors("lightcut sampling");
}

}  // namespace lgh
