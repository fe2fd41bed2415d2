#pragma once
// Test support: image measurements for render tests and render_bench. The comparison rule itself (differing
// pixels, PSNR, thresholds, the diff image) is the library's, src/image/compare.h, shared with
// `coinroll compare`.

#include <cstdint>
#include <vector>

#include "image/image.h"

namespace coinroll::testing {

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
