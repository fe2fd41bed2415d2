#pragma once
// The flights of a run with "flight": true (docs/flight.md): the free coin integrated from a lift-off
// or a bounce to the touchdown of its rim, and what the touchdown's impact leads to: another flight,
// the held contact once the bounces have died away, or rest on a face.

#include <optional>

#include "integrate/solver_config.h"
#include "integrate/trajectory.h"
#include "physics/flight.h"
#include "physics/forward.h"
#include "physics/sliding.h"
#include "pipeline/simulation.h"

namespace coinroll::pipeline {

struct ImpactRecord {
  double t = 0;             // s
  double normalSpeed = 0;   // m/s, how fast the rim closed on the floor
  double reboundSpeed = 0;  // m/s, how fast it left (0 once the bounces end)
  double energyLost = 0;    // J
};

struct FlightSample {
  physics::FlightState state;
  physics::Forward forward;
  double dissipated = 0;  // J, since t = 0
};

class FlightSegment {
 public:
  static constexpr int kSize = physics::kFlightStateSize + 1;  // with the dissipated energy, constant in flight

  FlightSegment(const Simulation& simulation, double t0, const physics::FlightState& start, double dissipated);

  // The sample at t >= every earlier query; std::nullopt once the rim has touched the floor before t.
  std::optional<FlightSample> sampleAt(double t);
  // The touchdown that ended the flight, once the integration has passed it.
  std::optional<FlightSample> touchdown() const;
  const integrate::Stats& stats() const { return trajectory_.stats(); }

 private:
  struct Rhs {
    physics::CoinModel model;
    integrate::Vec<kSize> operator()(double t, const integrate::Vec<kSize>& y) const;
  };
  FlightSample sampleOf(const integrate::Vec<kSize>& y) const;

  physics::CoinModel model_;
  integrate::Trajectory<kSize, Rhs> trajectory_;
};

// What a touchdown leads to (docs/flight.md §3-§5).
struct Landing {
  enum class Next {
    Flight,   // the rim bounced
    Contact,  // the bounces ended: the rim stays on the floor, sliding or rolling
    Rest,     // the coin arrived flat on a face (physics::ModelEvent::Rest)
    Jam,      // the impact has no solution (physics::ModelEvent::ImpactJam)
  };
  Next next = Next::Flight;
  physics::FlightState state;  // after the impact: Flight, Contact (rim's normal velocity zero); Rest, Jam: at touch
  double dissipated = 0;       // J, the impact's loss included
  ImpactRecord impact;
};

Landing land(const Simulation& simulation, const FlightSample& touchdown, double t);

// The held contact of a coin whose rim touches the floor without normal velocity: its attitude and
// rates, and the slip of the contact point.
physics::SlidingState contactStateOf(const physics::CoinModel& model, const physics::FlightState& state);

// The flight state of a held contact (a lift-off): the centre at its height and the contact's velocity.
physics::FlightState flightStateOf(const physics::Forward& forward, const physics::QuaternionState& state);

}  // namespace coinroll::pipeline
