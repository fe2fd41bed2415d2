#pragma once
// Where the rolling model stops describing the real coin. Each margin is positive while the model
// holds and crosses zero where it fails, so an integrator can locate the crossing as an event on
// its dense output instead of clamping or producing NaNs. One set for both formulations: the
// quaternion's state is read through toEulerState.

#include <numbers>

#include "physics/coin_model.h"
#include "physics/coin_state.h"

namespace coinroll::physics {

// rad. The Euler-angle equations carry tan(theta) and 1 / cos(theta); at 89 degrees the coin's
// face is within 1 degree of the floor, 1 / cos(theta) is 57 and the step sizes of an ideal
// (energy-conserving) fall collapse, so the seed's formulation stops an ideal run here.
inline constexpr double kFlatTilt = 89.0 * std::numbers::pi / 180.0;

// rad. The quaternion formulation stops an ideal run here: cos(theta) = 1.7e-4, the contact point
// runs round the rim at psi-dot ~ omega / cos(theta) and is undefined at 90 degrees; a real coin of
// any thickness has landed on its face before this.
inline constexpr double kQuaternionFlatTilt = 89.99 * std::numbers::pi / 180.0;

// rad. A run with effects (a spin-down) ends at 0.5 degrees above the floor in either formulation
// (docs/euler_disk.md §5): there the far rim of the 75 mm toy is 0.65 mm above the floor, t0 - t
// is milliseconds, and both formulations still agree.
inline constexpr double kSpinDownFlatTilt = 89.5 * std::numbers::pi / 180.0;

// The tilt at which a run of `model` in a formulation ends with "coin-flat".
double flatTiltFor(const CoinModel& model, bool quaternionFormulation);

// N / (M g): the normal force in units of the weight; below zero the coin would lift off.
double liftOffMargin(const CoinModel& model, const CoinState& state);

// (mu N - F) / (M g): static friction reserve; below zero the contact would slip.
double slipMargin(const CoinModel& model, const CoinState& state, double mu);

// flatTilt - |theta|, rad.
double flatMargin(const CoinState& state, double flatTilt);

}  // namespace coinroll::physics
