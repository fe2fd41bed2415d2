#pragma once
// CPU-side geometry, built without a GL context (so tests can check it): the coin as a closed
// cylinder (an annulus when it has a hole) whose outer rim may be rounded with the edge radius, and
// the trace ribbon (the overlay's text: overlay_text.h).

#include <glm/glm.hpp>
#include <vector>

#include "render/render_settings.h"

namespace coinroll::render {

// Which surface a coin vertex belongs to; the coin shader paints each differently.
enum class CoinPart : int { FrontFace = 0, BackFace = 1, OuterRim = 2, InnerRim = 3 };

struct CoinVertex {
  glm::vec3 position;  // m, body frame: the coin plane is body XY, its normal body Z
  glm::vec3 normal;
  float part;  // a CoinPart, as float for the vertex attribute
};

// Facets round the rim of the coin the renderer draws (and the page, from the same triangles).
inline constexpr int kCoinSegments = 128;

// Triangles (three vertices each) of the coin with `segments` facets around the rim.
std::vector<CoinVertex> coinTriangles(const CoinShape& shape, int segments);

struct RibbonVertex {
  glm::vec2 position;  // m, on the floor (x, z)
  float age;           // 0 at the newest point, 1 at the oldest
  float sliding;       // 1 where the coin slid, else 0; kTraceInTheAir where it flew
};

// RibbonVertex::sliding of a point the coin was in the air at: the trace shader draws nothing there,
// so the trace stops where the coin leaves the floor and starts again where it lands (within half a
// trace point).
inline constexpr float kTraceInTheAir = 2.0f;

// A triangle strip of the given width along `points` (oldest first). Consecutive duplicates
// are skipped; fewer than two distinct points give an empty strip.
// `slides`, `flies`: empty, or which points the coin slid at, and was in the air at.
std::vector<RibbonVertex> ribbonStrip(const std::vector<glm::vec2>& points, float width,
                                      const std::vector<bool>& slides = {}, const std::vector<bool>& flies = {});

}  // namespace coinroll::render
