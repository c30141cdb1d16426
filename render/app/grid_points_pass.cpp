#include "render/app/grid_points_pass.h"

#include <algorithm>
#include <cmath>

#include "render/gl/debug.h"
#include "shared/bindings.h"
#include "shared/lgh_types.h"

namespace lgh {

GridPointsPass::GridPointsPass() : program_(gl::Program::graphics("grid_points.vert", "grid_points.frag")) {
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  emptyVertexArray_ = gl::VertexArrayHandle(vao);
}

size_t GridPointsPass::execute(const GridPointsInputs& in, int level, float pointSize, DisplayImage& out) {
  const GpuHierarchy& hierarchy = in.hierarchy;
  if (level < 1 || level > hierarchy.grid.levels || size_t(level) >= hierarchy.levels.size()) return 0;
  const LghLevelRange& range = hierarchy.levels[size_t(level)];
  if (range.count == 0) return 0;
  gl::DebugGroup group("grid points");
  hierarchy.gridLights.bindBase(GL_SHADER_STORAGE_BUFFER, LGH_BINDING_PASS0);
  in.position.bindTexture(LGH_TEXTURE_SURFACE_POSITION);
  program_.set("viewProjection", in.view.viewProjection());
  program_.set("cameraPosition", in.view.position);
  program_.set("firstLight", unsigned(range.offset));
  program_.set("pointSize", std::max(pointSize, 1.0f));
  out.framebuffer.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glEnable(GL_PROGRAM_POINT_SIZE);
  program_.use();
  glBindVertexArray(emptyVertexArray_.id());
  glDrawArrays(GL_POINTS, 0, GLsizei(range.count));
  glBindVertexArray(0);
  glDisable(GL_PROGRAM_POINT_SIZE);
  glDisable(GL_BLEND);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  gl::checkErrors("grid points pass");
  return range.count;
}

}  // namespace lgh
