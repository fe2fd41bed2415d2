#include "render/overlay_text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <stdexcept>

#include "render/embedded_assets.h"

#include <stb_rect_pack.h>
#include <stb_truetype.h>

namespace coinroll::render {

namespace {

constexpr std::string_view kFontName = "DejaVuSansMono.ttf";
constexpr char32_t kReplacement = 0xFFFD;
constexpr int kSolidRows = 4;  // fully covered rows under the glyphs, for panels
constexpr int kPadding = 1;    // texels between glyphs, so linear filtering never bleeds

// The overlay's repertoire beyond ASCII: the signs its labels use (° × µ ± ²), the Greek of the
// physics' symbols, and what a label might want next (− ≈ → … ·).
std::vector<int> repertoire() {
  std::vector<int> codepoints;
  for (int c = 0x20; c < 0x7F; ++c) codepoints.push_back(c);
  for (int c : {0xB0, 0xB1, 0xB2, 0xB3, 0xB5, 0xB7, 0xD7}) codepoints.push_back(c);
  for (int c = 0x391; c <= 0x3A9; ++c) {
    if (c != 0x3A2) codepoints.push_back(c);  // 0x3A2 is unassigned
  }
  for (int c = 0x3B1; c <= 0x3C9; ++c) codepoints.push_back(c);
  for (int c : {0x2026, 0x2032, 0x2192, 0x2212, 0x2248, 0x2264, 0x2265, static_cast<int>(kReplacement)})
    codepoints.push_back(c);
  return codepoints;
}

std::span<const std::uint8_t> fontBytes() {
  const std::optional<std::span<const std::uint8_t>> font = embeddedAsset(kFontName);
  if (!font) throw std::runtime_error(fmt::format("overlay: the font {} is not embedded (rebuild)", kFontName));
  return *font;
}

int nextPowerOfTwo(double at_least) {
  int n = 64;
  while (n < at_least) n *= 2;
  return n;
}

}  // namespace

float overlayTextPixels(int height) { return std::max(10.0f, static_cast<float>(height) / 45.0f); }

GlyphAtlas::GlyphAtlas(float pixelHeight) {
  const std::span<const std::uint8_t> font = fontBytes();
  stbtt_fontinfo info;
  if (stbtt_InitFont(&info, font.data(), 0) == 0)
    throw std::runtime_error(fmt::format("overlay: cannot read the font {}", kFontName));
  std::vector<int> codepoints = repertoire();
  for (int c : codepoints) {
    if (stbtt_FindGlyphIndex(&info, c) == 0)
      throw std::runtime_error(fmt::format("overlay: {} has no glyph for U+{:04X}", kFontName, c));
  }
  const float scale = stbtt_ScaleForPixelHeight(&info, pixelHeight);
  int ascent = 0, descent = 0, lineGap = 0;
  stbtt_GetFontVMetrics(&info, &ascent, &descent, &lineGap);
  ascent_ = scale * static_cast<float>(ascent);
  lineHeight_ = std::ceil(scale * static_cast<float>(ascent - descent + lineGap));

  // Two texels per pixel across: glyphs placed at fractional pens keep their shape under linear
  // filtering (stb_truetype's oversampling), while rows stay one texel per pixel on whole-pixel baselines.
  constexpr int kOversampleX = 2;
  const double glyphTexels = (kOversampleX * 0.65 * pixelHeight + kPadding) * (1.05 * pixelHeight + kPadding);
  width_ = nextPowerOfTwo(std::sqrt(glyphTexels * static_cast<double>(codepoints.size())));
  std::vector<stbtt_packedchar> packed(codepoints.size());
  for (int glyphRows = width_ / 4;; glyphRows *= 2) {
    if (glyphRows > 16384)
      throw std::runtime_error(fmt::format("overlay: cannot fit the font at {} px into a texture", pixelHeight));
    height_ = glyphRows + kSolidRows;
    coverage_.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 0);
    stbtt_pack_context context;
    if (stbtt_PackBegin(&context, coverage_.data(), width_, glyphRows, width_, kPadding, nullptr) == 0) {
      throw std::runtime_error("overlay: out of memory for the glyph atlas");
    }
    stbtt_PackSetOversampling(&context, kOversampleX, 1);
    stbtt_pack_range range{};
    range.font_size = pixelHeight;
    range.array_of_unicode_codepoints = codepoints.data();
    range.num_chars = static_cast<int>(codepoints.size());
    range.chardata_for_range = packed.data();
    const int fitted = stbtt_PackFontRanges(&context, font.data(), 0, &range, 1);
    stbtt_PackEnd(&context);
    if (fitted != 0) break;
  }
  std::fill(coverage_.end() - static_cast<std::ptrdiff_t>(kSolidRows * width_), coverage_.end(), 255);
  solidTexel_ = glm::vec2(1.0f, static_cast<float>(height_ - kSolidRows / 2));
  for (std::size_t i = 0; i < codepoints.size(); ++i) {
    const stbtt_packedchar& p = packed[i];
    glyphs_[static_cast<char32_t>(codepoints[i])] = {.atlasMin = {p.x0, p.y0},
                                                     .atlasMax = {p.x1, p.y1},
                                                     .offsetMin = {p.xoff, p.yoff},
                                                     .offsetMax = {p.xoff2, p.yoff2},
                                                     .advance = p.xadvance};
  }
}

const AtlasGlyph& GlyphAtlas::glyph(char32_t codepoint) const {
  const auto found = glyphs_.find(codepoint);
  return found != glyphs_.end() ? found->second : glyphs_.at(kReplacement);
}

std::u32string decodeUtf8(std::string_view text) {
  std::u32string out;
  for (std::size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    const int length = lead < 0x80 ? 1 : (lead >> 5) == 0x6 ? 2 : (lead >> 4) == 0xE ? 3 : (lead >> 3) == 0x1E ? 4 : 0;
    char32_t codepoint = length == 1 ? lead : length == 2 ? lead & 0x1F : length == 3 ? lead & 0x0F : lead & 0x07;
    bool valid = length > 0 && i + static_cast<std::size_t>(length) <= text.size();
    for (int k = 1; valid && k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + static_cast<std::size_t>(k)]);
      valid = (next & 0xC0) == 0x80;
      codepoint = (codepoint << 6) | (next & 0x3F);
    }
    out.push_back(valid ? codepoint : kReplacement);
    i += valid ? static_cast<std::size_t>(length) : 1;
  }
  return out;
}

float textWidth(const GlyphAtlas& atlas, std::string_view line) {
  float width = 0;
  for (const char32_t c : decodeUtf8(line)) width += atlas.glyph(c).advance;
  return width;
}

namespace {

// The panel's margin inside its edge, pixels: a third of a line.
float panelPadding(const GlyphAtlas& atlas) { return std::round(atlas.lineHeight() / 3.0f); }

void appendQuad(std::vector<TextVertex>& out, glm::vec2 min, glm::vec2 max, glm::vec2 texelMin, glm::vec2 texelMax,
                glm::vec4 colour) {
  const TextVertex a{min, texelMin, colour}, b{{max.x, min.y}, {texelMax.x, texelMin.y}, colour},
      c{max, texelMax, colour}, d{{min.x, max.y}, {texelMin.x, texelMax.y}, colour};
  // push_back rather than insert(end, {...}): GCC 12 misreports the latter (-Wstringop-overflow).
  for (const TextVertex& v : {a, b, c, a, c, d}) out.push_back(v);
}

}  // namespace

glm::vec2 textPanelSize(const GlyphAtlas& atlas, const std::vector<std::string>& lines) {
  float width = 0;
  for (const std::string& line : lines) width = std::max(width, textWidth(atlas, line));
  const float padding = panelPadding(atlas);
  return {std::ceil(width) + 2 * padding, atlas.lineHeight() * static_cast<float>(lines.size()) + 2 * padding};
}

glm::vec2 appendTextPanel(const GlyphAtlas& atlas, const std::vector<std::string>& lines, glm::vec2 corner,
                          const TextStyle& style, std::vector<TextVertex>& out) {
  const glm::vec2 size = textPanelSize(atlas, lines);
  const glm::vec2 origin = glm::round(corner);
  appendQuad(out, origin, origin + size, atlas.solidTexel(), atlas.solidTexel(), style.panel);
  const float padding = panelPadding(atlas);
  for (std::size_t row = 0; row < lines.size(); ++row) {
    const float baseline =
        origin.y + padding + std::round(atlas.ascent() + atlas.lineHeight() * static_cast<float>(row));
    float pen = origin.x + padding;
    for (const char32_t c : decodeUtf8(lines[row])) {
      const AtlasGlyph& g = atlas.glyph(c);
      if (g.atlasMax.x > g.atlasMin.x) {
        appendQuad(out, glm::vec2(pen, baseline) + g.offsetMin, glm::vec2(pen, baseline) + g.offsetMax, g.atlasMin,
                   g.atlasMax, style.ink);
      }
      pen += g.advance;
    }
  }
  return size;
}

}  // namespace coinroll::render
