#include "pipeline/flight_segment.h"

#include <cmath>

#include "physics/impact.h"
#include "physics/validity.h"

namespace coinroll::pipeline {

namespace {

// m, per m of radius: the rim touches when it is this far into the floor. A flight starts with the
// rim on the floor (a bounce, a lift-off), where the gap is zero to round-off and, after a lift-off,
// grows only as t^3; a crossing of zero itself could be read in that round-off.
constexpr double kTouchDepth = 1e-12;

// docs/flight.md eq. (4.1): bounces end at a rebound that would lift the rim 1e-6 a.
constexpr double kRestHeight = 1e-6;

enum FlightEventId : int { kTouchdown = 2000 };

}  // namespace

integrate::Vec<FlightSegment::kSize> FlightSegment::Rhs::operator()(double /*t*/,
                                                                    const integrate::Vec<kSize>& y) const {
  integrate::Vec<kSize> dy;
  dy << physics::flightRhs(model, y.head<physics::kFlightStateSize>()), 0;
  return dy;
}

FlightSegment::FlightSegment(const Simulation& simulation, double t0, const physics::FlightState& start,
                             double dissipated)
    : model_(simulation.model),
      trajectory_(
          Rhs{simulation.model}, t0,
          (integrate::Vec<kSize>() << physics::toVector(start), dissipated).finished(), simulation.solver,
          {integrate::Event<kSize>{.name = "touchdown",
                                   .id = kTouchdown,
                                   .g = [model = simulation.model](double, const integrate::Vec<kSize>& y) {
                                     const physics::FlightState s =
                                         physics::toFlightState(y.head<physics::kFlightStateSize>());
                                     return physics::rimGap(model, s) + kTouchDepth * model.a;
                                   },
                                   .direction = -1,
                                   .terminal = true}}) {}

FlightSample FlightSegment::sampleOf(const integrate::Vec<kSize>& y) const {
  const physics::FlightState s = physics::toFlightState(y.head<physics::kFlightStateSize>());
  return {s, physics::flightForward(model_, s), y[kSize - 1]};
}

std::optional<FlightSample> FlightSegment::sampleAt(double t) {
  const std::optional<integrate::Vec<kSize>> y = trajectory_.stateAt(t);
  if (!y) return std::nullopt;
  return sampleOf(*y);
}

std::optional<FlightSample> FlightSegment::touchdown() const {
  const auto& hit = trajectory_.stoppedBy();
  if (!hit) return std::nullopt;
  return sampleOf(hit->y);
}

Landing land(const Simulation& simulation, const FlightSample& touchdown, double t) {
  const physics::CoinModel& model = simulation.model;
  Landing landing{.state = touchdown.state, .dissipated = touchdown.dissipated, .impact = {.t = t}};
  const physics::FlatStop flat = physics::flatStopFor(model, physics::Formulation::Quaternion);
  // A touchdown located where the rim has just stopped closing (a graze) has nothing to absorb.
  if (physics::pointVelocity(touchdown.state, physics::lowestPointVector(model, touchdown.state.q)).y() >= 0) {
    landing.next = Landing::Next::Contact;
    return landing;
  }
  const physics::ImpactOutcome bounce = physics::resolveImpact(model, touchdown.state, *simulation.flight);
  landing.impact.normalSpeed = bounce.approachSpeed;
  if (std::abs(physics::thetaOf(touchdown.state.q)) >= flat.tilt) {
    landing.next = Landing::Next::Rest;
    return landing;
  }
  if (bounce.jammed) {
    landing.next = Landing::Next::Jam;
    return landing;
  }
  const double restSpeed = std::sqrt(2 * model.g * kRestHeight * model.a);
  if (bounce.reboundSpeed >= restSpeed) {
    landing.next = Landing::Next::Flight;
    landing.state = bounce.after;
    landing.dissipated += bounce.energyLost;
    landing.impact.reboundSpeed = bounce.reboundSpeed;
    landing.impact.energyLost = bounce.energyLost;
    return landing;
  }
  // The last of a bounce sequence: made plastic, so the rim stays on the floor (docs/flight.md §4).
  physics::ImpactLaw plastic = *simulation.flight;
  plastic.restitution = 0;
  const physics::ImpactOutcome stay = physics::resolveImpact(model, touchdown.state, plastic);
  if (stay.jammed) {
    landing.next = Landing::Next::Jam;
    return landing;
  }
  landing.next = Landing::Next::Contact;
  landing.state = stay.after;
  landing.dissipated += stay.energyLost;
  landing.impact.energyLost = stay.energyLost;
  return landing;
}

physics::SlidingState contactStateOf(const physics::CoinModel& model, const physics::FlightState& state) {
  const Eigen::Vector3d r = physics::lowestPointVector(model, state.q);
  const Eigen::Vector3d u = physics::pointVelocity(state, r);
  return {.attitude = {.q = state.q, .omegaBody = state.omegaBody, .x = state.centre.x(), .z = state.centre.z()},
          .slip = Eigen::Vector2d(u.x(), u.z())};
}

physics::FlightState flightStateOf(const physics::Forward& forward, const physics::QuaternionState& state) {
  return {.q = state.q, .omegaBody = state.omegaBody, .centre = forward.centre, .velocity = forward.velocity};
}

}  // namespace coinroll::pipeline
