// What the renderer rebuilds between frames (render/light_builds.h), without a GPU: S0 when the
// lights or their settings change, the hierarchy when S0 or the level setting changes and only while
// a frame draws it.
#include "render/light_builds.h"

#include <gtest/gtest.h>

namespace lgh {
namespace {

// Plays what Renderer::updateLights does: plans, then records the builds it ran.
LightBuilds::Plan frame(LightBuilds& builds, const InputLightKey& key, int levels, bool drawsHierarchy,
                        bool drawsLightTree = false) {
  const LightBuilds::Plan plan = builds.plan(key, levels, drawsHierarchy, drawsLightTree);
  if (plan.inputLights) builds.builtInputLights(key);
  if (plan.hierarchy) builds.builtHierarchy(levels);
  if (plan.lightTree) builds.builtLightTree();
  return plan;
}

TEST(LightBuilds, FirstFrameBuildsBothThenNothing) {
  LightBuilds builds;
  const InputLightKey key;
  LightBuilds::Plan p = frame(builds, key, 0, true);
  EXPECT_TRUE(p.inputLights);
  EXPECT_TRUE(p.hierarchy);
  p = frame(builds, key, 0, true);
  EXPECT_FALSE(p.inputLights);
  EXPECT_FALSE(p.hierarchy);
}

TEST(LightBuilds, LightSettingsAndEditsRebuildBoth) {
  LightBuilds builds;
  InputLightKey key;
  frame(builds, key, 0, true);
  for (auto change :
       {+[](InputLightKey& k) { k.settings.vpls += 1; }, +[](InputLightKey& k) { k.settings.bounces = 3; },
        +[](InputLightKey& k) { k.settings.seed = 7; }, +[](InputLightKey& k) { k.settings.emitterSamples = 5; },
        +[](InputLightKey& k) { k.pointLightsToS0 = !k.pointLightsToS0; },
        +[](InputLightKey& k) { ++k.lightsVersion; }}) {
    change(key);
    const LightBuilds::Plan p = frame(builds, key, 0, true);
    EXPECT_TRUE(p.inputLights);
    EXPECT_TRUE(p.hierarchy) << "a hierarchy over the old S0 is stale";
  }
}

TEST(LightBuilds, LevelChangeRebuildsOnlyTheHierarchy) {
  LightBuilds builds;
  const InputLightKey key;
  frame(builds, key, 0, true);
  const LightBuilds::Plan p = frame(builds, key, 4, true);
  EXPECT_FALSE(p.inputLights);
  EXPECT_TRUE(p.hierarchy);
}

// Brute force draws no hierarchy: nothing is built for it, and a level change made meanwhile must
// still be built once the hierarchy is drawn again (the renderer once recorded the new level count
// without building, and kept the old hierarchy).
TEST(LightBuilds, LevelsChangedDuringBruteForceAreBuiltAfterwards) {
  LightBuilds builds;
  const InputLightKey key;
  frame(builds, key, 0, true);
  LightBuilds::Plan p = frame(builds, key, 3, /*drawsHierarchy=*/false);
  EXPECT_FALSE(p.hierarchy);
  p = frame(builds, key, 3, true);
  EXPECT_TRUE(p.hierarchy);
  EXPECT_FALSE(p.inputLights);
}

// Relit during brute force: S0 is rebuilt at once (brute force shades it), the hierarchy later.
TEST(LightBuilds, NewLightsDuringBruteForceRebuildTheHierarchyLater) {
  LightBuilds builds;
  InputLightKey key;
  frame(builds, key, 0, true);
  ++key.lightsVersion;
  LightBuilds::Plan p = frame(builds, key, 0, false);
  EXPECT_TRUE(p.inputLights);
  EXPECT_FALSE(p.hierarchy);
  p = frame(builds, key, 0, true);
  EXPECT_FALSE(p.inputLights);
  EXPECT_TRUE(p.hierarchy);
}

// Switching the indirect method to the lightcuts and back: each structure is built when first drawn and
// again only over a new S0.
TEST(LightBuilds, TheLightTreeIsBuiltWhenDrawnAndRebuiltOverNewLights) {
  LightBuilds builds;
  InputLightKey key;
  LightBuilds::Plan p = frame(builds, key, 0, true);
  EXPECT_FALSE(p.lightTree);
  p = frame(builds, key, 0, false, true);
  EXPECT_FALSE(p.inputLights);
  EXPECT_FALSE(p.hierarchy);
  EXPECT_TRUE(p.lightTree);
  p = frame(builds, key, 0, false, true);
  EXPECT_FALSE(p.lightTree);
  ++key.lightsVersion;
  p = frame(builds, key, 0, false, true);
  EXPECT_TRUE(p.inputLights);
  EXPECT_TRUE(p.lightTree) << "a tree over the old S0 is stale";
  p = frame(builds, key, 0, true);
  EXPECT_TRUE(p.hierarchy) << "the hierarchy was over the old S0";
  EXPECT_FALSE(p.lightTree);
}

}  // namespace
}  // namespace lgh
