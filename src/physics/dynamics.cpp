#include "physics/dynamics.h"

#include <cmath>

#include "physics/observables.h"

namespace coinroll::physics {

namespace {

// Eqs. (14)-(16) from precomputed sin/cos so rhs() pays for one sin and one cos per call.
AngularAcceleration idealAngularAcceleration(const CoinModel& m, double sinTheta, double cosTheta, double omega_X,
                                             double omega_Y, double omega_Z) {
  const double tanTheta = sinTheta / cosTheta;
  const double Ma2 = m.M * m.a * m.a;
  const double Mga = m.M * m.g * m.a;
  return {
      .dOmega_X = (-(m.I_Z + Ma2) * omega_Y * omega_Z - m.I_X * omega_Y * omega_Y * tanTheta
                   + Mga * sinTheta) / (m.I_X + Ma2),                                        // (14)
      .dOmega_Y = omega_X * omega_Y * tanTheta + (m.I_Z / m.I_X) * omega_Z * omega_X,       // (15)
      .dOmega_Z = Ma2 * omega_X * omega_Y / (m.I_Z + Ma2),                                  // (16)
  };
}

// A couple adds to (14)-(16) through the mass matrix diag(I_X + M a^2, I_X, I_Z + M a^2), which
// is what I_G + M (a^2 1 - c c^t) is in XYZ with c = -a e_Y (docs/euler_disk.md eqs. 1.4-1.5).
AngularAcceleration plusCouple(const CoinModel& m, AngularAcceleration ideal, const Eigen::Vector3d& torqueXYZ) {
  const double Ma2 = m.M * m.a * m.a;
  ideal.dOmega_X += torqueXYZ.x() / (m.I_X + Ma2);
  ideal.dOmega_Y += torqueXYZ.y() / m.I_X;
  ideal.dOmega_Z += torqueXYZ.z() / (m.I_Z + Ma2);
  return ideal;
}

// `axes` = coinAxesInFloor(s), computed once by the caller for all its passes.
Reaction reactionFrom(const CoinModel& m, const CoinState& s, const Eigen::Matrix3d& axes, const AngularAcceleration& dOmega) {
  // dv/dt in coin-frame components (seed section 4, checked in docs/derivations.md §2):
  //   a ( -(dOmega_Z - omega_X omega_Y), -(omega_X^2 - omega_Y omega_Z tan theta), dOmega_X + omega_Y omega_Z )
  const double tanTheta = std::tan(s.theta);
  const Eigen::Vector3d accelerationInCoinFrame =
      m.a * Eigen::Vector3d(-(dOmega.dOmega_Z - s.omega_X * s.omega_Y),
                            -(s.omega_X * s.omega_X - s.omega_Y * s.omega_Z * tanTheta),
                            dOmega.dOmega_X + s.omega_Y * s.omega_Z);
  // Rows of R are the coin axes in floor components, so floor components are R^t times coin ones.
  const Eigen::Vector3d acceleration = axes.transpose() * accelerationInCoinFrame;
  Reaction r;
  r.R = m.M * acceleration + Eigen::Vector3d(0, m.M * m.g, 0);
  r.N = r.R.y();
  r.F = std::hypot(r.R.x(), r.R.z());
  return r;
}

StateVec pack(const CoinModel& model, const StateVec& y, double sinTheta, double cosTheta, const AngularAcceleration& dOmega) {
  const double sinPhi = std::sin(y[kPhi]), cosPhi = std::cos(y[kPhi]);
  const double omega_X = y[kOmega_X], omega_Y = y[kOmega_Y], omega_Z = y[kOmega_Z];
  const double a = model.a;

  StateVec dy;
  dy[kTheta]   = omega_X;                                                   // (17), ERRATA
  dy[kPhi]     = omega_Y / cosTheta;                                        // (18)
  dy[kPsi]     = omega_Z + (sinTheta / cosTheta) * omega_Y;                 // (19)
  dy[kOmega_X] = dOmega.dOmega_X;
  dy[kOmega_Y] = dOmega.dOmega_Y;
  dy[kOmega_Z] = dOmega.dOmega_Z;
  dy[kX]       = a * (-omega_Z * cosPhi + omega_X * cosTheta * sinPhi);     // section 4, v_x
  dy[kZ]       = a * (omega_Z * sinPhi + omega_X * cosTheta * cosPhi);      // section 4, v_z
  return dy;
}

ContactKinematics kinematicsFrom(const CoinModel& model, const CoinState& s, const Eigen::Matrix3d& axes, double N) {
  return {.e_X = axes.row(0).transpose(),
          .e_Y = axes.row(1).transpose(),
          .e_Z = axes.row(2).transpose(),
          .omega = axes.transpose() * Eigen::Vector3d(s.omega_X, s.omega_Y, s.omega_Z),
          .a = model.a,
          .N = N};
}

}  // namespace

ContactKinematics contactKinematics(const CoinModel& model, const CoinState& s, double N) {
  return kinematicsFrom(model, s, coinAxesInFloor(s), N);
}

Dynamics dynamics(const CoinModel& model, const CoinState& s) {
  const AngularAcceleration ideal =
      idealAngularAcceleration(model, std::sin(s.theta), std::cos(s.theta), s.omega_X, s.omega_Y, s.omega_Z);
  const Eigen::Matrix3d axes = coinAxesInFloor(s);
  Dynamics d{.dOmega = ideal, .reaction = reactionFrom(model, s, axes, ideal), .loads = {}};
  if (model.effects.empty()) return d;
  // N depends on a couple only through its e_X part, and no N-dependent law has one (eq. 1.8):
  // the first pass finds N under the N-independent couples, the second is exact. Only N changes
  // between the passes.
  ContactKinematics kinematics = kinematicsFrom(model, s, axes, d.reaction.N);
  for (int pass = 0; pass < 2; ++pass) {
    kinematics.N = d.reaction.N;
    d.loads = totalLoads(model.effects, kinematics);
    d.dOmega = plusCouple(model, ideal, axes * d.loads.torque);
    d.reaction = reactionFrom(model, s, axes, d.dOmega);
  }
  return d;
}

Rates rates(const CoinModel& model, const StateVec& y) {
  const double sinTheta = std::sin(y[kTheta]), cosTheta = std::cos(y[kTheta]);
  if (model.effects.empty()) {
    const AngularAcceleration dOmega =
        idealAngularAcceleration(model, sinTheta, cosTheta, y[kOmega_X], y[kOmega_Y], y[kOmega_Z]);
    return {.dy = pack(model, y, sinTheta, cosTheta, dOmega), .power = 0};
  }
  const Dynamics d = dynamics(model, toState(y));
  return {.dy = pack(model, y, sinTheta, cosTheta, d.dOmega), .power = d.loads.power};
}

StateVec rhs(const CoinModel& model, double /*t*/, const StateVec& y) { return rates(model, y).dy; }

}  // namespace coinroll::physics
