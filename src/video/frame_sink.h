#pragma once
// Where rendered frames go. One sink per output format; the frame loop only knows this interface.

#include "image/image.h"

namespace coinroll::video {

class FrameSink {
 public:
  virtual ~FrameSink() = default;

  // Appends one frame (RGBA8, top row first). Throws std::runtime_error on an encoding or
  // writing failure, or std::invalid_argument on a frame the sink cannot take; after a throw
  // the sink is broken and should be destroyed (which removes its partial output).
  virtual void push(const image::Image& frame) = 0;

  // Completes the output and publishes it under its final name in one step. A sink destroyed
  // without a successful finish() leaves nothing under the final name.
  virtual void finish() = 0;

 protected:
  FrameSink() = default;
  FrameSink(const FrameSink&) = delete;
  FrameSink& operator=(const FrameSink&) = delete;
};

}  // namespace coinroll::video
