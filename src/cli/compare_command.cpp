#include "cli/commands.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <stdexcept>

#include "cli/command_support.h"
#include "cli/exit_codes.h"
#include "image/compare.h"
#include "image/image.h"
#include "io/destination.h"
#include "io/output_file.h"
#include "pipeline/resources.h"
#include "render/render_settings.h"
#include "video/video_kinds.h"

namespace coinroll::cli {

namespace {

// A picture to compare, checked as far as its header: its size, or a UsageError that names the
// file and says what to give instead.
image::PngSize checkComparedPng(const std::string& name) {
  const std::filesystem::path path(name);
  if (name.empty())
    throw UsageError("a PNG name is empty; give the paths of the two PNGs to compare, e.g. golden.png new.png");
  std::error_code error;
  if (!std::filesystem::exists(path, error)) {
    throw UsageError(fmt::format("{}: no such file; give the path of a PNG to compare", name));
  }
  if (!std::filesystem::is_regular_file(path, error)) {
    throw UsageError(fmt::format("{}: not a regular file; give the path of a PNG to compare", name));
  }
  // stb would also decode JPEG, BMP, GIF, ...: a golden in another format is a mistake to name.
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError(fmt::format("{}: cannot open: {}", name, std::strerror(errno)));
  constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  char head[8] = {};
  in.read(head, sizeof head);
  if (in.gcount() != sizeof head || std::memcmp(head, kSignature, sizeof head) != 0) {
    throw UsageError(
        fmt::format("{}: not a PNG file (no PNG signature); compare the PNGs coinroll still or render wrote", name));
  }
  image::PngSize size;
  try {
    size = image::readPngSize(path);
  } catch (const std::runtime_error& e) {
    throw UsageError(fmt::format("{} (a damaged or truncated PNG?)", e.what()));
  }
  // The decoder would read 16 bits per channel as 8, so two pictures that differ everywhere in
  // their low bytes would compare equal.
  if (size.bitDepth == 16) {
    throw UsageError(
        fmt::format("{}: 16 bits per channel; compare reads 8-bit PNGs (what coinroll writes): convert "
                    "both, e.g. ffmpeg -i {} -pix_fmt rgba out8.png, or compare the 16-bit files with "
                    "another tool",
                    name, name));
  }
  return size;
}

// The decoder ignores CRCs, so the chunks are checked first: a damaged golden is no verdict.
image::Image decodeComparedPng(const std::string& name) {
  try {
    image::checkPngChunks(name);
  } catch (const std::runtime_error& e) {
    throw UsageError(e.what());
  }
  try {
    return image::readPng(name);
  } catch (const std::runtime_error& e) {
    throw UsageError(fmt::format("{} (a damaged or truncated PNG?)", e.what()));
  }
}

}  // namespace

int runCompare(const CompareOptions& options) {
  // Exit 1 means "the pictures differ" here, so every failure to compare is exit 2 (cmp(1)'s
  // convention), whatever its kind: a CI must never read a broken comparison as a verdict.
  try {
    const image::CompareThresholds thresholds{.maxDifferingPixels = options.maxDifferingPixels,
                                              .maxDifferingFraction = options.maxDifferingFraction,
                                              .channelTolerance = options.channelTolerance,
                                              .minPsnr = options.minPsnr};
    image::checkThresholds(thresholds);
    if (options.diff) {
      refuseEmptyOutputName("--diff", *options.diff, "diff.png");
      if (!video::namesExtension(*options.diff, video::kPngExtension) && !io::namesStream(*options.diff)) {
        throw UsageError(
            fmt::format("--diff: the diff image is a PNG; give a name ending in .png, got \"{}\"", *options.diff));
      }
      refuseOverwritingInput("--diff", *options.diff, {options.a, options.b});
      io::checkOutputName(*options.diff);  // written after both pictures are read and compared
    }
    // Judged by the headers before anything is decoded: a small file may declare a huge picture.
    const image::PngSize sizeA = checkComparedPng(options.a), sizeB = checkComparedPng(options.b);
    if (sizeA.width != sizeB.width || sizeA.height != sizeB.height) {
      throw UsageError(
          fmt::format("{} is {}x{} but {} is {}x{}: compare pictures of the same size (render them with the same "
                      "render.width and render.height)",
                      options.a, sizeA.width, sizeA.height, options.b, sizeB.width, sizeB.height));
    }
    static_assert(image::kMaxComparedPixels == static_cast<long>(render::kMaxImageSide) * render::kMaxImageSide);
    const long pixels = static_cast<long>(sizeA.width) * sizeA.height;
    if (pixels > image::kMaxComparedPixels) {
      throw UsageError(
          fmt::format("{} and {} are {}x{}, more than the {} pixels compare decodes ({}x{}, the largest picture "
                      "coinroll draws); compare smaller pictures",
                      options.a, options.b, sizeA.width, sizeA.height, image::kMaxComparedPixels, render::kMaxImageSide,
                      render::kMaxImageSide));
    }
    // RGBA pictures at the peak: A, B and B's decoder buffer; with --diff, A, B, the diff image and
    // the two buffers encoding it.
    pipeline::requireAddressSpace((options.diff ? 5 : 3) * 4 * static_cast<std::uint64_t>(pixels),
                                  fmt::format("comparing two {}x{} pictures", sizeA.width, sizeA.height),
                                  "compare smaller pictures");
    // Each step is bounded by the size limit above, so polling between them answers Ctrl-C quickly.
    const auto stopIfInterrupted = [&] {
      if (interruptRequested()) {
        throw UsageError(options.diff ? interruptionMessage(*options.diff) : interruption() + "; nothing was compared");
      }
    };
    const image::Image a = decodeComparedPng(options.a);
    stopIfInterrupted();
    const image::Image b = decodeComparedPng(options.b);
    stopIfInterrupted();
    const image::ImageComparison result = image::compareImages(a, b, thresholds.channelTolerance);
    const image::CompareVerdict verdict = image::judge(result, thresholds);
    stopIfInterrupted();
    if (options.diff) image::writeDifferenceImage(a, b, thresholds.channelTolerance, *options.diff);
    fmt::print("{}\n", image::comparisonLine(result, verdict));
    errno = 0;
    std::fflush(stdout);
    if (std::ferror(stdout)) {
      throw std::runtime_error(fmt::format("writing to standard output failed: {}",
                                           errno != 0 ? std::strerror(errno) : "the stream reported an error"));
    }
    return verdict.pass ? kExitSuccess : kExitFailure;
  } catch (const UsageError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw UsageError(pipeline::outOfMemoryMessage());
  } catch (const std::exception& e) {
    throw UsageError(e.what());
  }
}

}  // namespace coinroll::cli
