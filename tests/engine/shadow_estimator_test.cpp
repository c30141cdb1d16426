// resolveShadowEstimator (render/shadow_estimator.h): every mode, the ablations' gates and the limits,
// without a GPU. Each expectation is a flag a pass would read: a wrong gate here is a wrong image there.
#include "render/shadow_estimator.h"

#include <gtest/gtest.h>

namespace lgh {
namespace {

ShadowEstimator resolved(const ShadowSettings& settings, const ShadowEstimatorLimits& limits = {}) {
  const ResolvedShadowEstimator r = resolveShadowEstimator(settings, limits);
  EXPECT_TRUE(r.switchedOff.empty()) << r.switchedOff.front();
  return r.estimator;
}

ShadowSettings withEstimator(const char* name, int samples = 4) {
  ShadowSettings s;
  s.estimator = name;
  s.samples = samples;
  return s;
}

TEST(ShadowEstimatorTest, ConvergingRunsEveryPartOfTheEstimator) {
  const ShadowEstimator e = resolved(withEstimator("converging"));
  EXPECT_EQ(e.mode, ShadowEstimatorMode::Converging);
  EXPECT_EQ(e.samples, 4);
  EXPECT_FALSE(e.uniformSelection);
  EXPECT_FALSE(e.skipFinest);
  EXPECT_EQ(e.drawnTargets, 8u);
  EXPECT_TRUE(e.resampleTargets && e.weighTargets && e.blendTargets);
  EXPECT_TRUE(e.countUnselectable);
  EXPECT_TRUE(e.correctIrradiance);
  EXPECT_FLOAT_EQ(e.correctionError, ShadowSettings{}.correctionError);
  EXPECT_FLOAT_EQ(e.correctionSampleSpread, ShadowSettings{}.correctionSampleSpread);
}

// m = min(max(targets, 2k), kMaxShadowTargets): at least two drawn lights per sample, at most the GPU's array.
TEST(ShadowEstimatorTest, DrawsAtLeastTwoTargetsPerSampleUpToTheLimit) {
  for (const auto& [k, targets, m] : {std::tuple{1, 8, 8u},
                                      {4, 8, 8u},
                                      {8, 8, 16u},
                                      {16, 8, 32u},
                                      {4, 32, 32u},
                                      {1, 1, 2u},
                                      {16, 32, unsigned(gpu::kMaxShadowTargets)}}) {
    ShadowSettings s = withEstimator("converging", k);
    s.targets = targets;
    EXPECT_EQ(resolved(s).drawnTargets, m) << "k = " << k << ", targets = " << targets;
  }
}

TEST(ShadowEstimatorTest, PaperIsLinAndYukselAsPublishedWhateverTheAblations) {
  ShadowSettings s = withEstimator("paper");
  s.targets = 16;  // ablations of the converging estimator: ignored
  s.defensive = 1.0f;
  s.skipFinest = false;
  s.spread = 0.5f;
  const ShadowEstimator e = resolved(s);
  EXPECT_EQ(e.mode, ShadowEstimatorMode::Paper);
  EXPECT_EQ(e.samples, 4);
  EXPECT_EQ(e.drawnTargets, 0u);  // jittered cluster centres
  EXPECT_FLOAT_EQ(e.spread, 0.5f);
  EXPECT_TRUE(e.skipFinest);  // S1 not selected
  EXPECT_FALSE(e.uniformSelection);
  EXPECT_FALSE(e.resampleTargets || e.weighTargets || e.blendTargets);
  EXPECT_FLOAT_EQ(e.defensive, 0.0f);
  EXPECT_FALSE(e.countUnselectable);
  EXPECT_FALSE(e.correctIrradiance);
}

TEST(ShadowEstimatorTest, UniformSelectsUniformlyAndCountsNothing) {
  const ShadowEstimator e = resolved(withEstimator("uniform"));
  EXPECT_EQ(e.mode, ShadowEstimatorMode::Uniform);
  EXPECT_TRUE(e.uniformSelection);
  EXPECT_FALSE(e.skipFinest);
  EXPECT_EQ(e.drawnTargets, 8u);  // rays aimed as the converging estimator aims them
  EXPECT_TRUE(e.resampleTargets && e.weighTargets);
  EXPECT_FALSE(e.countUnselectable);  // its T is the LGH's irradiance: nothing to complete
  EXPECT_FALSE(e.correctIrradiance);  // D = T / C with T the light pass's own irradiance: 1, interleaved too
}

TEST(ShadowEstimatorTest, NoSamplesMeansNoSelectionInEveryMode) {
  for (const char* name : {"converging", "paper", "uniform"}) {
    const ShadowEstimator e = resolved(withEstimator(name, 0));
    EXPECT_FALSE(e.shadowed()) << name;
    EXPECT_EQ(e.drawnTargets, 0u) << name;
    EXPECT_FALSE(e.countUnselectable || e.correctIrradiance || e.weighTargets || e.skipFinest) << name;
  }
}

// Each ablation switches off what rests on it, and nothing else.
TEST(ShadowEstimatorTest, AblationsSwitchOffWhatRestsOnThem) {
  ShadowSettings centres = withEstimator("converging");
  centres.targets = 0;
  centres.defensive = 1.0f;
  ShadowEstimator e = resolved(centres);
  EXPECT_EQ(e.drawnTargets, 0u);
  EXPECT_FALSE(e.resampleTargets || e.weighTargets || e.blendTargets || e.countUnselectable);
  EXPECT_FLOAT_EQ(e.defensive, 0.0f);  // a centre is weighed by itself: no heavy weights to bound
  EXPECT_TRUE(e.correctIrradiance);

  ShadowSettings unweighed = withEstimator("converging");
  unweighed.weighTargets = false;
  unweighed.defensive = 1.0f;
  e = resolved(unweighed);
  EXPECT_FALSE(e.weighTargets || e.countUnselectable);
  EXPECT_FLOAT_EQ(e.defensive, 0.0f);
  EXPECT_TRUE(e.resampleTargets && e.blendTargets && e.correctIrradiance);

  ShadowSettings skipped = withEstimator("converging");
  skipped.skipFinest = true;
  e = resolved(skipped);
  EXPECT_TRUE(e.skipFinest && e.weighTargets);
  EXPECT_FALSE(e.countUnselectable || e.correctIrradiance);  // the samples cover part of the LGH's sum

  ShadowSettings weighedDefensive = withEstimator("converging");
  weighedDefensive.defensive = 0.5f;
  EXPECT_FLOAT_EQ(resolved(weighedDefensive).defensive, 0.5f);

  ShadowSettings plain = withEstimator("converging");
  plain.countUnselectable = false;
  plain.correctIrradiance = false;
  e = resolved(plain);
  EXPECT_FALSE(e.countUnselectable || e.correctIrradiance);
  EXPECT_TRUE(e.weighTargets && e.blendTargets);
}

TEST(ShadowEstimatorTest, BruteForceDrawsNothingAndCorrectsNothing) {
  ShadowEstimatorLimits limits;
  limits.bruteForce = true;
  const ShadowEstimator e = resolved(withEstimator("converging"), limits);
  EXPECT_TRUE(e.shadowed());
  EXPECT_EQ(e.drawnTargets, 0u);
  EXPECT_FALSE(e.countUnselectable || e.correctIrradiance || e.weighTargets);
}

// The light pass reads any input light from every fragment to count the unselectable grid lights, so the
// input lights must fit one storage block; beyond it the counting goes, and the renderer is told why.
TEST(ShadowEstimatorTest, BlockLimitSwitchesTheCountingOffAndSaysSo) {
  ShadowEstimatorLimits limits;
  limits.inputLightsPerBlock = 1000;
  limits.inputLights = 1000;
  EXPECT_TRUE(resolved(withEstimator("converging"), limits).countUnselectable);

  limits.inputLights = 1001;
  const ResolvedShadowEstimator over = resolveShadowEstimator(withEstimator("converging"), limits);
  EXPECT_FALSE(over.estimator.countUnselectable);
  EXPECT_TRUE(over.estimator.correctIrradiance);  // the rest stays
  ASSERT_EQ(over.switchedOff.size(), 1u);
  EXPECT_NE(over.switchedOff[0].find("shadow-count-unselectable"), std::string::npos) << over.switchedOff[0];
  EXPECT_NE(over.switchedOff[0].find("1001"), std::string::npos) << over.switchedOff[0];

  // Modes and ablations that do not count are not told anything.
  ShadowSettings notCounting = withEstimator("converging");
  notCounting.countUnselectable = false;
  for (const ShadowSettings& s : {withEstimator("paper"), withEstimator("uniform"), notCounting})
    EXPECT_TRUE(resolveShadowEstimator(s, limits).switchedOff.empty()) << s.estimator;
}

TEST(ShadowEstimatorTest, TheSettingAcceptsExactlyTheModes) {
  for (const char* name : {"converging", "paper", "uniform"}) {
    RenderSettings settings;
    setSetting(settings, "shadow-estimator", name);
    EXPECT_STREQ(shadowEstimatorName(parseShadowEstimatorMode(settings.shadows.estimator)), name);
  }
  RenderSettings settings;
  EXPECT_THROW(setSetting(settings, "shadow-estimator", "lights"), std::invalid_argument);
  EXPECT_THROW(setSetting(settings, "shadow-estimator", ""), std::invalid_argument);
  EXPECT_THROW(parseShadowEstimatorMode("Paper"), std::invalid_argument);
}

}  // namespace
}  // namespace lgh
