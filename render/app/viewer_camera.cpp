#include "render/app/viewer_camera.h"

#include <algorithm>
#include <cmath>

namespace lgh {
namespace {
constexpr float kMaxPitch = 1.55f;  // just short of straight up or down, where yaw is undefined
}

void CameraController::reset(const Camera& camera, float sceneSize) {
  camera_ = camera;
  sceneSize_ = std::max(sceneSize, 1e-6f);
  const glm::vec3 f = -camera.orientation[2];
  pitch_ = std::asin(std::clamp(f.y, -1.0f, 1.0f));
  yaw_ = std::atan2(f.x, -f.z);
  // Orbit about a point a third of the scene ahead: the scene's centre is often behind a wall of
  // an interior (Sponza's atrium), and a point ahead keeps the first drag predictable.
  distance_ = sceneSize_ / 3.0f;
}

glm::vec3 CameraController::forward() const {
  return {std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), -std::cos(pitch_) * std::cos(yaw_)};
}

void CameraController::applyAngles() {
  pitch_ = std::clamp(pitch_, -kMaxPitch, kMaxPitch);
  const glm::vec3 f = forward();
  const glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, f);
  camera_.orientation = glm::mat3(right, up, -f);
}

void CameraController::orbit(float yaw, float pitch) {
  const glm::vec3 target = camera_.position + forward() * distance_;
  yaw_ += yaw;
  pitch_ += pitch;
  applyAngles();
  camera_.position = target - forward() * distance_;
}

void CameraController::look(float yaw, float pitch) {
  yaw_ += yaw;
  pitch_ += pitch;
  applyAngles();
}

void CameraController::pan(float right, float up) {
  camera_.position += (camera_.orientation[0] * right + camera_.orientation[1] * up) * sceneSize_;
}

void CameraController::dolly(float steps) {
  // Each step covers 15% of the way to the target, never passing it: the target comes along once
  // the camera is close, so scrolling keeps moving forward.
  const float travel = distance_ * (1.0f - std::pow(0.85f, steps));
  camera_.position += forward() * travel;
  distance_ = std::max(distance_ - travel, 0.02f * sceneSize_);
}

void CameraController::move(const glm::vec3& local) {
  const glm::vec3 f = forward(), right = camera_.orientation[0];
  camera_.position += (right * local.x + glm::vec3(0, 1, 0) * local.y + f * local.z) * sceneSize_;
}

}  // namespace lgh
