#pragma once
// Temporal accumulation of the indirect light (glsl/accumulate.comp), between the shadow rays and
// the shadow filter:
//   in:  AccumulationInputs: GBuffer (this frame's surfaces), this frame's camera, this frame's raw
//        irradiance (the light pass's target: full resolution, or the n x n tiles' n^2-scaled values)
//   in/out: AccumulationTargets: irradiance (resolved in, accumulated out), ratio (raw in, accumulated
//        out, alpha: the pixel's history length N, which the shadow filter reads), sampled irradiance
//        (this frame's in, the mean of the unresolved irradiances the frames' ratio weights T were drawn
//        against out)
//   history (kept here, ping-pong): sums of the raw irradiance, of the ratio's weighted values, weights
//        and variances, the frame whose weight strays the most (it bounds their variance), and the
//        surfaces they belong to
// The history is reprojected through the G-buffer each frame and dropped where the surface differs; in a
// frame in which the lights or the geometry moved it is also tested per pixel (AccumulationSettings::motion);
// restart() drops all of it (the estimate's settings changed, or motion restarts it).

#include "render/camera_view.h"
#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/gl/uniform_blocks.h"
#include "render/passes/gbuffer_pass.h"
#include "render/passes/interleave_pass.h"
#include "render/settings.h"

namespace lgh {

// The history is kept where the reprojected surface lies within this many pixel footprints of the
// previous frame's tangent plane and its normal within acos(kHistoryNormalTolerance).
inline constexpr float kHistoryPlaneTolerance = 2.0f;
inline constexpr float kHistoryNormalTolerance = 0.9f;

struct AccumulationInputs {
  const GBuffer& gbuffer;
  const CameraView& view;                         // this frame's camera (the next frame reprojects through it)
  const gl::Texture2D& rawIrradiance;             // in `layout`
  TileLayout layout;                              // tiled when layout.tilesPerAxis > 1
  int shadowSamples = 0;                          // k: the ratio target holds this frame's raw ratio (0: not read)
  InterleaveFilter resolve = kInterleaveResolve;  // the weights of the resolve of incomplete sums
  bool moved = false;            // the lights or the geometry moved since the last frame (AccumulationSettings::motion)
  bool wholeIrradiance = false;  // rawIrradiance is its lights' exact sum (AccumulationSource::wholeIrradiance)
};

// Read and written in place.
struct AccumulationTargets {
  gl::Texture2D& irradiance;
  gl::Texture2D& ratio;
  gl::Texture2D& sampledIrradiance;  // R32F (written only when shadowed)
};

class AccumulationPass {
 public:
  AccumulationPass();
  // The next execute() starts every pixel's history anew.
  void restart() { hasHistory_ = false; }
  // Frees the history (accumulation off); the next execute() starts without one.
  void release();
  void execute(const AccumulationInputs& in, const AccumulationSettings& settings, const AccumulationTargets& io);

 private:
  struct History {
    gl::Texture2D irradianceSum, ratioSum, heaviest, position, normal;
  };
  gl::Program program_;
  gl::UniformBlocks uniforms_;  // one gpu::AccumulationUniforms per dispatch
  History history_[2];
  gl::Texture2D rawRatios_;  // under motion: this frame's raw ratio, for the neighbourhoods of the history test
  int current_ = 0;          // history_[current_] holds the last frame's history
  bool hasHistory_ = false;
  CameraView previousView_;
};

}  // namespace lgh
