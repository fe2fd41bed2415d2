#pragma once
// One integration of a run for `render` and `still`: a single pass over a CoinRun, in increasing
// time, samples the trace grid (traceInterval), the frame times (chosen as it goes, since a time
// remap's next frame depends on the rate at the frame before) and the run's end, and keeps what the
// survey, the trace and each frame's picture, overlay, camera and sound need. The frame loop then
// only draws.

#include <Eigen/Core>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "integrate/solver_config.h"
#include "pipeline/coin_run.h"
#include "pipeline/motion_survey.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

// The coin at one frame time, as compact as the frame needs (a whole RunSample is 432 bytes): 112 bytes,
// so a clip at the default limit of 1 000 000 frames keeps at most 112 MB of them.
struct FrameState {
  double time = 0;                                   // s of simulated time
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // m, centre of mass (coin pose, camera)
  glm::quat attitude{1.0f, 0.0f, 0.0f, 0.0f};        // body axes -> floor frame, as drawn
  glm::vec2 contact{0.0f};                           // m, contact point on the floor (x, z)
  double theta = 0;                                  // rad
  double omega_Z = 0;                                // rad/s
  double precessionRate = 0;                         // rad/s, phi-dot (overlay, sound)
  double energy = 0;                                 // J
  double power = 0;                                  // W dissipated by the effects
  double slipSpeed = 0;                              // m/s, of the contact while sliding
  bool sliding = false;
  bool flying = false;         // "flight": true, between the floor's contacts
  bool axisGoesRound = false;  // physics::axisGoesRound
  int impacts = 0;             // the rim's impacts so far ("flight": true)
};

FrameState frameStateOf(double time, const RunSample& sample);

// The frames a pass records, chosen while it runs.
class FramePlan {
 public:
  virtual ~FramePlan() = default;
  // Simulated time (s) at which to sample frame k, or none when there is no frame k as far as a run
  // that goes on to its duration is concerned. `previous` is the sample at frame k - 1's time
  // (null for k = 0).
  virtual std::optional<double> timeOf(long k, const RunSample* previous) = 0;
  // Whether frame k, asked at `time`, belongs to a run that ends at `end` (s; an event's time, or
  // the duration): it is then shown at min(time, end). May throw to refuse the clip.
  virtual bool keeps(long k, double time, double end) = 0;
};

// Frames at given times, in increasing order; one past the run's end is shown at the end.
class FixedFrameTimes final : public FramePlan {
 public:
  explicit FixedFrameTimes(std::vector<double> times) : times_(std::move(times)) {}
  std::optional<double> timeOf(long k, const RunSample*) override;
  bool keeps(long, double, double) override { return true; }

 private:
  std::vector<double> times_;  // s
};

struct RunRecord {
  MotionSurvey survey;
  // The contact point every traceInterval from t = 0 while the run lasts (point j at j * interval).
  std::vector<glm::vec2> trace;
  std::vector<bool> traceSlides;
  std::vector<bool> traceFlies;       // "flight": true: the points the coin was in the air at
  std::vector<FrameState> frames;     // the plan's frames, in time order
  std::vector<ImpactRecord> impacts;  // "flight": true: the rim's impacts, for the sound track
  FrameState end;                     // the coin at survey.endTime
  integrate::Stats stats;             // of the pass's one CoinRun
};

// Adds a sample of the run to `record`'s survey (the box round every centre and contact point; `first`
// starts it) and, when it lies `onGrid` (at j traceInterval), the trace's next point.
void addSurveySample(RunRecord& record, const RunSample& sample, bool first, bool onGrid);

// Integrates `simulation` once, to its duration or the event that ends it.
RunRecord recordRun(const Simulation& simulation, FramePlan& plan);

}  // namespace coinroll::pipeline
