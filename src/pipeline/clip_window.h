#pragma once
// Which frames of a clip a render writes (render --from/--to, --from-video/--to-video, --last): a
// window on the simulated or the video clock, found on the clip's plan before anything is drawn.

#include <limits>
#include <optional>

#include "pipeline/playback_clock.h"

namespace coinroll::pipeline {

// The frames a render writes: those whose simulated time lies in [from, to] (render --from/--to), or
// whose video time k / fps does (--from-video/--to-video), or the last `last` s of video (--last),
// each within kWindowTolerance, exactly as the full render draws them. `to` past the end means the end.
struct TimeWindow {
  enum class Clock { Simulated, Video };
  double from = 0;                                      // s on `clock`
  double to = std::numeric_limits<double>::infinity();  // s on `clock`
  Clock clock = Clock::Simulated;
  // s of video: instead of from and to, the frames that play in the clip's last `last` seconds
  // (frame k plays from k / fps to (k + 1) / fps, so the window lasts exactly `last` s of video).
  std::optional<double> last = std::nullopt;
};
inline constexpr double kWindowTolerance = 1e-9;  // s: a frame time computed as a sum may miss a bound by round-off

// The frames [first, last] of `plan` that `window` keeps (frame times only grow, so they are a run of
// frames). Throws std::invalid_argument naming the window's options when it keeps none.
struct FrameRange {
  long first = 0;
  long last = -1;
};
FrameRange framesIn(const ClipPlan& plan, const TimeWindow& window);

}  // namespace coinroll::pipeline
