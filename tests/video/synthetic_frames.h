#pragma once
// Deterministic test pictures and a scratch directory for the video tests.

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "image/image.h"
#include "scratch_dir.h"

namespace coinroll::video::testing {

// A diagonal colour gradient with a white-edged red square sliding right, one step per frame:
// smooth areas, sharp edges and motion, the same bytes on every run.
inline image::Image movingSquareFrame(int width, int height, int index) {
  image::Image frame(width, height);
  const int side = height / 3;
  const int left = (index * 4) % (width - side);
  const int top = height / 3;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = frame.pixel(x, y);
      const bool inSquare = x >= left && x < left + side && y >= top && y < top + side;
      const bool onEdge = inSquare && (x < left + 2 || x >= left + side - 2 || y < top + 2 || y >= top + side - 2);
      if (onEdge) {
        p[0] = p[1] = p[2] = 255;
      } else if (inSquare) {
        p[0] = 220, p[1] = 30, p[2] = 40;
      } else {
        p[0] = static_cast<std::uint8_t>(255 * x / (width - 1));
        p[1] = static_cast<std::uint8_t>(255 * y / (height - 1));
        p[2] = static_cast<std::uint8_t>(255 * (width - 1 - x + y) / (width + height - 2));
      }
      p[3] = 255;
    }
  }
  return frame;
}

inline image::Image solidFrame(int width, int height, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  image::Image frame(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = frame.pixel(x, y);
      p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
    }
  }
  return frame;
}

// Root-mean-square difference of the RGB channels, in 8-bit levels (alpha ignored). PSNR in dB
// is 20 log10(255 / rms): 4.5 levels is 35.0 dB.
inline double rmsErrorRgb(const image::Image& reference, const image::Image& test) {
  double squaredError = 0;
  std::size_t samples = 0;
  for (std::size_t i = 0; i < reference.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    const double difference = double(reference.rgba[i]) - double(test.rgba[i]);
    squaredError += difference * difference;
    ++samples;
  }
  return std::sqrt(squaredError / double(samples));
}

using ScratchDirectory = coinroll::testing::ScratchDirectory;

}  // namespace coinroll::video::testing
