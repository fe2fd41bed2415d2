#include "physics/sliding_rhs.h"

#include <cstring>

namespace coinroll::physics {

Eigen::Vector3d SlidingRhs::frictionDirection(const SlidingStateVec& y) const {
  std::optional<Remembered>& last = *lastDirection;
  if (last && std::memcmp(last->y.data(), y.data(), sizeof(double) * y.size()) == 0) return last->direction;
  last = Remembered{.y = y, .direction = searchFrictionDirection(y)};
  return last->direction;
}

Eigen::Vector3d SlidingRhs::searchFrictionDirection(const SlidingStateVec& y) const {
  if (const std::optional<Creep> creep = findCreep(model, y, model.friction.kinetic, direction)) {
    return creep->slipHat;
  }
  const Eigen::Vector2d slip = y.tail<2>();
  return slip.norm() > kSlipRoundOff ? Eigen::Vector3d(slip.x() / slip.norm(), 0, slip.y() / slip.norm()) : direction;
}

Forward SlidingRhs::forward(const SlidingStateVec& y) const {
  const SlidingState state = toSlidingState(y);
  const double mu = model.friction.kinetic;
  return mode == Mode::Sliding ? slidingForward(model, state, mu, direction)
                               : slidingForwardAlong(model, state, mu, frictionDirection(y));
}

SlidingBudgetVec SlidingRhs::operator()(double /*t*/, const SlidingBudgetVec& y) const {
  const SlidingStateVec& coin = y.head<kSlidingStateSize>();
  const double mu = model.friction.kinetic;
  const SlidingRates r = mode == Mode::Sliding ? slidingRates(model, coin, mu, direction)
                                               : slidingRatesAlong(model, coin, mu, frictionDirection(coin));
  SlidingBudgetVec dy;
  dy << r.dy, r.power;
  return dy;
}

Eigen::Vector2d SlidingRhs::slipRate(double t, const SlidingBudgetVec& y) const {
  return (*this)(t, y).segment<2>(kSlidingStateSize - 2);
}

SlidingBudgetVec SlidingRhs::closedSlip(double t, const SlidingBudgetVec& y) const {
  const SlidingBudgetVec rate = (*this)(t, y);
  const Eigen::Vector2d slip = toSlidingState(y.head<kSlidingStateSize>()).slip;
  const double speed = slip.norm();
  const double closing = speed > 0 ? -slip.dot(rate.segment<2>(kSlidingStateSize - 2)) / speed : 0.0;
  if (!(slipStopLead(t) * closing > stoppedSlip(t))) return y;
  return y + (speed / closing) * rate;
}

}  // namespace coinroll::physics
