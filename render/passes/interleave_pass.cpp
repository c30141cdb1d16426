#include "render/passes/interleave_pass.h"

#include <stdexcept>
#include <string>

#include "render/gl/debug.h"
#include "render/pass_names.h"
#include "shared/bindings.h"
#include "shared/light_pass_types.h"

namespace lgh {

TileLayout TileLayout::of(int tilesPerAxis, int width, int height) {
  if (tilesPerAxis < 1 || tilesPerAxis > int(gpu::kMaxInterleave))
    throw std::invalid_argument("interleave: " + std::to_string(tilesPerAxis) + " tiles per axis (use 1 to " +
                                std::to_string(gpu::kMaxInterleave) + ")");
  TileLayout t;
  t.tilesPerAxis = tilesPerAxis;
  t.imageSize = {width, height};
  t.tileSize = (t.imageSize + tilesPerAxis - 1) / tilesPerAxis;  // the last tiles get padding
  return t;
}

Tiles::Tiles(const TileLayout& l, bool countFragments)
    : layout(l),
      position({passes::kInterleaveSplit, "tiles: position", kImageSize}, l.targetSize().x, l.targetSize().y,
               GL_RGBA32F),
      normal({passes::kInterleaveSplit, "tiles: normal", kImageSize}, l.targetSize().x, l.targetSize().y, GL_RGBA16F),
      irradiance({passes::kLightPass, "tiles: irradiance", kImageSize}, l.targetSize().x, l.targetSize().y, GL_RGBA32F),
      fragmentCounts(countFragments ? gl::Texture2D({passes::kLightPass, "tiles: fragment counts", kImageSize},
                                                    l.targetSize().x, l.targetSize().y, GL_R32UI)
                                    : gl::Texture2D()) {}

InterleavePass::InterleavePass()
    : split_(gl::Program::compute("deinterleave.comp")), resolve_(gl::Program::compute("interleave_resolve.comp")) {}

void InterleavePass::split(const GBuffer& gbuffer, Tiles& tiles) const {
  const TileLayout& l = tiles.layout;
  gbuffer.bindForReading();
  tiles.position.bindImage(LGH_IMAGE_TILED_POSITION, GL_WRITE_ONLY);
  tiles.normal.bindImage(LGH_IMAGE_TILED_NORMAL, GL_WRITE_ONLY);
  split_.set("tilesPerAxis", unsigned(l.tilesPerAxis));
  split_.set("tileSize", glm::uvec2(l.tileSize));
  split_.dispatch2D(l.targetSize().x, l.targetSize().y, {8, 8});
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  gl::checkErrors("interleave split");
}

void InterleavePass::resolve(const GBuffer& gbuffer, const Tiles& tiles, const InterleaveFilter& filter,
                             const InterleaveResolveTargets& out) const {
  const TileLayout& l = tiles.layout;
  gbuffer.bindForReading();
  tiles.irradiance.bindTexture(LGH_TEXTURE_TILED_IRRADIANCE);
  tiles.fragmentCounts.bindTexture(LGH_TEXTURE_TILED_FRAGMENT_COUNTS);
  out.irradiance.bindImage(LGH_IMAGE_RESOLVED_IRRADIANCE, GL_WRITE_ONLY);
  if (out.fragmentCounts) out.fragmentCounts->bindImage(LGH_IMAGE_RESOLVED_FRAGMENT_COUNTS, GL_WRITE_ONLY);
  resolve_.set("tilesPerAxis", unsigned(l.tilesPerAxis));
  resolve_.set("tileSize", glm::uvec2(l.tileSize));
  resolve_.set("countFragments", int(out.fragmentCounts != nullptr));
  resolve_.set("normalPower", filter.normalPower);
  resolve_.set("planeSigma", std::max(filter.planeSigma, 1e-6f));
  resolve_.dispatch2D(l.imageSize.x, l.imageSize.y, {8, 8});
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  gl::checkErrors("interleave resolve");
}

}  // namespace lgh
