#include "render/scale_bar.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace coinroll::render {

float scaleBarMetres(const ScaleBar& bar, float coinRadius) {
  if (bar.metres > 0) return bar.metres;
  const double decade = std::pow(10.0, std::floor(std::log10(static_cast<double>(coinRadius))));
  for (const double step : {5.0, 2.0, 1.0}) {
    if (step * decade <= coinRadius) return static_cast<float>(step * decade);
  }
  return static_cast<float>(decade);
}

std::string scaleBarLabel(float metres) {
  const double m = metres;
  if (m >= 1) return fmt::format("{:g} m", m);
  if (m >= 0.01) return fmt::format("{:g} cm", 100 * m);
  return fmt::format("{:g} mm", 1000 * m);
}

ScaleBarPlacement placeScaleBar(const ScaleBar& bar, float coinRadius, const CameraView& camera, const CoinPose& coin,
                                int pictureHeight) {
  const float length = scaleBarMetres(bar, coinRadius);
  const glm::vec3 forward = glm::normalize(camera.target - camera.eye);
  // The camera's own right (camera.cpp's look-at up: y, or -z looking straight down), flattened
  // onto the floor: horizontal in the picture, both ends at one depth.
  const glm::vec3 up = std::abs(forward.y) > 0.999f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  const glm::vec3 right = glm::normalize(glm::vec3(glm::cross(forward, up).x, 0.0f, glm::cross(forward, up).z));
  const glm::vec3 towardsCamera = glm::cross(right, glm::vec3(0, 1, 0));
  const glm::vec3 centre = glm::vec3(coin.centre.x, 0.0f, coin.centre.z) + 2.0f * coinRadius * towardsCamera;
  // A pixel at the bar's distance, in metres across the floor towards the camera (foreshortened
  // by the sine of the view's elevation there); the bar is a 240th of the picture high, at least 3 px.
  const glm::vec3 ray = centre - camera.eye;
  const float pixelMetres =
      2.0f * glm::length(ray) * std::tan(glm::radians(0.5f * camera.fovYDegrees)) / static_cast<float>(pictureHeight);
  const float elevation = std::max(0.2f, std::abs(ray.y) / glm::length(ray));
  const float pixels = std::max(3.0f, static_cast<float>(pictureHeight) / 240.0f);
  return {.start = centre - 0.5f * length * right,
          .end = centre + 0.5f * length * right,
          .across = towardsCamera,
          .thickness = pixels * pixelMetres / elevation,
          .label = scaleBarLabel(length)};
}

}  // namespace coinroll::render
