#include "video/make_sink.h"

#include <cctype>
#include <stdexcept>

#include "io/destination.h"
#include "video/png_sequence_sink.h"

namespace coinroll::video {

namespace {

// The video kind the path's extension names, in any case; nothing for any other extension.
std::optional<VideoFormat> formatOfExtension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const VideoFormat format : kVideoFormats) {
    if (extension == extensionOf(format)) return format;
  }
  return std::nullopt;
}

}  // namespace

std::optional<VideoFormat> videoFormatOf(const std::filesystem::path& path) {
  if (const std::optional<VideoFormat> format = formatOfExtension(path)) return format;
  // A device, FIFO or descriptor has no extension of its own to choose by (/dev/null,
  // /dev/fd/63 from `-o >(...)`): it gets the default kind, as the default name does.
  if (!namesPngSequence(path) && io::namesStream(path)) return VideoFormat::Mp4;
  return std::nullopt;
}

bool namesPngSequence(const std::filesystem::path& path) {
  return !formatOfExtension(path) && looksLikeSequencePattern(path.filename().string());
}

std::unique_ptr<FrameSink> makeSinkForPath(const std::filesystem::path& path, const VideoOptions& options,
                                           const std::vector<std::filesystem::path>& inputs) {
  if (namesPngSequence(path)) return std::make_unique<PngSequenceSink>(path, inputs, options.provenance);
  if (const std::optional<VideoFormat> format = videoFormatOf(path)) {
    VideoOptions chosen = options;
    chosen.format = *format;
    return std::make_unique<EncoderSink>(path, chosen);
  }
  throw std::invalid_argument(path.string() +
                              ": unknown output kind: expected a video ending in .mp4, .gif, .webm or .mov (out.mp4) "
                              "or a PNG sequence pattern with one %d or %0Nd conversion (out_%05d.png)");
}

}  // namespace coinroll::video
