#pragma once

// Which input lights a grid light stands for, and how much of it each one is (docs/design.md §5).
//
// A grid light at vertex V of level l collects its sources (the input lights for S1, the grid lights
// of level l-1 above it) with weight w a: trilinear weight times luminance. A source's share of V is
// w a / sum(w a), and a grid light's share in turn passes on to the sources it was built from, so
// input light i's share of V is the sum over the paths from i up to V of the products of the shares
// along them. The shares of one grid light sum to 1, and the luminance they carry is exactly the
// grid light's (luminance is linear and each source's trilinear weights sum to 1).
//
// A shadow ray towards a selected grid light should see what its input lights see: aimed at input
// light i with probability share(i), its expected visibility is the share-weighted visibility of
// the cluster. These functions are the exact CPU statement of that distribution, against which the
// GPU's sampling (glsl/shadow_targets.comp) is tested.

#include <cstddef>
#include <vector>

#include "lgh/hierarchy.h"
#include "lgh/light.h"

namespace lgh {

struct LightShare {
  size_t light;  // index into the input lights
  double share;  // of the grid light's importance; the shares of one grid light sum to 1
};

struct SourceWeight {
  size_t source;  // an input light (level 1, or any level of a scatter build) or a grid light of level - 1
  double weight;  // w a, not normalised
};

// The sources of every grid light of a hierarchy that buildGather (or, with gathered = false,
// buildScatter, whose levels all come from the input lights) made from `lights`. Memory follows
// the lights: at most 8 entries per source and level.
class ClusterSources {
 public:
  ClusterSources(const std::vector<Light>& lights, const Hierarchy& hierarchy, bool gathered = true);

  // Throws std::invalid_argument for a grid light the hierarchy does not have.
  const std::vector<SourceWeight>& of(int level, size_t index) const;

  // Exact shares of every input light in grid light `index` of `level`, by light index, zero shares left out.
  std::vector<LightShare> shares(int level, size_t index) const;

  // Draws one input light from the same distribution by descending one level at a time: a source
  // with probability proportional to its weight, then one of that source's sources, down to S0.
  // `uniform` is called for each U[0, 1) variate. SIZE_MAX for a grid light without lit sources.
  template <typename Uniform>
  size_t sample(int level, size_t index, Uniform&& uniform) const {
    for (;;) {
      const std::vector<SourceWeight>& sources = of(level, index);
      double total = 0.0;
      for (const SourceWeight& s : sources) total += s.weight;
      if (!(total > 0.0)) return SIZE_MAX;
      double u = uniform() * total;
      size_t picked = sources.back().source;
      for (const SourceWeight& s : sources) {
        if (u < s.weight) {
          picked = s.source;
          break;
        }
        u -= s.weight;
      }
      if (level == 1 || !gathered_) return picked;
      index = picked;
      --level;
    }
  }

 private:
  bool gathered_;
  std::vector<std::vector<std::vector<SourceWeight>>> sources_;  // [level][grid light]
};

}  // namespace lgh
