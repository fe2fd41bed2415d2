#pragma once
// A video file through libavformat/libavcodec/libswscale, of any kind video_kinds.h lists
// (VideoOptions::format).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

#include "io/output_group.h"
#include "video/frame_sink.h"
#include "video/video_options.h"

namespace coinroll::video {

// Throws std::invalid_argument naming the field, the rule and the value if `options` is unusable.
void validate(const VideoOptions& options);

// Writes <destination> (any name; the container is options.format's regardless of the extension)
// as the kind's row says: its muxer, encoder, options and pixel format (the alpha one with
// options.alpha), its index first or not, looping or not.
// Every kind: constant frame rate (time base 1/fps, pts = frame index, the last frame one period
// long); byte-identical for identical frames and options on the same FFmpeg and codec libraries
// (bit-exact flags, no dates or library versions; tested for each kind); the provenance, when
// given, as the container's "encoder" and "comment" tags, or by the row's addComment where the
// muxer drops them (GIF). YUV pixel formats are tagged BT.709 (primaries, transfer and matrix),
// limited ("TV") range; a palette format gets a fixed palette with ordered dithering (gif_palette.h).
// The file is written under a temporary name beside the destination and renamed in finish();
// for a stream destination (a device, FIFO or descriptor, which the muxer cannot seek) it is
// encoded in $TMPDIR and copied to the stream in finish() (io::OutputFile::Access::ByPath).
// With a `group`, a file is staged in it instead, and published by the group's commit() along
// with the run's other outputs (a sidecar); finish() then only completes it.
class EncoderSink final : public FrameSink {
 public:
  // Throws std::invalid_argument for bad options, std::runtime_error naming the destination if
  // its directory does not exist or the encoder cannot be set up.
  EncoderSink(std::filesystem::path destination, const VideoOptions& options, io::OutputGroup* group = nullptr);
  ~EncoderSink() override;

  // The frame must be options.width x options.height (std::invalid_argument otherwise).
  void push(const image::Image& frame) override;
  // Appends audio samples (mono, [-1, 1], kAudioSampleRate) after the frames pushed so far; the
  // muxer interleaves them with the video by timestamp. std::logic_error without options.audio.
  void pushAudio(std::span<const float> samples) override;
  // Drains the encoder, writes the trailer (moving moov to the front) and renames the file into
  // place (unless a group does). Throws std::runtime_error if no frame was pushed.
  void finish() override;
  // The encoder's frames in flight (for x264, lookahead, references and B-frames by preset, measured).
  std::uint64_t workingMemory(std::uint64_t frameBytes) const override;

  std::int64_t framesPushed() const { return framesPushed_; }

 private:
  struct Encoder;  // the FFmpeg state; keeps libav headers out of this header
  std::filesystem::path destination_;
  VideoOptions options_;
  std::unique_ptr<Encoder> encoder_;
  std::int64_t framesPushed_ = 0;
  bool finished_ = false;
};

}  // namespace coinroll::video
