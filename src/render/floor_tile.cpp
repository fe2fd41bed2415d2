#include "render/floor_tile.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace coinroll::render {

namespace {

constexpr float kMinorWidth = 0.0005f;  // m
constexpr float kMajorWidth = 0.0012f;  // m

float toSrgb(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

// Fraction of the texel [x0, x0 + step) covered by lines of `width` centred on multiples of `spacing`.
float lineCoverage(float x0, float step, float spacing, float width) {
  const float nearest = std::round((x0 + 0.5f * step) / spacing) * spacing;
  const float lo = std::max(x0, nearest - 0.5f * width), hi = std::min(x0 + step, nearest + 0.5f * width);
  return std::max(0.0f, hi - lo) / step;
}

}  // namespace

image::Image floorTile(int pixels, const FloorColours& colours) {
  image::Image tile(pixels, pixels);
  const float step = kFloorTileMetres / static_cast<float>(pixels);
  for (int j = 0; j < pixels; ++j) {
    for (int i = 0; i < pixels; ++i) {
      const float x = static_cast<float>(i) * step, z = static_cast<float>(j) * step;
      // Lines along both axes: the union of coverage, so crossings are not counted twice.
      auto covered = [&](float spacing, float width) {
        const float cx = lineCoverage(x, step, spacing, width), cz = lineCoverage(z, step, spacing, width);
        return cx + cz - cx * cz;
      };
      const float minor = covered(kFloorGridMetres, kMinorWidth), major = covered(kFloorTileMetres, kMajorWidth);
      std::uint8_t* p = tile.pixel(i, j);
      for (int c = 0; c < 3; ++c) {
        const float withMinor = colours.floor[c] + (colours.minorLine[c] - colours.floor[c]) * minor;
        const float linear = withMinor + (colours.majorLine[c] - withMinor) * major;
        p[c] = static_cast<std::uint8_t>(std::lround(255.0f * std::clamp(toSrgb(linear), 0.0f, 1.0f)));
      }
      p[3] = 255;
    }
  }
  return tile;
}

}  // namespace coinroll::render
