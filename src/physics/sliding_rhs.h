#pragma once
// The right-hand side of the sliding and creeping modes (docs/sliding.md §1, §4.6), with Coulomb
// friction model.friction.kinetic, and the energy dissipated integrated beside the state.

#include <memory>
#include <optional>

#include <Eigen/Core>

#include "physics/coin_model.h"
#include "physics/contact_mode.h"
#include "physics/forward.h"
#include "physics/sliding.h"

namespace coinroll::physics {

// The sliding state with the energy dissipated since the run's start last (J), so that the energy
// budget is integrated with the motion.
inline constexpr int kSlidingBudgetSize = kSlidingStateSize + 1;
using SlidingBudgetVec = Eigen::Matrix<double, kSlidingBudgetSize, 1>;

struct SlidingRhs {
  CoinModel model;
  Mode mode = Mode::Sliding;  // Sliding or Creeping
  Eigen::Vector3d direction;  // free: s_hat while the slip is below round-off

  // The last state's creeping friction direction, shared by the segment's copies of this
  // right-hand side: a step's last stage and the events at its end ask for the same state, and the
  // rest's search costs some twenty evaluations. A pure function's memo: the bits do not change.
  struct Remembered {
    SlidingStateVec y;
    Eigen::Vector3d direction;
  };
  std::shared_ptr<std::optional<Remembered>> lastDirection = std::make_shared<std::optional<Remembered>>();

  // Creeping: along the rest, searched from the segment's direction where rolling leaves every
  // direction neutral (a trial state past zero slip must not flip friction with it, or the slip's
  // stop is never crossed); where a trial state has no rest, along the slip itself, as when free.
  Eigen::Vector3d frictionDirection(const SlidingStateVec& y) const;
  Forward forward(const SlidingStateVec& y) const;
  SlidingBudgetVec operator()(double t, const SlidingBudgetVec& y) const;
  // m/s^2: the slip's rate, for the stop's rule (slipStopMargin).
  Eigen::Vector2d slipRate(double t, const SlidingBudgetVec& y) const;

  // A slide ended by slipStopLead (a slip closing faster than 100 m/s^2) stops with up to 1e-13 s of
  // slip left, whose centre velocity the roll would drop at once: M v |s| of energy, 2.4e-7 of a hard
  // skid's work. That last |s| / (closing rate) of sliding is applied as one increment instead
  // (docs/sliding.md §4.4), so the roll starts from the skid's closed form to O(lead^2); a slide that
  // reached stoppedSlip(t) is returned as it is.
  SlidingBudgetVec closedSlip(double t, const SlidingBudgetVec& y) const;

 private:
  Eigen::Vector3d searchFrictionDirection(const SlidingStateVec& y) const;
};

}  // namespace coinroll::physics
