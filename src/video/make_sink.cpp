#include "video/make_sink.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "io/destination.h"
#include "video/png_sequence_sink.h"
#include "video/video_kinds.h"

namespace coinroll::video {

namespace {

// The video kind the path's extension names; nothing for any other extension.
std::optional<VideoFormat> formatOfExtension(const std::filesystem::path& path) {
  for (const VideoKind& kind : videoKinds()) {
    if (namesExtension(path, kind.extension)) return kind.format;
  }
  return std::nullopt;
}

// The frame names of `output` when it names a PNG sequence with a well-formed pattern; a malformed
// one is the sink's to refuse, naming the rule it breaks.
std::optional<SequencePattern> sequencePatternOf(const std::filesystem::path& output) {
  if (!namesPngSequence(output)) return std::nullopt;
  try {
    return parseSequencePattern(output);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

}  // namespace

void refuseOverwritingInput(std::string_view argument, const std::filesystem::path& output,
                            const std::vector<std::filesystem::path>& inputs) {
  std::error_code error;
  const std::optional<SequencePattern> frames = sequencePatternOf(output);
  const std::string named = std::string(argument) + " " + output.string();
  for (const std::filesystem::path& input : inputs) {
    const std::filesystem::path outputDirectory = output.parent_path().empty() ? "." : output.parent_path();
    const std::filesystem::path inputDirectory = input.parent_path().empty() ? "." : input.parent_path();
    if (frames && std::filesystem::equivalent(outputDirectory, inputDirectory, error) &&
        frames->frameNumberOf(input.filename().string())) {
      throw std::invalid_argument(named + ": one of its frames would be the input " + input.string() +
                                  "; choose another output name");
    }
    if (std::filesystem::equivalent(output, input, error)) {
      throw std::invalid_argument(named + ": that is the input " + input.string() + "; choose another output name");
    }
  }
}

std::optional<VideoFormat> videoFormatOf(const std::filesystem::path& path) {
  if (const std::optional<VideoFormat> format = formatOfExtension(path)) return format;
  // A device, FIFO or descriptor has no extension of its own to choose by (/dev/null,
  // /dev/fd/63 from `-o >(...)`): it gets the default kind, as the default name does.
  if (!namesPngSequence(path) && io::namesStream(path)) return VideoOptions{}.format;
  return std::nullopt;
}

bool namesPngSequence(const std::filesystem::path& path) {
  return !formatOfExtension(path) && looksLikeSequencePattern(path.filename().string());
}

std::unique_ptr<FrameSink> makeSinkForPath(const std::filesystem::path& path, const VideoOptions& options,
                                           const std::vector<std::filesystem::path>& inputs, io::OutputGroup* group) {
  if (namesPngSequence(path)) return std::make_unique<PngSequenceSink>(path, inputs, options.provenance, group);
  if (const std::optional<VideoFormat> format = videoFormatOf(path)) {
    VideoOptions chosen = options;
    chosen.format = *format;
    return std::make_unique<EncoderSink>(path, chosen, group);
  }
  std::vector<std::string> extensions;
  for (const VideoKind& kind : videoKinds()) extensions.emplace_back(kind.extension);
  throw std::invalid_argument(path.string() + ": unknown output kind: expected a video ending in " +
                              joinedWithOr(extensions) + " (out" +
                              std::string(videoKind(VideoOptions{}.format).extension) +
                              ") or a PNG sequence pattern with one %d or %0Nd conversion (out_%05d.png)");
}

}  // namespace coinroll::video
