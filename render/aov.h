#pragma once
// The images a frame can hand back (AOVs), by name: lgh-render's --aov, the viewer's view and the display
// pass's encoding all use this list. No GL and no renderer here, so passes may include it.

#include <string>
#include <vector>

namespace lgh {

// Images a frame can hand back (AOVs).
//   indirect    radiance through the LGH, unshadowed (albedo / pi x irradiance); with the lightcuts, shadowed
//               (ratio, visibility and overdraw are the LGH's: with the lightcuts they hold nothing new)
//   overdraw    heat map of fragments rasterized per pixel in the light pass (needs settings.overdraw)
//   irradiance  the light pass's irradiance (before albedo), accumulated over the frames the history holds;
//               with the lightcuts their shadowed irradiance, accumulated and filtered
//   ratio       unfiltered visibility ratio of the indirect light (mean of the k shadow rays, accumulated)
//   visibility  the filtered ratio that multiplies the indirect light
//   history     frames in each pixel's accumulated history (heat map; black without accumulation): where a
//               moved light or mesh kept it and where it started anew
enum class Aov {
  Final,
  Direct,
  Indirect,
  Irradiance,
  Ratio,
  Visibility,
  Overdraw,
  History,
  Emission,
  Albedo,
  Normal,
  Position
};
Aov parseAov(const std::string& name);
std::vector<std::string> aovNames();
// AOVs that hold data rather than radiance: written without exposure or tone curve.
bool isDataAov(Aov aov);

}  // namespace lgh
