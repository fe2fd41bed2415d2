#include "physics/sliding.h"

#include <Eigen/LU>

#include <cmath>

#include "physics/body_contact.h"

namespace coinroll::physics {

namespace {

// Sherman-Morrison's passes converge in one or two for a couple that changes N by a part in 1e4;
// the cap only guards a law whose couple is steep in N.
constexpr int kMaxNormalForcePasses = 6;

struct Sliding {
  ContactGeometry geo;
  Eigen::Vector3d spinAtContact;  // floor: omega x c
  Eigen::Vector3d cDot;      // material derivative of c
  Eigen::Vector3d velocity;  // floor: (v_x, from the held contact, v_z)  (docs/sliding.md eq. 1.2)
  Eigen::Vector3d slip;      // floor, horizontal: v + omega x c          (1.3)
  Eigen::Vector3d slipHat;   // floor, unit
  double N0 = 0;             // N, the normal force without omega-dot's part (1.5)
  Eigen::Vector3d m, k;      // body: c x e_y and c x (e_y - mu s_hat)     (1.6)
};

Sliding slidingTerms(const CoinModel& model, const SlidingState& state, double mu, const Eigen::Vector3d& slipDirection) {
  const QuaternionState& s = state.attitude;
  Sliding t;
  t.geo = contactGeometry(model, s.q);
  const Eigen::Matrix3d& R = t.geo.floorFromBody;
  const Eigen::Vector3d& w = s.omegaBody;
  const Eigen::Vector3d& c = t.geo.c;
  t.cDot = contactDrift(model, t.geo, w);
  const Eigen::Vector3d& spinAtContact = t.spinAtContact = R * w.cross(c);
  t.slip = Eigen::Vector3d(state.slip.x(), 0, state.slip.y());  // horizontal: the held contact (1.2)
  t.velocity = t.slip - spinAtContact;
  const double speed = t.slip.norm();
  t.slipHat = speed > kSlipRoundOff ? Eigen::Vector3d(t.slip / speed) : slipDirection;
  const Eigen::Vector3d& u = t.geo.up;
  t.N0 = model.M * model.g - model.M * w.cross(t.cDot + w.cross(c)).dot(u);
  t.m = c.cross(u);
  t.k = c.cross(u - mu * R.transpose() * t.slipHat);
  return t;
}

// (1.7): [I + M k m^t] omega-dot = -omega x I omega + N0 k + tau, then N = N0 - M m . omega-dot (1.5).
void solve(const CoinModel& model, const Sliding& t, const Eigen::Vector3d& w, const Eigen::Vector3d& torqueBody,
           Eigen::Vector3d& dOmega, double& N) {
  const Eigen::Vector3d inertia(model.I_X, model.I_X, model.I_Z);
  const Eigen::Matrix3d A = Eigen::Matrix3d(inertia.asDiagonal()) + model.M * t.k * t.m.transpose();
  const Eigen::Vector3d b = -w.cross(inertia.cwiseProduct(w)) + t.N0 * t.k + torqueBody;
  dOmega = A.partialPivLu().solve(b);
  N = t.N0 - model.M * t.m.dot(dOmega);
}

Forward forwardFrom(const CoinModel& model, const SlidingState& state, double mu, const Sliding& t) {
  const QuaternionState& s = state.attitude;
  const Eigen::Matrix3d& R = t.geo.floorFromBody;
  Forward f;
  double N = 0;
  solve(model, t, s.omegaBody, Eigen::Vector3d::Zero(), f.dOmega, N);
  if (!model.effects.empty()) {
    ContactKinematics kinematics{.e_X = R * t.geo.e_X, .e_Y = R * t.geo.e_Y, .e_Z = R.col(2), .omega = R * s.omegaBody,
                                 .faceRadius = model.a - model.rim.edgeRadius, .N = N};
    for (int pass = 0; pass < kMaxNormalForcePasses; ++pass) {
      kinematics.N = N;
      f.loads = totalLoads(model.effects, kinematics);
      solve(model, t, s.omegaBody, R.transpose() * f.loads.torque, f.dOmega, N);
      if (N == kinematics.N) break;
    }
  }
  const Eigen::Vector3d inverseInertiaK(t.k.x() / model.I_X, t.k.y() / model.I_X, t.k.z() / model.I_Z);
  f.normalEffectiveMass = 1 + model.M * t.m.dot(inverseInertiaK);  // (3.2)
  f.reaction.R = N * (Eigen::Vector3d::UnitY() - mu * t.slipHat);
  f.reaction.N = N;
  f.reaction.F = mu * std::abs(N);
  f.slip = t.slip;
  f.sliding = true;
  f.loads.power += mu * N * t.slip.norm();  // friction's work rate (2.1)
  setAttitudeKinematics(model, s.q, s.omegaBody, s.x, s.z, t.geo, t.velocity, f);
  return f;
}

}  // namespace

SlidingStateVec toVector(const SlidingState& s) {
  SlidingStateVec y;
  y << toVector(s.attitude), s.slip;
  return y;
}

SlidingState toSlidingState(const SlidingStateVec& y) {
  return {.attitude = toQuaternionState(y.head<kQuaternionStateSize>()), .slip = y.tail<2>()};
}

Eigen::Vector2d slipOf(const CoinModel& model, const QuaternionState& attitude, const Eigen::Vector2d& velocity) {
  const ContactGeometry geo = contactGeometry(model, attitude.q);
  const Eigen::Vector3d spinAtContact = geo.floorFromBody * attitude.omegaBody.cross(geo.c);
  return velocity + Eigen::Vector2d(spinAtContact.x(), spinAtContact.z());
}

Forward slidingForward(const CoinModel& model, const SlidingState& state, double mu, const Eigen::Vector3d& slipDirection) {
  return forwardFrom(model, state, mu, slidingTerms(model, state, mu, slipDirection));
}

SlidingRates slidingRates(const CoinModel& model, const SlidingStateVec& y, double mu, const Eigen::Vector3d& slipDirection) {
  const Eigen::Quaterniond stored(y[kQw], y[kQx], y[kQy], y[kQz]);
  const SlidingState state = toSlidingState(y);
  const Sliding terms = slidingTerms(model, state, mu, slipDirection);
  const Forward f = forwardFrom(model, state, mu, terms);
  SlidingRates rates;
  SlidingStateVec& dy = rates.dy;
  // q-dot as in the rolling formulation (docs/quaternion_formulation.md eq. 4.1), norm pulled back to 1.
  const Eigen::Quaterniond& q = state.attitude.q;
  const Eigen::Vector3d& w = state.attitude.omegaBody;
  const Eigen::Quaterniond spin = q * Eigen::Quaterniond(0, w.x(), w.y(), w.z());
  const double restoring = naturalRate(model) * (1 - stored.squaredNorm());
  dy[kQw] = 0.5 * spin.w() + restoring * q.w();
  dy[kQx] = 0.5 * spin.x() + restoring * q.x();
  dy[kQy] = 0.5 * spin.y() + restoring * q.y();
  dy[kQz] = 0.5 * spin.z() + restoring * q.z();
  dy.segment<3>(kOmegaBody1) = f.dOmega;
  dy[kCentreX] = f.velocity.x();
  dy[kCentreZ] = f.velocity.z();
  // ds/dt = a_G + d(omega x c)/dt, the latter in the turning body frame (docs/sliding.md eq. 4.1);
  // horizontally a_G is friction's alone (1.8).
  const ContactGeometry& geo = terms.geo;
  const Eigen::Vector3d spinRate =
      geo.floorFromBody * (f.dOmega.cross(geo.c) + w.cross(terms.cDot) + w.cross(w.cross(geo.c)));
  dy[kSlipX] = f.reaction.R.x() / model.M + spinRate.x();
  dy[kSlipZ] = f.reaction.R.z() / model.M + spinRate.z();
  rates.power = f.loads.power;
  return rates;
}

}  // namespace coinroll::physics
