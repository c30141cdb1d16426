#include "render/aov.h"

#include <stdexcept>

namespace lgh {
namespace {

struct AovName {
  Aov aov;
  const char* name;
};
constexpr AovName kAovNames[] = {
    {Aov::Final, "final"},           {Aov::Direct, "direct"},   {Aov::Indirect, "indirect"},
    {Aov::Irradiance, "irradiance"}, {Aov::Ratio, "ratio"},     {Aov::Visibility, "visibility"},
    {Aov::Overdraw, "overdraw"},     {Aov::History, "history"}, {Aov::Emission, "emission"},
    {Aov::Albedo, "albedo"},         {Aov::Normal, "normal"},   {Aov::Position, "position"}};

}  // namespace

Aov parseAov(const std::string& name) {
  for (const auto& a : kAovNames)
    if (name == a.name) return a.aov;
  std::string list;
  for (const auto& a : kAovNames) list += (list.empty() ? "" : ", ") + std::string(a.name);
  throw std::invalid_argument("unknown AOV '" + name + "' (choose one of: " + list + ")");
}

std::vector<std::string> aovNames() {
  std::vector<std::string> names;
  for (const auto& a : kAovNames) names.emplace_back(a.name);
  return names;
}

bool isDataAov(Aov aov) {
  return aov == Aov::Overdraw || aov == Aov::History || aov == Aov::Ratio || aov == Aov::Visibility ||
         aov == Aov::Albedo || aov == Aov::Normal || aov == Aov::Position;
}

}  // namespace lgh
