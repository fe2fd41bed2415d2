#pragma once
// The second formulation (docs/quaternion_formulation.md): attitude quaternion, angular velocity
// in the coin's material frame and the centre of mass on the floor, with the Newton-Euler
// equation about the centre of mass solved for the angular acceleration. Unlike the seed's Euler
// angles it has no coordinate singularity: it integrates up to within a hundredth of a degree of
// flat, where the contact point itself (the lowest point of the rim) stops being defined.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/forward.h"

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

// The seed's theta of an attitude, as toEulerState computes it (eq. 1.4): cheap, for the flat events.
double thetaOf(const Eigen::Quaterniond& unitQ);

// theta's rate times cos theta, -d(n_y)/dt for the symmetry axis n (sin theta = -n_y): theta' where
// the tilt is small, with its sign and zeros at every tilt, without a forward pass (omegaBody: rad/s,
// material axes).
inline double tiltRate(const Eigen::Quaterniond& q, const Eigen::Vector3d& omegaBody) {
  const Eigen::Vector3d normal = q * Eigen::Vector3d::UnitZ();
  return -(q * omegaBody).cross(normal).y();
}

// The forward pass of this formulation at one state, read from the attitude and the material-frame
// rates alone (no Euler angles): Forward::dOmega is d(omega)/dt in material components (eq. 3.4
// with the effects' couple added to b), the reaction is eq. 5.2.
Forward forward(const CoinModel& model, const QuaternionState& state);

// dy/dt and the power the effects dissipate, W.
struct QuaternionRates {
  QuaternionStateVec dy;
  double power = 0;
};

QuaternionRates quaternionRates(const CoinModel& model, const QuaternionStateVec& y);

// dy/dt for y = (q, omegaBody, x, z): eqs. (3.4), (4.1) with the norm-restoring term, (2.3).
// q is normalised before use, so the result is the motion of the attitude q / |q|.
QuaternionStateVec quaternionRhs(const CoinModel& model, double t, const QuaternionStateVec& y);

}  // namespace coinroll::physics
