#pragma once
// The flights of a run with "flight": true (docs/flight.md): the free coin's state read in the seed's
// variables, the touchdown of its rim that ends a flight (its impact: physics/landing.h), and a
// flight as a HybridRun's segment.

#include <optional>
#include <vector>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/flight.h"
#include "pipeline/contact_segment.h"
#include "pipeline/motion.h"

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

// A chain's flight (HybridRun), ended by its touchdown.
class FlightSegment final : public ContactSegment {
 public:
  // `duration`: s, the run's; a touchdown after it is not the run's.
  FlightSegment(const physics::CoinModel& model, double t0, const physics::FlightState& start, double dissipated,
                double duration)
      : flight_(model, t0, start, dissipated, duration), duration_(duration) {}

  bool continuesAngles() const override { return true; }
  std::optional<RunSample> sampleAt(double t, const physics::CoinState& continuation) override;
  std::optional<RunEvent> stoppedBy(const physics::CoinState& continuation) const override;
  std::vector<RunEvent> warnings() const override { return {}; }
  integrate::Stats stats() const override { return {}; }
  std::optional<SegmentEnd> end() const override;

 private:
  FreeFlight flight_;
  double duration_;  // s
};

}  // namespace coinroll::pipeline
