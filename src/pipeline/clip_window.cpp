#include "pipeline/clip_window.h"

#include <fmt/format.h>

#include <stdexcept>

namespace coinroll::pipeline {

FrameRange framesIn(const ClipPlan& plan, const TimeWindow& window) {
  const double length = plan.videoSeconds();
  // A frame's place on the window's clock: simulated time, or video time k / fps.
  const bool byVideo = window.clock == TimeWindow::Clock::Video || window.last;
  const auto clockOf = [&](long k) {
    return byVideo ? static_cast<double>(k) / plan.fps : plan.times[static_cast<std::size_t>(k)];
  };
  if (window.last && *window.last > length + kWindowTolerance) {
    throw std::invalid_argument(
        fmt::format("--last {}: longer than the clip, which lasts {:.9g} s of video; give at "
                    "most that, or no window for the whole clip",
                    *window.last, length));
  }
  const double from = window.last ? length - *window.last : window.from;
  const double to = window.last ? length : window.to;
  FrameRange range{plan.frames(), plan.frames() - 1};
  for (long k = 0; k < plan.frames(); ++k) {
    const double t = clockOf(k);
    if (t < from - kWindowTolerance || t > to + kWindowTolerance) continue;
    range.first = std::min(range.first, k);
    range.last = k;
  }
  if (range.first <= range.last) return range;
  const double lastFrameAt = static_cast<double>(plan.frames() - 1) / plan.fps;  // s of video
  if (window.last) {
    throw std::invalid_argument(
        fmt::format("--last {}: no frame plays in the last {} s of the {:.6g} s clip; give "
                    "at least one frame's length, 1 / fps = {:.6g} s",
                    *window.last, *window.last, length, 1.0 / plan.fps));
  }
  if (byVideo && from > lastFrameAt + kWindowTolerance) {
    throw std::invalid_argument(
        fmt::format("--from-video {}: beyond the clip's last frame at {:.9g} s of video (the "
                    "clip lasts {:.9g} s); give a time in [0, {:.9g}]",
                    from, lastFrameAt, length, lastFrameAt));
  }
  if (byVideo) {
    throw std::invalid_argument(fmt::format(
        "--from-video {} --to-video {}: no frame plays in this window (frames are 1 / {} s of video apart); widen it",
        window.from, window.to, plan.fps));
  }
  if (window.from > plan.endTime + kWindowTolerance) {
    throw std::invalid_argument(
        fmt::format("--from {}: beyond the run's end at {:.9g} s{}; give a time in [0, {:.9g}]", window.from,
                    plan.endTime, plan.stopDescription ? " (" + *plan.stopDescription + ")" : "", plan.endTime));
  }
  throw std::invalid_argument(
      fmt::format("--from {} --to {}: no frame's simulated time lies in this window (frames "
                  "are {:.6g} s of simulated time apart{}); widen it",
                  window.from, window.to, plan.timeScale / plan.fps,
                  plan.remapped ? ", less where render.time_remap slows them" : ""));
}

}  // namespace coinroll::pipeline
