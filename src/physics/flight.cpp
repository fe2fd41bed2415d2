#include "physics/flight.h"

#include <cmath>

#include "physics/body_contact.h"
#include "physics/coin_model.h"
#include "physics/quaternion_dynamics.h"

namespace coinroll::physics {

namespace {

// Below this cos(theta) the coin is flat to round-off: the in-plane direction towards the floor,
// and with it the lowest point's place on the rim, is undefined (docs/flight.md §2).
constexpr double kFlatCosine = 1e-12;

Eigen::Vector3d principalMoments(const CoinModel& m) { return {m.I_X, m.I_X, m.I_Z}; }

// The contact geometry of the lowest point; flat, the one of the attitude turned by a hair about b1,
// so that every quantity stays finite and continuous with the nearby attitudes on the b2 side.
ContactGeometry lowestPointGeometry(const CoinModel& m, const Eigen::Quaterniond& unitQ) {
  const Eigen::Vector3d up = unitQ.toRotationMatrix().row(1).transpose();
  if (std::hypot(up.x(), up.y()) >= kFlatCosine) return contactGeometry(m, unitQ);
  const double hair = up.z() > 0 ? -kFlatCosine : kFlatCosine;
  return contactGeometry(m, unitQ * Eigen::Quaterniond(Eigen::AngleAxisd(hair, Eigen::Vector3d::UnitX())));
}

}  // namespace

FlightStateVec toVector(const FlightState& s) {
  FlightStateVec y;
  y << s.q.w(), s.q.x(), s.q.y(), s.q.z(), s.omegaBody, s.centre, s.velocity;
  return y;
}

FlightState toFlightState(const FlightStateVec& y) {
  return {.q = Eigen::Quaterniond(y[kFlightQw], y[kFlightQw + 1], y[kFlightQw + 2], y[kFlightQw + 3]).normalized(),
          .omegaBody = y.segment<3>(kFlightOmega),
          .centre = y.segment<3>(kFlightCentre),
          .velocity = y.segment<3>(kFlightVelocity)};
}

FlightStateVec flightRhs(const CoinModel& m, const FlightStateVec& y) {
  const Eigen::Quaterniond stored(y[kFlightQw], y[kFlightQw + 1], y[kFlightQw + 2], y[kFlightQw + 3]);
  const Eigen::Quaterniond q = stored.normalized();
  const Eigen::Vector3d w = y.segment<3>(kFlightOmega);
  // As in the quaternion formulation (docs/quaternion_formulation.md eq. 4.1): a pull back to the
  // unit sphere that vanishes on it.
  const Eigen::Quaterniond spin = q * Eigen::Quaterniond(0, w.x(), w.y(), w.z());
  const double restoring = naturalRate(m) * (1 - stored.squaredNorm());
  FlightStateVec dy;
  dy[kFlightQw] = 0.5 * spin.w() + restoring * q.w();
  dy[kFlightQw + 1] = 0.5 * spin.x() + restoring * q.x();
  dy[kFlightQw + 2] = 0.5 * spin.y() + restoring * q.y();
  dy[kFlightQw + 3] = 0.5 * spin.z() + restoring * q.z();
  const Eigen::Vector3d inertia = principalMoments(m);
  dy.segment<3>(kFlightOmega) = -w.cross(inertia.cwiseProduct(w)).cwiseQuotient(inertia);  // (1.3)
  dy.segment<3>(kFlightCentre) = y.segment<3>(kFlightVelocity);                            // (1.1)
  dy.segment<3>(kFlightVelocity) = Eigen::Vector3d(0, -m.g, 0);
  return dy;
}

FlightState flightAfter(const CoinModel& m, const FlightState& start, double elapsed) {
  const Eigen::Vector3d L = angularMomentum(m, start);
  const double bodyRate = start.omegaBody.z() * (m.I_X - m.I_Z) / m.I_X;  // lambda in (1.4)
  const Eigen::AngleAxisd aboutL(L.norm() * elapsed / m.I_X,
                                 L.norm() > 0 ? Eigen::Vector3d(L.normalized()) : Eigen::Vector3d::UnitY());
  const Eigen::AngleAxisd aboutAxis(bodyRate * elapsed, Eigen::Vector3d::UnitZ());
  FlightState s;
  s.q = (Eigen::Quaterniond(aboutL) * start.q * Eigen::Quaterniond(aboutAxis)).normalized();
  // R^T L is I omega_b; with R(t) from (1.4) it is Rot(b3, -lambda t) R(0)^T L.
  s.omegaBody = aboutAxis.inverse() * start.omegaBody;
  s.centre = start.centre + start.velocity * elapsed - 0.5 * m.g * elapsed * elapsed * Eigen::Vector3d::UnitY();
  s.velocity = start.velocity - m.g * elapsed * Eigen::Vector3d::UnitY();
  return s;
}

double uprightEnergy(const CoinModel& m) { return m.M * m.g * lowestPointDepth(m, Eigen::Quaterniond::Identity()); }

double reachBelowCentre(const CoinModel& m) { return std::hypot(m.a, 0.5 * m.rim.thickness); }

double lowestPointDepth(const CoinModel& m, const Eigen::Quaterniond& unitQ) {
  const Eigen::Vector3d up = unitQ.toRotationMatrix().row(1).transpose();
  const double cosTheta = std::hypot(up.x(), up.y());
  const double sinTheta = -up.z();
  return centreHeight(contactOffset(m.rim, m.a, sinTheta, cosTheta), sinTheta, cosTheta);  // (2.1)
}

double rimGap(const CoinModel& m, const FlightState& s) { return s.centre.y() - lowestPointDepth(m, s.q); }

Eigen::Vector3d lowestPointVector(const CoinModel& m, const Eigen::Quaterniond& unitQ) {
  const ContactGeometry geo = lowestPointGeometry(m, unitQ);
  return geo.floorFromBody * geo.c;
}

Eigen::Vector3d pointVelocity(const FlightState& s, const Eigen::Vector3d& r) {
  return s.velocity + (s.q * s.omegaBody).cross(r);
}

Forward flightForward(const CoinModel& m, const FlightState& s) {
  const ContactGeometry geo = lowestPointGeometry(m, s.q);
  Forward f;
  setAttitudeKinematics(m, s.q, s.omegaBody, s.centre.x(), s.centre.z(), geo, s.velocity, f);
  f.centre = s.centre;
  f.contactPoint = f.centre + f.contactVector;
  f.energy = kineticEnergy(m, s) + m.M * m.g * s.centre.y();
  const Eigen::Vector3d inertia = principalMoments(m);
  f.dOmega = -s.omegaBody.cross(inertia.cwiseProduct(s.omegaBody)).cwiseQuotient(inertia);
  f.flying = true;
  return f;
}

double kineticEnergy(const CoinModel& m, const FlightState& s) {
  return 0.5 * m.M * s.velocity.squaredNorm() + 0.5 * s.omegaBody.dot(principalMoments(m).cwiseProduct(s.omegaBody));
}

Eigen::Vector3d angularMomentum(const CoinModel& m, const FlightState& s) {
  return s.q * principalMoments(m).cwiseProduct(s.omegaBody);
}

}  // namespace coinroll::physics
