#pragma once
// Where the ideal rolling model stops describing the real coin. Each margin is positive while
// the model holds and crosses zero where it fails, so an integrator can locate the crossing as
// an event on its dense output instead of clamping or producing NaNs.

#include <numbers>

#include "physics/coin_model.h"
#include "physics/coin_state.h"

namespace coinroll::physics {

// rad. The Euler-angle equations carry tan(theta) and 1 / cos(theta); at 89 degrees the coin's
// face is within 1 degree of the floor, 1 / cos(theta) is 57 and the step sizes collapse, so the
// seed's formulation stops here with the "coin-flat" event.
inline constexpr double kFlatTilt = 89.0 * std::numbers::pi / 180.0;

// N / (M g): the normal force in units of the weight; below zero the coin would lift off.
double liftOffMargin(const CoinModel& model, const CoinState& state);

// (mu N - F) / (M g): static friction reserve; below zero the contact would slip.
double slipMargin(const CoinModel& model, const CoinState& state, double mu);

// kFlatTilt - |theta|, rad.
double flatMargin(const CoinState& state);

}  // namespace coinroll::physics
