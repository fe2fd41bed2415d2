// The overlay's typography, the themes and the scale bar against independent expectations: the
// symbols the labels use have ink, the text keeps its size relative to the picture's height, the
// bytes repeat, paper's floor is light where classic's is not, and the scale bar spans the
// projection of its metric length under the tests' own pinhole camera (tests/support/pinhole.h).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "render/inset_plot.h"
#include "render/overlay_text.h"
#include "render/renderer.h"
#include "render/scale_bar.h"
#include "pinhole.h"

namespace {

using coinroll::image::Image;
using coinroll::testing::pinholePixel;
using namespace coinroll::render;

constexpr float kRadius = 0.0375f;

RenderSettings settings(int width, int height) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.msaa = 4;
  s.coin = {kRadius, 0.0f, 0.00225f};
  return s;
}

FrameSnapshot uprightCoin() {
  FrameSnapshot s;
  s.camera = {{0.10f, 0.10f, 0.22f}, {0.0f, 0.025f, 0.0f}, 35.0f};
  s.coin.centre = glm::vec3(0.0f, kRadius, 0.0f);
  s.showContact = false;
  return s;
}

// The box (inclusive pixel bounds) of the pixels where `a` and `b` differ, if any.
struct PixelBox {
  int left = 0, top = 0, right = -1, bottom = -1;
  int height() const { return bottom - top + 1; }
};

std::optional<PixelBox> differingBox(const Image& a, const Image& b) {
  std::optional<PixelBox> box;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      if (!std::equal(a.pixel(x, y), a.pixel(x, y) + 4, b.pixel(x, y))) {
        if (!box) box = PixelBox{x, y, x, y};
        box->left = std::min(box->left, x);
        box->right = std::max(box->right, x);
        box->top = std::min(box->top, y);
        box->bottom = std::max(box->bottom, y);
      }
    }
  }
  return box;
}

// Renders `lines` over the upright coin, and the same with every character but spaces replaced
// by spaces: the panel is then the same size (the font is monospaced), so the pixels that differ
// are the glyphs' ink alone.
std::pair<Image, Image> withAndWithoutInk(Renderer& renderer, const std::vector<std::string>& lines,
                                          std::size_t blankColumns) {
  FrameSnapshot s = uprightCoin();
  s.hudLines = lines;
  const Image ink = renderer.draw(s);
  s.hudLines.assign(lines.size(), std::string(blankColumns, ' '));
  return {ink, renderer.draw(s)};
}

TEST(OverlayText, EverySymbolTheLabelsUseHasInk) {
  const GlyphAtlas atlas(overlayTextPixels(720));
  for (const char32_t c : std::u32string(U"θ°×ΩωφψµHz/mW0123456789")) {
    const AtlasGlyph& g = atlas.glyph(c);
    EXPECT_NE(&g, &atlas.glyph(0xFFFD)) << "U+" << std::hex << unsigned(c) << " falls back to the replacement glyph";
    long ink = 0;
    for (int y = int(g.atlasMin.y); y < int(g.atlasMax.y); ++y) {
      for (int x = int(g.atlasMin.x); x < int(g.atlasMax.x); ++x)
        ink += atlas.coverage()[std::size_t(y) * atlas.width() + x];
    }
    EXPECT_GT(ink, 255 * 4) << "U+" << std::hex << unsigned(c) << " has (almost) no ink";
  }
  EXPECT_EQ(decodeUtf8("θ=20°"), U"θ=20°");
  EXPECT_EQ(decodeUtf8("a\xC3"), std::u32string(U"a\uFFFD")) << "a cut-off sequence becomes U+FFFD";
  EXPECT_FLOAT_EQ(textWidth(atlas, "θ°"), textWidth(atlas, "ab")) << "monospaced: columns stay aligned";
}

TEST(OverlayText, DegreeSignAndThetaDrawOnThePicture) {
  Renderer renderer(settings(320, 180));
  for (const std::string symbol : {"°", "θ", "×"}) {
    const auto [ink, blank] = withAndWithoutInk(renderer, {symbol}, 1);
    const std::optional<PixelBox> box = differingBox(ink, blank);
    ASSERT_TRUE(box.has_value()) << symbol << " drew nothing";
    EXPECT_GE(box->height(), 3) << symbol;
  }
}

TEST(OverlayText, HeightScalesWithThePictureHeight) {
  // 480 and 1440 rows: the text is a 45th of the height at both (above the 10 px floor), so the
  // capital H three times as tall, to the rounding of its top and bottom rows.
  std::vector<int> heights;
  for (const int rows : {480, 1440}) {
    Renderer renderer(settings(320, rows));
    const auto [ink, blank] = withAndWithoutInk(renderer, {"H"}, 1);
    const std::optional<PixelBox> box = differingBox(ink, blank);
    ASSERT_TRUE(box.has_value());
    heights.push_back(box->height());
  }
  EXPECT_NEAR(heights[1], 3 * heights[0], 3)
      << "H is " << heights[0] << " px at 480 rows, " << heights[1] << " at 1440";
  // DejaVu Sans Mono's capitals are 1493 of the 2384 font units from descent to ascent, the size set.
  EXPECT_NEAR(heights[0], 1493.0 / 2384 * 480 / 45, 1.5);
}

TEST(OverlayText, SameLinesSameBytes) {
  FrameSnapshot s = uprightCoin();
  s.hudLines = {"t            1.000 s", "θ        20.00° from vertical", "slow motion ×1.5"};
  Renderer first(settings(320, 180)), second(settings(320, 180));
  const Image a = first.draw(s);
  EXPECT_EQ(first.draw(s).rgba, a.rgba);
  EXPECT_EQ(second.draw(s).rgba, a.rgba);
}

// Mean luma (Rec. 709, 0..255) of the bottom quarter of the picture: floor only in this view.
double floorLuma(const Image& picture) {
  double sum = 0;
  long count = 0;
  for (int y = 3 * picture.height / 4; y < picture.height; ++y) {
    for (int x = 0; x < picture.width; ++x) {
      const std::uint8_t* p = picture.pixel(x, y);
      sum += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
      ++count;
    }
  }
  return sum / double(count);
}

TEST(Themes, PaperHasALightFloorAndDarkText) {
  FrameSnapshot s = uprightCoin();
  s.coin.centre.x = 1000;  // out of view: floor alone
  RenderSettings paper = settings(320, 180);
  paper.theme = Theme::Paper;
  Renderer classicRenderer(settings(320, 180)), paperRenderer(paper);
  const double classic = floorLuma(classicRenderer.draw(s)), light = floorLuma(paperRenderer.draw(s));
  EXPECT_GT(light, 200) << "paper's floor is light";
  EXPECT_LT(classic, 160) << "classic's floor stays dark";
  // Paper's ink is darker than its panel; classic's lighter.
  for (const auto& [renderer, inkDarker] : {std::pair{&paperRenderer, true}, std::pair{&classicRenderer, false}}) {
    const auto [ink, blank] = withAndWithoutInk(*renderer, {"HHHH"}, 4);
    const std::optional<PixelBox> box = differingBox(ink, blank);
    ASSERT_TRUE(box.has_value());
    int darker = 0, lighter = 0;
    for (int y = box->top; y <= box->bottom; ++y) {
      for (int x = box->left; x <= box->right; ++x) (ink.pixel(x, y)[1] < blank.pixel(x, y)[1] ? darker : lighter) += 1;
    }
    EXPECT_EQ(darker > lighter, inkDarker) << darker << " pixels darkened, " << lighter << " lightened";
  }
}

TEST(ScaleBar, SpansTheProjectionOfItsLengthOnTheFloor) {
  for (const float metres : {0.0f, 0.05f}) {  // the automatic length (2 cm for this coin), then 5 cm
    RenderSettings with = settings(480, 270);
    with.scaleBar = {.shown = true, .metres = metres};
    Renderer withBar(with), withoutBar(settings(480, 270));
    const FrameSnapshot s = uprightCoin();
    const ScaleBarPlacement bar = placeScaleBar(with.scaleBar, kRadius, s.camera, s.coin, with.height);
    const double length = metres > 0 ? metres : 0.02;
    EXPECT_NEAR(glm::length(glm::dvec3(bar.end - bar.start)), length, 1e-7);
    EXPECT_EQ(bar.label, metres > 0 ? "5 cm" : "2 cm");
    EXPECT_EQ(bar.start.y, 0.0f);
    EXPECT_EQ(bar.end.y, 0.0f);

    const glm::dvec2 start = pinholePixel(s.camera, with.width, with.height, glm::dvec3(bar.start));
    const glm::dvec2 end = pinholePixel(s.camera, with.width, with.height, glm::dvec3(bar.end));
    ASSERT_NEAR(start.y, end.y, 1e-3) << "the bar lies across the view";
    const Image a = withBar.draw(s), b = withoutBar.draw(s);
    const int row = static_cast<int>(std::floor(0.5 * (start.y + end.y)));
    // Along the row through the bar's middle (inside its 3 px thickness), each pixel's share of the
    // bar: how far its green moved from the floor's towards the bar's. Summed, the covered length
    // to a fraction of a pixel (MSAA's coverage steps).
    const double barGreen = 255.0 * 0.97;  // render/theme.cpp, classic
    int left = a.width, right = -1;
    double covered = 0;
    for (int x = 0; x < a.width; ++x) {
      if (std::equal(a.pixel(x, row), a.pixel(x, row) + 4, b.pixel(x, row))) continue;
      left = std::min(left, x);
      right = std::max(right, x);
      covered += std::clamp((a.pixel(x, row)[1] - b.pixel(x, row)[1]) / (barGreen - b.pixel(x, row)[1]), 0.0, 1.0);
    }
    ASSERT_LE(left, right) << "no bar in row " << row;
    // Each end's partly covered pixel holds the projected end; the covered length is the projected
    // one to a pixel (4x MSAA counts a partly covered end pixel in quarters).
    EXPECT_NEAR(left, std::min(start.x, end.x), 1.0) << metres;
    EXPECT_NEAR(right + 1, std::max(start.x, end.x), 1.0) << metres;
    EXPECT_NEAR(covered, std::abs(end.x - start.x), 1.0) << metres;
    std::cerr << "scale bar " << bar.label << ": covers " << covered << " px, projects to " << std::abs(end.x - start.x)
              << " px\n";
    EXPECT_GT(std::abs(end.x - start.x), 20) << "the bar must be long enough for the test to mean something";
  }
}

TEST(ScaleBar, AutomaticLengthIsARoundNumberUnderTheRadius) {
  EXPECT_FLOAT_EQ(scaleBarMetres({.shown = true}, 0.0375f), 0.02f);
  EXPECT_FLOAT_EQ(scaleBarMetres({.shown = true}, 0.012f), 0.01f);
  EXPECT_FLOAT_EQ(scaleBarMetres({.shown = true}, 0.06f), 0.05f);
  EXPECT_FLOAT_EQ(scaleBarMetres({.shown = true, .metres = 0.03f}, 0.0375f), 0.03f);
  EXPECT_EQ(scaleBarLabel(0.005f), "5 mm");
  EXPECT_EQ(scaleBarLabel(0.025f), "2.5 cm");
  EXPECT_EQ(scaleBarLabel(2.0f), "2 m");
}

// render --inset: the plot lies in the lower right corner, changes nothing else in the picture, and
// draws each curve where its values put it, the part still to come fainter than the part shown.
TEST(InsetPlot, DrawsItsCurvesInTheLowerRightCornerOnly) {
  constexpr int kWidth = 320, kHeight = 180;
  Renderer renderer(settings(kWidth, kHeight));
  FrameSnapshot plain = uprightCoin();
  FrameSnapshot withInset = plain;
  // A rising line and a flat one at three quarters; the marker at the middle.
  withInset.inset = InsetPlot{.curves = {{.points = {{0, 0}, {1, 1}}, .label = "contact 1 Hz"},
                                         {.points = {{0, 0.75f}, {1, 0.75f}}, .label = "tilt 1°"}},
                              .now = 0.5f};
  const Image without = renderer.draw(plain), with = renderer.draw(withInset);
  const std::optional<PixelBox> changed = differingBox(without, with);
  ASSERT_TRUE(changed);
  EXPECT_GT(changed->left, kWidth / 2) << "the inset reaches into the left half";
  EXPECT_GT(changed->top, kHeight / 2) << "the inset reaches into the upper half";
  EXPECT_LT(changed->right, kWidth) << "no margin on the right";

  // Where the flat curve runs, a quarter of the way in (already shown) and three quarters in (to come).
  const GlyphAtlas atlas(overlayTextPixels(kHeight));
  std::vector<TextVertex> ignored;
  const InsetBox box = appendInsetPlot(atlas, *withInset.inset, kWidth, kHeight, TextStyle{}, ignored);
  EXPECT_GE(box.min.x, changed->left);
  EXPECT_LE(box.max.y, changed->bottom + 1);
  const auto pixelAt = [&](float x, float y) {
    return with.pixel(static_cast<int>(box.min.x + x * (box.max.x - box.min.x)),
                      static_cast<int>(std::round(box.max.y - y * (box.max.y - box.min.y))));
  };
  const glm::vec4 blue = kInsetCurveColours[1];
  const std::uint8_t* shown = pixelAt(0.25f, 0.75f);
  const std::uint8_t* toCome = pixelAt(0.75f, 0.75f);
  EXPECT_GT(shown[2], shown[0] + 60) << "the shown part is blue";
  EXPECT_GT(shown[2], toCome[2]) << "the part to come is fainter";
  EXPECT_GT(toCome[2], toCome[0]) << "the part to come is still there";
  EXPECT_GT(blue.b, blue.r);
}

}  // namespace
