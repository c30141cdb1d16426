#pragma once
// Lights added from the command line (lgh-render, lgh-viewer): most glTF models carry no lights.
//   --sun AZIMUTH,ELEVATION[,LUX]        a directional light (degrees; LUX default kDefaultSunLux)
//   --point X,Y,Z,INTENSITY[,R,G,B]      a point light at world position X,Y,Z (the file's frame),
//                                        INTENSITY in candela, colour default white
// Azimuth is measured in the horizontal (x, z) plane from +Z towards +X, elevation above it (+Y up, as
// glTF): the sun then stands in direction (cos e sin a, sin e, cos e cos a), as in the viewer's panel.

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "render/scene/scene.h"

namespace lgh {

inline constexpr float kDefaultSunLux = 8.0f;  // as the project's Sponza sun: a readable image at exposure 0

// Unit vector from the scene towards the sun.
glm::vec3 sunDirection(float azimuthDegrees, float elevationDegrees);
// The inverse: azimuth and elevation (degrees) of a unit vector towards the sun.
glm::vec2 sunAngles(const glm::vec3& towardsSun);

// An option value of `minCount` to `maxCount` comma-separated finite numbers; throws std::invalid_argument
// naming `option`, the value and the expected `form`.
std::vector<double> parseNumbers(const std::string& spec, const std::string& option, const std::string& form,
                                 size_t minCount, size_t maxCount);

// Parse one option value; throw std::invalid_argument naming the option and what is wrong.
PunctualLight parseSunOption(const std::string& spec);
PunctualLight parsePointOption(const std::string& spec, const Scene& scene);

// Appends the parsed lights to scene.lights (after loading, before the GPU upload).
void addCommandLineLights(Scene& scene, const std::vector<std::string>& suns, const std::vector<std::string>& points);

// True if anything in the scene emits light: a punctual light or an emissive material in use.
bool sceneHasLight(const Scene& scene);
// The one-line hint printed when it has none.
std::string noLightHint();

}  // namespace lgh
