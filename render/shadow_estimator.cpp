#include "render/shadow_estimator.h"

#include <algorithm>
#include <stdexcept>

namespace lgh {

ShadowEstimatorMode parseShadowEstimatorMode(const std::string& name) {
  if (name == "converging") return ShadowEstimatorMode::Converging;
  if (name == "paper") return ShadowEstimatorMode::Paper;
  if (name == "uniform") return ShadowEstimatorMode::Uniform;
  throw std::invalid_argument("unknown shadow estimator '" + name + "' (one of: " + kShadowEstimatorChoices + ")");
}

const char* shadowEstimatorName(ShadowEstimatorMode mode) {
  switch (mode) {
    case ShadowEstimatorMode::Paper:
      return "paper";
    case ShadowEstimatorMode::Uniform:
      return "uniform";
    case ShadowEstimatorMode::Converging:
      break;
  }
  return "converging";
}

ResolvedShadowEstimator resolveShadowEstimator(const ShadowSettings& settings, const ShadowEstimatorLimits& limits) {
  ResolvedShadowEstimator resolved;
  ShadowEstimator& e = resolved.estimator;
  e.mode = parseShadowEstimatorMode(settings.estimator);
  e.samples = settings.samples;
  if (!e.shadowed()) return resolved;
  e.spread = settings.spread;
  if (e.mode == ShadowEstimatorMode::Paper) {
    e.skipFinest = true;  // the paper selects among S2 and coarser; S1's shadows come from the filter
    return resolved;
  }
  e.uniformSelection = e.mode == ShadowEstimatorMode::Uniform;
  e.skipFinest = settings.skipFinest;
  // At least two drawn lights per sample: the m lights are shared by every pixel of the frame, and their mean
  // factor is what a sample's weight (and so D) rests on, an error the k samples do not average. Brute
  // force selects input lights, never grid lights: there is nothing to draw.
  if (settings.targets > 0 && !limits.bruteForce)
    e.drawnTargets = unsigned(std::min(std::max(settings.targets, 2 * e.samples), int(gpu::kMaxShadowTargets)));
  const bool drawn = e.drawnTargets > 0;
  e.resampleTargets = drawn && settings.resampleTargets;
  e.weighTargets = drawn && settings.weighTargets;
  e.blendTargets = drawn && settings.blendTargets;
  // Only samples weighed by their drawn lights have heavy weights to bound (a centre is weighed by itself).
  e.defensive = e.weighTargets ? settings.defensive : 0.0f;
  // T = F' mean(w) + U estimates the input lights' sum only when the samples are weighed by their lights
  // and every level is selected by contribution; uniform selection's T is the LGH's own irradiance.
  const bool estimatesSum = e.weighTargets && !e.skipFinest && !e.uniformSelection;
  e.countUnselectable = settings.countUnselectable && estimatesSum;
  if (e.countUnselectable && limits.inputLights > limits.inputLightsPerBlock) {
    e.countUnselectable = false;
    resolved.switchedOff.push_back("shadow-count-unselectable is off: " + std::to_string(limits.inputLights) +
                                   " input lights exceed the " + std::to_string(limits.inputLightsPerBlock) +
                                   " one storage block holds (the corrected image may come out darker)");
  }
  // D compares the samples' sum with the LGH's irradiance: meaningless with the finest level skipped (the
  // samples cover part of it), 1 with brute force, and 1 with uniform selection, whose T is the irradiance
  // its samples are compared with (interleaved too: both are the tile's).
  e.correctIrradiance = settings.correctIrradiance && !e.skipFinest && !limits.bruteForce && !e.uniformSelection;
  e.correctionError = settings.correctionError;
  e.correctionSampleSpread = settings.correctionSampleSpread;
  return resolved;
}

}  // namespace lgh
