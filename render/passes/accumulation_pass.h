#pragma once
// Temporal accumulation of the indirect light (glsl/accumulate.comp), between the shadow rays and
// the shadow filter:
//   in:  GBuffer (this frame's surfaces), this frame's raw irradiance (the light pass's target:
//        full resolution, or the n x n tiles' n^2-scaled values), the camera of the previous frame
//   in/out: irradiance (resolved in, accumulated out), ratio (raw in, accumulated out, alpha: the
//        pixel's history length N, which the shadow filter reads)
//   history (kept here, ping-pong): sums of the raw irradiance and of the (shadowed, unshadowed)
//        luminance, and the surfaces they belong to
// The history is reprojected through the G-buffer each frame and dropped where the surface differs;
// restart() drops all of it (the lights or the estimate's settings changed).

#include "render/camera_view.h"
#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/passes/gbuffer_pass.h"
#include "render/passes/interleave_pass.h"
#include "render/settings.h"

namespace lgh {

// The history is kept where the reprojected surface lies within this many pixel footprints of the
// previous frame's tangent plane and its normal within acos(kHistoryNormalTolerance).
inline constexpr float kHistoryPlaneTolerance = 2.0f;
inline constexpr float kHistoryNormalTolerance = 0.9f;

class AccumulationPass {
 public:
  AccumulationPass();
  // The next execute() starts every pixel's history anew.
  void restart() { hasHistory_ = false; }
  // `rawIrradiance` is in `layout` (tiled when layout.tilesPerAxis > 1); `ratio` is read only when
  // `shadowed`.
  void execute(const GBuffer& gbuffer, const CameraView& view, const gl::Texture2D& rawIrradiance,
               const TileLayout& layout, bool shadowed, const AccumulationSettings& settings, gl::Texture2D& irradiance,
               gl::Texture2D& ratio);

 private:
  struct History {
    gl::Texture2D irradianceSum, ratioSum, position, normal;
  };
  gl::Program program_;
  History history_[2];
  int current_ = 0;  // history_[current_] holds the last frame's history
  bool hasHistory_ = false;
  CameraView previousView_;
};

}  // namespace lgh
