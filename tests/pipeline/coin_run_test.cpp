// The run driver and its bookkeeping against truths computed another way: the Euler-angle
// formulation for the quaternion run's unwrapped angles, exact rational arithmetic for the CSV's
// row count, and an exact power law for the singular-time fit.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string_view>
#include <vector>

#include "pipeline/coin_run.h"
#include "pipeline/simulation.h"
#include "pipeline/singular_time.h"
#include "pipeline/trajectory_csv.h"
#include "scene/scene_loader.h"
#include "tolerance.h"

namespace {

using namespace coinroll;
using coinroll::testing::isBelow;
using coinroll::testing::isNear;

pipeline::Simulation wobblingToy(std::string_view formulation) {
  nlohmann::json doc = {
      {"coin", {{"radius", 0.0375}, {"mass", 0.4}}},
      {"initial", {{"theta", 20}, {"omega_X", 0.5}, {"omega_Y", 3.0}, {"omega_Z", 14.0}}},
      {"duration", 4.0},
      {"solver", {{"formulation", formulation}, {"rtol", 1e-12}, {"atol", 1e-14}}},
  };
  const std::vector<std::string_view> methods = {"dop853"};
  return pipeline::buildSimulation(scene::parseScene(doc, "test", {.solverMethods = methods}));
}

TEST(CoinRun, QuaternionRunUnwrapsPhiAndPsiLikeTheEulerAnglesBetweenSparseQueries) {
  // The quaternion carries phi and psi only modulo 2 pi; the run must keep them continuous however
  // far apart the queries are. psi turns about 15 rad/s here, so a query every 0.5 s skips more
  // than a turn; the Euler-angle formulation integrates phi and psi directly and is the truth.
  pipeline::CoinRun euler(wobblingToy("euler-angles")), quaternion(wobblingToy("quaternion"));
  for (int k = 1; k <= 8; ++k) {
    const double t = 0.5 * k;
    const physics::CoinState e = *euler.stateAt(t), q = *quaternion.stateAt(t);
    EXPECT_TRUE(isNear(q.phi, e.phi, 1e-6)) << "t = " << t;
    EXPECT_TRUE(isNear(q.psi, e.psi, 1e-6)) << "t = " << t;
    EXPECT_TRUE(isNear(q.theta, e.theta, 1e-6)) << "t = " << t;
  }
}

TEST(SampleCount, MatchesExactRationalArithmeticWhereTheQuotientRoundsBelowAWholeNumber) {
  // Rows k = 0 .. floor(d / S) for every duration 0.01 .. 30 s (step 0.01 s) and common sample
  // steps, all decimals: floor(dNum SDen / (dDen SNum)) + 1 in integers. In many of these the
  // double d / S lands just below its whole number (0.29 / 0.01 = 28.999999999999996).
  struct Ratio {
    long num, den;
  };
  int roundedBelow = 0, failures = 0;
  for (long n = 1; n <= 3000; ++n) {
    for (const Ratio S : {Ratio{1, 100}, Ratio{1, 1000}, Ratio{1, 10}, Ratio{2, 100}, Ratio{5, 100}, Ratio{25, 100},
                          Ratio{4, 1000}}) {
      const double d = static_cast<double>(n) / 100, dt = static_cast<double>(S.num) / static_cast<double>(S.den);
      const long expected = n * S.den / (100 * S.num) + 1;
      const long actual = pipeline::sampleCount(d, dt);
      if (actual != expected && ++failures <= 10) {
        ADD_FAILURE() << "sampleCount(" << n << " / 100 s, " << S.num << " / " << S.den << " s) = " << actual
                      << ", exactly " << expected;
      }
      if (n * S.den % (100 * S.num) == 0 && d / dt < static_cast<double>(expected - 1)) ++roundedBelow;
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_GT(roundedBelow, 100);
}

TEST(SingularTimeFit, RecoversTheSingularTimeAndExponentOfAnExactPowerLaw) {
  // E = c (t0 - t)^gamma dissipated at P = -dE/dt = c gamma (t0 - t)^(gamma - 1): u = E / P =
  // (t0 - t) / gamma is exactly linear, so the fit must return t0 and gamma to round-off, over
  // the samples within one decade of t0 - t of the last.
  const double t0 = 2.7, c = 0.02;
  for (const double gamma : {1.0 / 3, 0.5, 1.0, 1.5}) {
    pipeline::SingularTimeFit fit;
    std::vector<double> remaining;  // t0 - t of each sample
    for (int i = 0; i < 40; ++i) remaining.push_back(2.0 * std::pow(1e-3 / 2.0, i / 39.0));
    for (const double r : remaining) fit.add(t0 - r, c * std::pow(r, gamma), c * gamma * std::pow(r, gamma - 1));
    const std::optional<pipeline::SingularTimeEstimate> estimate = fit.estimate();
    ASSERT_TRUE(estimate.has_value()) << "gamma " << gamma;
    EXPECT_TRUE(isNear(estimate->t0, t0, 1e-12)) << "gamma " << gamma;
    EXPECT_TRUE(isNear(estimate->gamma, gamma, 1e-9)) << "gamma " << gamma;
    int inWindow = 0;
    for (const double r : remaining) inWindow += r <= 10 * remaining.back() * (1 + 1e-12);
    EXPECT_EQ(estimate->samples, inWindow) << "gamma " << gamma;
  }
}

TEST(SingularTimeFit, EnergyOverPowerGrowingTowardsTheEndGivesNoEstimate) {
  // u = E / P must shrink towards a singularity; growing, there is none ahead.
  pipeline::SingularTimeFit fit;
  for (int i = 0; i < 20; ++i) fit.add(0.1 * i, 1.0 + 0.1 * i, 1.0);
  EXPECT_FALSE(fit.estimate().has_value());
}

}  // namespace
