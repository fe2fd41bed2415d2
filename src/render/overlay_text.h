#pragma once
// The overlay's typography, built without a GL context (so tests can check it): DejaVu Sans Mono
// (fonts-dejavu-core, embedded in the binary like assets/, see assets.h) rasterised once per
// Renderer by stb_truetype into a one-channel glyph atlas at a size proportional to the picture's
// height, and text laid out as textured quads on translucent panels. Monospaced, so the columns
// the overlay's lines are formatted in stay aligned.

#include <glm/glm.hpp>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace coinroll::render {

// The em (the font's ascent to descent) in pixels for a picture `height` pixels high: a 45th of the
// height, so 480p and 4K show the same proportions, but never under 10 px, below which the
// digits stop being legible.
float overlayTextPixels(int height);

// Where one glyph lies in the atlas and how it sits on the baseline.
struct AtlasGlyph {
  glm::vec2 atlasMin{0.0f}, atlasMax{0.0f};    // texels, the glyph's box in the atlas
  glm::vec2 offsetMin{0.0f}, offsetMax{0.0f};  // pixels, that box relative to the pen on the baseline (y down)
  float advance = 0;                           // pixels, to the next glyph's pen
};

// Every glyph the overlay can show, rasterised at one size: ASCII, the Latin-1 signs (° × ± µ ²),
// Greek (θ φ ψ ω Ω ...), a few mathematical signs (− ≈ → …), and U+FFFD, which stands in for any
// other character. Pixels are coverage, row-major, top row first (GL_R8). A few rows below the
// glyphs are fully covered: panels sample there, so one program draws panels and glyphs.
class GlyphAtlas {
 public:
  // Throws std::runtime_error if the embedded font cannot be read or lacks a glyph it must have.
  explicit GlyphAtlas(float pixelHeight);

  int width() const { return width_; }
  int height() const { return height_; }
  const std::vector<unsigned char>& coverage() const { return coverage_; }
  float ascent() const { return ascent_; }              // pixels above the baseline
  float lineHeight() const { return lineHeight_; }      // pixels from one baseline to the next
  glm::vec2 solidTexel() const { return solidTexel_; }  // a fully covered texel's centre
  // The glyph for `codepoint`, or U+FFFD's when the atlas has none.
  const AtlasGlyph& glyph(char32_t codepoint) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<unsigned char> coverage_;
  float ascent_ = 0, lineHeight_ = 0;
  glm::vec2 solidTexel_{0.0f};
  std::map<char32_t, AtlasGlyph> glyphs_;
};

// UTF-8 to code points; a malformed sequence gives U+FFFD for its first byte and goes on.
std::u32string decodeUtf8(std::string_view text);

struct TextVertex {
  glm::vec2 position{0.0f};  // pixels, origin top-left
  glm::vec2 texel{0.0f};     // atlas texels (the shader divides by the atlas size)
  glm::vec4 colour{0.0f};    // straight alpha, multiplied by the atlas coverage
};

struct TextStyle {
  glm::vec4 ink{0.0f};    // the glyphs' colour
  glm::vec4 panel{0.0f};  // the panel's colour behind them
};

// The width in pixels of `line` set in `atlas` (sum of advances).
float textWidth(const GlyphAtlas& atlas, std::string_view line);

// Triangles of a panel holding `lines` whose top-left corner is at `corner` (pixels), glyph
// baselines on whole pixels so every row of the atlas lands on one row of the picture. Appended
// to `out`. Returns the panel's size in pixels.
glm::vec2 appendTextPanel(const GlyphAtlas& atlas, const std::vector<std::string>& lines, glm::vec2 corner,
                          const TextStyle& style, std::vector<TextVertex>& out);

// The panel's size for `lines`, without making it (to place it, e.g. centred under a point).
glm::vec2 textPanelSize(const GlyphAtlas& atlas, const std::vector<std::string>& lines);

}  // namespace coinroll::render
