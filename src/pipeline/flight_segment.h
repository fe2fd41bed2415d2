#pragma once
// The flights of a run with "flight": true (docs/flight.md): the free coin's integrated state read in
// the seed's variables, the touchdown of its rim that ends a flight, and what the touchdown's impact
// leads to: another flight, the held contact once the bounces have died away, or rest on a face.

#include <optional>
#include <vector>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/flight.h"
#include "physics/quaternion_dynamics.h"
#include "physics/sliding.h"
#include "pipeline/motion.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

// A free coin's state read in the seed's variables, phi and psi within pi of `continuation`'s.
RunSample flightSample(const physics::CoinModel& model, const physics::FlightState& state, double dissipated,
                       const physics::CoinState& continuation);

// One flight in closed form (physics::flightAfter, docs/flight.md §1): no steps, exact to round-off
// however many turns the coin makes, and its touchdown found on the closed form (§2).
class FreeFlight {
 public:
  // The flight that starts at t0 in `start` with `dissipated` J already lost; its touchdown is
  // searched for up to `until` s.
  FreeFlight(const physics::CoinModel& model, double t0, const physics::FlightState& start, double dissipated,
             double until);

  physics::FlightState at(double t) const { return physics::flightAfter(model_, start_, t - t0_); }
  RunSample sample(const physics::FlightState& state, const physics::CoinState& continuation) const {
    return flightSample(model_, state, dissipated_, continuation);
  }
  // s: where the rim reaches the floor (the gap falling through -1e-12 a), or none up to `until`.
  std::optional<double> touchdown() const { return touchdown_; }
  const physics::CoinModel& model() const { return model_; }
  double dissipated() const { return dissipated_; }

 private:
  physics::CoinModel model_;
  double t0_;
  physics::FlightState start_;
  double dissipated_;
  std::optional<double> touchdown_;
};

// `state` with its centre at the height where the rim's lowest point touches the floor: where a
// bounce or a lift-off starts a flight (the touchdown was located a root tolerance either side of it,
// the contact's height carries round-off), moved by at most 1e-12 a.
physics::FlightState onTheFloor(const physics::CoinModel& model, physics::FlightState state);

// m/s, u_rest of docs/flight.md eq. (4.1): bounces end at a rebound that would lift the rim 1e-6 a.
double restSpeed(const physics::CoinModel& model);

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
