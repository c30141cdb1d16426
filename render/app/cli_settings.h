#pragma once
// Turns the RenderSettings list into CLI11 options (--name, default shown, range checked).
#include <CLI/CLI.hpp>

#include "render/settings.h"

namespace lgh {

inline void addSettingsOptions(CLI::App& app, RenderSettings& settings) {
  visitSettings(settings, [&](auto& value, const SettingInfo& info) {
    using T = std::decay_t<decltype(value)>;
    const std::string flag = std::string("--") + info.name;
    if constexpr (std::is_same_v<T, bool>) {
      // Booleans take an explicit value so a default of true can be turned off: --direct-shadows=false.
      app.add_option(flag, value, info.help)->capture_default_str();
    } else {
      CLI::Option* option = app.add_option(flag, value, info.help)->capture_default_str();
      if constexpr (std::is_arithmetic_v<T>)
        if (info.min < info.max) option->check(CLI::Range(T(info.min), T(info.max)));
    }
  });
}

}  // namespace lgh
