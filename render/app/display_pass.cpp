#include "render/app/display_pass.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"
#include "shared/display_encode.h"

namespace lgh {

DisplayImage::DisplayImage(int w, int h)
    : width(w), height(h), color({"display", "colour", kImageSize}, w, h, GL_RGBA8), framebuffer({&color}, nullptr) {}

std::vector<std::uint8_t> DisplayImage::readRGB() const {
  std::vector<std::uint8_t> rgb(size_t(width) * size_t(height) * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(color.id(), 0, GL_RGB, GL_UNSIGNED_BYTE, GLsizei(rgb.size()), rgb.data());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  // GL rows are bottom-up; image files are top-down.
  const size_t row = size_t(width) * 3;
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(rgb.begin() + ptrdiff_t(size_t(y) * row), rgb.begin() + ptrdiff_t(size_t(y + 1) * row),
                     rgb.begin() + ptrdiff_t(size_t(height - 1 - y) * row));
  gl::checkErrors("read display image");
  return rgb;
}

std::uint32_t displayEncodingOf(Aov aov) {
  if (aov == Aov::Overdraw) return gpu::kDisplayCounts;
  if (aov == Aov::History) return gpu::kDisplayHistory;
  if (aov == Aov::Ratio || aov == Aov::Visibility) return gpu::kDisplayRatio;
  return isDataAov(aov) ? gpu::kDisplayData : gpu::kDisplayRadiance;
}

DisplayPass::DisplayPass()
    : floatProgram_(gl::Program::graphics("display.vert", "display.frag")),
      countProgram_(gl::Program::graphics("display.vert", "display.frag", {{"LGH_DISPLAY_COUNTS", "1"}})) {
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  emptyVertexArray_ = gl::VertexArrayHandle(vao);
}

void DisplayPass::execute(const gl::Texture2D& image, const DisplayOptions& options, DisplayImage& out) {
  gl::DebugGroup group("display");
  if (image.width() != out.width || image.height() != out.height)
    throw std::invalid_argument("display pass: a " + std::to_string(image.width()) + " x " +
                                std::to_string(image.height()) + " image into a " + std::to_string(out.width) + " x " +
                                std::to_string(out.height) + " target");
  // Counts are integers (R32UI) and need their own sampler type, hence their own program.
  const bool counts = options.encoding == gpu::kDisplayCounts;
  const gl::Program& program = counts ? countProgram_ : floatProgram_;
  program.set("encoding", unsigned(options.encoding));
  program.set("exposureEV", options.exposureEV);
  program.set("toneCurve", unsigned(options.toneMap));
  program.set("largestCount", float(std::max(options.largestCount, 1u)));
  image.bindTexture(LGH_TEXTURE_DISPLAY_IMAGE);
  out.framebuffer.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_FRAMEBUFFER_SRGB);  // the shader encodes sRGB itself, as the image files do
  program.use();
  glBindVertexArray(emptyVertexArray_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::checkErrors("display pass");
}

}  // namespace lgh
