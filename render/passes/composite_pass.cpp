#include "render/passes/composite_pass.h"

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"

namespace lgh {

CompositePass::CompositePass()
    : program_(gl::Program::compute("composite.comp")),
      black_({passes::kComposite, "black"}, 1, 1, GL_RGBA32F),
      white_({passes::kComposite, "white"}, 1, 1, GL_RGBA32F),
      counter_({passes::kComposite, "non-finite counter"}, sizeof(GLuint)) {
  black_.clear(glm::vec4(0.0f));
  white_.clear(glm::vec4(1.0f));
}

unsigned CompositePass::execute(const CompositeInputs& in, const CompositeTargets& out) {
  in.gbuffer.bindForReading();
  in.direct.bindTexture(LGH_TEXTURE_COMPOSITE_DIRECT);
  (in.indirectIrradiance ? *in.indirectIrradiance : black_).bindTexture(LGH_TEXTURE_COMPOSITE_INDIRECT);
  (in.visibility ? *in.visibility : white_).bindTexture(LGH_TEXTURE_COMPOSITE_VISIBILITY);
  out.final.bindImage(LGH_IMAGE_COMPOSITE_FINAL, GL_WRITE_ONLY);
  out.indirect.bindImage(LGH_IMAGE_COMPOSITE_INDIRECT, GL_WRITE_ONLY);
  counter_.clear();
  counter_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  program_.dispatch2D(in.gbuffer.width, in.gbuffer.height, {8, 8});
  glMemoryBarrier(GL_ALL_BARRIER_BITS);
  gl::checkErrors("composite pass");
  return counter_.download<GLuint>(1)[0];
}

}  // namespace lgh
