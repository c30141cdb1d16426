#pragma once
// Turns the RenderSettings list into CLI11 options by tier (render/settings.h): user settings as
// --name options shown by --help, advanced ones as --name options shown by --help-all only, ablations
// through --set NAME=VALUE only (which sets any setting), listed by --help-all.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "render/settings.h"

namespace lgh {

// The option group of what --help leaves out: visible only when the command line asks for --help-all
// (CLI11 hides a group named ""). Checked before the options are declared.
inline std::string advancedGroup(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--help-all") == 0) return "Advanced";
  return "";
}

template <typename T>
std::string settingValueText(const T& value) {
  std::ostringstream text;
  text << std::boolalpha << value;
  return text.str();
}

// Declares the user and advanced settings as --name options (the advanced ones in group `advanced`) and
// returns the ablations, one line each with its default, for a help text.
inline std::string addSettingsOptions(CLI::App& app, RenderSettings& settings, const std::string& advanced) {
  std::string ablations;
  visitSettings(settings, [&](auto& value, const SettingInfo& info) {
    using T = std::decay_t<decltype(value)>;
    if (info.tier == SettingTier::Ablation) {
      std::string assignment = std::string(info.name) + "=" + settingValueText(value);
      assignment.resize(std::max<size_t>(assignment.size() + 2, 38), ' ');  // the help in one column
      ablations += "  " + assignment + info.help + "\n";
      return;
    }
    const std::string flag = std::string("--") + info.name;
    // Booleans take an explicit value so a default of true can be turned off: --direct-shadows=false. An enum
    // is given by its choice's name (checked below, before the callback).
    CLI::Option* option = nullptr;
    if constexpr (std::is_enum_v<T>)
      option =
          app.add_option_function<std::string>(
                 flag, [&value, choices = info.choices](const std::string& v) { value = choiceValue<T>(v, choices); },
                 info.help)
              ->default_str(choiceName(value, info.choices));
    else
      option = app.add_option(flag, value, info.help)->capture_default_str();
    if (info.tier != SettingTier::User) option->group(advanced);
    if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>)
      if (info.min < info.max) option->check(CLI::Range(T(info.min), T(info.max)));
    if constexpr (std::is_same_v<T, std::string> || std::is_enum_v<T>)
      if (info.choices)
        option->check(CLI::Validator(
            [choices = info.choices](std::string& v) {
              return isChoice(choices, v) ? std::string() : "'" + v + "' is not one of " + choices;
            },
            info.choices));
  });
  return ablations;
}

// The settings of lgh-render and lgh-viewer: --help shows the user settings, --help-all every one, and
// --set NAME=VALUE sets any (applied after the --name options: CLI11 runs callbacks in declaration
// order). Returns the group the apps' own advanced options go in.
inline std::string addSettingsCommandLine(CLI::App& app, RenderSettings& settings, int argc, char** argv) {
  const std::string advanced = advancedGroup(argc, argv);
  const std::string ablations = addSettingsOptions(app, settings, advanced);
  app.add_option_function<std::vector<std::string>>(
         "--set",
         [&settings](const std::vector<std::string>& assignments) {
           for (const std::string& assignment : assignments) try {
               applySetting(settings, assignment);
             } catch (const std::invalid_argument& e) {
               throw CLI::ValidationError("--set", e.what());
             }
         },
         "NAME=VALUE: any setting, the ablations in docs/settings.md too; repeatable")
      ->group(advanced);
  app.set_help_all_flag("--help-all", "list every setting: the advanced ones and the ablations");
  if (advanced.empty())
    app.footer("More settings: --help-all. Measurements and the estimator's design: docs/.");
  else
    app.footer("Ablation settings (--set NAME=VALUE; docs/settings.md):\n" + ablations);
  return advanced;
}

}  // namespace lgh
