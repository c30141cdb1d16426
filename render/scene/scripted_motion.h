#pragma once
// The motions a user reaches for in a scene without an animation of its own, for sequences
// (lgh-render --sequence, lgh-bench motion), frame by frame:
//   --sun-step DAZ,DEL     every directional light turns DAZ degrees of azimuth and DEL of elevation a
//                          frame (the angles of added_lights.h; elevation held within [-90, 90])
//   --point-step DX,DY,DZ  every point light moves by (DX, DY, DZ) a frame (world units)
//   --orbit-step DEG       the camera turns DEG a frame about the vertical axis through the scene's centre
// A glTF animation, where the scene has one, plays as well (poseScene); these move what it leaves.

#include <string>
#include <vector>

#include "render/scene/scene.h"

namespace lgh {

struct ScriptedMotion {
  glm::vec2 sunStep{0.0f};    // degrees of azimuth, elevation a frame
  glm::vec3 pointStep{0.0f};  // world units a frame
  float orbitStep = 0.0f;     // degrees a frame
  bool empty() const { return sunStep == glm::vec2(0.0f) && pointStep == glm::vec3(0.0f) && orbitStep == 0.0f; }
};

// From the options' values ("" for an option not given); throws std::invalid_argument naming the option.
ScriptedMotion parseScriptedMotion(const std::string& sunStep, const std::string& pointStep, double orbitStep);

// Frame `frame` of the motion: scene.lights set from `start` (the lights at frame 0) moved `frame` steps,
// and `camera` (at frame 0) orbited. Returns the lights it moved, for SceneGpu::follow.
PoseChange applyScriptedMotion(const ScriptedMotion& motion, int frame, const std::vector<PunctualLight>& start,
                               Scene& scene, Camera& camera);

}  // namespace lgh
