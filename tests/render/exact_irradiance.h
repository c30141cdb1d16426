#pragma once
// Exact references at a renderer's surfaces, shared by the GL tests that hold its frames to them.
#include "render/exact/brute_force_pass.h"
#include "render/image_compare.h"
#include "render/renderer.h"
#include "render/scene/scene_gpu.h"

namespace lgh::test {

// Every input light of the renderer's last frame at every pixel of its G-buffer (BruteForcePass):
// unshadowed, or with one shadow ray per light and pixel through `shadowing`'s BVH.
inline ImageRGBA exactIrradiance(const Renderer& renderer, const SceneGpu* shadowing = nullptr) {
  static BruteForcePass bruteForce;  // one GL context per test process: the program is compiled once
  const RenderSettings& s = renderer.settings();
  gl::Texture2D out({"test", "out"}, s.image.width, s.image.height, GL_RGBA32F);
  bruteForce.execute({renderer.gbuffer(), renderer.inputLights().lights, renderer.inputLights().count, shadowing},
                     renderer.clampDistance(), out);
  return fromGLRows(s.image.width, s.image.height, out.readRGBA());
}

// The last frame's shadowed indirect irradiance: its irradiance times its (filtered) visibility.
inline ImageRGBA shadowedIrradiance(const Renderer& renderer) {
  ImageRGBA shadowed = renderer.readImage(Aov::Irradiance);
  const ImageRGBA ratio = renderer.readImage(Aov::Visibility);
  for (size_t i = 0; i < shadowed.pixels.size(); ++i) shadowed.pixels[i] *= ratio.pixels[i].r;
  return shadowed;
}

}  // namespace lgh::test
