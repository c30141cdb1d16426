#pragma once
// The shadow estimator a frame runs with: ShadowSettings (the user's choice of estimator and the
// ablations of it) resolved into the flags the light pass and the shadow-ray pass read. Every gate
// between those settings lives here and nowhere else; a pass reads the resolved flags as they are.
//   converging  rays to input lights drawn per grid light by their share, picked per pixel by what they
//               add, each sample weighed by what its lights add over what its centre adds, the lights of
//               unselectable grid lights counted, the LGH's irradiance corrected by the samples' mean
//               weight as far as its variance allows (docs/design.md §5). The ablations switch parts off.
//   paper       Lin & Yuksel as published: rays to the cluster centre jittered by its spread, the finest
//               level not selected, no weights, no correction.
//   uniform     the paper's baseline: every contributing light equally likely; rays aimed as in
//               converging, but its estimate of the unshadowed sum (lights x mean weight) is too noisy to
//               correct by: its T is the light pass's irradiance (so D = 1: nothing corrected), nothing counted.
// No GL here: tests/engine/shadow_estimator_test.cpp covers every mode and limit without a GPU.

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "render/settings.h"

namespace lgh {

enum class ShadowEstimatorMode { Converging, Paper, Uniform };

// "converging", "paper" or "uniform"; throws std::invalid_argument naming the choices otherwise.
ShadowEstimatorMode parseShadowEstimatorMode(const std::string& name);
const char* shadowEstimatorName(ShadowEstimatorMode mode);

// What the passes run with. Every flag is effective: a pass never re-derives one from another.
struct ShadowEstimator {
  ShadowEstimatorMode mode = ShadowEstimatorMode::Converging;
  int samples = 0;                      // k; 0: no selection, the indirect light unshadowed
  bool uniformSelection = false;        // every contributing light equally likely instead of by contribution
  bool skipFinest = false;              // the finest level blended takes no part in the selection
  unsigned drawnTargets = 0;            // m input lights drawn per grid light as ray targets; 0: jittered centres
  float spread = 1.0f;                  // the jittered centres' spread, in the cluster's standard deviations (m = 0)
  bool resampleTargets = false;         // each pixel picks among the m drawn lights by what they add there
  bool weighTargets = false;            // a sample weighs what its drawn lights add over what its centre adds
  bool blendTargets = false;            // each drawn light blended by its own distance (else its centre's)
  float defensive = 0.0f;               // a grid light's selection importance adds this x its cosine-free term
  bool countUnselectable = false;       // the light pass adds what unselectable grid lights add to T (U)
  bool correctIrradiance = false;       // the filter scales the LGH irradiance by the trusted mean weight D
  float correctionError = 0.0f;         // f: the LGH irradiance's expected relative error (D's prior spread)
  float correctionSampleSpread = 1.0f;  // the prior spread of one sample's D
  bool shadowed() const { return samples > 0; }
};

// What the frame imposes on the estimator, beyond the settings.
struct ShadowEstimatorLimits {
  bool bruteForce = false;  // the light pass's irradiance is the input lights' own sum: nothing to correct
  size_t inputLights = 0;   // |S0|
  // Input lights one storage block holds: counting the unselectable grid lights reads any input light
  // from every fragment, so it needs them in one block (LightVolumePass::inputLightsPerBlock).
  size_t inputLightsPerBlock = std::numeric_limits<size_t>::max();
};

struct ResolvedShadowEstimator {
  ShadowEstimator estimator;
  // A feature the settings ask for that a limit switched off, one line each (the renderer prints each once).
  std::vector<std::string> switchedOff;
};

ResolvedShadowEstimator resolveShadowEstimator(const ShadowSettings& settings, const ShadowEstimatorLimits& limits);

}  // namespace lgh
