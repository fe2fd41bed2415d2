#pragma once
// Slow motion in the air and around each impact (render.time_remap.flight and .impact): time_scale's
// multiplier as a function of simulated time alone. A frame plan chooses frame k + 1's time from
// frame k's sample, so it sees only the past, and an impact's slow-down must begin before the impact
// arrives: the times are taken from a first run of the same Simulation (runs are deterministic), the
// pass that then records the frames follows them.

#include <cstdint>
#include <vector>

#include "pipeline/run_record.h"
#include "pipeline/simulation.h"
#include "scene/scene_config.h"

namespace coinroll::pipeline {

// What the flight and impact slow-downs follow.
struct SlowMotionSchedule {
  struct Span {
    double start = 0, end = 0;  // s
  };
  // The stretches in the air, in time order. Each starts at the last sample of the first run's grid
  // (traceInterval apart) that was on the floor (or at 0), so a lift-off is slowed a grid step early
  // at most; each ends at the impact that ends it (the last in the grid step where the coin is down
  // again), or at the run's end.
  std::vector<Span> flights;
  std::vector<double> impacts;  // s, every impact of the rim, in time order
};

// The schedule read from a pass's record: its trace grid's flight flags (point j at j * gridInterval)
// and its impacts.
SlowMotionSchedule scheduleOf(const RunRecord& record, double gridInterval);

// The schedule `scene` asks for: a first run of `simulation` when the scene has "flight": true and a
// flight or impact slow-down; none otherwise (a coin that never leaves the floor has nothing to slow).
SlowMotionSchedule planSlowMotion(const scene::SceneConfig& scene, const Simulation& simulation);

// time_scale's multiplier `distance` s of simulated time from what `slowDown` follows (0 inside it):
//   slow + (1 - slow) e(distance / window),   e(x) = 3 x^2 - 2 x^3 on [0, 1], 1 beyond
// Smooth in simulated time (neither the rate nor its slope jumps), and in video time too: frames
// advance simulated time by the rate itself, so where the multiplier m rises by dm/dd the rate's
// logarithm rises by time_scale dm/dd per video second, at most 1.5 (1 - slow) time_scale / window,
// whatever slow is. A window of 0 switches at once. (An ease geometric in simulated time, the rate's
// logarithm smoothstepped, lingers at the slow end and rushes the fast one: at the toss's 60 fps it
// jumped x2.8 to x1.1 between two frames.)
double easedMultiplier(const scene::EventSlowDown& slowDown, double distance);

// Which rule set a frame's playback rate (render --plan).
enum class SlowedBy : std::uint8_t {
  Nothing,  // time_scale
  Rate,     // render.time_remap.spin_rate or precession_rate
  Flight,   // render.time_remap.flight
  Impact,   // render.time_remap.impact
};

struct ScheduledSlowDown {
  double multiplier = 1;  // of time_scale, in (0, 1]
  SlowedBy by = SlowedBy::Nothing;
};

// The flight and impact slow-downs at simulated time t: the slower of the two.
ScheduledSlowDown scheduledSlowDown(const scene::RenderSpec& render, const SlowMotionSchedule& schedule, double t);

}  // namespace coinroll::pipeline
