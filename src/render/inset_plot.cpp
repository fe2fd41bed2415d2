#include "render/inset_plot.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace coinroll::render {

namespace {

// Of the picture: the plot is a third of its width and a fifth of its height, so it reads at 480p
// and leaves the coin, framed in the middle, in view.
constexpr float kPlotWidthFraction = 0.32f, kPlotHeightFraction = 0.2f;
constexpr float kFutureAlpha = 0.3f;  // the part of a curve still to come: there, but faint

// A line from a to b, `thickness` pixels across, as two triangles of the atlas's solid texel.
void appendSegment(std::vector<TextVertex>& out, glm::vec2 a, glm::vec2 b, float thickness, glm::vec4 colour,
                   glm::vec2 solid) {
  const glm::vec2 along = b - a;
  const float length = glm::length(along);
  if (length == 0) return;
  const glm::vec2 across = glm::vec2(-along.y, along.x) / length * (0.5f * thickness);
  const TextVertex p{a - across, solid, colour}, q{b - across, solid, colour}, r{b + across, solid, colour},
      s{a + across, solid, colour};
  for (const TextVertex& v : {p, q, r, p, r, s}) out.push_back(v);
}

}  // namespace

InsetBox appendInsetPlot(const GlyphAtlas& atlas, const InsetPlot& plot, int width, int height, const TextStyle& style,
                         std::vector<TextVertex>& out) {
  const float line = atlas.lineHeight();
  const float margin = std::round(0.5f * line), padding = std::round(line / 3.0f);
  const float thickness = std::max(1.5f, static_cast<float>(height) / 360.0f);  // pixels
  std::vector<std::string> labels;
  for (const InsetCurve& curve : plot.curves) labels.push_back(curve.label);
  const glm::vec2 labelSize = textPanelSize(atlas, labels);
  const float plotWidth = std::max(std::round(kPlotWidthFraction * static_cast<float>(width)), labelSize.x);
  const float plotHeight = std::round(kPlotHeightFraction * static_cast<float>(height));
  const glm::vec2 panelSize(plotWidth + 2 * padding, labelSize.y + plotHeight + padding);
  const glm::vec2 panelMin = glm::vec2(width, height) - margin - panelSize;
  // The panel, then each label in its curve's colour on it.
  TextStyle clear = style;
  clear.panel = glm::vec4(0.0f);
  const glm::vec2 solid = atlas.solidTexel();
  appendSegment(out, panelMin + glm::vec2(0.0f, 0.5f * panelSize.y),
                panelMin + glm::vec2(panelSize.x, 0.5f * panelSize.y), panelSize.y, style.panel, solid);
  for (std::size_t i = 0; i < plot.curves.size(); ++i) {
    clear.ink = kInsetCurveColours[i % kInsetCurveColours.size()];
    appendTextPanel(atlas, {plot.curves[i].label}, panelMin + glm::vec2(0.0f, line * static_cast<float>(i)), clear,
                    out);
  }
  const InsetBox box{panelMin + glm::vec2(padding, labelSize.y), panelMin + panelSize - glm::vec2(padding)};
  const auto at = [&](glm::vec2 point) {
    return glm::vec2(box.min.x + point.x * (box.max.x - box.min.x), box.max.y - point.y * (box.max.y - box.min.y));
  };
  // Axes: the bottom and left edges, half the ink's strength.
  glm::vec4 axis = style.ink;
  axis.a *= 0.5f;
  appendSegment(out, at({0, 0}), at({1, 0}), 1.0f, axis, solid);
  appendSegment(out, at({0, 0}), at({0, 1}), 1.0f, axis, solid);
  for (std::size_t i = 0; i < plot.curves.size(); ++i) {
    const std::vector<glm::vec2>& points = plot.curves[i].points;
    const glm::vec4 shown = kInsetCurveColours[i % kInsetCurveColours.size()];
    const glm::vec4 toCome(glm::vec3(shown), kFutureAlpha);
    for (std::size_t k = 0; k + 1 < points.size(); ++k) {
      const glm::vec2 a = points[k], b = points[k + 1];
      if (b.x <= plot.now || a.x >= plot.now || b.x == a.x) {
        appendSegment(out, at(a), at(b), thickness, a.x < plot.now ? shown : toCome, solid);
        continue;
      }
      // The segment the marker crosses: shown up to it, faint after.
      const glm::vec2 split = a + (b - a) * ((plot.now - a.x) / (b.x - a.x));
      appendSegment(out, at(a), at(split), thickness, shown, solid);
      appendSegment(out, at(split), at(b), thickness, toCome, solid);
    }
  }
  // The marker: this frame's place in the clip.
  appendSegment(out, at({plot.now, 0}), at({plot.now, 1}), thickness, style.ink, solid);
  return box;
}

}  // namespace coinroll::render
