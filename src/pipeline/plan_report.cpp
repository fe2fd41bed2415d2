#include "pipeline/plan_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

namespace coinroll::pipeline {

namespace {

// A playback rate as the overlay says it: slow motion or fast forward by how much.
std::string speedOf(double rate) {
  if (rate == 0) return "landing held";
  if (rate < 1 - 1e-9) return fmt::format("slow x{:.3g}", 1 / rate);
  if (rate > 1 + 1e-9) return fmt::format("fast x{:.3g}", rate);
  return "real time";
}

// The rule a frame's rate is set by, as the plan's table names it.
std::string_view ruleOf(SlowedBy by) {
  switch (by) {
    case SlowedBy::Rate: return "rate";
    case SlowedBy::Flight: return "flight";
    case SlowedBy::Impact: return "impact";
    case SlowedBy::Nothing: break;
  }
  return "-";
}

// The flight and impact slow-downs' line of the plan: what they followed and how many frames they set.
std::string slowMotionLine(const ClipPlan& plan) {
  const auto framesBy = [&](SlowedBy by) { return std::count(plan.slowedBy.begin(), plan.slowedBy.end(), by); };
  std::vector<std::string> stretches;
  for (const SlowMotionSchedule::Span& span : plan.flights) {
    stretches.push_back(fmt::format("{:.6f} to {:.6f} s", span.start, span.end));
  }
  constexpr std::size_t kListed = 4;  // stretches named; a hopping coin may have hundreds
  if (stretches.size() > kListed) {
    stretches.resize(kListed);
    stretches.emplace_back("...");
  }
  return fmt::format(
      "slow motion: {} frames by flight, in the air {} time{} ({}); {} frames by impact, {} impact{}{}",
      framesBy(SlowedBy::Flight), plan.flights.size(), plan.flights.size() == 1 ? "" : "s", fmt::join(stretches, ", "),
      framesBy(SlowedBy::Impact), plan.impacts.size(), plan.impacts.size() == 1 ? "" : "s",
      plan.impacts.empty() ? "" : fmt::format(" from {:.6f} to {:.6f} s", plan.impacts.front(), plan.impacts.back()));
}

}  // namespace

std::vector<std::string> planLines(const ClipPlan& plan, const TimeWindow& window) {
  const long holdFrames = plan.frames() - plan.simulatedFrames;
  std::vector<std::string> lines;
  lines.push_back(fmt::format(
      "video: {} frames at {} fps, {:.3f} s{}", plan.frames(), plan.fps, plan.videoSeconds(),
      holdFrames > 0 ? fmt::format(" (the last {} hold the landing, {:g} s)", holdFrames, kLandingHoldSeconds) : ""));
  lines.push_back(fmt::format("simulated: 0 to {:.6f} s{}", plan.endTime,
                              plan.stopDescription ? "; the run stops early: " + *plan.stopDescription : ""));
  if (plan.byEvents) lines.push_back(slowMotionLine(plan));
  const FrameRange range = framesIn(plan, window);
  const auto first = static_cast<std::size_t>(range.first), last = static_cast<std::size_t>(range.last);
  const long written = range.last - range.first + 1;
  lines.push_back(
      fmt::format("written: {} frames {} to {}, {:.3f} s of video from {:.3f} s; simulated {:.6f} to "
                  "{:.6f} s",
                  written == plan.frames() ? "all" : std::to_string(written), range.first, range.last,
                  static_cast<double>(written) / plan.fps, static_cast<double>(range.first) / plan.fps,
                  plan.times[first], plan.times[last]));
  // A row where the playback rate or the contact point's rate has changed by kRowChange since the
  // last row; a wobbling run whose rates swing by more would list most of its frames, so the step
  // grows until the table is small.
  constexpr double kRowChange = 1.25;
  constexpr std::size_t kMaxRows = 24;
  const auto changed = [](double now, double before, double factor) {
    return now > 0 && before > 0 ? std::max(now / before, before / now) >= factor : (now > 0) != (before > 0);
  };
  std::vector<std::size_t> rows;
  for (double factor = kRowChange; rows.empty() || rows.size() > kMaxRows; factor *= kRowChange) {
    rows = {0};
    for (std::size_t k = 1; k < plan.times.size(); ++k) {
      const std::size_t row = rows.back();
      if (changed(plan.playbackRates[k], plan.playbackRates[row], factor) ||
          changed(plan.contactRates[k], plan.contactRates[row], factor) || k + 1 == plan.times.size()) {
        rows.push_back(k);
      }
    }
  }
  lines.emplace_back(
      "playback over the clip (a row where a rate changed by 25 % or more; rate: simulated s per "
      "video s; contact: the contact point round the floor, turns per s; slowed_by: the time remap's "
      "rule that set the rate):");
  lines.emplace_back(
      "    frame    video_s        sim_s       rate        speed  contact_Hz  contact_turns_per_video_s  slowed_by");
  for (const std::size_t k : rows) {
    const double rate = plan.playbackRates[k], turns = plan.contactRates[k] / (2 * std::numbers::pi);
    lines.push_back(fmt::format("{:9d} {:10.3f} {:12.6f} {:10.6f} {:>12} {:11.3f} {:26.3f}  {:>9}", k,
                                static_cast<double>(k) / plan.fps, plan.times[k], rate, speedOf(rate), turns,
                                turns * rate, ruleOf(plan.slowedBy[k])));
  }
  return lines;
}

std::vector<std::string> overlayExtraLines(const ClipPlan& plan, long k) {
  // Simulated time stands still in the hold, so the overlay says so instead of the landing's playback rate.
  if (k >= plan.simulatedFrames) return {fmt::format("landed, held {:g} s", kLandingHoldSeconds)};
  const double slowdown = 1 / plan.playbackRates[static_cast<std::size_t>(k)];
  if (slowdown > 1 + 1e-9) return {fmt::format("slow motion ×{:.3g}", slowdown)};
  if (slowdown < 1 - 1e-9) return {fmt::format("fast forward ×{:.3g}", 1 / slowdown)};
  return {};
}

}  // namespace coinroll::pipeline
