#include "image/compare.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

namespace coinroll::image {

namespace {

void requireComparable(const Image& a, const Image& b, int channelTolerance) {
  if (a.width != b.width || a.height != b.height) {
    throw std::invalid_argument("the pictures differ in size: " + std::to_string(a.width) + "x" +
                                std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                                std::to_string(b.height));
  }
  const std::size_t bytes = static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height) * 4;
  if (a.width < 0 || a.height < 0 || a.rgba.size() != bytes || b.rgba.size() != bytes) {
    throw std::invalid_argument("an image's pixel buffer does not match its size");
  }
  if (channelTolerance < 0 || channelTolerance > 255) {
    throw std::invalid_argument("channel tolerance: must be 0..255, got " + std::to_string(channelTolerance));
  }
}

// Largest |a - b| over the four channels of pixel p (byte offset).
int pixelDifference(const Image& a, const Image& b, std::size_t p) {
  int largest = 0;
  for (std::size_t c = 0; c < 4; ++c) largest = std::max(largest, std::abs(int(a.rgba[p + c]) - int(b.rgba[p + c])));
  return largest;
}

}  // namespace

ImageComparison compareImages(const Image& a, const Image& b, int channelTolerance) {
  requireComparable(a, b, channelTolerance);
  ImageComparison result;
  result.pixels = static_cast<long>(a.width) * a.height;
  result.channelTolerance = channelTolerance;
  // Exact integer sum: 255^2 * 3 per pixel stays far below 2^63 for any picture that fits in memory.
  std::uint64_t squaredError = 0;
  for (std::size_t p = 0; p < a.rgba.size(); p += 4) {
    for (std::size_t c = 0; c < 3; ++c) {
      const int delta = int(a.rgba[p + c]) - int(b.rgba[p + c]);
      squaredError += static_cast<std::uint64_t>(delta * delta);
    }
    const int largest = pixelDifference(a, b, p);
    result.maxChannelDifference = std::max(result.maxChannelDifference, largest);
    if (largest > channelTolerance) ++result.differingPixels;
  }
  if (squaredError == 0) {
    result.psnr = std::numeric_limits<double>::infinity();
  } else {
    const double meanSquaredError = static_cast<double>(squaredError) / (3.0 * static_cast<double>(result.pixels));
    result.psnr = 10 * std::log10(255.0 * 255.0 / meanSquaredError);
  }
  return result;
}

void checkThresholds(const CompareThresholds& thresholds) {
  if (thresholds.channelTolerance < 0 || thresholds.channelTolerance > 255) {
    throw std::invalid_argument(
        fmt::format("--channel-tolerance: must be a whole number 0..255, got {}", thresholds.channelTolerance));
  }
  if (thresholds.maxDifferingPixels && *thresholds.maxDifferingPixels < 0) {
    throw std::invalid_argument(
        fmt::format("--max-differing-pixels: must be >= 0, got {}", *thresholds.maxDifferingPixels));
  }
  if (thresholds.maxDifferingFraction &&
      !(*thresholds.maxDifferingFraction >= 0 && *thresholds.maxDifferingFraction <= 1)) {
    throw std::invalid_argument(
        fmt::format("--max-differing-fraction: must be in [0, 1] (0.01 is 1 % of the pixels), got {}",
                    *thresholds.maxDifferingFraction));
  }
  if (thresholds.minPsnr && std::isnan(*thresholds.minPsnr))
    throw std::invalid_argument("--min-psnr: must be a number of dB, got nan");
}

CompareVerdict judge(const ImageComparison& comparison, const CompareThresholds& thresholds) {
  checkThresholds(thresholds);
  if (comparison.channelTolerance != thresholds.channelTolerance) {
    throw std::invalid_argument(
        fmt::format("--channel-tolerance: the pixels were counted with {}, the thresholds ask for {}",
                    comparison.channelTolerance, thresholds.channelTolerance));
  }
  // No pixel limit at all means exact: a tolerance is always something the caller asked for.
  const long maxPixels =
      thresholds.maxDifferingPixels.value_or(thresholds.maxDifferingFraction ? comparison.pixels : 0);
  std::string broken, heldTo;
  const auto add = [](std::string& list, const std::string& item) { list += (list.empty() ? "" : ", ") + item; };
  if (thresholds.channelTolerance > 0) add(heldTo, fmt::format("--channel-tolerance {}", thresholds.channelTolerance));
  if (thresholds.maxDifferingPixels || !thresholds.maxDifferingFraction) {
    add(heldTo, fmt::format("--max-differing-pixels {}", maxPixels));
    if (comparison.differingPixels > maxPixels) {
      add(broken, fmt::format("{} > --max-differing-pixels {}", comparison.differingPixels, maxPixels));
    }
  }
  if (const std::optional<double> fraction = thresholds.maxDifferingFraction) {
    add(heldTo, fmt::format("--max-differing-fraction {}", *fraction));
    if (comparison.differingFraction() > *fraction) {
      add(broken, fmt::format("{:.6g} > --max-differing-fraction {}", comparison.differingFraction(), *fraction));
    }
  }
  if (const std::optional<double> minPsnr = thresholds.minPsnr) {
    add(heldTo, fmt::format("--min-psnr {}", *minPsnr));
    if (!(comparison.psnr >= *minPsnr))
      add(broken, fmt::format("{:.2f} dB < --min-psnr {}", comparison.psnr, *minPsnr));
  }
  if (!broken.empty()) return {.pass = false, .text = fmt::format("DIFFERENT ({})", broken)};
  if (comparison.maxChannelDifference == 0) return {.pass = true, .text = "SAME (identical pixels)"};
  return {.pass = true, .text = fmt::format("SAME within {}", heldTo)};
}

bool withinThresholds(const ImageComparison& comparison, const CompareThresholds& thresholds) {
  return judge(comparison, thresholds).pass;
}

std::string comparisonLine(const ImageComparison& comparison, const CompareVerdict& verdict) {
  return fmt::format(
      "PSNR {:.2f} dB, {} of {} pixels differ ({:.4g} %, channel tolerance {}), max channel difference {}: {}",
      comparison.psnr, comparison.differingPixels, comparison.pixels, 100 * comparison.differingFraction(),
      comparison.channelTolerance, comparison.maxChannelDifference, verdict.text);
}

Image differenceImage(const Image& a, const Image& b, int channelTolerance) {
  requireComparable(a, b, channelTolerance);
  Image diff(a.width, a.height);
  for (std::size_t p = 0; p < a.rgba.size(); p += 4) {
    const int largest = pixelDifference(a, b, p);
    std::uint8_t* out = diff.rgba.data() + p;
    if (largest > channelTolerance) {
      out[0] = static_cast<std::uint8_t>(std::min(255, 128 + 4 * (largest - 1)));
      out[1] = out[2] = 0;
    } else if (largest > 0) {
      out[0] = 160;
      out[1] = 110;
      out[2] = 0;
    } else {
      // Rec. 709 luma of a, in integers; a third of it keeps the red marks the brightest thing.
      const int luma = (2126 * a.rgba[p] + 7152 * a.rgba[p + 1] + 722 * a.rgba[p + 2]) / 10000;
      out[0] = out[1] = out[2] = static_cast<std::uint8_t>(luma / 3);
    }
    out[3] = 255;
  }
  return diff;
}

void writeDifferenceImage(const Image& a, const Image& b, int channelTolerance, const std::filesystem::path& path) {
  writePng(differenceImage(a, b, channelTolerance), path);  // atomic: a temporary beside it, then a rename
}

}  // namespace coinroll::image
