#include "render/scene/added_lights.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "render/text_parse.h"

namespace lgh {
namespace {

constexpr double kRadians = 3.14159265358979323846 / 180.0;

}  // namespace

std::vector<double> parseNumbers(const std::string& spec, const std::string& option, const std::string& form,
                                 size_t minCount, size_t maxCount) {
  std::vector<double> values;
  std::stringstream in(spec);
  std::string item;
  const auto bad = [&](const std::string& why) {
    return std::invalid_argument(option + " " + spec + ": " + why + " (expected " + form + ")");
  };
  while (std::getline(in, item, ',')) {
    double v = 0;
    if (!parseNumber(item, v)) throw bad("'" + item + "' is not a number");
    if (!std::isfinite(v) || std::abs(v) > 3.0e38) throw bad("'" + item + "' is not a finite float");
    values.push_back(v);
  }
  if (!spec.empty() && spec.back() == ',') throw bad("trailing comma");
  if (values.size() < minCount || values.size() > maxCount) throw bad(std::to_string(values.size()) + " numbers");
  return values;
}

glm::vec3 sunDirection(float azimuthDegrees, float elevationDegrees) {
  const double a = double(azimuthDegrees) * kRadians, e = double(elevationDegrees) * kRadians;
  return glm::vec3(glm::dvec3(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)));
}

glm::vec2 sunAngles(const glm::vec3& towardsSun) {
  const glm::vec3 d = glm::normalize(towardsSun);
  return glm::vec2(float(std::atan2(d.x, d.z) / kRadians),
                   float(std::asin(std::clamp(double(d.y), -1.0, 1.0)) / kRadians));
}

PunctualLight parseSunOption(const std::string& spec) {
  const std::string form = "AZIMUTH,ELEVATION[,LUX] in degrees and lux";
  const std::vector<double> v = parseNumbers(spec, "--sun", form, 2, 3);
  if (v[1] < -90.0 || v[1] > 90.0)
    throw std::invalid_argument("--sun " + spec + ": elevation must lie in [-90, 90] degrees (expected " + form + ")");
  const double lux = v.size() > 2 ? v[2] : double(kDefaultSunLux);
  if (lux < 0.0) throw std::invalid_argument("--sun " + spec + ": LUX must be >= 0");
  PunctualLight sun;
  sun.name = "sun (--sun " + spec + ")";
  sun.type = LightType::Directional;
  sun.direction = -sunDirection(float(v[0]), float(v[1]));  // the direction the light travels
  sun.intensity = glm::vec3(float(lux));
  return sun;
}

PunctualLight parsePointOption(const std::string& spec, const Scene& scene) {
  const std::string form = "X,Y,Z,INTENSITY[,R,G,B]: world position, candela, linear colour";
  const std::vector<double> v = parseNumbers(spec, "--point", form, 4, 7);
  if (v.size() != 4 && v.size() != 7)
    throw std::invalid_argument("--point " + spec + ": give R,G,B together (expected " + form + ")");
  if (v[3] < 0.0) throw std::invalid_argument("--point " + spec + ": INTENSITY must be >= 0");
  const glm::dvec3 colour = v.size() == 7 ? glm::dvec3(v[4], v[5], v[6]) : glm::dvec3(1.0);
  if (glm::any(glm::lessThan(colour, glm::dvec3(0.0))))
    throw std::invalid_argument("--point " + spec + ": R,G,B must be >= 0");
  PunctualLight point;
  point.name = "point (--point " + spec + ")";
  point.type = LightType::Point;
  // World coordinates as the user reads them in the file; scene space is world minus the origin (double).
  point.position = glm::vec3(glm::dvec3(v[0], v[1], v[2]) - scene.origin);
  point.intensity = glm::vec3(colour * v[3]);
  return point;
}

void addCommandLineLights(Scene& scene, const std::vector<std::string>& suns, const std::vector<std::string>& points) {
  for (const std::string& s : suns) scene.lights.push_back(parseSunOption(s));
  for (const std::string& p : points) scene.lights.push_back(parsePointOption(p, scene));
}

bool sceneHasLight(const Scene& scene) {
  for (const PunctualLight& l : scene.lights)
    if (l.intensity.r > 0 || l.intensity.g > 0 || l.intensity.b > 0) return true;
  for (const MaterialRange& r : scene.materialRanges)
    if (scene.materials[r.material].isEmissive()) return true;
  return false;
}

std::string noLightHint() {
  return "the scene has no lights (no punctual lights, no emissive materials) and renders black; add one with "
         "--sun AZIMUTH,ELEVATION[,LUX] or --point X,Y,Z,INTENSITY[,R,G,B]";
}

}  // namespace lgh
