#include "video/gif_palette.h"

#include <algorithm>
#include <cmath>

namespace coinroll::video::detail {

namespace {

constexpr int kBayer8[8][8] = {{0, 32, 8, 40, 2, 34, 10, 42},  {48, 16, 56, 24, 50, 18, 58, 26},
                               {12, 44, 4, 36, 14, 46, 6, 38}, {60, 28, 52, 20, 62, 30, 54, 22},
                               {3, 35, 11, 43, 1, 33, 9, 41},  {51, 19, 59, 27, 49, 17, 57, 25},
                               {15, 47, 7, 39, 13, 45, 5, 37}, {63, 31, 55, 23, 61, 29, 53, 21}};

int levelValue(int level, int levels) { return (level * 255 + (levels - 1) / 2) / (levels - 1); }

// For each dither cell and 8-bit value, the level's contribution to the palette index: the value
// scaled to levels - 1 steps, rounded up when its fraction exceeds the cell's threshold.
struct ChannelTable {
  std::array<std::array<std::uint8_t, 256>, 64> contribution{};
  ChannelTable(int levels, int weight) {
    for (int cell = 0; cell < 64; ++cell) {
      const double threshold = (cell + 0.5) / 64;
      for (int value = 0; value < 256; ++value) {
        const double scaled = value * (levels - 1) / 255.0;
        const int level = static_cast<int>(std::floor(scaled)) + (scaled - std::floor(scaled) > threshold ? 1 : 0);
        contribution[cell][value] = static_cast<std::uint8_t>(std::min(level, levels - 1) * weight);
      }
    }
  }
};

}  // namespace

std::array<std::uint32_t, 256> gifPalette() {
  std::array<std::uint32_t, 256> palette{};
  for (int r = 0; r < kGifRedLevels; ++r) {
    for (int g = 0; g < kGifGreenLevels; ++g) {
      for (int b = 0; b < kGifBlueLevels; ++b) {
        palette[static_cast<std::size_t>((r * kGifGreenLevels + g) * kGifBlueLevels + b)] =
            0xFF000000u | static_cast<std::uint32_t>(levelValue(r, kGifRedLevels)) << 16 |
            static_cast<std::uint32_t>(levelValue(g, kGifGreenLevels)) << 8 |
            static_cast<std::uint32_t>(levelValue(b, kGifBlueLevels));
      }
    }
  }
  return palette;
}

void quantizeForGif(const image::Image& frame, std::uint8_t* indices, int stride) {
  static const ChannelTable red(kGifRedLevels, kGifGreenLevels * kGifBlueLevels),
      green(kGifGreenLevels, kGifBlueLevels), blue(kGifBlueLevels, 1);
  for (int y = 0; y < frame.height; ++y) {
    const std::uint8_t* pixel = frame.pixel(0, y);
    std::uint8_t* row = indices + static_cast<std::ptrdiff_t>(y) * stride;
    for (int x = 0; x < frame.width; ++x, pixel += 4) {
      const int cell = kBayer8[y & 7][x & 7];
      row[x] = static_cast<std::uint8_t>(red.contribution[cell][pixel[0]] + green.contribution[cell][pixel[1]] +
                                         blue.contribution[cell][pixel[2]]);
    }
  }
}

}  // namespace coinroll::video::detail
