#pragma once
// The second formulation (docs/quaternion_formulation.md): attitude quaternion, angular velocity
// in the coin's material frame and the centre of mass on the floor, with the Newton-Euler
// equation about the centre of mass solved for the angular acceleration. Unlike the seed's Euler
// angles it has no coordinate singularity: it integrates up to within a hundredth of a degree of
// flat, where the contact point itself (the lowest point of the rim) stops being defined.

#include <numbers>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/observables.h"

namespace coinroll::physics {

struct QuaternionState {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  // unit, active rotation floor-from-body (= attitude())
  Eigen::Vector3d omegaBody = Eigen::Vector3d::Zero();    // rad/s, along the material axes b1, b2, b3 = e_Z
  double x = 0;                                           // m, centre of mass on the floor plane
  double z = 0;                                           // m
};

inline constexpr int kQuaternionStateSize = 9;
using QuaternionStateVec = Eigen::Matrix<double, kQuaternionStateSize, 1>;

// Layout of QuaternionStateVec: q = (w, x, y, z), omegaBody, then the centre of mass.
enum QuaternionStateIndex : int { kQw, kQx, kQy, kQz, kOmegaBody1, kOmegaBody2, kOmegaBody3, kCentreX, kCentreZ };

QuaternionStateVec toVector(const QuaternionState& state);

// Reads q as the attitude it stands for, q / |q|: the integrated q is unit only up to the
// integrator's error (docs/quaternion_formulation.md §4).
QuaternionState toQuaternionState(const QuaternionStateVec& y);

// The same motion in the second formulation: q = attitude(state), omega turned from the seed's
// XYZ axes to the material axes by -psi about e_Z (eq. 1.3).
QuaternionState fromEulerState(const CoinState& state);

// The seed's angles and XYZ rates (eqs. 1.4, 1.5). phi and psi are taken within pi of
// `continuation`'s, so a sequence of calls each given the previous result stays continuous.
// Precondition: not flat (|theta| < 90 degrees), where phi and psi are defined.
CoinState toEulerState(const QuaternionState& state, const CoinState& continuation);

// |theta|, rad: the coin plane's tilt from the vertical, in [0, pi/2]; pi/2 is lying flat.
double tiltMagnitude(const QuaternionState& state);

// Body-frame angular acceleration d(omegaBody)/dt, rad/s^2, from the 3x3 system (eq. 3.4).
Eigen::Vector3d angularAccelerationBody(const CoinModel& model, const QuaternionState& state);

// dy/dt for y = (q, omegaBody, x, z): eqs. (3.4), (4.1) with the norm-restoring term, (2.3).
// q is normalised before use, so the result is the motion of the attitude q / |q|.
QuaternionStateVec quaternionRhs(const CoinModel& model, double t, const QuaternionStateVec& y);

// Total energy, J, as in the seed's section 4 but from this state (eq. 5.1).
double energy(const CoinModel& model, const QuaternionState& state);

// The point of the rim touching the floor, m, floor frame.
Eigen::Vector3d contactPoint(const CoinModel& model, const QuaternionState& state);

// The floor's reaction R = M dv/dt + M g e_y (eq. 5.2).
Reaction reaction(const CoinModel& model, const QuaternionState& state);

// rad. The quaternion formulation stops here with the "coin-flat" event: cos(theta) = 1.7e-4,
// the contact point runs round the rim at psi-dot ~ omega / cos(theta) and is undefined at 90
// degrees; a real coin of any thickness has landed on its face before this.
inline constexpr double kQuaternionFlatTilt = 89.99 * std::numbers::pi / 180.0;

// Validity margins as in validity.h, positive while the ideal model holds.
double liftOffMargin(const CoinModel& model, const QuaternionState& state);
double slipMargin(const CoinModel& model, const QuaternionState& state, double mu);
double flatMargin(const QuaternionState& state);  // kQuaternionFlatTilt - |theta|, rad

}  // namespace coinroll::physics
