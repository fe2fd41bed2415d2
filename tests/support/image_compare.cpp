#include "image_compare.h"

#include <algorithm>
#include <cmath>

namespace coinroll::testing {

std::vector<double> boxDownsample(const image::Image& large, int scale) {
  const int w = large.width / scale, h = large.height / scale;
  std::vector<double> small(std::size_t(w) * h * 3, 0.0);
  for (int y = 0; y < h * scale; ++y) {
    for (int x = 0; x < w * scale; ++x) {
      for (int c = 0; c < 3; ++c)
        small[(std::size_t(y / scale) * w + x / scale) * 3 + c] += large.pixel(x, y)[c] / double(scale * scale);
    }
  }
  return small;
}

double edgePsnr(const image::Image& picture, const std::vector<double>& reference) {
  const int w = picture.width, h = picture.height;
  auto ref = [&](int x, int y, int c) { return reference[(std::size_t(y) * w + x) * 3 + c]; };
  double squared = 0;
  long count = 0;
  for (int y = 1; y + 1 < h; ++y) {
    for (int x = 1; x + 1 < w; ++x) {
      double contrast = 0, error = 0;
      for (int c = 0; c < 3; ++c) {
        contrast =
            std::max({contrast, std::abs(ref(x, y, c) - ref(x + 1, y, c)), std::abs(ref(x, y, c) - ref(x - 1, y, c)),
                      std::abs(ref(x, y, c) - ref(x, y + 1, c)), std::abs(ref(x, y, c) - ref(x, y - 1, c))});
        const double d = picture.pixel(x, y)[c] - ref(x, y, c);
        error += d * d / 3;
      }
      if (contrast > 8) {
        squared += error;
        ++count;
      }
    }
  }
  return 10 * std::log10(255.0 * 255.0 * static_cast<double>(count) / squared);
}

std::uint64_t pixelChecksum(const image::Image& image) {
  std::uint64_t hash = 1469598103934665603ull;
  for (std::uint8_t byte : image.rgba) hash = (hash ^ byte) * 1099511628211ull;
  return hash;
}

}  // namespace coinroll::testing
