#pragma once
// A run that rolls and slides ("sliding": true; docs/sliding.md §4): a chain of segments, each one
// integrator over one contact mode, switched at located events. Rolling integrates the quaternion
// formulation and leaves it when the rolling reaction reaches friction_static N; sliding integrates
// physics/sliding.h and leaves it when the slip speed reaches zero and the rolling reaction fits the
// cone. Every switch is kept, with its time, for the command's stderr.

#include <memory>
#include <optional>
#include <vector>

#include "integrate/pace.h"
#include "integrate/solver_config.h"
#include "physics/coin_state.h"
#include "physics/flight.h"
#include "physics/contact_mode.h"
#include "physics/sliding.h"
#include "pipeline/motion.h"
#include "pipeline/run_event.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

// One contact mode's stretch of the chain (hybrid_run.cpp): a Motion that may end in a switch.
class ContactSegment;

class HybridRun final : public Motion {
 public:
  explicit HybridRun(const Simulation& simulation);
  ~HybridRun() override;

  bool continuesAngles() const override { return true; }
  std::optional<RunSample> sampleAt(double t, const physics::CoinState& continuation) override;
  std::optional<RunEvent> stoppedBy(const physics::CoinState& continuation) const override;
  std::vector<RunEvent> warnings() const override;
  std::vector<ModeSwitch> switches() const override { return switches_; }
  std::vector<ImpactRecord> impacts() const override { return impacts_; }
  integrate::Stats stats() const override;

 private:
  void startRolling(double t, const physics::QuaternionState& state, double dissipated);
  // `mode`: Sliding (friction along the slip) or Creeping (along its rest, physics::Creep: from zero
  // slip, or a slip too small for its direction to be integrated).
  void startSliding(double t, const physics::SlidingState& state, double dissipated, physics::ContactMode mode);
  void startFlight(double t, const physics::FlightState& state, double dissipated);
  // The rim held on the floor after a landing (docs/flight.md §4): sliding, creeping or rolling as
  // at a start, or flying on where the floor cannot hold it (N <= 0).
  void startContact(double t, const physics::SlidingState& state, double dissipated);
  // The touchdown at t: the impact, and what follows it; false when the run ends there. With
  // `otherCorner` (floor components, from the centre of mass) the landing is a cornered rim's corner
  // as the coin passes upright, the other corner the one it rolled on (docs/flight.md §4a).
  bool land(double t, const physics::FlightState& atTouch, double dissipated,
            std::optional<Eigen::Vector3d> otherCorner = std::nullopt);
  // Moves to the next segment when the current one ended in a switch; false when a model event ended it.
  bool switchIfDue();

  Simulation simulation_;
  std::unique_ptr<ContactSegment> segment_;
  std::vector<ModeSwitch> switches_;
  std::vector<RunEvent> warnings_;  // of the segments before the current one
  std::vector<ImpactRecord> impacts_;
  // A landing that ended the run (rest on a face, an impact jam): the event and the state at touch.
  struct Ending {
    physics::ModelEvent event;
    double t = 0;
    physics::FlightState state;
    double dissipated = 0;
  };
  std::optional<Ending> ending_;
  // The current segment's switch was refused (more than the run allows per second): stick-slip ends
  // the run there. Any other switch the segment ended in is the next sample's to take, not a stop.
  bool switchRefused_ = false;
  integrate::Stats finishedStats_;  // of the segments before the current one
  integrate::PaceWatch pace_;       // of all the segments' steps
};

}  // namespace coinroll::pipeline
