#pragma once
// A run that rolls and slides ("sliding": true; docs/sliding.md §4), and flies and lands ("flight":
// true; docs/flight.md): a chain of segments, one per stretch of a contact mode (physics/contact_mode.h),
// each ending in a located transition. Where each one leads is physics::next's table; the chain keeps
// the books: the segments' work and crossings, the switches and impacts with their times (for the
// command's stderr), and its bounds on how fast it switches and lands.

#include <memory>
#include <optional>
#include <vector>

#include "integrate/pace.h"
#include "integrate/solver_config.h"
#include "physics/coin_state.h"
#include "physics/contact_mode.h"
#include "physics/flight.h"
#include "physics/validity.h"
#include "pipeline/motion.h"
#include "pipeline/run_event.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

// One contact mode's stretch of the chain (contact_segment.h).
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
  // Takes `transition` from `from` where physics::next leads: starts that mode's segment, or resolves
  // its impact; false when the run ends there.
  bool enter(physics::Mode from, physics::Transition transition, const physics::Handover& handover);
  // The segment of each mode, from the state handed on to it.
  void startRolling(const physics::Handover& start);
  void startSliding(const physics::Handover& start, physics::Mode mode);  // Sliding or Creeping
  void startFlight(double t, const physics::FlightState& state, double dissipated);
  // The impact of a flight's touchdown (from Flight) or of a cornered rim's other corner (from a held
  // contact), and what its outcome leads to; false when the run ends there.
  bool strike(physics::Mode from, const physics::Handover& handover);
  // The stderr's switches: each slide that starts from rolling or where there was no contact, and each
  // return from a slide to rolling; none between sliding and creeping.
  void noteSwitch(physics::Mode from, physics::Mode to, double t);
  // Ends the run at `event` with the coin handed over there.
  void endAt(physics::ModelEvent event, const physics::Handover& handover);
  // Past the bound of rolling-sliding switches per second: the run ends (stick-slip or on-edge).
  bool tooManySwitches(const physics::Handover& handover);
  // Moves to the next segment when the current one ended in a transition; false when a model event
  // ended it, or the run ends at the transition.
  bool switchIfDue();

  Simulation simulation_;
  physics::Mode mode_ = physics::Mode::Rolling;  // the current segment's
  std::unique_ptr<ContactSegment> segment_;
  std::vector<ModeSwitch> switches_;
  std::vector<RunEvent> warnings_;  // of the segments before the current one
  std::vector<ImpactRecord> impacts_;
  // A transition that ended the run (rest on a face, an impact jam, on its edge, decided): the event
  // and the coin there.
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
