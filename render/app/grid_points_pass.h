#pragma once
// Shows where the hierarchy put its lights: the grid lights of one level drawn as round points at
// their illumination centres over a displayed frame, faint where the visible surface hides them
// (compared with the G-buffer's position at the point's pixel).
//   in:  GridPointsInputs: GpuHierarchy (grid lights and the level table), G-buffer position, the
//        frame's camera; the level and the points' size
//   out: points blended into a DisplayImage

#include "render/app/display_pass.h"
#include "render/camera_view.h"
#include "render/gl/program.h"
#include "render/passes/lgh_build_pass.h"

namespace lgh {

struct GridPointsInputs {
  const GpuHierarchy& hierarchy;
  const CameraView& view;         // the frame's camera
  const gl::Texture2D& position;  // the frame's G-buffer position, the size of `out`
};

class GridPointsPass {
 public:
  GridPointsPass();
  // level in 1..hierarchy.grid.levels (other levels draw nothing). Returns the number of points drawn.
  size_t execute(const GridPointsInputs& in, int level, float pointSize, DisplayImage& out);

 private:
  gl::Program program_;
  gl::VertexArrayHandle emptyVertexArray_;  // points come from gl_VertexID
};

}  // namespace lgh
