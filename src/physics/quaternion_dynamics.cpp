#include "physics/quaternion_dynamics.h"

#include <Eigen/Cholesky>

#include <cmath>
#include <numbers>

#include "physics/body_contact.h"
#include "physics/observables.h"

namespace coinroll::physics {

namespace {

// (3.4): [I_G + M (|c|^2 1 - c c^t)] omega-dot = -omega x I_G omega - M c x (omega x c-dot + omega x (omega x c))
//                                                + M g c x e_y + tau
// The matrix and the couple-free right-hand side of one state, factorised once: the effects' passes
// solve it again with their couples (the same operations as solving from scratch, so the same bits).
struct EulerSystem {
  Eigen::LLT<Eigen::Matrix3d> A;
  Eigen::Vector3d b;

  EulerSystem(const CoinModel& m, const ContactGeometry& geo, const Eigen::Vector3d& omega,
              const Eigen::Vector3d& cDot) {
    const Eigen::Vector3d inertia(m.I_X, m.I_X, m.I_Z);  // principal moments about G, material frame
    const Eigen::Vector3d& c = geo.c;
    A.compute(Eigen::Matrix3d(inertia.asDiagonal()) +
              m.M * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose()));
    b = -omega.cross(inertia.cwiseProduct(omega)) - m.M * c.cross(omega.cross(cDot) + omega.cross(omega.cross(c))) +
        m.M * m.g * c.cross(geo.up);
  }

  // A couple adds to b (docs/euler_disk.md eq. 1.3); the ideal path adds none, so a scene without
  // effects integrates exactly as before.
  Eigen::Vector3d angularAcceleration() const { return A.solve(b); }
  Eigen::Vector3d angularAcceleration(const Eigen::Vector3d& torqueBody) const {
    Eigen::Vector3d withCouple = b;
    withCouple += torqueBody;
    return A.solve(withCouple);
  }
};

Eigen::Vector3d angularAcceleration(const CoinModel& m, const ContactGeometry& geo, const Eigen::Vector3d& omega,
                                    const Eigen::Vector3d& cDot) {
  return EulerSystem(m, geo, omega, cDot).angularAcceleration();
}

Eigen::Vector3d centreOfMassVelocityBody(const ContactGeometry& geo, const Eigen::Vector3d& omega) {
  return -omega.cross(geo.c);  // no slip, seed eq. (3)
}

Reaction reactionFrom(const CoinModel& m, const QuaternionState& s, const ContactGeometry& geo,
                      const Eigen::Vector3d& cDot, const Eigen::Vector3d& dw) {
  const Eigen::Vector3d& w = s.omegaBody;
  // (5.2): dv/dt of v = -omega x c, with c-dot the contact's drift round the rim and the frame's turn.
  const Eigen::Vector3d accelerationBody =
      -(dw.cross(geo.c) + w.cross(cDot)) + w.cross(centreOfMassVelocityBody(geo, w));
  Reaction r;
  r.R = m.M * geo.floorFromBody * accelerationBody + Eigen::Vector3d(0, m.M * m.g, 0);
  r.N = r.R.y();
  r.F = std::hypot(r.R.x(), r.R.z());
  return r;
}

ContactKinematics contactKinematics(const CoinModel& m, const QuaternionState& s, const ContactGeometry& geo,
                                    double N) {
  return {.e_X = geo.floorFromBody * geo.e_X,
          .e_Y = geo.floorFromBody * geo.e_Y,
          .e_Z = geo.floorFromBody.col(2),
          .omega = geo.floorFromBody * s.omegaBody,
          .faceRadius = m.a - m.rim.edgeRadius,
          .outerRadius = m.a,
          .holeRadius = m.holeRadius,
          .N = N};
}

// The angular acceleration and reaction with the effects' couples: two passes, exact for the same
// reason as in the Euler angles (docs/rim.md eq. 4.3). `f` holds the ideal ones on entry.
void addEffects(const CoinModel& m, const QuaternionState& s, const ContactGeometry& geo, const Eigen::Vector3d& cDot,
                const EulerSystem& euler, Forward& f) {
  NormalForceLoads effectLoads(m.effects, contactKinematics(m, s, geo, f.reaction.N));
  for (int pass = 0; pass < 2; ++pass) {
    f.loads = effectLoads.at(f.reaction.N);
    const Eigen::Vector3d torqueBody = geo.floorFromBody.transpose() * f.loads.torque;
    f.dOmega = euler.angularAcceleration(torqueBody);
    f.reaction = reactionFrom(m, s, geo, cDot, f.dOmega);
  }
}

Forward forwardAt(const CoinModel& m, const QuaternionState& s, const ContactGeometry& geo) {
  const Eigen::Vector3d cDot = contactDrift(m, geo, s.omegaBody);
  const EulerSystem euler(m, geo, s.omegaBody, cDot);
  Forward f;
  f.dOmega = euler.angularAcceleration();
  f.reaction = reactionFrom(m, s, geo, cDot, f.dOmega);
  if (!m.effects.empty()) addEffects(m, s, geo, cDot, euler, f);
  setAttitudeKinematics(m, s.q, s.omegaBody, s.x, s.z, geo,
                        geo.floorFromBody * centreOfMassVelocityBody(geo, s.omegaBody), f);
  return f;
}

}  // namespace

QuaternionStateVec toVector(const QuaternionState& s) {
  QuaternionStateVec y;
  y << s.q.w(), s.q.x(), s.q.y(), s.q.z(), s.omegaBody, s.x, s.z;
  return y;
}

QuaternionState toQuaternionState(const QuaternionStateVec& y) {
  return {.q = Eigen::Quaterniond(y[kQw], y[kQx], y[kQy], y[kQz]).normalized(),
          .omegaBody = y.segment<3>(kOmegaBody1),
          .x = y[kCentreX],
          .z = y[kCentreZ]};
}

QuaternionState fromEulerState(const CoinState& s) {
  const double c = std::cos(s.psi), sn = std::sin(s.psi);
  return {.q = attitude(s),
          .omegaBody = {c * s.omega_X + sn * s.omega_Y, -sn * s.omega_X + c * s.omega_Y, s.omega_Z},  // (1.3)
          .x = s.x,
          .z = s.z};
}

CoinState toEulerState(const QuaternionState& s, const CoinState& continuation) {
  const Eigen::Matrix3d floorFromBody = s.q.toRotationMatrix();
  const Eigen::Vector3d normal = floorFromBody.col(2);          // e_Z = (cos th sin phi, -sin th, cos th cos phi)
  const Eigen::Vector3d up = floorFromBody.row(1).transpose();  // e_y in material components
  const auto nearest = [](double angle, double reference) {
    return angle + 2 * std::numbers::pi * std::round((reference - angle) / (2 * std::numbers::pi));
  };
  CoinState e;
  e.theta = thetaOf(s.q);
  e.phi = nearest(std::atan2(normal.x(), normal.z()), continuation.phi);
  e.psi = nearest(std::atan2(up.x(), up.y()), continuation.psi);  // e_Y = (sin psi, cos psi, 0)
  const double c = std::cos(e.psi), sn = std::sin(e.psi);
  const Eigen::Vector3d& w = s.omegaBody;
  e.omega_X = c * w.x() - sn * w.y();  // (1.5)
  e.omega_Y = sn * w.x() + c * w.y();
  e.omega_Z = w.z();
  e.x = s.x;
  e.z = s.z;
  return e;
}

double thetaOf(const Eigen::Quaterniond& unitQ) {
  const Eigen::Matrix3d floorFromBody = unitQ.toRotationMatrix();
  const Eigen::Vector3d normal = floorFromBody.col(2);
  return std::atan2(-normal.y(), std::hypot(normal.x(), normal.z()));  // (1.4)
}

Forward forward(const CoinModel& model, const QuaternionState& s) {
  return forwardAt(model, s, contactGeometry(model, s.q));
}

QuaternionRates quaternionRates(const CoinModel& model, const QuaternionStateVec& y) {
  const Eigen::Quaterniond stored(y[kQw], y[kQx], y[kQy], y[kQz]);
  const double normSquared = stored.squaredNorm();
  const Eigen::Quaterniond q = stored.normalized();
  const Eigen::Vector3d omega = y.segment<3>(kOmegaBody1);
  const ContactGeometry geo = contactGeometry(model, q);

  // (4.1): q-dot = q (0, omega) / 2, plus a pull back to |q| = 1 at the natural rate sqrt(g/a)
  // that vanishes on the unit sphere, so it leaves the exact solution alone and only damps drift.
  const Eigen::Quaterniond spin = q * Eigen::Quaterniond(0, omega.x(), omega.y(), omega.z());
  const double restoring = naturalRate(model) * (1 - normSquared);
  const Eigen::Vector3d velocity = geo.floorFromBody * centreOfMassVelocityBody(geo, omega);  // (2.3)

  QuaternionRates rates;
  QuaternionStateVec& dy = rates.dy;
  dy[kQw] = 0.5 * spin.w() + restoring * q.w();
  dy[kQx] = 0.5 * spin.x() + restoring * q.x();
  dy[kQy] = 0.5 * spin.y() + restoring * q.y();
  dy[kQz] = 0.5 * spin.z() + restoring * q.z();
  const Eigen::Vector3d cDot = contactDrift(model, geo, omega);
  if (model.effects.empty()) {
    dy.segment<3>(kOmegaBody1) = angularAcceleration(model, geo, omega, cDot);  // (3.4)
  } else {
    const QuaternionState s{.q = q, .omegaBody = omega, .x = y[kCentreX], .z = y[kCentreZ]};
    const EulerSystem euler(model, geo, omega, cDot);
    Forward f;
    f.dOmega = euler.angularAcceleration();
    f.reaction = reactionFrom(model, s, geo, cDot, f.dOmega);
    addEffects(model, s, geo, cDot, euler, f);
    dy.segment<3>(kOmegaBody1) = f.dOmega;
    rates.power = f.loads.power;
  }
  dy[kCentreX] = velocity.x();
  dy[kCentreZ] = velocity.z();
  return rates;
}

QuaternionStateVec quaternionRhs(const CoinModel& model, double /*t*/, const QuaternionStateVec& y) {
  return quaternionRates(model, y).dy;
}

}  // namespace coinroll::physics
