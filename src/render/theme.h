#pragma once
// The colours of each render.theme (render_settings.h Theme), in one place: what the floor tile,
// the sky, the trace shader, the overlay and the scale bar are drawn in.

#include <glm/glm.hpp>

#include "render/floor_tile.h"
#include "render/overlay_text.h"
#include "render/render_settings.h"

namespace coinroll::render {

// The trace ribbon's colours (linear RGB into an sRGB target, as the shader has always mixed
// them): `recent` at the newest point, `old` at the oldest, each while rolling and while sliding,
// and its opacity from newest to oldest.
struct TraceColours {
  glm::vec3 recentRolling{0.0f}, oldRolling{0.0f}, recentSliding{0.0f}, oldSliding{0.0f};
  glm::vec2 opacity{0.0f};  // (newest, oldest)
};

struct Palette {
  glm::vec3 backgroundSrgb{0.0f};  // the sky behind the floor, which the floor fades into
  FloorColours floor;
  TraceColours trace;
  TextStyle overlay;  // the corner overlay and the scale bar's label
  glm::vec4 scaleBar{0.0f};
};

const Palette& palette(Theme theme);

}  // namespace coinroll::render
