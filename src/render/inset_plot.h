#pragma once
// The inset plot's geometry (frame_snapshot.h InsetPlot), built without a GL context so a test can
// check where it lies: triangles in the overlay's vertex format, drawn by the overlay's program
// with the atlas's solid texel for lines and its glyphs for the labels.

#include <glm/glm.hpp>
#include <array>
#include <vector>

#include "render/frame_snapshot.h"
#include "render/overlay_text.h"

namespace coinroll::render {

// The curves' colours, in order: orange and blue, apart in hue and in lightness, so both read on
// the classic theme's dark panel and the paper theme's light one, and in grey print.
inline constexpr std::array<glm::vec4, 2> kInsetCurveColours = {glm::vec4(0.95f, 0.45f, 0.05f, 1.0f),
                                                                glm::vec4(0.20f, 0.55f, 0.95f, 1.0f)};

// The plot's box, pixels (origin top-left): the curves' x = 0..1 spans min.x..max.x and y = 0..1
// spans max.y..min.y (up).
struct InsetBox {
  glm::vec2 min{0.0f}, max{0.0f};
};

// Appends the inset's panel, labels, axes, curves and marker for a `width` x `height` picture to
// `out`, in the lower right corner; returns the plot's box.
InsetBox appendInsetPlot(const GlyphAtlas& atlas, const InsetPlot& plot, int width, int height, const TextStyle& style,
                         std::vector<TextVertex>& out);

}  // namespace coinroll::render
