#pragma once
// Interleaved sampling (Keller & Heidrich 2001; docs/design.md §6) around the light pass:
//   split:   GBuffer (position, normal)             -> Tiles (the same surfaces as n x n tiles)
//   resolve: Tiles' irradiance (and fragment counts) -> full-resolution irradiance, the interleaving
//            pattern removed by an edge-aware n x n filter
// With n = 1 neither step runs: the light pass shades the G-buffer directly.

#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/passes/gbuffer_pass.h"

namespace lgh {

// n x n tiles of tileSize each; tile (tx, ty) holds pixels (x, y) with x mod n = tx, y mod n = ty.
struct TileLayout {
  int tilesPerAxis = 1;
  glm::ivec2 imageSize{0}, tileSize{0};
  static TileLayout of(int tilesPerAxis, int width, int height);
  glm::ivec2 targetSize() const { return tileSize * tilesPerAxis; }
};

// The de-interleaved surfaces and what the light pass writes for them.
struct Tiles {
  Tiles() = default;
  // countFragments: with the fragment counter (the overdraw measurement), else without.
  Tiles(const TileLayout& layout, bool countFragments);
  TileLayout layout;
  gl::Texture2D position;        // RGBA32F, w = 0 on background and padding
  gl::Texture2D normal;          // RGBA16F
  gl::Texture2D irradiance;      // RGBA32F: the light pass's target
  gl::Texture2D fragmentCounts;  // R32UI: the light pass's fragment counter
};

struct InterleaveFilter {
  float normalPower = 32.0f;  // neighbour weight max(0, n.n')^normalPower
  float planeSigma = 2.0f;    // distance from the tangent plane, in pixel footprints, at weight e^-1/2
};

// The one resolve window's weights: the frame's resolve, the accumulation's of incomplete sums and the
// shadow filter's of the ratio's sums use these, so that what they divide by each other covers the same
// pixels (glsl/shared/interleave_window.glsl).
inline constexpr InterleaveFilter kInterleaveResolve{};

// What resolve writes, at full resolution.
struct InterleaveResolveTargets {
  gl::Texture2D& irradiance;
  gl::Texture2D* fragmentCounts = nullptr;  // not null: the tiles' fragment counts copied here too
};

class InterleavePass {
 public:
  InterleavePass();
  void split(const GBuffer& gbuffer, Tiles& tiles) const;
  void resolve(const GBuffer& gbuffer, const Tiles& tiles, const InterleaveFilter& filter,
               const InterleaveResolveTargets& out) const;

 private:
  gl::Program split_, resolve_;
};

}  // namespace lgh
