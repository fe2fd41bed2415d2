#include "physics/contact_mode.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "physics/validity.h"

namespace coinroll::physics {

namespace {

// rad: the creeping slip's direction lags its rest by at most this before it is integrated freely
// (docs/sliding.md §4.6): the lag is (turn rate of the rest) |s| / pull (eq. 4.17).
constexpr double kCreepLag = 1e-3;
// rad: a free slip is handed back to its rest only within this angle of it (docs/sliding.md §4.6).
constexpr double kCreepAlignment = 1e-5;

}  // namespace

// m/s. Sliding ends when the slip speed falls to this, not to 0, where friction's direction is no
// longer defined: the last of the slip is closed by friction at once, its kinetic energy booked as
// dissipated (docs/sliding.md §4.5). A free slip's direction turns at restoring / |s|, so the steps
// near the stop shrink with |s|; the stop must come while they are still above the integrator's
// floor of 1e-14 |t|, hence a threshold growing with t (10^-11 m/s up to 1 s: a skid switches about
// 3e-12 s early at mu g = 3 m/s^2; at 1e-12 m/s a skid at t = 4.8 s stalled).
double stoppedSlip(double t) { return 1e-11 * std::max(1.0, std::abs(t)); }

ContactMode startingMode(const CoinModel& model, const Forward& rolling, const Forward& slipping) {
  if (slipping.slip.norm() > stoppedSlip(0)) return ContactMode::Sliding;
  return modeAfterSlipStops(model, rolling);
}

double slideOnsetMargin(const CoinModel& model, const Forward& rolling) {
  return slipMargin(model, rolling, *model.friction.cone);
}

ContactMode modeAfterSlipStops(const CoinModel& model, const Forward& rolling) {
  return slideOnsetMargin(model, rolling) < 0 ? ContactMode::Creeping : ContactMode::Rolling;
}

// s. A slip closing at c m/s^2 reaches stoppedSlip(t) only stoppedSlip(t) / c before its zero: for a
// hard skid (c = 3 mu g = 5.9e4 m/s^2 at mu = 2000) 1.7e-16 s, and the steps that approach the zero's
// kink (rejected past it, docs/sliding.md §4.4) fell below the integrator's floor of 1e-14 max(1, |t|) s
// first: "integration stalled" (issue 40). Ending the slide once the slip would stop within ten such
// floors keeps the last steps above it. Only slips closing faster than 100 m/s^2 (10^-11 m/s over
// 10^-13 s) end earlier than at stoppedSlip(t): a skid with mu g above about 33 m/s^2 (mu > 3.4).
double slipStopLead(double t) { return 1e-13 * std::max(1.0, std::abs(t)); }

namespace {

// m/s: the slip at which a slide ends, given how fast the slip closes along its direction (m/s^2).
double stopThreshold(double t, double closingRate) {
  return std::max(stoppedSlip(t), slipStopLead(t) * closingRate);
}

}  // namespace

double slipStopMargin(double t, const Eigen::Vector2d& slip, const Eigen::Vector2d& slipRate, double resolvedSlip) {
  const double speed = slip.norm();
  const double closing = speed > 0 ? -slip.dot(slipRate) / speed : 0.0;
  return speed - std::max(stopThreshold(t, closing), resolvedSlip);
}

double creepStopMargin(double t, const Eigen::Vector2d& slip, const Eigen::Vector2d& slipRate, double resolvedSlip,
                       const Eigen::Vector3d& rest) {
  const double closing = -(slipRate.x() * rest.x() + slipRate.y() * rest.z());
  return slip.x() * rest.x() + slip.y() * rest.z() - std::max(stopThreshold(t, closing), resolvedSlip);
}

// The rest turns with the fastest of the body's rotation, the contact's precession and the rocking
// rate sqrt(g/a) (kCreepLag).
double freeSlipSpeed(const CoinModel& model, const Forward& sliding, double pull) {
  const double turnRate =
      std::max({sliding.omega.norm(), std::abs(sliding.precessionRate), std::sqrt(model.g / model.a)});
  return kCreepLag * std::max(pull, 0.0) / turnRate;
}

// A slip that falls back to half the creep's threshold hands its direction to its rest, once it has
// come to the rest: the threshold fades to zero as the slip's angle from the rest grows to
// kCreepAlignment, so a slide that ends across the rest's pull (a skid) is integrated to its end.
//
// The rest's search costs some twenty evaluations of the slip's rate, and a slide asks at every step.
// The threshold is at most half the free slip speed at the rest's pull, and it is nonzero only within
// kCreepAlignment of the rest, where the pull differs from the slip direction's own (three
// evaluations) by a part in 1e5 unless the pull itself is next to none: a slip faster than the free
// slip speed at its own direction's pull is above the threshold whatever the rest, and its margin
// is its speed (positive as the true margin is, so the event sees the same crossings).
double slipCreepMargin(const CoinModel& model, const SlidingStateVec& y, const Forward& sliding) {
  const SlidingState state = toSlidingState(y);
  const Eigen::Vector2d& slip = state.slip;
  const double pullHere = slipDirectionPull(model, state, model.friction.kinetic);
  if (slip.norm() > freeSlipSpeed(model, sliding, pullHere)) return slip.norm();
  const std::optional<Creep> creep = findCreep(model, y, model.friction.kinetic);
  if (!creep) return slip.norm();
  const Eigen::Vector2d rest(creep->slipHat.x(), creep->slipHat.z());
  const double angleFromRest = std::acos(std::clamp(rest.dot(slip.normalized()), -1.0, 1.0));
  const double nearness = std::max(0.0, 1 - angleFromRest / kCreepAlignment);
  return slip.norm() - 0.5 * nearness * freeSlipSpeed(model, sliding, creep->pull);
}

double slipFreeMargin(const CoinModel& model, const SlidingStateVec& y, const Forward& sliding) {
  const double pull = findCreep(model, y, model.friction.kinetic).value_or(Creep{}).pull;
  return toSlidingState(y).slip.norm() - freeSlipSpeed(model, sliding, pull);
}

}  // namespace coinroll::physics
