#pragma once
// The indirect light through the lighting grid hierarchy (docs/design.md §2-§5): the hierarchy built over
// S0, the light volumes' irradiance with k shadow samples picked per pixel (n x n interleaved when asked),
// the shadow rays' raw visibility ratio and the a-trous ratio filter.
//   structure: LghBuildPass (not under brute force)
//   estimate:  [interleave split] shadow targets, light pass, [interleave resolve], shadow rays
//   filter:    the shadow filter: the visibility (times the corrected mean weight)
//   targets:   irradiance (full resolution), tiles (n > 1), fragment counts (overdraw), shadow slots and
//              targets, raw ratio, sampled irradiance, visibility

#include <set>
#include <string>

#include "render/indirect/indirect_light.h"
#include "render/passes/interleave_pass.h"
#include "render/passes/lgh_build_pass.h"
#include "render/passes/light_volume_pass.h"
#include "render/passes/shadow_filter_pass.h"
#include "render/passes/shadow_ray_pass.h"
#include "render/passes/shadow_targets_pass.h"
#include "render/shadow_estimator.h"

namespace lgh {

class LghIndirect final : public IndirectLight {
 public:
  // floatAtomics: GL_NV_shader_atomic_float is available (the build's and the selection's sums use it).
  explicit LghIndirect(bool floatAtomics);
  void allocate(const RenderSettings& settings) override;
  void release(LightBuilds& builds) override;
  bool updateStructure(const IndirectFrame& frame, const InputLightKey& lights, LightBuilds& builds) override;
  LightStats estimate(const IndirectFrame& frame) override;
  AccumulationSource accumulation(const IndirectFrame& frame) override;
  IndirectImage filter(const IndirectFrame& frame) override;
  void countWork(LightStats& stats) const override;
  const gl::Texture2D* target(Aov aov) const override;

  // How the hierarchy is built for this scene and these settings (levels, smallest top cell).
  static LghBuildOptions buildOptions(const SceneGpu& scene, const RenderSettings& settings);
  const GpuHierarchy& hierarchy() const { return hierarchy_; }
  const ShadowSlots& shadowSlots() const { return shadowSlots_; }  // the last frame's selection
  // The frames' shadow rays recorded into `rays` from the next frame on (ShadowRayTargets::recordedRays),
  // until called with nullptr; the buffer is the caller's.
  void recordShadowRays(gl::Buffer* rays) { recordedRays_ = rays; }

 private:
  // The targets freed (allocate() makes the new set after); the shadow sampling's slots, targets and passes freed.
  void freeTargets();
  void releaseShadowSampling();
  bool shadowed() const { return allocated_.shadows.samples > 0; }
  bool interleaved() const { return allocated_.lightPass.interleave > 1; }
  // Shadow rays aim at input lights drawn from the selected grid lights' clusters.
  bool drawsShadowTargets() const { return shadowEstimator_.drawnTargets > 0 && hierarchy_.gridLightCount > 0; }
  // This frame's shadow estimator (the settings resolved against its limits); says once on stderr what a
  // limit switched off.
  void resolveShadows(const IndirectFrame& frame);
  LightPassOptions lightPassOptions(const IndirectFrame& frame) const;
  // What the shadow rays read of the light pass that filled the slots, to recompute its selection.
  static ShadowRayOptions shadowRayOptions(const IndirectFrame& frame, const LightPassOptions& lightPass);
  ShadowFilterOptions shadowFilterOptions(const IndirectFrame& frame) const;
  // The light pass's surfaces and targets: the tiles when interleaving, else the image's (slots sized to them).
  LightPassTarget lightPassTarget(const IndirectFrame& frame);
  TileLayout fullLayout() const { return TileLayout::of(1, allocated_.image.width, allocated_.image.height); }

  RenderSettings allocated_;  // what the targets were allocated for (size, interleaving, shadows, overdraw)
  LghBuildPass buildPass_;
  InterleavePass interleavePass_;
  LightVolumePass lightPass_;
  ShadowTargetsPass shadowTargetsPass_;
  ShadowRayPass shadowRayPass_;
  ShadowFilterPass shadowFilterPass_;

  GpuHierarchy hierarchy_;
  ShadowEstimator shadowEstimator_;       // resolved each frame by resolveShadows()
  std::set<std::string> reportedLimits_;  // what a limit switched off, said once

  Tiles tiles_;                         // interleaved surfaces and light-pass targets (n > 1)
  gl::Texture2D irradiance_;            // full resolution
  gl::Texture2D fragmentCounts_;        // R32UI, light-pass fragments per pixel (settings.overdraw)
  gl::Buffer* recordedRays_ = nullptr;  // recordShadowRays
  ShadowSlots shadowSlots_;             // k selected lights per light-pass pixel
  ShadowTargets shadowTargets_;         // input lights drawn per grid light as the rays' targets
  gl::Texture2D rawRatio_;              // r: visibility ratio from the shadow rays (accumulated; a: frames)
  gl::Texture2D sampledIrradiance_;     // R32F: the irradiance luminance the shadow samples were drawn against
  gl::Texture2D visibility_;            // r: filtered ratio
};

}  // namespace lgh
