#pragma once
// The indirect light by the peer method, real-time stochastic lightcuts (Lin & Yuksel 2020; docs/design.md
// §12): a light tree over S0, a cut per block of pixels, one light drawn under each cut node per pixel with
// its shadow ray (an unbiased shadowed irradiance), and SVGF's variance-guided filter, as the paper denoises.
//   structure: LightTreePass
//   estimate:  RtslcPass (cuts, then sampling)
//   filter:    IrradianceFilterPass: the m x m resolve and the variance-guided a-trous passes; in ratio
//              form (rtslc-denoiser ratio, measured and not the default) over the unshadowed sum, and
//              ShadowFilterPass over the visibility ratio
//   targets:   the raw and the filtered irradiance; accumulating, the luminance's moments; the ratio form's

#include "render/indirect/indirect_light.h"
#include "render/passes/irradiance_filter_pass.h"
#include "render/passes/light_tree_pass.h"
#include "render/passes/rtslc_pass.h"
#include "render/passes/shadow_filter_pass.h"

namespace lgh {

class RtslcIndirect final : public IndirectLight {
 public:
  void allocate(const RenderSettings& settings) override;
  void release(LightBuilds& builds) override;
  bool updateStructure(const IndirectFrame& frame, const InputLightKey& lights, LightBuilds& builds) override;
  LightStats estimate(const IndirectFrame& frame) override;
  AccumulationSource accumulation(const IndirectFrame& frame) override;
  IndirectImage filter(const IndirectFrame& frame) override;
  const gl::Texture2D* target(Aov aov) const override;

  const GpuLightTree& lightTree() const { return lightTree_; }

 private:
  RenderSettings allocated_;  // what the targets were allocated for
  LightTreePass lightTreePass_;
  RtslcPass rtslcPass_;
  IrradianceFilterPass filterPass_;
  void freeTargets();  // every target, allocated or not
  bool ratioForm() const { return allocated_.rtslc.denoiser == RtslcDenoiser::Ratio; }
  ShadowFilterPass ratioFilterPass_;  // the ratio form's visibility
  GpuLightTree lightTree_;
  gl::Texture2D irradiance_;         // the sampling's shadowed irradiance (accumulated in place)
  gl::Texture2D filtered_;           // what the composite reads
  gl::Texture2D moments_;            // accumulating: the luminance's temporal moments (g: the mean's variance, a: N)
  gl::Texture2D sampledIrradiance_;  // accumulating: the accumulation's, unused here
  // The ratio form's: the same samples unshadowed (accumulated in place), their raw visibility ratio and its
  // weight, and the filtered visibility
  gl::Texture2D unshadowed_, ratio_, sampledLuminance_, visibility_;
};

}  // namespace lgh
