#pragma once
// The floor's look, computed once on the CPU: one 10 cm x 10 cm tile of the metric grid (thin
// lines every centimetre, a stronger one on the tile's edge, so every 10 cm), lit and in sRGB,
// repeated over the floor by the sampler. Mipmaps of it fade the grid smoothly with distance, at
// a fraction of the cost of drawing the lines in the fragment shader per pixel.

#include <glm/glm.hpp>

#include "image/image.h"

namespace coinroll::render {

inline constexpr float kFloorTileMetres = 0.10f;
inline constexpr float kFloorGridMetres = 0.01f;  // the thin lines' spacing

// Linear reflectance times the key light's irradiance on a flat floor, RGB.
struct FloorColours {
  glm::vec3 floor{0.0f}, minorLine{0.0f}, majorLine{0.0f};
};

// `pixels` x `pixels` RGBA; texel (i, j) covers floor [i, i+1) x [j, j+1) * tile / pixels.
image::Image floorTile(int pixels, const FloorColours& colours);

}  // namespace coinroll::render
