#pragma once
// Turns one image of a frame into display pixels, as lgh-render writes a PNG: radiance exposed,
// tone-mapped and sRGB-encoded, data clamped, ratios as grey, fragment counts as a heat map
// (shared/display_encode.h holds the mapping, so both agree to 8-bit rounding). The viewer shows the
// result in its window and writes it as its PNG screenshot.
//   in:  an AOV texture of the frame (RGBA32F, or R32UI fragment counts), its encoding
//   out: DisplayImage (RGBA8, the frame's size), drawn 1:1

#include <cstdint>
#include <vector>

#include "render/aov.h"
#include "render/gl/program.h"
#include "render/gl/texture.h"
#include "render/image_io.h"

namespace lgh {

// An RGBA8 image to show or save, with a framebuffer so overlays can draw into it.
struct DisplayImage {
  DisplayImage() = default;
  DisplayImage(int width, int height);
  int width = 0, height = 0;
  gl::Texture2D color;
  gl::Framebuffer framebuffer;
  // The pixels as 8-bit RGB, rows top-down (ready for writeDisplayImage).
  std::vector<std::uint8_t> readRGB() const;
};

// How lgh-render encodes an AOV for a display file: gpu::kDisplayRadiance, kDisplayData, kDisplayRatio
// or kDisplayCounts (shared/display_encode.h).
std::uint32_t displayEncodingOf(Aov aov);

struct DisplayOptions {
  std::uint32_t encoding = 0;  // gpu::kDisplay*
  float exposureEV = 0.0f;     // radiance only
  ToneMap toneMap = ToneMap::Aces;
  unsigned largestCount = 1;  // counts only: the count shown as the top of the heat map
};

class DisplayPass {
 public:
  DisplayPass();
  // `image` must have the size of `out`.
  void execute(const gl::Texture2D& image, const DisplayOptions& options, DisplayImage& out);

 private:
  gl::Program floatProgram_, countProgram_;
  gl::VertexArrayHandle emptyVertexArray_;  // the full-screen triangle comes from gl_VertexID
};

}  // namespace lgh
