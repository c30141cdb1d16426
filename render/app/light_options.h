#pragma once
// --sun and --point for lgh-render and lgh-viewer (render/scene/added_lights.h does the work).
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace lgh {

struct AddedLightOptions {
  std::vector<std::string> suns, points;
};

// `group`: the option group they are listed in (render/app/cli_settings.h, addSettingsCommandLine).
inline void addLightOptions(CLI::App& app, AddedLightOptions& options, const std::string& group) {
  app.add_option("--sun", options.suns,
                 "add a directional light: AZIMUTH,ELEVATION[,LUX] (degrees from +Z towards +X, above the horizon; "
                 "default 8 lux); repeatable")
      ->take_all()
      ->allow_extra_args(false)
      ->group(group);
  app.add_option("--point", options.points,
                 "add a point light: X,Y,Z,INTENSITY[,R,G,B] (world position, candela, linear colour); repeatable")
      ->take_all()
      ->allow_extra_args(false)
      ->group(group);
}

}  // namespace lgh
