#include "render/passes/volume_culling.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"
#include "shared/light_levels.h"

namespace lgh {
namespace {

// Relative widening of every culling bound (light_volume.vert's kCullingMargin).
constexpr float kCullingMargin = 1e-3f;

bool hasExtension(const char* name) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
    if (std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i))), name) == 0) return true;
  return false;
}

gl::VertexArrayHandle newVertexArray() {
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  return gl::VertexArrayHandle(vao);
}

}  // namespace

static_assert(kCullingSlices >= 1 && kCullingSlices <= gpu::kMaxCullingSlices, "slices must fit the 8-bit stencil");

VolumeCulling::VolumeCulling()
    : stencilExport_(hasExtension("GL_ARB_shader_stencil_export")),
      emptyVertexArray_(newVertexArray()),
      sortedVertexArray_(newVertexArray()) {
  // Attribute 0: one light index per instance, honouring each indirect draw's base instance.
  glVertexArrayAttribIFormat(sortedVertexArray_.id(), 0, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(sortedVertexArray_.id(), 0, 0);
  glVertexArrayBindingDivisor(sortedVertexArray_.id(), 0, 1);
  glEnableVertexArrayAttrib(sortedVertexArray_.id(), 0);
}

void VolumeCulling::release() {
  depthStencil_ = {};
  pyramid_ = {};
  for (gl::Buffer* b : {&sliceCounts_, &sliceAndRank_, &commands_, &sortedLights_}) *b = {};
}

const gl::Texture2D& VolumeCulling::depthStencil(glm::ivec2 size) {
  if (depthStencil_.width() != size.x || depthStencil_.height() != size.y) {
    depthStencil_ = gl::Texture2D({passes::kLightPass, "culling: depth and stencil", "width x height"}, size.x, size.y,
                                  GL_DEPTH32F_STENCIL8);
    const int levels = 1 + int(std::floor(std::log2(double(std::max(size.x, size.y)))));
    pyramid_ = gl::Texture2D({passes::kLightPass, "culling: depth pyramid", "width x height"}, size.x, size.y, GL_R32F,
                             levels);
    pyramid_.setFilter(GL_NEAREST_MIPMAP_NEAREST, GL_NEAREST);  // mipmapped: texelFetch may read every level
  }
  return depthStencil_;
}

void VolumeCulling::prepare(const gl::Texture2D& position, float sceneSize) {
  glBindVertexArray(emptyVertexArray_.id());
  writeDepthAndSlices(position, sceneSize);
  buildPyramid(position, sceneSize);
  glBindVertexArray(0);
}

// A full-screen triangle writes each surface's depth and, with stencil export, its slice; without,
// one instanced draw of full-screen triangles at the slice boundaries counts in the stencil the
// boundaries at or before each surface (slices - 1 fill passes: cheap on a GPU, not on llvmpipe).
// Depth is volumeDepth, reversed (far = 0), with GL_ZERO_TO_ONE. Colour untouched.
void VolumeCulling::writeDepthAndSlices(const gl::Texture2D& position, float sceneSize) {
  if (!depthProgram_) {
    gl::Defines defines;
    if (stencilExport_) defines.emplace_back("LGH_STENCIL_EXPORT", "1");
    depthProgram_ = gl::Program::graphics("display.vert", "light_depth.frag", defines);
  }
  const float clearDepth = 0.0f;
  GLint framebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  glClearNamedFramebufferfi(GLuint(framebuffer), GL_DEPTH_STENCIL, 0, clearDepth, 0);
  glColorMaski(0, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);
  glDepthMask(GL_TRUE);
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_ALWAYS, 0, 0xff);
  glStencilMask(0xff);
  glStencilOp(GL_KEEP, GL_KEEP, stencilExport_ ? GL_REPLACE : GL_KEEP);
  depthProgram_.use();
  depthProgram_.set("depthScale", sceneSize);
  depthProgram_.set("slices", kCullingSlices);
  position.bindTexture(LGH_TEXTURE_SURFACE_POSITION);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_FALSE);

  if (!stencilExport_) {
    if (!boundaryProgram_) boundaryProgram_ = gl::Program::graphics("slice_boundaries.vert", "no_color.frag");
    glDepthFunc(GL_GEQUAL);  // boundary at or before the surface (reversed depth): one more boundary
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
    boundaryProgram_.use();
    boundaryProgram_.set("slices", kCullingSlices);
    boundaryProgram_.set("depthScale", sceneSize);
    glDrawArraysInstanced(GL_TRIANGLES, 0, 3, GLsizei(kCullingSlices - 1));
  }
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_DEPTH_TEST);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);  // other passes use GL's default
  glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

// Level 0 from the positions, then each level from the one below (an image barrier between).
void VolumeCulling::buildPyramid(const gl::Texture2D& position, float sceneSize) {
  if (!pyramidProgram_) pyramidProgram_ = gl::Program::compute("light_depth_pyramid.comp");
  pyramidProgram_.use();
  pyramidProgram_.set("depthScale", sceneSize);
  position.bindTexture(LGH_TEXTURE_SURFACE_POSITION);
  GLint levels = 1;
  glGetTextureParameteriv(pyramid_.id(), GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
  for (int level = 0; level < levels; ++level) {
    pyramidProgram_.set("level", level);
    glBindImageTexture(LGH_IMAGE_PYRAMID_FINER, pyramid_.id(), std::max(level - 1, 0), GL_FALSE, 0, GL_READ_ONLY,
                       GL_R32F);
    glBindImageTexture(LGH_IMAGE_PYRAMID_COARSER, pyramid_.id(), level, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    pyramidProgram_.dispatch2D(std::max(pyramid_.width() >> level, 1), std::max(pyramid_.height() >> level, 1), {8, 8});
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
}

// Stable counting sort (light_slices.comp): slices and ranks in light order, offsets and draw
// commands, scatter.
void VolumeCulling::sortBySlice(const SortInputs& in) {
  if (!sortProgram_) sortProgram_ = gl::Program::compute("light_slices.comp");
  gl::fitSize(sliceAndRank_, {passes::kLightPass, "culling: slice and rank", "the grid lights"},
              std::max<size_t>(in.count, 1) * sizeof(GLuint));
  gl::fitSize(sortedLights_, {passes::kLightPass, "culling: sorted lights", "the grid lights"},
              std::max<size_t>(in.count, 1) * sizeof(GLuint));
  // One bucket per slice and one more for the spheres that reach the eye plane (light_slices.comp).
  gl::ensureSize(sliceCounts_, {passes::kLightPass, "culling: slice counts"}, (kCullingSlices + 1) * sizeof(GLuint));
  gl::ensureSize(commands_, {passes::kLightPass, "culling: draw commands"}, (kCullingSlices + 1) * 4 * sizeof(GLuint));
  glVertexArrayVertexBuffer(sortedVertexArray_.id(), 0, sortedLights_.id(), 0, sizeof(GLuint));
  sliceCounts_.clear();
  in.gridLights->bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  sliceCounts_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS1);
  sliceAndRank_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS2);
  commands_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS3);
  sortedLights_.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS4);
  const gl::Program& p = sortProgram_;
  p.use();
  p.set("first", unsigned(in.first));
  p.set("count", unsigned(in.count));
  p.set("slices", kCullingSlices);
  p.set("verticesPerVolume", 8u);  // light_volume.vert's octagon strip
  p.set("alpha", in.alpha);
  p.set("topCellSize", in.topCellSize);
  p.set("depthScale", in.sceneSize);
  p.set("margin", kCullingMargin);
  p.set("levels", unsigned(in.levels));
  const GLbitfield barriers =
      GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT;
  // Step 0 in one work group, in order, a range per dispatch: each invocation loops about 2 x 64 times
  // per 64 lights, so 16K lights keep it under llvmpipe's 65,535 iterations.
  constexpr size_t kRankRange = 16384;
  p.set("step", 0);
  for (size_t start = 0; start < in.count; start += kRankRange) {
    p.set("rangeStart", unsigned(start));
    p.set("rangeCount", unsigned(std::min(kRankRange, in.count - start)));
    p.dispatch1D(64, 64);
    glMemoryBarrier(barriers);
  }
  for (int step : {1, 2}) {
    p.set("step", step);
    p.dispatch1D(step == 1 ? 1 : std::max<size_t>(in.count, 1), 64);
    glMemoryBarrier(barriers);
  }
}

void VolumeCulling::bindPyramid() const { pyramid_.bindTexture(LGH_TEXTURE_SURFACE_DEPTH_PYRAMID); }

void VolumeCulling::drawSorted() const {
  glBindVertexArray(sortedVertexArray_.id());
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, commands_.id());
  // First the spheres that reach the eye plane (their near side is in slice 0: no stencil test), as
  // icosahedra whose back faces are kept; then the octagons slice by slice.
  glEnable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glCullFace(GL_FRONT);
  glDrawArraysIndirect(GL_TRIANGLES, reinterpret_cast<const void*>(uintptr_t(kCullingSlices) * 4 * sizeof(GLuint)));
  glDisable(GL_CULL_FACE);
  glEnable(GL_STENCIL_TEST);
  glStencilMask(0);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  for (unsigned k = 0; k < kCullingSlices; ++k) {
    glStencilFunc(GL_LEQUAL, GLint(k), 0xff);  // passes where the surface's slice is k or farther
    glDrawArraysIndirect(GL_TRIANGLE_STRIP, reinterpret_cast<const void*>(uintptr_t(k) * 4 * sizeof(GLuint)));
  }
  glStencilMask(0xff);
  glDisable(GL_STENCIL_TEST);
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

}  // namespace lgh
