// The comparison rule of `coinroll compare` and the golden tests (image/compare.h) against
// expectations computed here: counts by construction, PSNR from the MSE formula.

#include "image/compare.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>

#include "scratch_dir.h"

namespace {

namespace fs = std::filesystem;
using coinroll::image::compareImages;
using coinroll::image::CompareThresholds;
using coinroll::image::Image;
using coinroll::image::ImageComparison;
using coinroll::image::withinThresholds;

constexpr int kWidth = 10, kHeight = 8;  // 80 pixels

// An opaque picture with every channel value in use somewhere, so no difference is hidden by 0 or 255.
Image pattern() {
  Image image(kWidth, kHeight);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      p[0] = static_cast<std::uint8_t>(40 + 17 * x);
      p[1] = static_cast<std::uint8_t>(30 + 23 * y);
      p[2] = static_cast<std::uint8_t>(90 + 5 * (x + y));
      p[3] = 255;
    }
  }
  return image;
}

// The pattern with pixel (3, 2) changed by +20 in red and -7 in green.
Image patternWithOnePixelChanged() {
  Image image = pattern();
  image.pixel(3, 2)[0] += 20;
  image.pixel(3, 2)[1] -= 7;
  return image;
}

// 10 log10(255^2 / MSE), the MSE over the R, G, B values of all 80 pixels: 20^2 + 7^2 in one pixel.
double onePixelPsnr() {
  const double meanSquaredError = (20.0 * 20.0 + 7.0 * 7.0) / (3.0 * kWidth * kHeight);
  return 10 * std::log10(255.0 * 255.0 / meanSquaredError);  // 36.36 dB
}

// Thresholds with every field named (GCC warns about designated initializers that skip one).
CompareThresholds limits(std::optional<long> pixels, std::optional<double> fraction = std::nullopt,
                         std::optional<double> psnr = std::nullopt, int tolerance = 0) {
  return {
      .maxDifferingPixels = pixels, .maxDifferingFraction = fraction, .channelTolerance = tolerance, .minPsnr = psnr};
}

TEST(CompareImages, IdenticalPicturesHaveInfinitePsnrAndNoDifferingPixel) {
  const ImageComparison c = compareImages(pattern(), pattern());
  EXPECT_EQ(c.pixels, kWidth * kHeight);
  EXPECT_EQ(c.differingPixels, 0);
  EXPECT_EQ(c.maxChannelDifference, 0);
  EXPECT_EQ(c.psnr, std::numeric_limits<double>::infinity());
  EXPECT_EQ(c.differingFraction(), 0.0);
  EXPECT_TRUE(withinThresholds(c, CompareThresholds{}));
}

TEST(CompareImages, OnePixelChangeGivesExactCountsAndTheMsePsnr) {
  const ImageComparison c = compareImages(pattern(), patternWithOnePixelChanged());
  EXPECT_EQ(c.differingPixels, 1);
  EXPECT_EQ(c.maxChannelDifference, 20);
  EXPECT_DOUBLE_EQ(c.differingFraction(), 1.0 / 80);
  EXPECT_NEAR(c.psnr, onePixelPsnr(), 1e-12);
  // Symmetric: which picture is the reference does not change the numbers.
  const ImageComparison reversed = compareImages(patternWithOnePixelChanged(), pattern());
  EXPECT_EQ(reversed.differingPixels, 1);
  EXPECT_EQ(reversed.psnr, c.psnr);
}

TEST(CompareImages, ChannelToleranceDecidesWhichPixelsDifferButNotThePsnr) {
  EXPECT_EQ(compareImages(pattern(), patternWithOnePixelChanged(), 19).differingPixels, 1);  // 20 > 19
  const ImageComparison tolerant = compareImages(pattern(), patternWithOnePixelChanged(), 20);
  EXPECT_EQ(tolerant.differingPixels, 0);
  EXPECT_EQ(tolerant.maxChannelDifference, 20);
  EXPECT_NEAR(tolerant.psnr, onePixelPsnr(), 1e-12);
}

TEST(CompareImages, AlphaCountsForDifferingPixelsNotForPsnr) {
  Image translucent = pattern();
  translucent.pixel(0, 0)[3] = 200;
  const ImageComparison c = compareImages(pattern(), translucent);
  EXPECT_EQ(c.differingPixels, 1);
  EXPECT_EQ(c.maxChannelDifference, 55);
  EXPECT_EQ(c.psnr, std::numeric_limits<double>::infinity());
}

TEST(CompareThresholds, ExactByDefaultAndEveryGivenLimitMustHold) {
  const ImageComparison c = compareImages(pattern(), patternWithOnePixelChanged());  // 1 pixel, 1.25 %, 36.36 dB
  const double psnr = onePixelPsnr();
  EXPECT_FALSE(withinThresholds(c, {}));
  EXPECT_TRUE(withinThresholds(c, limits(1)));
  EXPECT_FALSE(withinThresholds(c, limits(0)));
  EXPECT_TRUE(withinThresholds(c, limits(std::nullopt, 0.0125)));  // a fraction alone lifts the count limit
  EXPECT_FALSE(withinThresholds(c, limits(std::nullopt, 0.01)));
  EXPECT_TRUE(withinThresholds(c, limits(1, std::nullopt, psnr - 0.01)));
  EXPECT_FALSE(withinThresholds(c, limits(1, std::nullopt, psnr + 0.01)));
  EXPECT_FALSE(withinThresholds(c, limits(0, 0.5)));  // both given: both hold
  EXPECT_TRUE(withinThresholds(compareImages(pattern(), patternWithOnePixelChanged(), 20),
                               limits(std::nullopt, std::nullopt, std::nullopt, 20)));
  // A PSNR bound alone keeps the exact pixel count: tolerance is never implied.
  EXPECT_FALSE(withinThresholds(c, limits(std::nullopt, std::nullopt, 30)));
  // The other-CPU rule: at most 0.1 % of the pixels and at least 60 dB; this change is neither.
  EXPECT_FALSE(withinThresholds(c, coinroll::image::otherCpuThresholds()));
  EXPECT_TRUE(withinThresholds(compareImages(pattern(), pattern()), coinroll::image::otherCpuThresholds()));
}

TEST(CompareThresholds, BadLimitsAreRefused) {
  const ImageComparison c = compareImages(pattern(), pattern());
  EXPECT_THROW(withinThresholds(c, limits(-1)), std::invalid_argument);
  EXPECT_THROW(withinThresholds(c, limits(std::nullopt, 1.5)), std::invalid_argument);
  EXPECT_THROW(withinThresholds(c, limits(std::nullopt, std::nan(""))), std::invalid_argument);
  EXPECT_THROW(withinThresholds(c, limits(std::nullopt, std::nullopt, std::nan(""))), std::invalid_argument);
  EXPECT_THROW(withinThresholds(c, limits(std::nullopt, std::nullopt, std::nullopt, 3)),
               std::invalid_argument);  // c was counted with 0
  EXPECT_THROW(compareImages(pattern(), pattern(), 256), std::invalid_argument);
  EXPECT_THROW(compareImages(pattern(), pattern(), -1), std::invalid_argument);
}

TEST(CompareImages, DifferentSizesAreRefused) {
  const Image wider(kWidth + 2, kHeight);
  try {
    compareImages(pattern(), wider);
    FAIL() << "different sizes compared";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("10x8"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("12x8"), std::string::npos) << e.what();
  }
  EXPECT_THROW(coinroll::image::differenceImage(pattern(), wider), std::invalid_argument);
}

TEST(DifferenceImage, DifferingPixelsRedEqualOnesDimGreyOfTheReference) {
  Image b = patternWithOnePixelChanged();
  b.pixel(5, 5)[2] += 2;  // within a tolerance of 2
  const Image diff = coinroll::image::differenceImage(pattern(), b, 2);
  const std::uint8_t* changed = diff.pixel(3, 2);
  EXPECT_EQ(changed[0], 128 + 4 * 19);  // 20 levels
  EXPECT_EQ(changed[1], 0);
  EXPECT_EQ(changed[2], 0);
  const std::uint8_t* tolerated = diff.pixel(5, 5);
  EXPECT_GT(tolerated[0], tolerated[2]);  // amber
  EXPECT_GT(tolerated[1], tolerated[2]);
  const Image a = pattern();
  const std::uint8_t* source = a.pixel(7, 1);
  const int luma = (2126 * source[0] + 7152 * source[1] + 722 * source[2]) / 10000;
  for (int c = 0; c < 3; ++c) EXPECT_EQ(diff.pixel(7, 1)[c], luma / 3) << "channel " << c;
  for (std::size_t p = 3; p < diff.rgba.size(); p += 4) ASSERT_EQ(diff.rgba[p], 255);
}

TEST(DifferenceImage, IsWrittenAtomicallyAsPng) {
  const coinroll::testing::ScratchDirectory scratch;
  const fs::path path = scratch / "diff.png";
  coinroll::image::writeDifferenceImage(pattern(), patternWithOnePixelChanged(), 0, path);
  EXPECT_EQ(coinroll::image::readPng(path).rgba,
            coinroll::image::differenceImage(pattern(), patternWithOnePixelChanged()).rgba);
  EXPECT_EQ(scratch.fileCount(), 1) << "a temporary file was left beside the diff";
  EXPECT_THROW(coinroll::image::writeDifferenceImage(pattern(), pattern(), 0, scratch / "no_such_dir" / "diff.png"),
               std::runtime_error);
  EXPECT_EQ(scratch.fileCount(), 1);
}

}  // namespace

// `coinroll compare`'s verdict, in the words of its options: the broken limits with the values
// that broke them, or the limits a difference was held to.
TEST(CompareVerdict, NamesTheLimitsBrokenOrHeldTo) {
  const ImageComparison c = compareImages(pattern(), patternWithOnePixelChanged());  // 1 of 80 pixels
  EXPECT_EQ(coinroll::image::judge(c, {}).text, "DIFFERENT (1 > --max-differing-pixels 0)");
  EXPECT_FALSE(coinroll::image::judge(c, {}).pass);
  const coinroll::image::CompareVerdict held = coinroll::image::judge(c, limits(1, 0.5));
  EXPECT_TRUE(held.pass);
  EXPECT_EQ(held.text, "SAME within --max-differing-pixels 1, --max-differing-fraction 0.5");
  // A fraction alone: the pixel count is not a limit then, and is not named.
  EXPECT_EQ(coinroll::image::judge(c, limits(std::nullopt, 0.01)).text,
            "DIFFERENT (0.0125 > --max-differing-fraction 0.01)");
  const double psnr = onePixelPsnr();
  EXPECT_EQ(coinroll::image::judge(c, limits(1, std::nullopt, 100)).text,
            fmt::format("DIFFERENT ({:.2f} dB < --min-psnr 100)", psnr));
  EXPECT_EQ(coinroll::image::judge(compareImages(pattern(), pattern()), {}).text, "SAME (identical pixels)");
  // Within the channel tolerance the pixels count as equal, though not identical.
  const ImageComparison tolerant = compareImages(pattern(), patternWithOnePixelChanged(), 255);
  EXPECT_EQ(coinroll::image::judge(tolerant, limits(std::nullopt, std::nullopt, std::nullopt, 255)).text,
            "SAME within --channel-tolerance 255, --max-differing-pixels 0");
}

TEST(CompareVerdict, TheLineGivesPsnrCountsAndVerdict) {
  const ImageComparison c = compareImages(pattern(), patternWithOnePixelChanged());
  const std::string line = coinroll::image::comparisonLine(c, coinroll::image::judge(c, {}));
  EXPECT_EQ(line, fmt::format(
                      "PSNR {:.2f} dB, 1 of 80 pixels differ (1.25 %, channel tolerance 0), max channel difference {}: "
                      "DIFFERENT (1 > --max-differing-pixels 0)",
                      onePixelPsnr(), c.maxChannelDifference));
}

TEST(CompareThresholds, BadLimitsAreNamedAsTheOptionsThatSetThem) {
  const auto messageOf = [](const coinroll::image::CompareThresholds& thresholds) {
    try {
      coinroll::image::checkThresholds(thresholds);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(messageOf(limits(-1)), "--max-differing-pixels: must be >= 0, got -1");
  EXPECT_EQ(messageOf(limits(std::nullopt, 1.5)),
            "--max-differing-fraction: must be in [0, 1] (0.01 is 1 % of the pixels), got 1.5");
  EXPECT_EQ(messageOf(limits(std::nullopt, std::nullopt, std::nan(""))), "--min-psnr: must be a number of dB, got nan");
  EXPECT_EQ(messageOf(limits(std::nullopt, std::nullopt, std::nullopt, 256)),
            "--channel-tolerance: must be a whole number 0..255, got 256");
  EXPECT_EQ(messageOf(limits(0, 0, 60, 255)), "accepted");
}
