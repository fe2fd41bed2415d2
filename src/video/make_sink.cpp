#include "video/make_sink.h"

#include <cctype>
#include <stdexcept>

#include "io/destination.h"
#include "video/png_sequence_sink.h"

namespace coinroll::video {

namespace {

bool hasMp4Extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".mp4";
}

}  // namespace

bool namesPngSequence(const std::filesystem::path& path) {
  return !hasMp4Extension(path) && looksLikeSequencePattern(path.filename().string());
}

std::unique_ptr<FrameSink> makeSinkForPath(const std::filesystem::path& path, const Mp4Options& options,
                                           const std::vector<std::filesystem::path>& inputs) {
  if (namesPngSequence(path)) return std::make_unique<PngSequenceSink>(path, inputs);
  // A device, FIFO or descriptor has no extension of its own to choose by (/dev/null,
  // /dev/fd/63 from `-o >(...)`): it gets the default kind, as the default name does.
  if (hasMp4Extension(path) || io::namesStream(path)) return std::make_unique<Mp4Sink>(path, options);
  throw std::invalid_argument(path.string() +
                              ": unknown output kind: expected a video ending in .mp4 (out.mp4) or a PNG "
                              "sequence pattern with one %d or %0Nd conversion (out_%05d.png)");
}

}  // namespace coinroll::video
