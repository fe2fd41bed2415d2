#include "pipeline/flight_segment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "integrate/event_location.h"
#include "physics/landing.h"
#include "physics/quaternion_dynamics.h"
#include "physics/validity.h"

namespace coinroll::pipeline {

namespace {

// m, per m of radius: the rim touches when it is this far into the floor. A flight starts with the
// rim exactly on the floor (a bounce, a lift-off: onTheFloor), so the touchdown's g starts at this
// depth, above zero, however slowly the gap then grows (as t^3 after a lift-off).
constexpr double kTouchDepth = 1e-12;

// The shortest hop the touchdown's search resolves, in the natural time sqrt(a / g): a rebound below the
// bounce-end's speed (eq. 4.1) lasts 2 sqrt(2e-6) ~ 3e-3 of it.
constexpr double kShortestHop = 1e-3;
// rad: the tumbling coin turns at most this between two readings of its gap.
constexpr double kStepTurn = std::numbers::pi / 8;

// The gap function of the touchdown's search at `elapsed` s into the flight: g = gap + kTouchDepth a
// and its rate, the lowest point's vertical velocity (docs/flight.md §2, the envelope theorem).
struct GapReading {
  double elapsed = 0, g = 0, rate = 0;
};

// g's smallest value on the cubic Hermite interpolant of two readings, a cheap bound of whether a
// dip between them can reach the floor when their rates say nothing (both falling, or both rising).
double hermiteLow(const GapReading& a, const GapReading& b) {
  constexpr int kProbes = 16;
  const double h = b.elapsed - a.elapsed;
  double low = std::min(a.g, b.g);
  for (int k = 1; k < kProbes; ++k) {
    const double s = static_cast<double>(k) / kProbes, s2 = s * s, s3 = s2 * s;
    low = std::min(low, (2 * s3 - 3 * s2 + 1) * a.g + (s3 - 2 * s2 + s) * h * a.rate + (-2 * s3 + 3 * s2) * b.g +
                            (s3 - s2) * h * b.rate);
  }
  return low;
}

// s after the flight's start: the first touchdown between two readings with g(a) > 0, or none. A
// sign change of g is located on g. Without one, a dip between them touches only at a minimum of g,
// where its rate rises through zero: that minimum is located on the rate and read, and g's root
// located before it (a graze shallower than the readings' spacing shows no sign change, its width
// going as the square root of its depth). Where the rates do not bracket a minimum but the
// readings' cubic dips to the floor, the interval is halved and each half searched.
template <class Read>
std::optional<double> touchdownBetween(const Read& read, const GapReading& a, const GapReading& b, int depth) {
  constexpr int kMaxHalvings = 24;
  const auto g = [&](double elapsed) { return read(elapsed).g; };
  if (b.g <= 0) return integrate::locateRoot(g, a.elapsed, a.g, b.elapsed, b.g);
  if (a.rate < 0 && b.rate > 0) {
    const double low =
        integrate::locateRoot([&](double elapsed) { return read(elapsed).rate; }, a.elapsed, a.rate, b.elapsed, b.rate);
    const double gLow = g(low);
    if (gLow > 0) return std::nullopt;
    return integrate::locateRoot(g, a.elapsed, a.g, low, gLow);
  }
  if (depth >= kMaxHalvings || hermiteLow(a, b) > 0) return std::nullopt;
  const GapReading middle = read(0.5 * (a.elapsed + b.elapsed));
  if (const std::optional<double> first = touchdownBetween(read, a, middle, depth + 1)) return first;
  return touchdownBetween(read, middle, b, depth + 1);
}

// s: the first time the closed form's g = gap + kTouchDepth a of `model`'s rim falls through zero
// after t0, up to `until`. Before the centre comes down to reachBelowCentre no attitude can touch:
// the search starts there. From then on g and its rate are read every eighth of a turn of the coin
// (its rim dips towards the floor twice a turn) and every quarter of a rebound's hop, and each pair
// of readings searched by touchdownBetween, so that no dip is missed however shallow (docs/flight.md §2).
std::optional<double> touchdownOfBranch(const physics::CoinModel& model, double t0, const physics::FlightState& start,
                                        double until) {
  const auto read = [&](double elapsed) {
    const physics::FlightState s = physics::flightAfter(model, start, elapsed);
    return GapReading{.elapsed = elapsed,
                      .g = physics::rimGap(model, s) + kTouchDepth * model.a,
                      .rate = physics::pointVelocity(s, physics::lowestPointVector(model, s.q)).y()};
  };
  const double high = start.centre.y() - physics::reachBelowCentre(model), up = start.velocity.y();
  double elapsed = high > 0 ? (up + std::sqrt(up * up + 2 * model.g * high)) / model.g : 0.0;
  const double rising = std::max(physics::pointVelocity(start, physics::lowestPointVector(model, start.q)).y(), 0.0);
  const double turn = start.omegaBody.norm();
  const bool fromTheFloor = physics::rimGap(model, start) <= kTouchDepth * model.a;
  const double hop = fromTheFloor ? std::max(0.5 * rising / model.g, kShortestHop * physics::naturalTime(model))
                                  : std::numeric_limits<double>::infinity();
  const double reading = std::min(hop, turn > 0 ? kStepTurn / turn : hop);
  // A coin dropped without spin from above falls straight: its gap, the centre's parabola less a
  // constant, falls monotonically, read every natural time.
  const double step = std::isfinite(reading) ? reading : physics::naturalTime(model);
  GapReading before = read(elapsed);
  while (t0 + before.elapsed < until) {
    const GapReading after = read(before.elapsed + step);
    if (before.g > 0) {
      if (const std::optional<double> touch = touchdownBetween(read, before, after, 0)) return t0 + *touch;
    }
    before = after;
  }
  return std::nullopt;
}

// The touchdown of the whole rim. A rim with corners reaches lowest on either corner's circle, and
// the gap is the lesser of the two circles' (eq. 2.1's |sin theta| is the greater of +-sin theta):
// where the coin passes upright the gap has a kink, between two minima a few degrees of tilt apart,
// often inside one pair of readings, where the rate's bracket finds only one. Each circle's gap is
// smooth through upright and searched alone; the rim touches down at the earlier.
std::optional<double> touchdownAfter(const physics::CoinModel& model, double t0, const physics::FlightState& start,
                                     double until) {
  if (!physics::hasCorners(model)) return touchdownOfBranch(model, t0, start, until);
  std::optional<double> first;
  for (const double corner : {-1.0, 1.0}) {
    physics::CoinModel holding = model;
    holding.rim.heldCorner = corner;
    const std::optional<double> touch = touchdownOfBranch(holding, t0, start, first ? *first : until);
    if (touch && (!first || *touch < *first)) first = touch;
  }
  return first;
}

}  // namespace

FreeFlight::FreeFlight(const physics::CoinModel& model, double t0, const physics::FlightState& start, double dissipated,
                       double until)
    : model_(model),
      t0_(t0),
      start_(start),
      dissipated_(dissipated),
      touchdown_(touchdownAfter(model, t0, start, until)) {}

RunSample flightSample(const physics::CoinModel& model, const physics::FlightState& s, double dissipated,
                       const physics::CoinState& continuation) {
  const physics::QuaternionState attitude{.q = s.q, .omegaBody = s.omegaBody, .x = s.centre.x(), .z = s.centre.z()};
  return {.state = physics::toEulerState(attitude, continuation),
          .forward = physics::flightForward(model, s),
          .dissipated = dissipated};
}

std::optional<RunSample> FlightSegment::sampleAt(double t, const physics::CoinState& continuation) {
  if (flight_.touchdown() && t > *flight_.touchdown()) return std::nullopt;
  return flight_.sample(flight_.at(t), continuation);
}

std::optional<RunEvent> FlightSegment::stoppedBy(const physics::CoinState& continuation) const {
  if (!flight_.touchdown() || *flight_.touchdown() > duration_) return std::nullopt;
  const double t = *flight_.touchdown();
  return runEventOf(switchId(physics::Transition::Touchdown), t, flight_.sample(flight_.at(t), continuation));
}

std::optional<SegmentEnd> FlightSegment::end() const {
  if (!flight_.touchdown()) return std::nullopt;
  const double t = *flight_.touchdown();
  return SegmentEnd{.transition = physics::Transition::Touchdown,
                    .handover = physics::flightHandover(flight_.model(), t, flight_.at(t), flight_.dissipated())};
}

}  // namespace coinroll::pipeline
