#include "render/settings.h"

#include <algorithm>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "render/text_parse.h"

namespace lgh {

std::vector<std::string> choiceList(const char* choices) {
  std::vector<std::string> list;
  const std::string text = choices;
  for (size_t begin = 0; begin <= text.size();) {
    const size_t end = std::min(text.find('|', begin), text.size());
    list.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  return list;
}

bool isChoice(const char* choices, const std::string& value) {
  const std::vector<std::string> list = choiceList(choices);
  return !value.empty() && std::find(list.begin(), list.end(), value) != list.end();
}

SettingInfo settingInfo(const std::string& name) {
  RenderSettings settings;
  bool found = false;
  SettingInfo info{"", ""};
  visitSettings(settings, [&](const auto&, const SettingInfo& i) {
    if (name != i.name) return;
    info = i;
    found = true;
  });
  if (!found) throw std::invalid_argument("unknown setting '" + name + "'");
  return info;
}

std::ostream& operator<<(std::ostream& out, IndirectMethod method) {
  return out << choiceName(method, kIndirectMethodChoices);
}

std::ostream& operator<<(std::ostream& out, BvhLayout layout) { return out << choiceName(layout, kBvhLayoutChoices); }

std::ostream& operator<<(std::ostream& out, RtslcDenoiser denoiser) {
  return out << choiceName(denoiser, kRtslcDenoiserChoices);
}

std::ostream& operator<<(std::ostream& out, HistoryMotion motion) {
  return out << choiceName(motion, kHistoryMotionChoices);
}

void setSetting(RenderSettings& settings, const std::string& name, const std::string& value) {
  bool found = false;
  std::string names;
  visitSettings(settings, [&](auto& field, const SettingInfo& info) {
    using T = std::decay_t<decltype(field)>;
    names += (names.empty() ? "" : ", ") + std::string(info.name);
    if (name != info.name) return;
    found = true;
    const std::string where = "setting '" + name + "'";
    if constexpr (std::is_same_v<T, bool>) {
      if (value == "true" || value == "1" || value == "on")
        field = true;
      else if (value == "false" || value == "0" || value == "off")
        field = false;
      else
        throw std::invalid_argument(where + ": '" + value + "' is not true or false");
    } else if constexpr (std::is_enum_v<T>) {
      if (!isChoice(info.choices, value))
        throw std::invalid_argument(where + ": '" + value + "' is not one of " + info.choices);
      field = choiceValue<T>(value, info.choices);
    } else if constexpr (std::is_arithmetic_v<T>) {
      T v{};
      if (!parseNumber(value, v)) throw std::invalid_argument(where + ": '" + value + "' is not a number");
      if (info.min < info.max && (double(v) < info.min || double(v) > info.max)) {
        std::ostringstream msg;
        msg << where << ": " << value << " is outside [" << info.min << ", " << info.max << "]";
        throw std::invalid_argument(msg.str());
      }
      field = v;
    } else {
      if (info.choices && !isChoice(info.choices, value))
        throw std::invalid_argument(where + ": '" + value + "' is not one of " + info.choices);
      field = value;
    }
  });
  if (!found) throw std::invalid_argument("unknown setting '" + name + "' (one of: " + names + ")");
}

void applySetting(RenderSettings& settings, const std::string& assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos) throw std::invalid_argument("'" + assignment + "': expected NAME=VALUE");
  setSetting(settings, assignment.substr(0, eq), assignment.substr(eq + 1));
}

}  // namespace lgh
