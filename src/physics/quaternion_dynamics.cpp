#include "physics/quaternion_dynamics.h"

#include <Eigen/Cholesky>

#include <cmath>
#include <numbers>

#include "physics/observables.h"

namespace coinroll::physics {

namespace {

// What the attitude alone fixes, in material-frame components (docs/quaternion_formulation.md §2).
struct ContactGeometry {
  Eigen::Matrix3d floorFromBody;  // columns: the material axes b1, b2, b3 in floor components
  Eigen::Vector3d up;             // e_y, the floor's upward normal
  Eigen::Vector3d e_X, e_Y;       // the seed's in-plane axes: e_Y points up the coin plane (eq. 2.1)
  double cosTheta = 0;            // |e_y minus its normal part|, = cos(theta) >= 0
  Eigen::Vector3d c;              // m, from the centre of mass to the contact point, -a e_Y (eq. 2.2)
};

ContactGeometry contactGeometry(const CoinModel& m, const Eigen::Quaterniond& unitQ) {
  ContactGeometry geo;
  geo.floorFromBody = unitQ.toRotationMatrix();
  geo.up = geo.floorFromBody.row(1).transpose();
  geo.cosTheta = std::hypot(geo.up.x(), geo.up.y());
  geo.e_Y = Eigen::Vector3d(geo.up.x(), geo.up.y(), 0) / geo.cosTheta;
  geo.e_X = Eigen::Vector3d(geo.e_Y.y(), -geo.e_Y.x(), 0);  // e_Y x e_Z
  geo.c = -m.a * geo.e_Y;
  return geo;
}

// dc/dt in material components: the contact point runs round the rim at psi-dot (eq. 2.4).
// psi-dot = e_X . (e_y x omega) / cos(theta) is the one place 1 / cos(theta) remains; it is the
// physical rolling rate, finite along every finite-energy motion short of flat.
Eigen::Vector3d contactDrift(const CoinModel& m, const ContactGeometry& geo, const Eigen::Vector3d& omega) {
  const double psiDot = geo.e_X.dot(geo.up.cross(omega)) / geo.cosTheta;
  return -m.a * psiDot * geo.e_X;
}

// The ideal path adds no couple, so a scene without effects integrates exactly as before.
Eigen::Vector3d angularAcceleration(const CoinModel& m, const ContactGeometry& geo, const Eigen::Vector3d& omega,
                                    const Eigen::Vector3d* torqueBody = nullptr) {
  const Eigen::Vector3d inertia(m.I_X, m.I_X, m.I_Z);  // principal moments about G, material frame
  const Eigen::Vector3d& c = geo.c;
  const Eigen::Vector3d cDot = contactDrift(m, geo, omega);
  // (3.4): [I_G + M (a^2 1 - c c^t)] omega-dot = -omega x I_G omega - M c x (omega x c-dot + omega x (omega x c))
  //                                              + M g c x e_y
  const Eigen::Matrix3d A = Eigen::Matrix3d(inertia.asDiagonal()) +
                            m.M * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  // A couple adds to b (docs/euler_disk.md eq. 1.3).
  Eigen::Vector3d b = -omega.cross(inertia.cwiseProduct(omega)) -
                      m.M * c.cross(omega.cross(cDot) + omega.cross(omega.cross(c))) + m.M * m.g * c.cross(geo.up);
  if (torqueBody != nullptr) b += *torqueBody;
  return A.llt().solve(b);
}

Eigen::Vector3d centreOfMassVelocityBody(const ContactGeometry& geo, const Eigen::Vector3d& omega) {
  return -omega.cross(geo.c);  // no slip, seed eq. (3)
}

Reaction reactionFrom(const CoinModel& m, const QuaternionState& s, const ContactGeometry& geo, const Eigen::Vector3d& dw) {
  const Eigen::Vector3d& w = s.omegaBody;
  // (5.2): dv/dt of v = -omega x c, with c-dot the contact's drift round the rim and the frame's turn.
  const Eigen::Vector3d accelerationBody =
      -(dw.cross(geo.c) + w.cross(contactDrift(m, geo, w))) + w.cross(centreOfMassVelocityBody(geo, w));
  Reaction r;
  r.R = m.M * geo.floorFromBody * accelerationBody + Eigen::Vector3d(0, m.M * m.g, 0);
  r.N = r.R.y();
  r.F = std::hypot(r.R.x(), r.R.z());
  return r;
}

ContactKinematics contactKinematics(const CoinModel& m, const QuaternionState& s, const ContactGeometry& geo, double N) {
  return {.e_X = geo.floorFromBody * geo.e_X,
          .e_Y = geo.floorFromBody * geo.e_Y,
          .e_Z = geo.floorFromBody.col(2),
          .omega = geo.floorFromBody * s.omegaBody,
          .a = m.a,
          .N = N};
}

QuaternionDynamics dynamicsAt(const CoinModel& m, const QuaternionState& s, const ContactGeometry& geo) {
  QuaternionDynamics d;
  d.dOmegaBody = angularAcceleration(m, geo, s.omegaBody);
  d.reaction = reactionFrom(m, s, geo, d.dOmegaBody);
  // Two passes, exact for the same reason as in the Euler angles (docs/euler_disk.md eq. 1.8).
  if (m.effects.empty()) return d;
  ContactKinematics kinematics = contactKinematics(m, s, geo, d.reaction.N);  // only N changes per pass
  for (int pass = 0; pass < 2; ++pass) {
    kinematics.N = d.reaction.N;
    d.loads = totalLoads(m.effects, kinematics);
    const Eigen::Vector3d torqueBody = geo.floorFromBody.transpose() * d.loads.torque;
    d.dOmegaBody = angularAcceleration(m, geo, s.omegaBody, &torqueBody);
    d.reaction = reactionFrom(m, s, geo, d.dOmegaBody);
  }
  return d;
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
  const Eigen::Vector3d normal = floorFromBody.col(2);    // e_Z = (cos th sin phi, -sin th, cos th cos phi)
  const Eigen::Vector3d up = floorFromBody.row(1).transpose();  // e_y in material components
  const auto nearest = [](double angle, double reference) {
    return angle + 2 * std::numbers::pi * std::round((reference - angle) / (2 * std::numbers::pi));
  };
  CoinState e;
  e.theta = std::atan2(-normal.y(), std::hypot(normal.x(), normal.z()));          // (1.4)
  e.phi = nearest(std::atan2(normal.x(), normal.z()), continuation.phi);
  e.psi = nearest(std::atan2(up.x(), up.y()), continuation.psi);                  // e_Y = (sin psi, cos psi, 0)
  const double c = std::cos(e.psi), sn = std::sin(e.psi);
  const Eigen::Vector3d& w = s.omegaBody;
  e.omega_X = c * w.x() - sn * w.y();                                             // (1.5)
  e.omega_Y = sn * w.x() + c * w.y();
  e.omega_Z = w.z();
  e.x = s.x;
  e.z = s.z;
  return e;
}

QuaternionDynamics quaternionDynamics(const CoinModel& model, const QuaternionState& s) {
  return dynamicsAt(model, s, contactGeometry(model, s.q));
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
  if (model.effects.empty()) {
    dy.segment<3>(kOmegaBody1) = angularAcceleration(model, geo, omega);           // (3.4)
  } else {
    const QuaternionDynamics d = dynamicsAt(model, {.q = q, .omegaBody = omega, .x = y[kCentreX], .z = y[kCentreZ]}, geo);
    dy.segment<3>(kOmegaBody1) = d.dOmegaBody;
    rates.power = d.loads.power;
  }
  dy[kCentreX] = velocity.x();
  dy[kCentreZ] = velocity.z();
  return rates;
}

QuaternionStateVec quaternionRhs(const CoinModel& model, double /*t*/, const QuaternionStateVec& y) {
  return quaternionRates(model, y).dy;
}

}  // namespace coinroll::physics
