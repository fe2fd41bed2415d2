#pragma once
// H.264 (libx264) in an MP4 container, through libavformat/libavcodec/libswscale.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

#include "video/frame_sink.h"
#include "video/mp4_options.h"

namespace coinroll::video {

// Throws std::invalid_argument naming the field, the rule and the value if `options` is unusable.
void validate(const Mp4Options& options);

// Writes <destination> (any name; the container is MP4 regardless of the extension).
// Properties of the file: constant frame rate (time base 1/fps, pts = frame index), yuv420p with
// BT.709 primaries, transfer and matrix, limited ("TV") range, all tagged; moov before mdat
// (faststart, so players can start before the download ends); byte-identical for identical
// frames and options on the same FFmpeg/x264 build (bit-exact flags, no dates or version tags).
// The file is written under a temporary name beside the destination and renamed in finish();
// for a stream destination (a device, FIFO or descriptor, which the muxer cannot seek) it is
// encoded in $TMPDIR and copied to the stream in finish() (io::OutputFile::Access::ByPath).
class Mp4Sink final : public FrameSink {
 public:
  // Throws std::invalid_argument for bad options, std::runtime_error naming the destination if
  // its directory does not exist or the encoder cannot be set up.
  Mp4Sink(std::filesystem::path destination, const Mp4Options& options);
  ~Mp4Sink() override;

  // The frame must be options.width x options.height (std::invalid_argument otherwise).
  void push(const image::Image& frame) override;
  // Appends audio samples (mono, [-1, 1], kAudioSampleRate) after the frames pushed so far; the
  // muxer interleaves them with the video by timestamp. std::logic_error without options.audio.
  void pushAudio(std::span<const float> samples) override;
  // Drains the encoder, writes the trailer (moving moov to the front) and renames the file into
  // place. Throws std::runtime_error if no frame was pushed.
  void finish() override;
  // x264's frames in flight (lookahead, references, B-frames) for the preset, from measurements.
  std::uint64_t workingMemory(std::uint64_t frameBytes) const override;

  std::int64_t framesPushed() const { return framesPushed_; }

 private:
  struct Encoder;  // the FFmpeg state; keeps libav headers out of this header
  std::filesystem::path destination_;
  Mp4Options options_;
  std::unique_ptr<Encoder> encoder_;
  std::int64_t framesPushed_ = 0;
  bool finished_ = false;
};

}  // namespace coinroll::video
