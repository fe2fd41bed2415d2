#pragma once
// A run that rolls and slides ("sliding": true; docs/sliding.md §4): a chain of segments, each one
// integrator over one contact mode, switched at located events. Rolling integrates the quaternion
// formulation and leaves it when the rolling reaction reaches friction_static N; sliding integrates
// physics/sliding.h and leaves it when the slip speed reaches zero and the rolling reaction fits the
// cone. Every switch is kept, with its time, for the command's stderr.

#include <atomic>
#include <memory>
#include <optional>
#include <vector>

#include "integrate/solver_config.h"
#include "integrate/trajectory.h"
#include "physics/coin_rhs.h"
#include "physics/sliding.h"
#include "pipeline/run_event.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

struct ModeSwitch {
  double t = 0;          // s
  bool toSliding = false;  // true: rolling -> sliding; false: sliding -> rolling
};

// A sample of the hybrid run: the integrated state's seed variables, the forward pass of the mode it
// is in, the energy dissipated so far (friction included).
struct HybridSample {
  physics::CoinState state;
  physics::Forward forward;
  double dissipated = 0;
};

// How a sliding segment takes friction's direction: along the slip (free), or along the slip's rest
// while the slip is too small for its own direction to be integrated (creeping, physics::Creep).
enum class SlipMode { Free, Creeping };

class HybridRun {
 public:
  explicit HybridRun(const Simulation& simulation);
  ~HybridRun();
  HybridRun(HybridRun&&) noexcept;
  HybridRun& operator=(HybridRun&&) noexcept;

  // The sample at t >= every earlier query (phi and psi continued from `continuation`); std::nullopt
  // once a model event has ended the run before t.
  std::optional<HybridSample> sampleAt(double t, const physics::CoinState& continuation);

  std::optional<RunEvent> stoppedBy(const physics::CoinState& continuation) const;
  std::vector<RunEvent> warnings() const;
  const std::vector<ModeSwitch>& switches() const { return switches_; }
  integrate::Stats stats() const;

 private:
  struct Segment;
  void startRolling(double t, const physics::QuaternionState& state, double dissipated);
  // `mode`: friction along the slip (free) or along its rest (creeping, physics::Creep: from zero
  // slip, or a slip too small for its direction to be integrated).
  void startSliding(double t, const physics::SlidingState& state, double dissipated, SlipMode mode);
  // Moves to the next segment when the current one ended in a switch; false when a model event ended it.
  bool switchIfDue();

  Simulation simulation_;
  std::unique_ptr<Segment> segment_;
  std::vector<ModeSwitch> switches_;
  std::vector<RunEvent> warnings_;
  integrate::Stats finishedStats_;  // of the segments before the current one
};

}  // namespace coinroll::pipeline
