#pragma once
// The LGH light pass (Lin & Yuksel 2019, Sec. 3.2; docs/design.md §4): every grid light of every level drawn
// as a light volume around the support of its blending function (d < 2R_l), the top level as a
// full-screen triangle; each fragment adds B_l(d) x the light's irradiance at the pixel's surface into
// an RGBA32F target with additive blending. Volumes are either the paper's cubes of half-size 2R_l
// (no depth test: every pixel under the cube is shaded) or, with volume culling, the screen octagon
// of the 2R_l sphere depth-tested against the surfaces, so that a pixel whose surface lies behind the
// sphere is rejected before shading, and skipped whole when every surface under it lies in front of
// the sphere (a max-depth pyramid); a sphere that contains the camera (or reaches its eye plane) as
// the far faces of an icosahedron around it, each at its own depth. Only zero-weight fragments go: the image and the
// shadow selection are the same, only cheaper.
//   in:  surfaces (G-buffer position and normal, or their interleaved tiles), the input lights S0
//        and the hierarchy built over them, frame uniforms (LGH_UBO_FRAME); with shadow selection, this
//        frame's drawn shadow-ray targets (for the grid lights that cannot be selected at a pixel)
//   out: irradiance (rgb: W/m^2, albedo / pi gives radiance; a: fragments that shaded the pixel),
//        optionally the count of every fragment rasterized per pixel (overdraw), and the shadow slots
// Brute force draws every S0 light full-screen with weight 1: the unshadowed exact sum, rasterized.

#include <map>
#include <string>

#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/gl/uniform_blocks.h"
#include "render/passes/interleave_pass.h"
#include "render/passes/lgh_build_pass.h"
#include "render/passes/shadow_targets_pass.h"
#include "render/passes/volume_culling.h"
#include "render/settings.h"
#include "render/shadow_estimator.h"

namespace lgh {

// One light pass: the user's settings (render/settings.h) and what the frame resolves. The pass reads
// alpha, the start level, brute force and overdraw from `pass` (interleaving is the target's layout).
struct LightPassOptions {
  LightPassSettings pass;
  // Shadow-sample selection (docs/design.md §5): k slots per pixel, filled in proportion to each light's
  // contribution (or uniformly, for comparison); samples = 0: no selection. Resolved: read as it is.
  ShadowEstimator shadows;
  float clampDistance = 0.0f;  // d_c, resolved
  float sceneSize = 1.0f;      // spreads the culling depth over [0, 1) (shared/light_levels.h)
  unsigned frameSeed = 0;
  unsigned tileRotation = 0;  // n x n interleaving: lights are dealt to tile (index + rotation) mod n^2
};

// gpu::kSelect* of a resolved estimator: the selection the light pass makes, which the shadow rays recompute.
unsigned selectionFlags(const ShadowEstimator& shadows);

// What the light pass reads besides its surfaces (LightPassTarget).
struct LightPassInputs {
  const gl::Buffer& lights;  // S0 (gpu::GpuLight), `lightCount` valid
  size_t lightCount = 0;
  const GpuHierarchy& hierarchy;
  // This frame's shadow-ray targets, through which the pass counts the grid lights it cannot select
  // (options.shadows.countUnselectable; it throws if the input lights exceed inputLightsPerBlock()).
  const ShadowTargets* drawnTargets = nullptr;
};

// Per pixel of the light pass's target: the running importance total, k selected lights, and what the
// grid lights that cannot be selected there add.
struct ShadowSlots {
  gl::Buffer totals;        // float per pixel
  gl::Buffer slots;         // uint per pixel and slot: gpu::kSlotS0 | S0 index, grid-light index, or kNoLight
  gl::Buffer unselectable;  // float per pixel: luminance, on the totals' scale (ShadowEstimator::countUnselectable)
  int k = 0;
  glm::ivec2 size{0};  // the target's size (tiled when interleaving)
  void allocate(glm::ivec2 targetSize, int samples);
};

// The surfaces a light pass shades and the targets it writes, all in the same (tiled or not) layout.
// (Outputs structs hold references to what a pass writes: passed as const, written through.)
struct LightPassTarget {
  const gl::Texture2D& position;
  const gl::Texture2D& normal;
  TileLayout layout;              // n x n tiles; 1: the image itself
  gl::Texture2D& irradiance;      // RGBA32F
  gl::Texture2D* fragmentCounts;  // R32UI, required with countFragments
  ShadowSlots* shadowSlots;       // required with shadowSamples > 0
};

struct LightPassDraws {
  std::vector<size_t> lightsPerLevel;  // [0]: S0 lights drawn, [l]: grid lights of level l drawn
  size_t lightsDrawn() const;
};

class LightVolumePass {
 public:
  // floatAtomics: GL_NV_shader_atomic_float is available (the selection's running total uses it).
  explicit LightVolumePass(bool floatAtomics);
  // Input lights one storage block holds (ShadowEstimatorLimits: counting the unselectable grid lights
  // needs every input light in one block).
  size_t inputLightsPerBlock() const { return maxBlockLights_; }

  // Frees the GPU memory the pass holds between frames (it allocates again when next executed).
  void release();
  LightPassDraws execute(const LightPassInputs& in, const LightPassOptions& options, const LightPassTarget& target);

 private:
  struct Draw;
  static void checkTarget(const LightPassOptions& options, const LightPassTarget& target, int levels);
  // m when the pass counts the unselectable grid lights through the drawn targets, else 0.
  unsigned unselectableTargets(const LightPassOptions& options, size_t lightCount, int levels,
                               const ShadowTargets* drawnTargets) const;
  std::vector<Draw> drawList(const gl::Buffer& lights, size_t lightCount, const GpuHierarchy& hierarchy,
                             const LightPassOptions& options, int levels, LightPassDraws& counts) const;
  void uploadUniforms(const std::vector<Draw>& draws, const GpuHierarchy& hierarchy, const LightPassOptions& options,
                      const TileLayout& layout, int levels, unsigned drawnTargets);
  void bindTargets(const LightPassOptions& options, const LightPassTarget& target);
  void prepareCulling(const std::vector<Draw>& draws, const GpuHierarchy& hierarchy, const LightPassOptions& options,
                      const LightPassTarget& target, int levels);
  void bindInputs(const LightPassOptions& options, const LightPassTarget& target, const gl::Buffer& lights,
                  size_t lightCount, const ShadowTargets* drawnTargets);
  void issueDraws(const std::vector<Draw>& draws, const LightPassOptions& options, bool countUnselectable);
  const gl::Program& program(const Draw& draw, const LightPassOptions& options, bool countUnselectable);

  bool floatAtomics_;
  std::map<std::string, gl::Program> programs_;  // by their defines, compiled on first use
  gl::UniformBlocks uniforms_;                   // one gpu::LightPassUniforms per draw
  size_t maxBlockLights_ = 0;                    // S0 lights per storage block binding
  gl::VertexArrayHandle emptyVertexArray_;       // draws take their vertices from gl_VertexID
  VolumeCulling culling_;                        // depth, slices, pyramid and sorting for culled volumes
  gl::Framebuffer framebuffer_;                  // irradiance (+ culling depth-stencil), made by each execute
};

}  // namespace lgh
