#pragma once
// A run seen through the seed's CoinState, whatever integrates it: one formulation's equations over
// the whole run (formulation_run.h) or a chain of contact modes (hybrid_run.h). CoinRun holds one and
// continues phi and psi across its samples; a new formulation or contact mode is one more Motion.

#include <optional>
#include <vector>

#include "integrate/solver_config.h"
#include "physics/coin_state.h"
#include "physics/contact_mode.h"
#include "physics/forward.h"
#include "physics/validity.h"
#include "pipeline/run_event.h"

namespace coinroll::pipeline {

// One sample of a run.
struct RunSample {
  physics::CoinState state;  // the seed's variables
  physics::Forward forward;  // the integrating formulation's forward pass at this state
  double dissipated = 0;     // J, energy the effects have dissipated since t = 0
  int impacts = 0;           // the rim's impacts so far ("flight": true)
};

struct ModeSwitch {
  double t = 0;            // s
  bool toSliding = false;  // true: rolling -> sliding; false: sliding -> rolling
};

// An impact of the rim on the floor ("flight": true; docs/flight.md §3).
struct ImpactRecord {
  double t = 0;             // s
  double normalSpeed = 0;   // m/s, how fast the rim closed on the floor
  double reboundSpeed = 0;  // m/s, how fast it left; 0 at the bounce-end, where the rim stays down
  double energyLost = 0;    // J
  bool bouncesEnd = false;  // the last impact of a bounce sequence (the event bounce-end)
  bool corner = false;      // a cornered rim's other corner, landing as the coin passes upright
};

class Motion {
 public:
  Motion() = default;
  Motion(const Motion&) = delete;
  Motion& operator=(const Motion&) = delete;
  virtual ~Motion() = default;

  // Whether the integrated state carries no phi or psi (a quaternion attitude): they are then taken
  // within pi of a continuation's, which CoinRun keeps close enough by sampling often (kUnwrapTurn).
  virtual bool continuesAngles() const = 0;

  // The sample at t >= every earlier query, phi and psi within pi of `continuation`'s; std::nullopt
  // once an event has ended the run before t.
  virtual std::optional<RunSample> sampleAt(double t, const physics::CoinState& continuation) = 0;

  // The event that ended the run before its duration.
  virtual std::optional<RunEvent> stoppedBy(const physics::CoinState& continuation) const = 0;

  // Lift-off and slip crossings the run went on past (on_invalid "warn"), in time order so far.
  virtual std::vector<RunEvent> warnings() const = 0;

  // The switches between rolling and sliding so far (none unless the scene has "sliding": true); a run
  // that starts off the rolling constraint (an initial slip, or the static cone exceeded) has one at t = 0.
  virtual std::vector<ModeSwitch> switches() const { return {}; }

  // The rim's impacts so far, in time order (none unless the scene has "flight": true).
  virtual std::vector<ImpactRecord> impacts() const { return {}; }

  virtual integrate::Stats stats() const = 0;
};

// Event ids from this one on are a chain's transitions between contact modes (hybrid_run.h), past
// physics::ModelEvent's values.
inline constexpr int kFirstSwitchId = 1000;

inline int switchId(physics::Transition transition) { return kFirstSwitchId + static_cast<int>(transition); }

// The RunEvent of event `id` hit at t and sampled as `at`: a model event as itself; a switch that
// ends the run (one the chain could not make: stick-slip past its bound) as stick-slip.
inline RunEvent runEventOf(int id, double t, const RunSample& at) {
  return {.event = id < kFirstSwitchId ? static_cast<physics::ModelEvent>(id) : physics::ModelEvent::StickSlip,
          .t = t,
          .state = at.state,
          .forward = at.forward,
          .dissipated = at.dissipated};
}

}  // namespace coinroll::pipeline
