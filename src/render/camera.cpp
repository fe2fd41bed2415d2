#include "render/camera.h"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

namespace coinroll::render {

ClipPlanes clipPlanes(const CameraView& camera) {
  const float distance = glm::length(camera.eye - camera.target);
  return {.near = std::max(1e-3f, 0.02f * distance), .far = 200.0f * distance};
}

glm::vec3 upOf(const CameraView& camera) {
  const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  return std::abs(forward.y) > 0.999f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
}

CameraMatrices cameraMatrices(const CameraView& camera, int width, int height) {
  const ClipPlanes planes = clipPlanes(camera);
  return {glm::lookAt(camera.eye, camera.target, upOf(camera)),
          glm::perspective(glm::radians(camera.fovYDegrees), static_cast<float>(width) / static_cast<float>(height),
                           planes.near, planes.far)};
}

glm::vec2 pixelFromWorld(const CameraView& camera, int width, int height, const glm::vec3& world) {
  const CameraMatrices m = cameraMatrices(camera, width, height);
  const glm::vec4 clip = m.projection * m.view * glm::vec4(world, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {(ndc.x + 1.0f) * 0.5f * static_cast<float>(width), (1.0f - ndc.y) * 0.5f * static_cast<float>(height)};
}

}  // namespace coinroll::render
