// The singular-time fit against an exact power law.

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "pipeline/singular_time.h"
#include "tolerance.h"

namespace {

using namespace coinroll;
using coinroll::testing::isNear;

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
