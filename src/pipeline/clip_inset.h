#pragma once
// The inset plot of `render --inset`: the contact point's rate and the tilt over the frames written,
// with a marker at each frame.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "pipeline/clip_window.h"
#include "pipeline/playback_clock.h"
#include "pipeline/run_record.h"
#include "render/frame_snapshot.h"

namespace coinroll::pipeline {

// Points per inset curve: a few per pixel of a 1080p plot, which a clip of a million frames would
// otherwise carry into every frame's overlay.
inline constexpr std::size_t kInsetPoints = 600;
// A contact rate spanning this factor or more is plotted on a log scale, where an Euler's disk's
// finite-time speed-up is a curve that steepens instead of a flat line and a wall.
inline constexpr double kLogScaleSpan = 4;

// The inset (render --inset) of the frames `range` of `plan`, the video written: the contact point's
// rate (Hz) and the tilt above the floor (degrees, from 0) against video time, each over its range
// within those frames (the last 20 s of the Euler's disk fill the plot), and each frame's labels.
class ClipInset {
 public:
  ClipInset(const ClipPlan& plan, const std::vector<FrameState>& frames, FrameRange range)
      : plan_(plan), frames_(frames), range_(range) {
    for (long k = range.first; k <= range.last; ++k) {
      rateMin_ = std::min(rateMin_, hertz(k));
      rateMax_ = std::max(rateMax_, hertz(k));
      tiltMax_ = std::max(tiltMax_, tiltDegrees(k));
    }
    logRate_ = rateMin_ > 0 && rateMax_ >= kLogScaleSpan * rateMin_;
  }

  render::InsetPlot plot() const {
    render::InsetPlot plot{.curves = {{}, {}}};
    const long count = range_.last - range_.first + 1;
    const long stride = std::max(1L, (count + static_cast<long>(kInsetPoints) - 1) / static_cast<long>(kInsetPoints));
    // Every stride-th frame, and the last.
    for (long k = range_.first;; k = std::min(k + stride, range_.last)) {
      const float x = progress(k);
      plot.curves[0].points.emplace_back(x, static_cast<float>(rateScaled(hertz(k))));
      plot.curves[1].points.emplace_back(x, static_cast<float>(tiltMax_ > 0 ? tiltDegrees(k) / tiltMax_ : 0));
      if (k == range_.last) break;
    }
    return plot;
  }

  float progress(long k) const {
    return range_.last > range_.first
               ? static_cast<float>(k - range_.first) / static_cast<float>(range_.last - range_.first)
               : 0.0f;
  }

  std::vector<std::string> labels(long k) const {
    return {fmt::format("contact {:6.1f} Hz  ({}{:.3g} to {:.3g} Hz)", hertz(k), logRate_ ? "log, " : "", rateMin_,
                        rateMax_),
            fmt::format("tilt    {:6.2f}°   (0 to {:.3g}° above the floor)", tiltDegrees(k), tiltMax_)};
  }

 private:
  double hertz(long k) const { return plan_.contactRates[static_cast<std::size_t>(k)] / (2 * std::numbers::pi); }
  double tiltDegrees(long k) const {
    const std::size_t shown = std::min(static_cast<std::size_t>(k), frames_.size() - 1);  // the hold: the landing
    return 90 - frames_[shown].theta * 180 / std::numbers::pi;
  }
  double rateScaled(double value) const {
    if (logRate_) return std::log(value / rateMin_) / std::log(rateMax_ / rateMin_);
    return rateMax_ > 0 ? value / rateMax_ : 0;
  }

  const ClipPlan& plan_;
  const std::vector<FrameState>& frames_;
  FrameRange range_;
  double rateMin_ = std::numeric_limits<double>::infinity(), rateMax_ = 0, tiltMax_ = 0;  // Hz, Hz, degrees
  bool logRate_ = false;
};

}  // namespace coinroll::pipeline
