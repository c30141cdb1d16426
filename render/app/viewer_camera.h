#pragma once
// Orbit and fly navigation over an lgh::Camera. Until it is moved, camera() is exactly the camera it
// was reset to (a scene camera renders as lgh-render renders it); a move re-derives the orientation
// from yaw and pitch about the world's +Y, dropping any roll the scene camera had.

#include "render/scene/scene.h"

namespace lgh {

class CameraController {
 public:
  // `sceneSize` (the scene's diagonal) scales movement speeds and the smallest orbit distance.
  void reset(const Camera& camera, float sceneSize);
  const Camera& camera() const { return camera_; }

  void orbit(float yaw, float pitch);  // radians, about the target
  void look(float yaw, float pitch);   // radians, in place (fly)
  void pan(float right, float up);     // in scene sizes
  void dolly(float steps);             // towards the target (orbit) or along the view (fly)
  void move(const glm::vec3& local);   // in scene sizes: x right, y up, z forward
  float targetDistance() const { return distance_; }

 private:
  glm::vec3 forward() const;
  void applyAngles();  // orientation from yaw and pitch

  Camera camera_;
  float sceneSize_ = 1.0f;
  float yaw_ = 0.0f, pitch_ = 0.0f;  // forward = (cos p sin y, sin p, -cos p cos y): yaw 0 looks down -Z
  float distance_ = 1.0f;            // from the camera to the orbit target, along forward
};

}  // namespace lgh
