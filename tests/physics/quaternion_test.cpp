// The quaternion formulation against the seed's Euler-angle one (a second formulation is an
// independent truth: different state, different equations, same motion), and on its own near flat.

#include "physics/quaternion_dynamics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "integrate/trajectory.h"
#include "physics/dynamics.h"
#include "physics/observables.h"
#include "physics/steady.h"
#include "physics/validity.h"
#include "physics/coin_rhs.h"
#include "reference_solver.h"
#include "tolerance.h"

namespace coinroll::physics {
namespace {

using coinroll::testing::isBelow;
using coinroll::testing::isNear;
using integrate::Method;
using integrate::SolverConfig;

using reference::kDeg;
constexpr double kRhsTolerance = 1e-12;        // relative; both sides are a few dozen flops from the state
constexpr double kTrajectoryTolerance = 1e-9;  // angles rad, rates in sqrt(g/a), positions in a
using reference::kTight;
// The unstable straight roll amplifies integration error (its tilt grows e-fold every 0.09 s
// until it saturates); one more digit keeps 4 s of it within kTrajectoryTolerance, so what is
// compared is the formulations, not the integrator's error.
const SolverConfig kTighter{.method = Method::Dop853, .rtol = 1e-13, .atol = 1e-15};

using SeedRhs = CoinRhs<Formulation::EulerAngles>;
using QuaternionRhs = CoinRhs<Formulation::Quaternion>;

// The seed's variables of a quaternion state (phi and psi modulo 2 pi; observables do not care).
CoinState seed(const QuaternionState& q) { return toEulerState(q, CoinState{}); }
double tiltMagnitude(const QuaternionState& q) { return std::abs(seed(q).theta); }

Eigen::Quaterniond pure(const Eigen::Vector3d& v) { return {0, v.x(), v.y(), v.z()}; }

// d/dt of fromEulerState(s) along the seed's flow, by the chain rule on q_y(phi) q_x(theta) q_z(psi)
// (d q_n(alpha) / d alpha = q_n(alpha) (0, n) / 2) and on omegaBody = R_z(-psi) omega_XYZ.
QuaternionStateVec seedRateInQuaternionVariables(const CoinModel& m, const CoinState& s) {
  const StateVec dy = rhs(m, 0.0, toVector(s));
  const Eigen::Quaterniond qy(Eigen::AngleAxisd(s.phi, Eigen::Vector3d::UnitY()));
  const Eigen::Quaterniond qx(Eigen::AngleAxisd(s.theta, Eigen::Vector3d::UnitX()));
  const Eigen::Quaterniond qz(Eigen::AngleAxisd(s.psi, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector4d qDot = 0.5 * (dy[kPhi] * (qy * pure(Eigen::Vector3d::UnitY()) * qx * qz).coeffs() +
                                      dy[kTheta] * (qy * qx * pure(Eigen::Vector3d::UnitX()) * qz).coeffs() +
                                      dy[kPsi] * (qy * qx * qz * pure(Eigen::Vector3d::UnitZ())).coeffs());
  const double c = std::cos(s.psi), sn = std::sin(s.psi);
  const Eigen::Vector3d omegaBody = fromEulerState(s).omegaBody;
  QuaternionStateVec rate;
  rate << qDot.w(), qDot.x(), qDot.y(), qDot.z(), c * dy[kOmega_X] + sn * dy[kOmega_Y] + dy[kPsi] * omegaBody.y(),
      -sn * dy[kOmega_X] + c * dy[kOmega_Y] - dy[kPsi] * omegaBody.x(), dy[kOmega_Z], dy[kX], dy[kZ];
  return rate;
}

TEST(QuaternionRhs, EqualsTheSeedRhsAtRandomStatesAwayFromFlat) {
  std::mt19937 random(20261124);
  std::uniform_real_distribution<double> tilt(-80 * kDeg, 80 * kDeg), angle(-7, 7), rate(-20, 20), position(-1, 1);
  int checked = 0;
  for (const CoinModel& m :
       {diskModel(0.4, 0.0375, 9.81), ringModel(0.4, 0.0375, 0.03, 9.81),
        CoinModel{.M = 2, .a = 0.1, .g = 3, .I_X = 0.004, .I_Z = 0.0065, .rim = {}, .effects = {}}}) {
    for (int i = 0; i < 1000; ++i) {
      const CoinState s{tilt(random), angle(random), angle(random),    rate(random),
                        rate(random), rate(random),  position(random), position(random)};
      const QuaternionStateVec expected = seedRateInQuaternionVariables(m, s);
      const QuaternionStateVec actual = quaternionRhs(m, 0.0, toVector(fromEulerState(s)));
      EXPECT_TRUE(isBelow((actual - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff(), kRhsTolerance))
          << "theta " << s.theta;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 3000);
}

// Coins with a rim (docs/rim.md §2-3): the Euler-angle form (2.7) in XYZ and the material-frame form
// (3.3) are two derivations of one motion; on both sides of upright for the cornered rims.
TEST(QuaternionRhs, EqualsTheSeedRhsForCoinsWithARim) {
  std::mt19937 random(20261201);
  std::uniform_real_distribution<double> tilt(-80 * kDeg, 80 * kDeg), angle(-7, 7), rate(-20, 20), position(-1, 1);
  const auto thick = [](double h, double rho) {
    CoinModel m = diskModel(0.4, 0.0375, 9.81);
    m.I_X += 0.4 * h * h / 12;
    m.rim = {.thickness = h, .edgeRadius = rho};
    return m;
  };
  for (const CoinModel& m : {thick(0.013, 0.0065), thick(0.013, 0.0016), thick(0.013, 0.0), thick(0.002, 0.001)}) {
    for (int i = 0; i < 500; ++i) {
      const CoinState s{tilt(random), angle(random), angle(random),    rate(random),
                        rate(random), rate(random),  position(random), position(random)};
      const QuaternionStateVec expected = seedRateInQuaternionVariables(m, s);
      const QuaternionStateVec actual = quaternionRhs(m, 0.0, toVector(fromEulerState(s)));
      EXPECT_TRUE(isBelow((actual - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff(), kRhsTolerance))
          << "theta " << s.theta << ", rho " << m.rim.edgeRadius;
      const QuaternionState q = fromEulerState(s);
      const Forward euler = forward(m, s), quaternion = forward(m, q);
      EXPECT_TRUE(isBelow((quaternion.reaction.R - euler.reaction.R).norm() / euler.reaction.R.norm(), kRhsTolerance));
      EXPECT_TRUE(isNear(quaternion.energy / euler.energy, 1, kRhsTolerance));
      EXPECT_TRUE(isBelow((quaternion.contactPoint - euler.contactPoint).norm(), 1e-15));
      EXPECT_TRUE(isBelow(std::abs(quaternion.contactPoint.y()), 1e-15));
      EXPECT_TRUE(isNear(quaternion.precessionRate, euler.precessionRate,
                         kRhsTolerance * std::abs(euler.precessionRate) + 1e-12));
      EXPECT_TRUE(isNear(quaternion.spinRate, euler.spinRate, kRhsTolerance * std::abs(euler.spinRate) + 1e-12));
    }
  }
}

TEST(QuaternionConversion, RoundTripsAndUnwrapsTheAngles) {
  const CoinState s{
      .theta = -0.7, .phi = 9.0, .psi = -13.0, .omega_X = 1.5, .omega_Y = -2.5, .omega_Z = 8.0, .x = 0.3, .z = -0.4};
  const CoinState back = toEulerState(fromEulerState(s), CoinState{.phi = 8.0, .psi = -12.0});
  const StateVec difference = toVector(back) - toVector(s);
  EXPECT_TRUE(isBelow(difference.cwiseAbs().maxCoeff(), 1e-13));
}

TEST(QuaternionDynamics, ReactionMatchesTheSeedFormulas) {
  // Eq. (5.2) in material components against seed section 4 in XYZ: two derivations of one force.
  const CoinModel m = ringModel(0.4, 0.0375, 0.02, 9.81);
  const CoinState s{
      .theta = 0.6, .phi = -1.1, .psi = 2.3, .omega_X = 0.7, .omega_Y = -1.9, .omega_Z = 5.2, .x = 0.1, .z = -0.2};
  const QuaternionState q = fromEulerState(s);
  EXPECT_TRUE(isBelow((forward(m, q).reaction.R - forward(m, s).reaction.R).norm(), 1e-14));
  EXPECT_TRUE(isNear(tiltMagnitude(q), 0.6, 1e-15));
}

// Largest difference between the two formulations' trajectories, sampled every 0.01 s: angles in
// rad, rates in units of sqrt(g/a), positions in units of a.
double formulationDisagreement(const CoinModel& m, const CoinState& start, double duration) {
  integrate::Trajectory euler(SeedRhs{m}, 0.0, toVector(start), kTighter);
  integrate::Trajectory quaternion(QuaternionRhs{m}, 0.0, toVector(fromEulerState(start)), kTighter);
  const Eigen::Matrix<double, kStateSize, 1> scale =
      (StateVec() << 1, 1, 1, naturalRate(m), naturalRate(m), naturalRate(m), m.a, m.a).finished();
  CoinState continuation = start;
  double worst = 0;
  for (int k = 1; k <= static_cast<int>(std::round(duration / 0.01)); ++k) {
    const double t = 0.01 * k;
    const StateVec fromEuler = *euler.stateAt(t);
    continuation = toEulerState(toQuaternionState(*quaternion.stateAt(t)), continuation);
    worst = std::max(worst, (toVector(continuation) - fromEuler).cwiseQuotient(scale).cwiseAbs().maxCoeff());
  }
  return worst;
}

TEST(QuaternionTrajectory, AgreesWithTheEulerAngleFormulationOnTheExamples) {
  const CoinModel disk = diskModel(0.4, 0.0375, 9.81), ring = ringModel(0.4, 0.0375, 0.03, 9.81);
  // examples/: steady circle, perturbed circle, straight roll (stable and unstable), ring;
  // plus a general wobbling state with every rate nonzero.
  EXPECT_TRUE(isBelow(formulationDisagreement(disk, steadyCircle(disk, 20 * kDeg, 10, +1), 4), kTrajectoryTolerance));
  EXPECT_TRUE(isBelow(formulationDisagreement(disk, {.theta = 23 * kDeg, .omega_Y = 5.76333705059, .omega_Z = 10}, 4),
                      kTrajectoryTolerance));
  EXPECT_TRUE(isBelow(formulationDisagreement(disk, {.theta = 3 * kDeg, .omega_Z = 14}, 4), kTrajectoryTolerance));
  EXPECT_TRUE(isBelow(formulationDisagreement(disk, {.theta = 3 * kDeg, .omega_Z = 6}, 4), kTrajectoryTolerance));
  EXPECT_TRUE(isBelow(formulationDisagreement(ring, steadyCircle(ring, 15 * kDeg, 12, +1), 4), kTrajectoryTolerance));
  EXPECT_TRUE(isBelow(
      formulationDisagreement(
          ring, {.theta = 0.4, .phi = 1, .psi = -2, .omega_X = 0.7, .omega_Y = -1.9, .omega_Z = 9, .x = 0.1, .z = -0.2},
          4),
      kTrajectoryTolerance));
}

TEST(QuaternionTrajectory, ConservesEnergyAndHoldsTheQuaternionNorm) {
  for (const CoinModel& m : {diskModel(0.4, 0.0375, 9.81), ringModel(0.4, 0.0375, 0.02, 9.81)}) {
    const CoinState start{.theta = 20 * kDeg, .omega_X = 0.5, .omega_Y = 3.0, .omega_Z = 14.0};
    integrate::Trajectory trajectory(QuaternionRhs{m}, 0.0, toVector(fromEulerState(start)), kTight);
    const double E0 = energy(m, start);
    const double period = 2 * std::numbers::pi * naturalTime(m);
    double worstEnergy = 0, firstQuarterNorm = 0, lastQuarterNorm = 0;
    for (int k = 1; k <= 1000; ++k) {
      const QuaternionStateVec y = *trajectory.stateAt(0.1 * k * period);
      worstEnergy = std::max(worstEnergy, std::abs(energy(m, seed(toQuaternionState(y))) - E0) / E0);
      double& quarter = k <= 250 ? firstQuarterNorm : lastQuarterNorm;
      if (k <= 250 || k > 750) quarter = std::max(quarter, std::abs(y.head<4>().norm() - 1));
    }
    EXPECT_TRUE(isBelow(worstEnergy, 1e-10));
    EXPECT_TRUE(isBelow(std::max(firstQuarterNorm, lastQuarterNorm), 1e-10));
    // The restoring term of eq. (4.1) holds the norm error at the local error level instead of
    // letting it random-walk: the last 25 periods are no worse than the first 25.
    EXPECT_TRUE(isBelow(lastQuarterNorm, 2 * firstQuarterNorm));
  }
}

// A coin let go at 60 degrees with a slow spin (1 % of the critical spin) falls nearly flat:
// its tilt peaks near 89.93 degrees after 0.075 s, then the spin's gyroscopic torque rights it;
// seven such falls in 1 s, all between 89.9 and 89.95 degrees. N stays above 0.13 M g
// throughout, so the ideal model holds.
CoinState fallingNearlyFlat() { return {.theta = 60 * kDeg, .omega_Z = 0.1}; }

TEST(NearFlat, EulerAnglesStopAtTheCoinFlatEventWhileTheQuaternionContinues) {
  const CoinModel m = diskModel(0.4, 0.0375, 9.81);
  const CoinState start = fallingNearlyFlat();
  std::vector<integrate::Event<kStateSize>> eulerFlat{
      {.name = "coin-flat",
       .g = [](double, const StateVec& y) { return flatMargin(toState(y).theta, kFlatTilt); },
       .direction = -1}};
  std::vector<integrate::Event<kQuaternionStateSize>> quaternionFlat{
      {.name = "coin-flat",
       .g =
           [](double, const QuaternionStateVec& y) {
             return flatMargin(seed(toQuaternionState(y)).theta, kQuaternionFlatTilt);
           },
       .direction = -1}};
  integrate::Trajectory euler(SeedRhs{m}, 0.0, toVector(start), kTight, eulerFlat);
  integrate::Trajectory quaternion(QuaternionRhs{m}, 0.0, toVector(fromEulerState(start)), kTight, quaternionFlat);

  EXPECT_FALSE(euler.stateAt(1.0).has_value());
  ASSERT_TRUE(euler.stoppedBy().has_value());
  EXPECT_EQ(euler.stoppedBy()->name, "coin-flat");
  EXPECT_TRUE(isNear(euler.stoppedBy()->y[kTheta], kFlatTilt, 1e-9));

  const double E0 = energy(m, start);
  double largestTilt = 0, worstEnergy = 0;
  for (double t = 1e-4; t <= 1.0; t += 1e-4) {
    const std::optional<QuaternionStateVec> y = quaternion.stateAt(t);
    ASSERT_TRUE(y.has_value()) << "stopped at t = " << t;
    const QuaternionState s = toQuaternionState(*y);
    largestTilt = std::max(largestTilt, tiltMagnitude(s));
    worstEnergy = std::max(worstEnergy, std::abs(energy(m, seed(s)) - E0) / E0);
  }
  EXPECT_GT(largestTilt, 89.9 * kDeg);
  EXPECT_LT(largestTilt, kQuaternionFlatTilt);
  EXPECT_TRUE(isBelow(worstEnergy, 1e-8));
}

TEST(NearFlat, PlanarFallRunsToTheQuaternionFlatStopWithTheEnergyIntegralsRate) {
  // Let go at 60 degrees from rest, the coin tips over about e_X without spinning: omega_Y and
  // omega_Z stay 0 and energy gives the tipping rate in closed form,
  // (I_X + M a^2) omega_X^2 / 2 = M g a (cos theta0 - cos theta).
  const CoinModel m = diskModel(0.4, 0.0375, 9.81);
  const CoinState start{.theta = 60 * kDeg};
  std::vector<integrate::Event<kQuaternionStateSize>> flat{{.name = "coin-flat",
                                                            .g =
                                                                [](double, const QuaternionStateVec& y) {
                                                                  return flatMargin(seed(toQuaternionState(y)).theta,
                                                                                    kQuaternionFlatTilt);
                                                                },
                                                            .direction = -1}};
  integrate::Trajectory quaternion(QuaternionRhs{m}, 0.0, toVector(fromEulerState(start)), kTight, flat);
  EXPECT_FALSE(quaternion.stateAt(1.0).has_value());
  ASSERT_TRUE(quaternion.stoppedBy().has_value());
  const QuaternionState s = toQuaternionState(quaternion.stoppedBy()->y);
  EXPECT_TRUE(isNear(tiltMagnitude(s), kQuaternionFlatTilt, 1e-12));
  const double Ma2 = m.M * m.a * m.a;
  const double expectedRate =
      std::sqrt(2 * m.M * m.g * m.a * (std::cos(start.theta) - std::cos(kQuaternionFlatTilt)) / (m.I_X + Ma2));
  EXPECT_TRUE(isNear(s.omegaBody.norm(), expectedRate, 1e-9 * naturalRate(m)));
  EXPECT_TRUE(isNear(energy(m, seed(s)), energy(m, start), 1e-12 * energy(m, start)));
  EXPECT_GT(forward(m, s).reaction.N, 0);  // still on the floor: the stop is the geometry's, not lift-off
}

// The same comparison in coordinate-free terms, every 1 ms. Near flat phi and psi are
// ill-conditioned one by one (an attitude error e moves them by e / cos(theta)), so there the
// Euler-variable comparison would measure the chart, not the motion.
struct Disagreement {
  double attitude = 0;     // rad, angle of the rotation between the two attitudes
  double omega = 0;        // |material-frame omega difference| / sqrt(g/a)
  double position = 0;     // |centre-of-mass difference on the floor| / a
  double largestTilt = 0;  // rad, over the run
};

Disagreement coordinateFreeDisagreement(const CoinModel& m, const CoinState& start, double duration) {
  integrate::Trajectory euler(SeedRhs{m}, 0.0, toVector(start), kTighter);
  integrate::Trajectory quaternion(QuaternionRhs{m}, 0.0, toVector(fromEulerState(start)), kTighter);
  Disagreement worst;
  for (int k = 1; k <= static_cast<int>(std::round(duration / 0.001)); ++k) {
    const QuaternionState fromEuler = fromEulerState(toState(*euler.stateAt(0.001 * k)));
    const QuaternionState s = toQuaternionState(*quaternion.stateAt(0.001 * k));
    worst.attitude = std::max(worst.attitude, s.q.angularDistance(fromEuler.q));
    worst.omega = std::max(worst.omega, (s.omegaBody - fromEuler.omegaBody).norm() / naturalRate(m));
    worst.position = std::max(worst.position, std::hypot(s.x - fromEuler.x, s.z - fromEuler.z) / m.a);
    worst.largestTilt = std::max(worst.largestTilt, tiltMagnitude(s));
  }
  return worst;
}

TEST(NearFlat, WithoutTheirStopTheEulerAnglesAgreeThereToo) {
  // The honest control: the seed's equations, integrated past their 89-degree stop, follow the
  // same motion through seven passes to 89.95 degrees: their 1 / cos(theta) multiplies omega_Y,
  // which vanishes like cos(theta) on every finite-energy approach to flat. The quaternion
  // formulation instead finds the contact direction from q, which amplifies q's integration error
  // by 1 / cos(theta) in omega-dot (docs/quaternion_formulation.md §6): omega agrees to the
  // attitude tolerance times that condition number, and no better.
  const Disagreement d = coordinateFreeDisagreement(diskModel(0.4, 0.0375, 9.81), fallingNearlyFlat(), 1.0);
  EXPECT_GT(d.largestTilt, 89.9 * kDeg);
  EXPECT_TRUE(isBelow(d.attitude, kTrajectoryTolerance));
  EXPECT_TRUE(isBelow(d.position, kTrajectoryTolerance));
  EXPECT_TRUE(isBelow(d.omega, kTrajectoryTolerance / std::cos(d.largestTilt)));
}

}  // namespace
}  // namespace coinroll::physics
