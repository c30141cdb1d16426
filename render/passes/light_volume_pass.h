#pragma once
// The LGH light pass (Lin & Yuksel 2019, Sec. 3.2; DESIGN 4): every grid light of every level drawn
// as a light volume, a cube of half-size 2R_l around it (the support of its blending function), the
// top level as a full-screen triangle; each fragment adds B_l(d) x the light's irradiance at the
// pixel's surface into an RGBA32F target with additive blending.
//   in:  surfaces (G-buffer position and normal, or their interleaved tiles), the input lights S0
//        and the hierarchy built over them, frame uniforms (LGH_UBO_FRAME)
//   out: irradiance (rgb: W/m^2, albedo / pi gives radiance; a: fragments that shaded the pixel),
//        optionally the count of every fragment rasterized per pixel (overdraw)
// Brute force draws every S0 light full-screen with weight 1: the unshadowed exact sum, rasterized.

#include <array>

#include "render/gl/buffer.h"
#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/passes/interleave_pass.h"
#include "render/passes/lgh_build_pass.h"

namespace lgh {

struct LightPassOptions {
  float alpha = 1.0f;          // R_l = alpha h_l
  int firstLevel = 1;          // finest level blended: 1 (S1, the paper's default) or 0 (S0 itself)
  float clampDistance = 0.0f;  // d_c
  bool bruteForce = false;     // every S0 light, full-screen, weight 1 (ignores the hierarchy)
  bool countFragments = false; // count every rasterized fragment per pixel (an image atomic each)
};

// The surfaces a light pass shades and the targets it writes, all in the same (tiled or not) layout.
struct LightPassTarget {
  const gl::Texture2D& position;
  const gl::Texture2D& normal;
  TileLayout layout;                // n x n tiles; 1: the image itself
  gl::Texture2D& irradiance;        // RGBA32F
  gl::Texture2D* fragmentCounts;    // R32UI, required with countFragments
};

struct LightPassDraws {
  std::vector<size_t> lightsPerLevel;  // [0]: S0 lights drawn, [l]: grid lights of level l drawn
  size_t lightsDrawn() const;
};

class LightVolumePass {
 public:
  LightVolumePass();

  LightPassDraws execute(const gl::Buffer& lights, size_t lightCount, const GpuHierarchy& hierarchy,
                         const LightPassOptions& options, LightPassTarget& target);

 private:
  struct Draw;
  const gl::Program& program(bool s0Input, bool countFragments);

  std::array<gl::Program, 4> programs_;  // [s0Input * 2 + countFragments], compiled on first use
  gl::Buffer uniforms_;                  // one LightPassUniforms per draw, at aligned offsets
  size_t uniformStride_ = 0;
  size_t maxBlockLights_ = 0;            // S0 lights per storage block binding
  gl::VertexArrayHandle emptyVertexArray_;  // draws take their vertices from gl_VertexID
};

}  // namespace lgh
