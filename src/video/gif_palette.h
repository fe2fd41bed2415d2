#pragma once
// Internal to src/video: RGBA frames to the 8-bit palette indices a GIF holds.

#include <array>
#include <cstdint>

#include "image/image.h"

namespace coinroll::video::detail {

// One palette for every frame of every clip: 6 levels of red, 7 of green and 6 of blue (252
// colours), each index (r * 7 + g) * 6 + b. Entries are 0xAARRGGBB, opaque, as FFmpeg's PAL8 holds them.
inline constexpr int kGifRedLevels = 6, kGifGreenLevels = 7, kGifBlueLevels = 6;
inline constexpr int kGifColours = kGifRedLevels * kGifGreenLevels * kGifBlueLevels;
std::array<std::uint32_t, 256> gifPalette();

// Maps `rgba` (alpha ignored) to indices into gifPalette() with an 8x8 ordered (Bayer) dither:
// `indices` gets `frame.height` rows of `frame.width` bytes, `stride` bytes apart. The dither is
// fixed to the pixel's position, so a pixel that does not change keeps its index from frame to
// frame and the GIF encoder's frame-difference rectangles stay small.
void quantizeForGif(const image::Image& frame, std::uint8_t* indices, int stride);

}  // namespace coinroll::video::detail
