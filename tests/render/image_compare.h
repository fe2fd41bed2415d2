#pragma once
// Snapshot comparison for render tests: exact pixels first; on a mismatch, how far off (largest
// channel difference, PSNR) and a diff image to look at.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "image/image.h"

namespace coinroll::testing {

struct ImageDifference {
  int differingPixels = 0;
  int maxChannelDifference = 0;  // 0..255
  double psnr = 0;               // dB over RGB; infinity when identical
};

ImageDifference compareImages(const image::Image& actual, const image::Image& expected);

// |actual - expected| per channel, amplified x8 so small differences show, alpha opaque.
image::Image differenceImage(const image::Image& actual, const image::Image& expected);

// The picture `scale` times smaller, each pixel the mean of a scale x scale block (RGB, doubles):
// a supersampled reference for anti-aliasing measurements.
std::vector<double> boxDownsample(const image::Image& large, int scale);

// PSNR (dB) of `picture` against `reference` (from boxDownsample) over edge pixels only: those
// where the reference differs from a 4-neighbour by more than 8 levels. Flat areas would swamp
// the difference between anti-aliasing methods.
double edgePsnr(const image::Image& picture, const std::vector<double>& reference);

// FNV-1a of the pixel bytes: a short name for "these exact pixels" in messages.
std::uint64_t pixelChecksum(const image::Image& image);

}  // namespace coinroll::testing
