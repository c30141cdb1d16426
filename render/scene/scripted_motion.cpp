#include "render/scene/scripted_motion.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

#include "render/scene/added_lights.h"

namespace lgh {

ScriptedMotion parseScriptedMotion(const std::string& sunStep, const std::string& pointStep, double orbitStep) {
  ScriptedMotion m;
  if (!sunStep.empty()) {
    const std::vector<double> v = parseNumbers(sunStep, "--sun-step", "DAZIMUTH,DELEVATION in degrees a frame", 2, 2);
    m.sunStep = glm::vec2(float(v[0]), float(v[1]));
  }
  if (!pointStep.empty()) {
    const std::vector<double> v = parseNumbers(pointStep, "--point-step", "DX,DY,DZ in world units a frame", 3, 3);
    m.pointStep = glm::vec3(float(v[0]), float(v[1]), float(v[2]));
  }
  if (!std::isfinite(orbitStep)) throw std::invalid_argument("--orbit-step must be a finite number of degrees");
  m.orbitStep = float(orbitStep);
  return m;
}

PoseChange applyScriptedMotion(const ScriptedMotion& motion, int frame, const std::vector<PunctualLight>& start,
                               Scene& scene, Camera& camera) {
  PoseChange change;
  const float steps = float(frame);
  const SceneAnimation& animation = scene.animation;
  for (size_t i = 0; i < start.size() && i < scene.lights.size(); ++i) {
    // A light the scene's own animation carries is left to it.
    if (animation.carriesLight(i)) continue;
    PunctualLight light = start[i];
    if (light.type == LightType::Directional && motion.sunStep != glm::vec2(0.0f)) {
      const glm::vec2 angles = sunAngles(-light.direction) + steps * motion.sunStep;
      light.direction = -sunDirection(angles.x, std::clamp(angles.y, -90.0f, 90.0f));
    } else if (light.type == LightType::Point && motion.pointStep != glm::vec3(0.0f)) {
      light.position += steps * motion.pointStep;
    } else {
      continue;
    }
    scene.lights[i] = light;
    change.lights.push_back(i);
  }
  if (motion.orbitStep != 0.0f) {
    const glm::vec3 centre = scene.bounds.empty() ? glm::vec3(0.0f) : scene.bounds.center();
    const glm::mat3 turn(glm::rotate(glm::mat4(1.0f), glm::radians(steps * motion.orbitStep), glm::vec3(0, 1, 0)));
    camera.position = centre + turn * (camera.position - centre);
    camera.orientation = turn * camera.orientation;
  }
  return change;
}

}  // namespace lgh
