#include "lgh/cluster_shares.h"

#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace lgh {
namespace {

// Adds every source with non-zero importance to the grid lights at the corners of its cell.
template <typename Sources, typename Importance>
void collectSources(const Sources& sources, Importance&& importance, const GridGeometry& grid, int level,
                    const std::vector<GridLight>& gridLights, std::vector<std::vector<SourceWeight>>& out) {
  std::unordered_map<uint64_t, size_t> indexOf;
  for (size_t g = 0; g < gridLights.size(); ++g) indexOf[packVertex(gridLights[g].vertex)] = g;
  out.assign(gridLights.size(), {});
  for (size_t s = 0; s < sources.size(); ++s) {
    const double a = importance(sources[s]);
    if (!(a > 0.0)) continue;
    forEachCorner(grid, level, glm::dvec3(sources[s].position), [&](const glm::ivec3& v, double w, const glm::dvec3&) {
      const auto it = indexOf.find(packVertex(v));
      if (it == indexOf.end())
        throw std::invalid_argument("ClusterSources: the hierarchy was not built from these lights");
      out[it->second].push_back({s, w * a});
    });
  }
}

}  // namespace

ClusterSources::ClusterSources(const std::vector<Light>& lights, const Hierarchy& hierarchy, bool gathered)
    : gathered_(gathered), sources_(hierarchy.levels.size()) {
  for (size_t level = 1; level < hierarchy.levels.size(); ++level) {
    if (level == 1 || !gathered)
      collectSources(
          lights, [](const Light& l) { return luminance(glm::dvec3(l.intensity)); }, hierarchy.grid, int(level),
          hierarchy.levels[level], sources_[level]);
    else
      collectSources(
          hierarchy.levels[level - 1], [](const GridLight& g) { return luminance(g.intensity); }, hierarchy.grid,
          int(level), hierarchy.levels[level], sources_[level]);
  }
}

const std::vector<SourceWeight>& ClusterSources::of(int level, size_t index) const {
  if (level < 1 || size_t(level) >= sources_.size() || index >= sources_[size_t(level)].size())
    throw std::invalid_argument("ClusterSources: no grid light " + std::to_string(index) + " at level " +
                                std::to_string(level));
  return sources_[size_t(level)][index];
}

std::vector<LightShare> ClusterSources::shares(int level, size_t index) const {
  const std::vector<SourceWeight>& sources = of(level, index);
  double total = 0.0;
  for (const SourceWeight& s : sources) total += s.weight;
  std::map<size_t, double> shares;
  if (total > 0.0) {
    for (const SourceWeight& s : sources) {
      const double share = s.weight / total;
      if (level == 1 || !gathered_) {
        shares[s.source] += share;
        continue;
      }
      for (const LightShare& below : this->shares(level - 1, s.source)) shares[below.light] += share * below.share;
    }
  }
  std::vector<LightShare> out;
  for (const auto& [light, share] : shares)
    if (share > 0.0) out.push_back({light, share});
  return out;
}

}  // namespace lgh
