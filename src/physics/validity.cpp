#include "physics/validity.h"

#include <cmath>

#include "physics/observables.h"

namespace coinroll::physics {

double flatTiltFor(const CoinModel& model, bool quaternionFormulation) {
  if (!model.effects.empty()) return kSpinDownFlatTilt;
  return quaternionFormulation ? kQuaternionFlatTilt : kFlatTilt;
}

double liftOffMargin(const CoinModel& model, const CoinState& state) {
  return reaction(model, state).N / (model.M * model.g);
}

double slipMargin(const CoinModel& model, const CoinState& state, double mu) {
  const Reaction r = reaction(model, state);
  return (mu * r.N - r.F) / (model.M * model.g);
}

double flatMargin(const CoinState& state, double flatTilt) { return flatTilt - std::abs(state.theta); }

}  // namespace coinroll::physics
