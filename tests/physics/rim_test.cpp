// A coin with a rim (docs/rim.md) against truths computed another way: the thin coin it tends to,
// the energy it conserves, the second formulation, Newton's second law, and the ball it becomes
// when the rim is all there is.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "integrate/trajectory.h"
#include "physics/coin_rhs.h"
#include "physics/dynamics.h"
#include "physics/observables.h"
#include "physics/quaternion_dynamics.h"
#include "physics/solid_inertia.h"
#include "reference_solver.h"
#include "tolerance.h"

namespace coinroll::physics {
namespace {

using coinroll::testing::isBelow;
using coinroll::testing::isNear;

using reference::kDeg;
using reference::kTight;

// The Euler's-disk toy as a solid: 75 mm across, 13 mm thick, its rim rounded with `rho`.
CoinModel toy(double rho, double h = 0.013) {
  CoinModel m = diskModel(0.4, 0.0375, 9.81);
  const PrincipalMoments I = filletedCylinderInertia(m.M, m.a, 0, h, rho);
  m.I_X = I.I_X;
  m.I_Z = I.I_Z;
  m.rim = {.thickness = h, .edgeRadius = rho};
  return m;
}

TEST(Rim, TendsToTheThinCoinLinearlyInTheThickness) {
  // The rim's terms are O(h / a): ten times thinner, ten times closer to the seed's (14)-(19).
  const CoinState s{.theta = 0.4, .phi = 0.3, .psi = -1.2, .omega_X = 1.1, .omega_Y = -3.0, .omega_Z = 13.0};
  const CoinModel thin = diskModel(0.4, 0.0375, 9.81);
  const StateVec reference = rhs(thin, 0, toVector(s));
  double previous = 0;
  for (double h : {1e-4, 1e-5, 1e-6}) {
    CoinModel m = thin;
    m.rim = {.thickness = h, .edgeRadius = h / 2};
    const double difference =
        (rhs(m, 0, toVector(s)) - reference).cwiseAbs().maxCoeff() / reference.cwiseAbs().maxCoeff();
    EXPECT_TRUE(isBelow(difference, h / thin.a)) << "h = " << h;
    if (previous > 0) {
      EXPECT_TRUE(isNear(previous / difference, 10, 0.05)) << "h = " << h;
    }
    previous = difference;
  }
}

TEST(Rim, ReactionIsMassTimesAccelerationPlusWeight) {
  // R from eq. (4.1) against M dv/dt + M g e_y, dv/dt by central differences along the flow.
  for (const CoinModel& m : {toy(0.0065), toy(0.0016), toy(0.0)}) {
    const CoinState s{.theta = -0.5, .phi = 0.2, .psi = 0.9, .omega_X = 0.8, .omega_Y = 4.0, .omega_Z = -6.0};
    const double dt = 1e-5;
    const StateVec y = toVector(s);
    const StateVec f = rhs(m, 0, y);
    // One RK4 step each way, so the difference quotient's error is that of the quotient alone.
    const auto step = [&m](const StateVec& y0, double h) {
      const StateVec k1 = rhs(m, 0, y0), k2 = rhs(m, 0, y0 + 0.5 * h * k1), k3 = rhs(m, 0, y0 + 0.5 * h * k2),
                     k4 = rhs(m, 0, y0 + h * k3);
      return StateVec(y0 + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4));
    };
    const Eigen::Vector3d acceleration =
        (centreOfMassVelocity(m, toState(step(y, dt))) - centreOfMassVelocity(m, toState(step(y, -dt)))) / (2 * dt);
    const Eigen::Vector3d expected = m.M * acceleration + Eigen::Vector3d(0, m.M * m.g, 0);
    EXPECT_TRUE(isBelow((forward(m, s).reaction.R - expected).norm() / expected.norm(), 1e-8))
        << "rho " << m.rim.edgeRadius;
    EXPECT_TRUE(isNear(f[kTheta], s.omega_X, 0));
  }
}

// |E(t) - E(0)| / E(0) over a run, sampled every 10 ms.
template <Formulation F>
double energyDrift(const CoinModel& m, const CoinState& start, double duration, double* thetaMin = nullptr) {
  Eigen::Matrix<double, kMotionSize<F>, 1> y0;
  if constexpr (F == Formulation::EulerAngles)
    y0 = toVector(start);
  else
    y0 = toVector(fromEulerState(start));
  integrate::Trajectory run(CoinRhs<F>{m}, 0.0, y0, kTight);
  const double E0 = energy(m, start);
  double worst = 0, lowest = start.theta;
  for (int k = 1; k <= static_cast<int>(duration * 100); ++k) {
    const auto y = run.stateAt(0.01 * k);
    if (!y) break;
    Forward f;
    if constexpr (F == Formulation::EulerAngles)
      f = forward(m, toState(*y));
    else
      f = forward(m, toQuaternionState(*y));
    worst = std::max(worst, std::abs(f.energy - E0) / E0);
    lowest = std::min(lowest, f.theta);
  }
  if (thetaMin != nullptr) *thetaMin = lowest;
  return worst;
}

TEST(Rim, ConservesEnergyOverLongRunsAndThroughUprightWhenRounded) {
  // A fully rounded toy rolling fast with a wobble that carries it through upright again and again.
  const CoinState throughUpright{.theta = 2 * kDeg, .omega_X = -1.5, .omega_Z = 20.0};
  double thetaMin = 0;
  EXPECT_TRUE(isBelow(energyDrift<Formulation::EulerAngles>(toy(0.0065), throughUpright, 30, &thetaMin), 1e-10));
  EXPECT_LT(thetaMin, -0.5 * kDeg);  // it did pass upright
  EXPECT_TRUE(isBelow(energyDrift<Formulation::Quaternion>(toy(0.0065), throughUpright, 30), 1e-10));
  // The filleted toy tilted, precessing and wobbling, never upright.
  const CoinState wobbling{.theta = 25 * kDeg, .omega_X = 0.5, .omega_Y = 4.0, .omega_Z = 10.0};
  EXPECT_TRUE(isBelow(energyDrift<Formulation::EulerAngles>(toy(0.0016), wobbling, 30, &thetaMin), 1e-10));
  EXPECT_GT(thetaMin, 0);
  EXPECT_TRUE(isBelow(energyDrift<Formulation::Quaternion>(toy(0.0016), wobbling, 30), 1e-10));
}

TEST(Rim, ACornerOfAnySizeMeetsTheFloorAtUprightWithTwiceItsOffsetTimesTheTiltRate) {
  // docs/rim.md (7.0a)-(7.0b): rolling on one corner up to upright, the other corner's material point,
  // c_new = c_old - 2 sigma e e_Z, moves at -2 sigma e omega x e_Z: into the floor at 2 e |theta'| and
  // along it at 2 e |omega_Y|, for every e > 0. No held contact can continue from there (docs/rim.md §7).
  for (const double e : {4.9e-3, 1e-6, 1e-9}) {
    const CoinModel m = toy(0.0065 - e);
    ASSERT_FALSE(m.rim.fullyRounded());
    for (const double sigma : {1.0, -1.0}) {
      // Just short of upright on the side sigma, tilting towards the other.
      const CoinState s{.theta = sigma * 1e-12, .omega_X = -sigma * 1.5, .omega_Y = 0.7, .omega_Z = 20};
      for (const Forward& f : {forward(m, s), forward(m, fromEulerState(s))}) {
        const Eigen::Vector3d e_Z = f.axes.row(2).transpose();
        const double offset = m.rim.cornerOffset();
        const Eigen::Vector3d cNew = f.contactVector - 2 * sigma * offset * e_Z;
        const Eigen::Vector3d u = f.velocity + f.omega.cross(cNew);
        // u is v + omega x c_new, a difference of two ~0.75 m/s vectors: 1e-15 m/s of round-off besides.
        EXPECT_TRUE(isNear(u.y(), -2 * offset * 1.5, 1e-8 * offset + 1e-15)) << e << " " << sigma;  // into the floor
        EXPECT_TRUE(isNear(Eigen::Vector2d(u.x(), u.z()).norm(), 2 * offset * 0.7, 1e-8 * offset + 1e-15)) << e;
      }
    }
  }
}

TEST(Rim, TheTwoFormulationsFollowOneTrajectory) {
  const CoinModel m = toy(0.0016);
  const CoinState start{.theta = 35 * kDeg, .phi = 0.3, .omega_X = 0.7, .omega_Y = 3.0, .omega_Z = 6.0, .x = 0.01};
  integrate::Trajectory euler(CoinRhs<Formulation::EulerAngles>{m}, 0.0, toVector(start), kTight);
  integrate::Trajectory quaternion(CoinRhs<Formulation::Quaternion>{m}, 0.0, toVector(fromEulerState(start)), kTight);
  double worst = 0;
  for (int k = 1; k <= 300; ++k) {
    const Forward a = forward(m, toState(*euler.stateAt(0.01 * k)));
    const Forward b = forward(m, toQuaternionState(*quaternion.stateAt(0.01 * k)));
    worst = std::max({worst, std::abs(a.theta - b.theta), (a.omega - b.omega).norm() / naturalRate(m),
                      (a.centre - b.centre).norm() / m.a, (a.contactPoint - b.contactPoint).norm() / m.a});
  }
  EXPECT_TRUE(isBelow(worst, 1e-8));
}

TEST(Rim, ABallRollsInAStraightLineAtConstantVelocityWhateverItsSpin) {
  // a = rho, h = 2 rho: the rim is the whole body, a sphere of radius r with I = 2/5 M r^2. Its centre
  // is r above the contact and a rolling ball keeps v and omega (Routh): whatever the "tilt".
  const double r = 0.02, M = 0.1;
  CoinModel ball{.M = M,
                 .a = r,
                 .g = 9.81,
                 .I_X = 0.4 * M * r * r,
                 .I_Z = 0.4 * M * r * r,
                 .rim = {.thickness = 2 * r, .edgeRadius = r},
                 .effects = {}};
  // omega mostly along the axis, so the axis cones within 12 degrees of its start and the tilt stays
  // between 10 and 50 degrees, where both formulations' e_Y is defined.
  const CoinState start{.theta = 30 * kDeg, .phi = 0.4, .omega_X = 1.0, .omega_Y = 2.0, .omega_Z = 11.0};
  const Forward f0 = forward(ball, start);
  integrate::Trajectory quaternion(CoinRhs<Formulation::Quaternion>{ball}, 0.0, toVector(fromEulerState(start)),
                                   kTight);
  integrate::Trajectory euler(CoinRhs<Formulation::EulerAngles>{ball}, 0.0, toVector(start), kTight);
  double worst = 0, height = 0;
  for (int k = 1; k <= 300; ++k) {
    for (const Forward& f : {forward(ball, toQuaternionState(*quaternion.stateAt(0.01 * k))),
                             forward(ball, toState(*euler.stateAt(0.01 * k)))}) {
      worst = std::max({worst, (f.velocity - f0.velocity).norm() / f0.velocity.norm(),
                        (f.omega - f0.omega).norm() / f0.omega.norm()});
      height = std::max(height, std::abs(f.centre.y() - r));
    }
  }
  EXPECT_TRUE(isBelow(worst, 1e-10));
  EXPECT_TRUE(isBelow(height, 1e-15));
  EXPECT_TRUE(isNear(f0.velocity.y(), 0, 1e-15));
}

}  // namespace
}  // namespace coinroll::physics
