#include "render/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace coinroll::testing {

ImageDifference compareImages(const image::Image& actual, const image::Image& expected) {
  if (actual.width != expected.width || actual.height != expected.height) {
    throw std::invalid_argument("compareImages: sizes differ");
  }
  ImageDifference d;
  double squaredError = 0;
  for (std::size_t p = 0; p < actual.rgba.size(); p += 4) {
    bool differs = false;
    for (std::size_t c = 0; c < 3; ++c) {
      const int delta = std::abs(int(actual.rgba[p + c]) - int(expected.rgba[p + c]));
      d.maxChannelDifference = std::max(d.maxChannelDifference, delta);
      squaredError += double(delta) * delta;
      differs = differs || delta != 0;
    }
    d.differingPixels += differs ? 1 : 0;
  }
  const double meanSquaredError = squaredError / (3.0 * actual.width * actual.height);
  d.psnr = meanSquaredError == 0 ? std::numeric_limits<double>::infinity() : 10 * std::log10(255.0 * 255.0 / meanSquaredError);
  return d;
}

image::Image differenceImage(const image::Image& actual, const image::Image& expected) {
  image::Image diff(actual.width, actual.height);
  for (std::size_t p = 0; p < actual.rgba.size(); p += 4) {
    for (std::size_t c = 0; c < 3; ++c) {
      diff.rgba[p + c] = static_cast<std::uint8_t>(std::min(255, 8 * std::abs(int(actual.rgba[p + c]) - int(expected.rgba[p + c]))));
    }
    diff.rgba[p + 3] = 255;
  }
  return diff;
}

std::uint64_t pixelChecksum(const image::Image& image) {
  std::uint64_t hash = 1469598103934665603ull;
  for (std::uint8_t byte : image.rgba) hash = (hash ^ byte) * 1099511628211ull;
  return hash;
}

}  // namespace coinroll::testing
