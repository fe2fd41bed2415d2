#pragma once
// The rule for "are these two pictures the same": the one rule `coinroll compare` applies and
// the project's own golden tests use, so a user's CI that compares coinroll stills judges them
// exactly as the project does.
//
// A pixel differs when one of its channels (R, G, B or A) differs by more than the channel
// tolerance. PSNR is 10 log10(255^2 / MSE) with the MSE over the R, G and B values of every
// pixel (infinity when they are all equal); it and the largest channel difference ignore the
// tolerance. Exact matching is the default; tolerance is opted into with thresholds.

#include <filesystem>
#include <optional>
#include <string>

#include "image/image.h"

namespace coinroll::image {

// Pixels of the largest picture `coinroll compare` decodes: the largest coinroll draws (7680 on
// both sides, render::kMaxImageSide), 225 MiB as RGBA. A PNG's header can declare far more than
// its file holds (a 20000x20000 picture of one colour is 389 KB and decodes to 1.5 GiB), so a
// caller reads the header first (readPngSize) and refuses a picture above this before decoding.
inline constexpr long kMaxComparedPixels = 7680L * 7680L;

struct ImageComparison {
  long pixels = 0;               // width * height
  long differingPixels = 0;      // pixels with a channel off by more than the tolerance
  int maxChannelDifference = 0;  // 0..255, over R, G, B, A and every pixel
  double psnr = 0;               // dB over R, G, B; +infinity when those are identical
  int channelTolerance = 0;      // the tolerance the pixels were counted with
  double differingFraction() const {
    return pixels == 0 ? 0.0 : static_cast<double>(differingPixels) / static_cast<double>(pixels);
  }
};

// What a comparison may show and still pass. Every limit given must hold. With neither pixel
// limit given, no pixel may differ: the default-constructed thresholds are an exact match.
struct CompareThresholds {
  std::optional<long> maxDifferingPixels;      // >= 0
  std::optional<double> maxDifferingFraction;  // of all pixels, in [0, 1]
  int channelTolerance = 0;                    // 0..255: a channel off by at most this is equal
  std::optional<double> minPsnr;               // dB
};

// The tolerant rule for the same Mesa on another x86-64 CPU (docs/snapshot_testing.md). llvmpipe
// compiles its shaders for the CPU it runs on; measured over its code paths on one machine, a CPU
// without AVX/FMA changes at most 0.008 % of the pixels (PSNR >= 84 dB) of every example still
// and golden, and one with AVX-512 none. This allows over 10 times those pixels and 24 dB less,
// while a still 1 ms later (2.1 % of pixels, 47 dB), without its trace (0.44 %, 42 dB) or zoomed
// by 0.05 deg of field of view (28 %, 49 dB) fails. CPUs without SSSE3 take another texture path
// (up to 78 % of the pixels off by at most 10 levels, 41 dB): not rounding, so not covered here;
// pin GALLIUM_OVERRIDE_CPU_CAPS instead (the doc says how).
// `coinroll compare --max-differing-fraction 0.001 --min-psnr 60` is the same rule.
inline CompareThresholds otherCpuThresholds() {
  return {.maxDifferingPixels = std::nullopt, .maxDifferingFraction = 0.001, .channelTolerance = 0, .minPsnr = 60.0};
}

// Compares two pictures of the same size. Throws std::invalid_argument if the sizes differ or
// channelTolerance is outside 0..255.
ImageComparison compareImages(const Image& a, const Image& b, int channelTolerance = 0);

// Throws std::invalid_argument naming the limit in the words of `coinroll compare`'s options
// ("--max-differing-fraction: must be in [0, 1] ...") for a channel tolerance outside 0..255, a
// negative pixel count, a fraction outside [0, 1] or a NaN PSNR bound.
void checkThresholds(const CompareThresholds& thresholds);

// The verdict on a comparison: whether every limit holds, and in words (the limits named as
// `coinroll compare`'s options), "DIFFERENT (<each limit broken, with the value that broke it>)",
// "SAME (identical pixels)", or "SAME within <every limit it was held to>".
struct CompareVerdict {
  bool pass = false;
  std::string text;
};
// Throws as checkThresholds, and for a comparison counted with another channel tolerance than
// thresholds.channelTolerance.
CompareVerdict judge(const ImageComparison& comparison, const CompareThresholds& thresholds);
bool withinThresholds(const ImageComparison& comparison, const CompareThresholds& thresholds);  // judge(...).pass

// `coinroll compare`'s one line: "PSNR 47.31 dB, 12 of 57600 pixels differ (0.02083 %, channel
// tolerance 0), max channel difference 9: <verdict>" (no line break).
std::string comparisonLine(const ImageComparison& comparison, const CompareVerdict& verdict);

// A picture of where `b` differs from `a`: pixels equal within `channelTolerance` are a dimmed
// grey of `a` (its luma / 3, so the scene stays recognisable); pixels that differ by more are red,
// from 128 for a difference of one level to 255 for 33 levels or more, so the worst stand out;
// pixels off by at most the tolerance but not equal are dim amber. Opaque. Same preconditions
// as compareImages.
Image differenceImage(const Image& a, const Image& b, int channelTolerance = 0);

// differenceImage(a, b, channelTolerance) written as PNG to `path` atomically (nothing under
// `path` on failure; std::runtime_error naming it, with the system's reason).
void writeDifferenceImage(const Image& a, const Image& b, int channelTolerance, const std::filesystem::path& path);

}  // namespace coinroll::image
