#include "pipeline/slow_motion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pipeline/motion_survey.h"

namespace coinroll::pipeline {

SlowMotionSchedule scheduleOf(const RunRecord& record, double gridInterval) {
  SlowMotionSchedule schedule;
  for (const ImpactRecord& impact : record.impacts) schedule.impacts.push_back(impact.t);
  const std::vector<bool>& flies = record.traceFlies;
  const auto gridTime = [&](std::size_t j) { return static_cast<double>(j) * gridInterval; };  // as the pass
  for (std::size_t j = 0; j < flies.size();) {
    if (!flies[j]) {
      ++j;
      continue;
    }
    // Grid points first to last in the air: the coin lifted off after the point before the first.
    const std::size_t first = j;
    while (j < flies.size() && flies[j]) ++j;
    SlowMotionSchedule::Span span{.start = first == 0 ? 0.0 : gridTime(first - 1), .end = record.survey.endTime};
    if (j < flies.size()) {
      // Down again at point j: the flight ended at the last impact after the point before (a landing is an impact).
      span.end = gridTime(j);
      const auto after = std::upper_bound(schedule.impacts.begin(), schedule.impacts.end(), gridTime(j - 1));
      const auto upTo = std::upper_bound(after, schedule.impacts.end(), gridTime(j));
      if (upTo != after) span.end = *(upTo - 1);
    }
    schedule.flights.push_back(span);
  }
  return schedule;
}

SlowMotionSchedule planSlowMotion(const scene::SceneConfig& scene, const Simulation& simulation) {
  if (!simulation.flight || (!scene.render.flightSlowDown && !scene.render.impactSlowDown)) return {};
  FixedFrameTimes none({});
  return scheduleOf(recordRun(simulation, none), traceInterval(simulation.duration));
}

double easedMultiplier(const scene::EventSlowDown& slowDown, double distance) {
  if (distance <= 0) return slowDown.slow;
  if (distance >= slowDown.window) return 1;
  const double x = distance / slowDown.window;
  return slowDown.slow + (1 - slowDown.slow) * x * x * (3 - 2 * x);
}

namespace {

// s from t to the nearest of `times` (sorted); infinity when there are none.
double distanceToNearest(const std::vector<double>& times, double t) {
  const auto next = std::lower_bound(times.begin(), times.end(), t);
  double distance = std::numeric_limits<double>::infinity();
  if (next != times.end()) distance = *next - t;
  if (next != times.begin()) distance = std::min(distance, t - *(next - 1));
  return distance;
}

// s from t to the nearest span (sorted, disjoint); 0 inside one.
double distanceToNearest(const std::vector<SlowMotionSchedule::Span>& spans, double t) {
  const auto next = std::lower_bound(spans.begin(), spans.end(), t,
                                     [](const SlowMotionSchedule::Span& span, double time) { return span.end < time; });
  double distance = std::numeric_limits<double>::infinity();
  if (next != spans.end()) distance = std::max(0.0, next->start - t);
  if (next != spans.begin()) distance = std::min(distance, t - (next - 1)->end);
  return distance;
}

}  // namespace

ScheduledSlowDown scheduledSlowDown(const scene::RenderSpec& render, const SlowMotionSchedule& schedule, double t) {
  ScheduledSlowDown slowest;
  if (render.flightSlowDown) {
    const double multiplier = easedMultiplier(*render.flightSlowDown, distanceToNearest(schedule.flights, t));
    if (multiplier < slowest.multiplier) slowest = {multiplier, SlowedBy::Flight};
  }
  if (render.impactSlowDown) {
    const double multiplier = easedMultiplier(*render.impactSlowDown, distanceToNearest(schedule.impacts, t));
    if (multiplier < slowest.multiplier) slowest = {multiplier, SlowedBy::Impact};
  }
  return slowest;
}

}  // namespace coinroll::pipeline
