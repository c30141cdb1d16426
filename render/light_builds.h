#pragma once
// What the light-dependent part of a frame must (re)build: the input lights S0 and the structure over
// them that the frame's indirect method draws (the LGH, or the stochastic lightcuts' light tree). Both depend on the
// lights and their settings, not on the camera; the renderer asks for a plan each frame and reports each build it
// actually ran. A setting changed while its build was not needed (brute force draws no hierarchy) is therefore still
// honoured when the build is next needed. No GL here, so the rules are tested without a GPU
// (tests/engine/light_builds_test.cpp).

#include <optional>

#include "render/settings.h"

namespace lgh {

// Everything S0 is made from.
struct InputLightKey {
  InputLightSettings settings;
  bool pointLightsToS0 = false;  // the scene's point lights go into S0 (too many for exact direct light)
  unsigned lightsVersion = 0;    // SceneGpu::lightsVersion(): a punctual light was edited or moved
  unsigned geometryVersion = 0;  // SceneGpu::geometryVersion(): the vertices moved (the paths hit elsewhere)
  bool operator==(const InputLightKey& o) const {
    return settings == o.settings && pointLightsToS0 == o.pointLightsToS0 && lightsVersion == o.lightsVersion &&
           geometryVersion == o.geometryVersion;
  }
  bool operator!=(const InputLightKey& o) const { return !(*this == o); }
};

class LightBuilds {
 public:
  struct Plan {
    bool inputLights = false;  // build S0
    bool hierarchy = false;    // build the hierarchy over S0
    bool lightTree = false;    // build the light tree over S0
  };

  // What a frame that wants S0 from `key`, (when `drawsHierarchy`) a hierarchy of `levels` and (when
  // `drawsLightTree`) the light tree must build.
  Plan plan(const InputLightKey& key, int levels, bool drawsHierarchy, bool drawsLightTree = false) const {
    Plan p;
    p.inputLights = inputLights_ != key;
    p.hierarchy = drawsHierarchy && (p.inputLights || hierarchyLevels_ != levels);
    p.lightTree = drawsLightTree && (p.inputLights || !lightTreeBuilt_);
    return p;
  }
  // Records a build that ran. A new S0 invalidates the hierarchy and the tree built over the old one.
  void builtInputLights(const InputLightKey& key) {
    inputLights_ = key;
    hierarchyLevels_.reset();
    lightTreeBuilt_ = false;
  }
  void builtHierarchy(int levels) { hierarchyLevels_ = levels; }
  void builtLightTree() { lightTreeBuilt_ = true; }
  // Records what the renderer freed (its method or feature off): built again when next wanted.
  void freedInputLights() { *this = LightBuilds(); }
  void freedHierarchy() { hierarchyLevels_.reset(); }
  void freedLightTree() { lightTreeBuilt_ = false; }

 private:
  std::optional<InputLightKey> inputLights_;  // what S0 was built from; none yet
  std::optional<int> hierarchyLevels_;        // the level setting the hierarchy was built with; none yet
  bool lightTreeBuilt_ = false;               // over the S0 in use
};

}  // namespace lgh
