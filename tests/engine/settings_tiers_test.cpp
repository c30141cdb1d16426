// The settings' declarations (render/settings.h): tiers, one-line help, what keeps the accumulated
// history, and docs/settings.md naming every one of them.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>

#include "render/settings.h"

namespace lgh {
namespace {

std::set<std::string> namesWhere(bool (*pick)(const SettingInfo&)) {
  RenderSettings settings;
  std::set<std::string> names;
  visitSettings(settings, [&](const auto&, const SettingInfo& info) {
    if (pick(info)) names.insert(info.name);
  });
  return names;
}

TEST(SettingsTiersTest, HelpShowsAFewUserSettingsOneLineEach) {
  const std::set<std::string> user = namesWhere([](const SettingInfo& i) { return i.tier == SettingTier::User; });
  EXPECT_LE(user.size(), 12u);  // lgh-render --help adds scene, -o, --frames, -h and --help-all: about 15
  for (const char* name :
       {"vpls", "alpha", "interleave", "shadow-samples", "shadow-estimator", "filter-passes", "accumulate", "exposure"})
    EXPECT_TRUE(user.count(name)) << name << " is not a user setting";
  RenderSettings settings;
  visitSettings(settings, [&](const auto&, const SettingInfo& info) {
    EXPECT_EQ(std::strchr(info.help, '\n'), nullptr) << info.name;
    EXPECT_LE(std::strlen(info.help), 100u) << info.name << ": help longer than one line";
  });
}

TEST(SettingsTiersTest, AblationsAreTheEstimatorsParts) {
  const std::set<std::string> ablations =
      namesWhere([](const SettingInfo& i) { return i.tier == SettingTier::Ablation; });
  EXPECT_GE(ablations.size(), 10u);
  for (const std::string& name : ablations) EXPECT_EQ(name.rfind("shadow-", 0), 0u) << name;
  EXPECT_FALSE(ablations.count("shadow-samples"));
  EXPECT_FALSE(ablations.count("shadow-estimator"));
}

// A setting that changes a frame's raw estimate must restart the history; one that does not must keep it.
TEST(SettingsTiersTest, OnlySettingsThatLeaveTheRawEstimatesKeepTheHistory) {
  const std::set<std::string> keeps = namesWhere([](const SettingInfo& i) { return i.keepsHistory; });
  for (const char* name : {"camera", "exposure", "tonemap", "overdraw", "filter-passes", "filter-normal-power",
                           "filter-plane-sigma", "filter-ratio-sigma", "accumulate-max-frames",
                           "accumulate-filter-fade", "shadow-correct-irradiance", "shadow-correction-lgh-error"})
    EXPECT_TRUE(keeps.count(name)) << name << " should keep the history";
  for (const char* name :
       {"vpls", "alpha", "interleave", "levels", "shadow-samples", "shadow-estimator", "shadow-targets",
        "shadow-count-unselectable", "shadow-correction-sample-spread", "seed", "clamp-distance", "accumulate"})
    EXPECT_FALSE(keeps.count(name)) << name << " changes the raw estimates: it must restart the history";
}

TEST(SettingsTiersTest, DocsNameEverySetting) {
  std::ifstream file(std::string(LGH_SOURCE_DIR) + "/docs/settings.md");
  ASSERT_TRUE(file) << "docs/settings.md is missing";
  const std::string docs{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  RenderSettings settings;
  visitSettings(settings, [&](const auto&, const SettingInfo& info) {
    if (info.tier != SettingTier::Ablation) return;
    EXPECT_NE(docs.find("`" + std::string(info.name) + "`"), std::string::npos)
        << "docs/settings.md does not describe the ablation " << info.name;
  });
}

TEST(SettingsTiersTest, ChoicesAreCheckedWhenSet) {
  RenderSettings settings;
  setSetting(settings, "tonemap", "reinhard");
  EXPECT_EQ(settings.image.toneMap, "reinhard");
  EXPECT_THROW(setSetting(settings, "tonemap", "filmic"), std::invalid_argument);
  EXPECT_THROW(setSetting(settings, "tonemap", "aces|reinhard"), std::invalid_argument);
  EXPECT_TRUE(isChoice("a|bc|d", "bc"));
  EXPECT_FALSE(isChoice("a|bc|d", "b"));
  EXPECT_FALSE(isChoice("a|bc|d", ""));
}

}  // namespace
}  // namespace lgh
