#pragma once
// The flights of a run with "flight": true (docs/flight.md): the free coin's integrated state read in
// the seed's variables, the touchdown of its rim that ends a flight, and what the touchdown's impact
// leads to: another flight, the held contact once the bounces have died away, or rest on a face.

#include <vector>

#include "integrate/events.h"
#include "integrate/solver_config.h"
#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/flight.h"
#include "physics/quaternion_dynamics.h"
#include "physics/sliding.h"
#include "pipeline/motion.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

inline constexpr int kFlightSize = physics::kFlightStateSize + 1;  // with the dissipated energy, constant in flight

struct FlightRhs {
  physics::CoinModel model;
  integrate::Vec<kFlightSize> operator()(double t, const integrate::Vec<kFlightSize>& y) const;
};

// A flight's integrated state read in the seed's variables (TrajectoryMotion's Kind).
struct FlightKind {
  using Rhs = FlightRhs;
  static constexpr bool kContinuesAngles = true;

  physics::CoinModel model;

  Rhs rhs() const { return Rhs{model}; }
  RunSample sample(const integrate::Vec<kFlightSize>& y, const physics::CoinState& continuation) const;
};

physics::FlightState flightStateOf(const integrate::Vec<kFlightSize>& y);

// The rim reaching the floor, falling through zero (docs/flight.md §2), with event id `id`.
integrate::Event<kFlightSize> touchdownEvent(const physics::CoinModel& model, int id);

// `state` with its centre at the height where the rim's lowest point touches the floor: where a
// bounce or a lift-off starts a flight (the touchdown was located a root tolerance either side of it,
// the contact's height carries round-off), moved by at most 1e-12 a.
physics::FlightState onTheFloor(const physics::CoinModel& model, physics::FlightState state);

// The scene's solver with its steps capped so that none spans a hop of the rim or a turn of the coin.
integrate::SolverConfig flightSolver(const Simulation& simulation, const physics::FlightState& start);

// What a touchdown leads to (docs/flight.md §3-§5).
struct Landing {
  enum class Next {
    Flight,   // the rim bounced
    Contact,  // the bounces ended: the rim stays on the floor, sliding or rolling
    Rest,     // the coin arrived flat on a face (physics::ModelEvent::Rest)
    Jam,      // the impact has no solution (physics::ModelEvent::ImpactJam)
  };
  Next next = Next::Flight;
  physics::FlightState state;  // after the impact (Contact: the rim's normal velocity zero); Rest, Jam: at touch
  double dissipated = 0;       // J, the impact's loss included
  ImpactRecord impact;
};

// `plastic`: end the bounces here whatever the rebound (a run past its bound of impacts per second).
Landing land(const Simulation& simulation, double t, const physics::FlightState& atTouch, double dissipated,
             bool plastic);

// The held contact of a coin whose rim touches the floor without normal velocity: its attitude and
// rates, and the slip of the contact point.
physics::SlidingState contactStateOf(const physics::CoinModel& model, const physics::FlightState& state);

// The flight that a held contact leaves in (a lift-off): its forward pass's centre and velocity.
physics::FlightState flightStateOf(const physics::QuaternionState& attitude, const physics::Forward& contact);

}  // namespace coinroll::pipeline
