#include "render/camera.h"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

namespace coinroll::render {

CameraMatrices cameraMatrices(const CameraView& camera, int width, int height) {
  const float distance = glm::length(camera.eye - camera.target);
  const float nearPlane = std::max(1e-3f, 0.02f * distance);
  const float farPlane = 200.0f * distance;
  const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  // Looking straight down makes y useless as "up"; fall back to -z so the view stays defined.
  const glm::vec3 up = std::abs(forward.y) > 0.999f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  return {glm::lookAt(camera.eye, camera.target, up),
          glm::perspective(glm::radians(camera.fovYDegrees), static_cast<float>(width) / static_cast<float>(height),
                           nearPlane, farPlane)};
}

glm::vec2 pixelFromWorld(const CameraView& camera, int width, int height, const glm::vec3& world) {
  const CameraMatrices m = cameraMatrices(camera, width, height);
  const glm::vec4 clip = m.projection * m.view * glm::vec4(world, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {(ndc.x + 1.0f) * 0.5f * static_cast<float>(width), (1.0f - ndc.y) * 0.5f * static_cast<float>(height)};
}

}  // namespace coinroll::render
