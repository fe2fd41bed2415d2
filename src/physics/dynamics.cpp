#include "physics/dynamics.h"

#include <cmath>
#include <optional>

#include "physics/observables.h"

namespace coinroll::physics {

namespace {

// Eqs. (14)-(16) from precomputed sin/cos so rhs() pays for one sin and one cos per call.
Eigen::Vector3d thinAngularAcceleration(const CoinModel& m, double sinTheta, double cosTheta, double omega_X,
                                        double omega_Y, double omega_Z) {
  const double tanTheta = sinTheta / cosTheta;
  const double Ma2 = m.M * m.a * m.a;
  const double Mga = m.M * m.g * m.a;
  return {(-(m.I_Z + Ma2) * omega_Y * omega_Z - m.I_X * omega_Y * omega_Y * tanTheta + Mga * sinTheta) /
              (m.I_X + Ma2),                                                   // (14)
          omega_X * omega_Y * tanTheta + (m.I_Z / m.I_X) * omega_Z * omega_X,  // (15)
          Ma2 * omega_X * omega_Y / (m.I_Z + Ma2)};                            // (16)
}

// What a rim's geometry and the rates fix before the angular acceleration is known, in XYZ
// components (docs/rim.md §2): c = (0, -reach, lift), its component rate, the frame's rate Omega,
// the centre-of-mass velocity and the floor normal.
struct RimTerms {
  Eigen::Vector3d c;
  Eigen::Vector3d cRate;      // theta-dot (0, -d reach, d lift)        (2.3)
  Eigen::Vector3d frameRate;  // (omega_X, omega_Y, -omega_Y tan theta)  (2.1)
  Eigen::Vector3d v;          // -omega x c                             (2.4)
  Eigen::Vector3d up;         // e_y = (0, cos theta, -sin theta)
};

RimTerms rimTerms(const CoinModel& m, double sinTheta, double cosTheta, const Eigen::Vector3d& omega) {
  const ContactOffset o = contactOffset(m.rim, m.a, sinTheta, cosTheta);
  RimTerms t;
  t.c = Eigen::Vector3d(0, -o.reach, o.lift);
  t.cRate = omega.x() * Eigen::Vector3d(0, -o.dReach, o.dLift);
  t.frameRate = Eigen::Vector3d(omega.x(), omega.y(), -omega.y() * sinTheta / cosTheta);
  t.v = -omega.cross(t.c);
  t.up = Eigen::Vector3d(0, cosTheta, -sinTheta);
  return t;
}

// (2.7): [I + M (|c|^2 1 - c c^t)] omega-dot = -Omega x I omega + M c x (Omega x v - omega x c-rate)
//        + M g c x e_y + tau. The X row stands alone; Y and Z share the 2 x 2 block of (2.8).
Eigen::Vector3d rimAngularAcceleration(const CoinModel& m, const RimTerms& t, const Eigen::Vector3d& omega,
                                       const Eigen::Vector3d& torqueXYZ) {
  const Eigen::Vector3d inertia(m.I_X, m.I_X, m.I_Z);
  const Eigen::Vector3d b = -t.frameRate.cross(inertia.cwiseProduct(omega)) +
                            m.M * t.c.cross(t.frameRate.cross(t.v) - omega.cross(t.cRate)) +
                            m.M * m.g * t.c.cross(t.up) + torqueXYZ;
  const double reach = -t.c.y(), lift = t.c.z();
  const double mXX = m.I_X + m.M * (reach * reach + lift * lift);
  const double mYY = m.I_X + m.M * lift * lift, mZZ = m.I_Z + m.M * reach * reach, mYZ = m.M * reach * lift;
  const double det = mYY * mZZ - mYZ * mYZ;
  return {b.x() / mXX, (mZZ * b.y() - mYZ * b.z()) / det, (mYY * b.z() - mYZ * b.y()) / det};
}

// A couple adds to (14)-(16) through the mass matrix diag(I_X + M a^2, I_X, I_Z + M a^2), which
// is what I_G + M (a^2 1 - c c^t) is in XYZ with c = -a e_Y (docs/euler_disk.md eqs. 1.4-1.5).
Eigen::Vector3d thinPlusCouple(const CoinModel& m, Eigen::Vector3d ideal, const Eigen::Vector3d& torqueXYZ) {
  const double Ma2 = m.M * m.a * m.a;
  ideal.x() += torqueXYZ.x() / (m.I_X + Ma2);
  ideal.y() += torqueXYZ.y() / m.I_X;
  ideal.z() += torqueXYZ.z() / (m.I_Z + Ma2);
  return ideal;
}

// dv/dt of the centre of mass in XYZ components.
Eigen::Vector3d centreAcceleration(const CoinModel& m, const CoinState& s, const std::optional<RimTerms>& rim,
                                   const Eigen::Vector3d& omega, const Eigen::Vector3d& dOmega) {
  if (!rim) {
    // Seed section 4, checked in docs/derivations.md §2:
    //   a ( -(dOmega_Z - omega_X omega_Y), -(omega_X^2 - omega_Y omega_Z tan theta), dOmega_X + omega_Y omega_Z )
    const double tanTheta = std::tan(s.theta);
    return m.a * Eigen::Vector3d(-(dOmega.z() - s.omega_X * s.omega_Y),
                                 -(s.omega_X * s.omega_X - s.omega_Y * s.omega_Z * tanTheta),
                                 dOmega.x() + s.omega_Y * s.omega_Z);
  }
  // (4.1): d/dt(-omega x c) in a frame turning at Omega.
  return -(dOmega.cross(rim->c) + omega.cross(rim->cRate)) + rim->frameRate.cross(rim->v);
}

Reaction reactionFrom(const CoinModel& m, const Eigen::Matrix3d& axes, const Eigen::Vector3d& accelerationXYZ) {
  // Rows of R are the coin axes in floor components, so floor components are R^t times coin ones.
  const Eigen::Vector3d acceleration = axes.transpose() * accelerationXYZ;
  Reaction r;
  r.R = m.M * acceleration + Eigen::Vector3d(0, m.M * m.g, 0);
  r.N = r.R.y();
  r.F = std::hypot(r.R.x(), r.R.z());
  return r;
}

// `velocityXZ`: the centre of mass's floor velocity (x, z).
StateVec pack(const StateVec& y, double sinTheta, double cosTheta, const Eigen::Vector3d& dOmega, double vx,
              double vz) {
  StateVec dy;
  dy[kTheta] = y[kOmega_X];                                      // (17), docs/seed.md §3
  dy[kPhi] = y[kOmega_Y] / cosTheta;                             // (18)
  dy[kPsi] = y[kOmega_Z] + (sinTheta / cosTheta) * y[kOmega_Y];  // (19)
  dy[kOmega_X] = dOmega.x();
  dy[kOmega_Y] = dOmega.y();
  dy[kOmega_Z] = dOmega.z();
  dy[kX] = vx;
  dy[kZ] = vz;
  return dy;
}

StateVec packThin(const CoinModel& model, const StateVec& y, double sinTheta, double cosTheta,
                  const Eigen::Vector3d& dOmega) {
  const double sinPhi = std::sin(y[kPhi]), cosPhi = std::cos(y[kPhi]);
  const double omega_X = y[kOmega_X], omega_Z = y[kOmega_Z];
  const double a = model.a;
  return pack(y, sinTheta, cosTheta, dOmega,
              a * (-omega_Z * cosPhi + omega_X * cosTheta * sinPhi),  // section 4, v_x
              a * (omega_Z * sinPhi + omega_X * cosTheta * cosPhi));  // section 4, v_z
}

StateVec packRim(const StateVec& y, double sinTheta, double cosTheta, const Eigen::Vector3d& dOmega,
                 const Eigen::Vector3d& velocityFloor) {
  return pack(y, sinTheta, cosTheta, dOmega, velocityFloor.x(), velocityFloor.z());
}

ContactKinematics kinematicsFrom(const CoinModel& model, const CoinState& s, const Eigen::Matrix3d& axes, double N) {
  return {.e_X = axes.row(0).transpose(),
          .e_Y = axes.row(1).transpose(),
          .e_Z = axes.row(2).transpose(),
          .omega = axes.transpose() * Eigen::Vector3d(s.omega_X, s.omega_Y, s.omega_Z),
          .faceRadius = model.a - model.rim.edgeRadius,
          .outerRadius = model.a,
          .holeRadius = model.holeRadius,
          .N = N};
}

}  // namespace

ContactKinematics contactKinematics(const CoinModel& model, const CoinState& s, double N) {
  return kinematicsFrom(model, s, coinAxesInFloor(s), N);
}

namespace {

// The part of the forward pass the right-hand side needs: axes, omega, the angular acceleration, the
// reaction and the effects' loads; `rim` is left holding the rim's terms (empty for the thin coin).
Forward accelerations(const CoinModel& model, const CoinState& s, double sinTheta, double cosTheta,
                      std::optional<RimTerms>& rim) {
  const Eigen::Vector3d omega(s.omega_X, s.omega_Y, s.omega_Z);
  Eigen::Vector3d ideal;  // without the effects' couple
  if (model.rim.thin()) {
    ideal = thinAngularAcceleration(model, sinTheta, cosTheta, s.omega_X, s.omega_Y, s.omega_Z);
  } else {
    rim = rimTerms(model, sinTheta, cosTheta, omega);
    ideal = rimAngularAcceleration(model, *rim, omega, Eigen::Vector3d::Zero());
  }
  const auto withCouple = [&](const Eigen::Vector3d& torqueXYZ) -> Eigen::Vector3d {
    return rim ? rimAngularAcceleration(model, *rim, omega, torqueXYZ) : thinPlusCouple(model, ideal, torqueXYZ);
  };

  Forward f;
  f.theta = s.theta;
  f.axes = coinAxesInFloor(s);
  f.omega = f.axes.transpose() * omega;
  f.dOmega = ideal;
  f.reaction = reactionFrom(model, f.axes, centreAcceleration(model, s, rim, omega, f.dOmega));
  if (!model.effects.empty()) {
    // N depends on a couple only through its e_X part, and no N-dependent law has one (docs/rim.md
    // eq. 4.3): the first pass finds N under the N-independent couples, the second is exact. Only N
    // changes between the passes.
    NormalForceLoads effectLoads(model.effects, kinematicsFrom(model, s, f.axes, f.reaction.N));
    for (int pass = 0; pass < 2; ++pass) {
      f.loads = effectLoads.at(f.reaction.N);
      f.dOmega = withCouple(f.axes * f.loads.torque);
      f.reaction = reactionFrom(model, f.axes, centreAcceleration(model, s, rim, omega, f.dOmega));
    }
  }
  return f;
}

}  // namespace

Forward forward(const CoinModel& model, const CoinState& s) {
  const double sinTheta = std::sin(s.theta), cosTheta = std::cos(s.theta);
  const Eigen::Vector3d omega(s.omega_X, s.omega_Y, s.omega_Z);
  std::optional<RimTerms> rim;
  Forward f = accelerations(model, s, sinTheta, cosTheta, rim);
  const Eigen::Vector3d e_X = f.axes.row(0).transpose(), e_Y = f.axes.row(1).transpose(),
                        e_Z = f.axes.row(2).transpose();
  if (rim) {
    f.contactVector = f.axes.transpose() * rim->c;  // (1.3)
    f.centre = Eigen::Vector3d(s.x, -f.contactVector.y(), s.z);
    f.velocity = -f.omega.cross(f.contactVector);
    const Eigen::Vector3d inertia(model.I_X, model.I_X, model.I_Z);
    f.energy = 0.5 * model.M * f.velocity.squaredNorm() + 0.5 * omega.dot(inertia.cwiseProduct(omega)) +
               model.M * model.g * f.centre.y();  // (4.4)
  } else {
    // The seed's forms, in the operations observables.cpp uses, so the CSV keeps its bytes.
    f.contactVector = -model.a * e_Y;
    f.centre = Eigen::Vector3d(s.x, model.a * cosTheta, s.z);
    f.velocity = model.a * (-s.omega_Z * e_X + s.omega_X * e_Z);
    f.energy = energy(model, s);
  }
  f.contactPoint = rim ? Eigen::Vector3d(f.centre + f.contactVector) : Eigen::Vector3d(f.centre - model.a * e_Y);
  f.spinRate = spinRate(s);
  f.precessionRate = precessionRate(s);
  return f;
}

Rates rates(const CoinModel& model, const StateVec& y) {
  const double sinTheta = std::sin(y[kTheta]), cosTheta = std::cos(y[kTheta]);
  if (model.effects.empty()) {
    const Eigen::Vector3d omega = y.segment<3>(kOmega_X);
    if (model.rim.thin()) {
      const Eigen::Vector3d dOmega =
          thinAngularAcceleration(model, sinTheta, cosTheta, y[kOmega_X], y[kOmega_Y], y[kOmega_Z]);
      return {.dy = packThin(model, y, sinTheta, cosTheta, dOmega), .power = 0};
    }
    const RimTerms rim = rimTerms(model, sinTheta, cosTheta, omega);
    const Eigen::Vector3d dOmega = rimAngularAcceleration(model, rim, omega, Eigen::Vector3d::Zero());
    const Eigen::Vector3d velocity = coinAxesInFloor(toState(y)).transpose() * rim.v;
    return {.dy = packRim(y, sinTheta, cosTheta, dOmega, velocity), .power = 0};
  }
  std::optional<RimTerms> rim;
  const Forward f = accelerations(model, toState(y), sinTheta, cosTheta, rim);
  if (!rim) return {.dy = packThin(model, y, sinTheta, cosTheta, f.dOmega), .power = f.loads.power};
  return {.dy = packRim(y, sinTheta, cosTheta, f.dOmega, f.axes.transpose() * rim->v), .power = f.loads.power};
}

StateVec rhs(const CoinModel& model, double /*t*/, const StateVec& y) { return rates(model, y).dy; }

}  // namespace coinroll::physics
