#pragma once
// Where rendered frames go. One sink per output format; the frame loop only knows this interface.

#include <cstdint>
#include <span>

#include "image/image.h"

namespace coinroll::video {

// Hz. The sample rate of every audio track coinroll writes.
inline constexpr int kAudioSampleRate = 48000;

class FrameSink {
 public:
  virtual ~FrameSink() = default;

  // Appends one frame (RGBA8, top row first). Throws std::runtime_error on an encoding or
  // writing failure, or std::invalid_argument on a frame the sink cannot take; after a throw
  // the sink is broken and should be destroyed (which removes its partial output).
  virtual void push(const image::Image& frame) = 0;

  // Appends mono audio samples in [-1, 1] at kAudioSampleRate, to play from where the samples
  // pushed so far end. Formats without an audio track (PNG sequences) ignore them.
  virtual void pushAudio(std::span<const float> /*samples*/) {}

  // Completes the output and publishes it under its final name in one step. A sink destroyed
  // without a successful finish() leaves nothing under the final name.
  virtual void finish() = 0;

  // Bytes the sink may allocate while frames of `frameBytes` bytes each arrive (an upper
  // estimate): an encoder that runs short of memory mid-clip fails without saying why ("Generic
  // error in an external library"), so the frame loop checks this against the memory left
  // before any work (pipeline/resources.h).
  virtual std::uint64_t workingMemory(std::uint64_t /*frameBytes*/) const { return 0; }

 protected:
  FrameSink() = default;
  FrameSink(const FrameSink&) = delete;
  FrameSink& operator=(const FrameSink&) = delete;
};

}  // namespace coinroll::video
