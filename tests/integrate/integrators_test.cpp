#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "integrate/dop853.h"
#include "integrate/event_location.h"
#include "integrate/gauss_legendre.h"
#include "integrate/steppers.h"
#include "integrate/pace.h"
#include "integrate/trajectory.h"
#include "tolerance.h"

namespace coinroll::integrate {
namespace {

using coinroll::testing::isBelow;
using coinroll::testing::isNear;
using V1 = Vec<1>;
using V2 = Vec<2>;

// y' = -2 t y^2, y(0) = 1: exact y = 1 / (1 + t^2). Nonlinear and non-autonomous.
struct Riccati {
  V1 operator()(double t, const V1& y) const { return V1(-2 * t * y[0] * y[0]); }
  static double exact(double t) { return 1 / (1 + t * t); }
};

// Fixed-step global error at t = 2 with n steps of the named method.
double globalError(Method method, int n) {
  Riccati f;
  const double h = 2.0 / n;
  V1 y(1.0);
  GaussLegendre4<1> gauss4;
  long rhsEvaluations = 0;
  for (int i = 0; i < n; ++i) {
    const double t = i * h;
    const V1 f0 = f(t, y);
    switch (method) {
      case Method::Euler: y = eulerStep<1>(f, t, y, f0, h); break;
      case Method::Rk4: y = rk4Step<1>(f, t, y, f0, h); break;
      case Method::Dopri5: y = dopri5Step<1>(f, t, y, f0, h).y1; break;
      case Method::Dop853: y = dop853Step<1>(f, t, y, f0, h).y1; break;
      case Method::Gauss4: y = gauss4.step(f, t, y, f0, h, rhsEvaluations); break;
    }
  }
  return std::abs(y[0] - Riccati::exact(2.0));
}

double observedOrder(Method method, int n) { return std::log2(globalError(method, n) / globalError(method, 2 * n)); }

constexpr double kOrderTolerance = 0.3;  // asymptotic slopes on a smooth problem

TEST(FixedStep, EulerConvergesAtOrderOne) {
  EXPECT_TRUE(isNear(observedOrder(Method::Euler, 400), 1, kOrderTolerance));
}
TEST(FixedStep, Rk4ConvergesAtOrderFour) { EXPECT_TRUE(isNear(observedOrder(Method::Rk4, 80), 4, kOrderTolerance)); }
TEST(FixedStep, Gauss4ConvergesAtOrderFour) {
  EXPECT_TRUE(isNear(observedOrder(Method::Gauss4, 40), 4, kOrderTolerance));
}
TEST(FixedStep, Dopri5ConvergesAtOrderFive) {
  EXPECT_TRUE(isNear(observedOrder(Method::Dopri5, 160), 5, kOrderTolerance));
}

TEST(FixedStep, Dop853ConvergesAtOrderEight) {
  // The Riccati problem is solved to round-off by DOP853 within 20 steps; five periods of an
  // oscillator keep the error measurable.
  auto oscillator = [](double, const V2& y) { return V2(y[1], -y[0]); };
  auto errorWith = [&](int n) {
    const double T = 10 * std::numbers::pi, h = T / n;
    V2 y(0, 1);
    for (int i = 0; i < n; ++i) y = dop853Step<2>(oscillator, i * h, y, oscillator(i * h, y), h).y1;
    return std::abs(y[0] - std::sin(T));
  };
  EXPECT_TRUE(isNear(std::log2(errorWith(50) / errorWith(100)), 8, kOrderTolerance));
}

TEST(ButcherTables, Dop853WeightsSatisfyTheFirstOrderConditions) {
  using namespace dop853;
  EXPECT_TRUE(isNear(b1 + b6 + b7 + b8 + b9 + b10 + b11 + b12, 1.0, 1e-15));
  EXPECT_TRUE(isNear(b6 * c6 + b7 * c7 + b8 * c8 + b9 * c9 + b10 * c10 + b11 * c11 + b12, 0.5, 1e-15));
  EXPECT_TRUE(
      isNear(b6 * c6 * c6 + b7 * c7 * c7 + b8 * c8 * c8 + b9 * c9 * c9 + b10 * c10 * c10 + b11 * c11 * c11 + b12,
             1.0 / 3, 1e-15));
  // Row sums equal the nodes.
  EXPECT_TRUE(isNear(a121 + a124 + a125 + a126 + a127 + a128 + a129 + a1210 + a1211, 1.0, 1e-14));
  EXPECT_TRUE(isNear(a91 + a94 + a95 + a96 + a97 + a98, c9, 1e-14));
}

TEST(ButcherTables, Dopri5WeightsSatisfyTheFirstOrderConditions) {
  using namespace dopri5;
  EXPECT_TRUE(isNear(b1 + b3 + b4 + b5 + b6, 1.0, 1e-15));
  EXPECT_TRUE(isNear(b3 * c3 + b4 * c4 + b5 * c5 + b6, 0.5, 1e-15));
  EXPECT_TRUE(isNear(e1 + e3 + e4 + e5 + e6 + e7, 0.0, 1e-16));  // both weight sets sum to 1
}

// Interpolation error at the middle of one step started on the exact solution.
double midpointError(Method method, double h) {
  Riccati f;
  const double t0 = 0.3;
  const V1 y0(Riccati::exact(t0));
  const V1 k1 = f(t0, y0);
  DenseInterval<1> d;
  if (method == Method::Dopri5)
    d = dopri5Interval<1>(t0, h, y0, k1, dopri5Step<1>(f, t0, y0, k1, h));
  else
    d = dop853Interval<1>(f, t0, h, y0, k1, dop853Step<1>(f, t0, y0, k1, h));
  return std::abs(d.at(t0 + 0.5 * h)[0] - Riccati::exact(t0 + 0.5 * h));
}

TEST(DenseOutput, Dopri5InterpolantHasOrderFour) {
  // Local interpolation error O(h^5).
  EXPECT_TRUE(isNear(std::log2(midpointError(Method::Dopri5, 0.05) / midpointError(Method::Dopri5, 0.025)), 5,
                     kOrderTolerance));
}

TEST(DenseOutput, Dop853InterpolantHasOrderSeven) {
  // Local interpolation error O(h^8).
  EXPECT_TRUE(isNear(std::log2(midpointError(Method::Dop853, 0.1) / midpointError(Method::Dop853, 0.05)), 8, 0.5));
}

TEST(DenseOutput, AQueryOutsideItsStepThrowsInEveryBuild) {
  // Beyond round-off at the ends the interpolant would extrapolate silently; the check is not an
  // assert, so it holds under NDEBUG too.
  const V1 y0(1.0), y1(0.5), f0(-1.0), f1(-0.25);
  const DenseInterval<1> d = hermiteInterval<1>(2.0, 0.5, y0, f0, y1, f1);
  EXPECT_EQ(d.at(2.0)[0], 1.0);
  EXPECT_NO_THROW(d.at(2.5 + 1e-13));  // round-off past the end is allowed
  EXPECT_THROW(d.at(2.5 + 1e-9), std::logic_error);
  EXPECT_THROW(d.at(2.0 - 1e-9), std::logic_error);
}

struct Oscillator {
  V2 operator()(double, const V2& y) const { return V2(y[1], -y[0]); }
};

TEST(Trajectory, SamplesFromDenseOutputMatchTheExactSolution) {
  for (Method method : {Method::Dopri5, Method::Dop853}) {
    Trajectory trajectory(Oscillator{}, 0.0, V2(0, 1), SolverConfig{.method = method, .rtol = 1e-12, .atol = 1e-14});
    double worst = 0;
    for (int k = 0; k <= 10'000; ++k) {
      const double t = 1e-3 * k;
      worst = std::max(worst, std::abs((*trajectory.stateAt(t))[0] - std::sin(t)));
    }
    EXPECT_TRUE(isBelow(worst, 1e-9)) << nameOf(method);
    // Samples must not force steps: far fewer steps than samples.
    EXPECT_LT(trajectory.stats().acceptedSteps, 2000) << nameOf(method);
  }
}

TEST(Trajectory, GlobalErrorFollowsTheTolerance) {
  for (Method method : {Method::Dopri5, Method::Dop853}) {
    for (double rtol : {1e-6, 1e-9, 1e-12}) {
      Trajectory trajectory(Oscillator{}, 0.0, V2(0, 1), SolverConfig{.method = method, .rtol = rtol, .atol = rtol});
      const double t = 20 * std::numbers::pi;  // ten periods
      const double error = std::abs((*trajectory.stateAt(t))[0] - std::sin(t));
      EXPECT_TRUE(isBelow(error, 200 * rtol)) << nameOf(method) << " rtol " << rtol;
    }
  }
}

TEST(Trajectory, Dop853PaysForDenseOutputOnlyInStepsThatAreQueried) {
  // Evaluations: the first slope, one for the starting step's estimate, 12 per attempted step
  // and 3 for each interpolant actually built.
  auto run = [](int queries) {
    Trajectory trajectory(Oscillator{}, 0.0, V2(0, 1),
                          SolverConfig{.method = Method::Dop853, .rtol = 1e-10, .atol = 1e-10});
    for (int k = 1; k <= queries; ++k) trajectory.stateAt(10.0 * k / queries);
    return trajectory.stats();
  };
  const Stats sparse = run(1), dense = run(10'000);
  EXPECT_EQ(sparse.rhsEvaluations, 2 + 12 * (sparse.acceptedSteps + sparse.rejectedSteps) + 3);
  EXPECT_EQ(dense.acceptedSteps, sparse.acceptedSteps);  // queries never change the steps
  EXPECT_EQ(dense.rhsEvaluations, 2 + 15 * dense.acceptedSteps + 12 * dense.rejectedSteps);
}

TEST(Trajectory, FixedStepMethodsLandOnTheirGrid) {
  Trajectory trajectory(Oscillator{}, 0.0, V2(0, 1), SolverConfig{.method = Method::Rk4, .dt = 0.01});
  trajectory.stateAt(1.0);
  EXPECT_EQ(trajectory.stats().acceptedSteps, 100);
  EXPECT_EQ(trajectory.stats().rhsEvaluations, 1 + 4 * 100);
}

// RK4 at dt = 0.01 takes exactly 100 steps per second, so the pace is known: an end at 1e4 s
// needs 1e6 steps. With maxSteps 5e5 the run must fail at the first check past a hundredth of
// maxSteps at its steady pace (2^13 = 8192 steps, t = 81.92 s), not after 5e5 steps; with
// maxSteps 2e6 it runs on.
TEST(Trajectory, AnEndOutOfReachAtThePaceSoFarFailsEarly) {
  SolverConfig config{.method = Method::Rk4, .dt = 0.01, .maxSteps = 500'000, .endTime = 1e4};
  Trajectory hopeless(Oscillator{}, 0.0, V2(0, 1), config);
  EXPECT_THROW(
      try { hopeless.stateAt(1e4); } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("would need about 1e+06 steps to reach t = 10000 s"), std::string::npos)
            << e.what();
        throw;
      },
      std::runtime_error);
  EXPECT_EQ(hopeless.stats().acceptedSteps, 8'192);

  config.maxSteps = 2'000'000;
  Trajectory reachable(Oscillator{}, 0.0, V2(0, 1), config);
  ASSERT_TRUE(reachable.stateAt(1e4));
  EXPECT_EQ(reachable.stats().acceptedSteps, 1'000'000);
}

// An end so far that a hundredth of the way is itself out of reach (1e8 s: 1e10 steps) is refused
// at a hundredth of maxSteps (2^13 steps, 82 s of 1e8), not run to maxSteps (docs/bad_inputs.md
// "absurd sizes": a hopeless pace is refused within seconds).
TEST(Trajectory, AFarEndAtASteadyPaceFailsWithinAHundredthOfTheSteps) {
  Trajectory hopeless(Oscillator{}, 0.0, V2(0, 1),
                      SolverConfig{.method = Method::Rk4, .dt = 0.01, .maxSteps = 500'000, .endTime = 1e8});
  try {
    hopeless.stateAt(1e8);
    ADD_FAILURE() << "ran to its end";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("would need about 1e+10 steps to reach t = 100000000 s"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(hopeless.stats().acceptedSteps, 8'192);
}

// A pace that keeps rising is how a coin approaches falling flat, and its event ends the run long
// before a far end: no early refusal. Here an oscillator whose frequency 1 / (2 - t)^2 grows
// without bound, stopped by an event at t = 1.9999 after about 1600 periods and thousands of
// steps; the pace at the end, projected over the 1e6 s left, would be 10^10 steps.
TEST(Trajectory, ARisingPaceIsNotProjectedOverAFarEnd) {
  const auto chirp = [](double t, const V2& y) { return V2(y(1), -std::pow(2 - t, -4) * y(0)); };
  std::vector<Event<2>> events = {{.name = "near", .g = [](double t, const V2&) { return t - 1.9999; }}};
  Trajectory run(chirp, 0.0, V2(1, 0), SolverConfig{.maxSteps = 200'000, .endTime = 1e6}, events);
  EXPECT_FALSE(run.stateAt(1e6));
  ASSERT_TRUE(run.stoppedBy());
  EXPECT_NEAR(run.stoppedBy()->t, 1.9999, 1e-9);
  EXPECT_GT(run.stats().acceptedSteps, 4 * 2'000) << "past a hundredth of maxSteps at two checks";
}

// A run of many short integrations (a toss rolling on its edge for 1e6 s makes thousands of
// segments, none hopeless alone) reports its steps in lumps. At a steady 100 steps per second, in
// lumps of 37 steps, an end at 1e4 s (1e6 steps) is refused at the first lump past a hundredth of
// maxSteps (5e5); the same lumps run on under maxSteps 2e6. Before, the hybrid run never judged
// its steps as a whole and ran on for minutes (docs/bad_inputs.md "absurd sizes").
TEST(PaceWatch, StepsReportedInLumpsAreJudgedAsOneRun) {
  const auto lumpsUntilRefused = [](long maxSteps) -> std::optional<long> {
    PaceWatch pace(0, 1e4, maxSteps);
    for (long steps = 37; steps <= 1'000'000; steps += 37) {
      try {
        pace.afterSteps(steps, 0.01 * static_cast<double>(steps));
      } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("would need about 1e+06 steps to reach t = 10000 s"), std::string::npos)
            << e.what();
        return steps;
      }
    }
    return std::nullopt;
  };
  const std::optional<long> refusedAt = lumpsUntilRefused(500'000);
  ASSERT_TRUE(refusedAt);
  EXPECT_GE(*refusedAt, 5'000);
  EXPECT_LT(*refusedAt, 8'192 + 37);
  EXPECT_FALSE(lumpsUntilRefused(2'000'000));
}

// Lumps whose pace doubles from one to the next (a coin nearing a singular time, in segments) are
// not projected over a far end; their total past maxSteps still is refused.
TEST(PaceWatch, ARisingPaceInLumpsIsNotProjectedButTheLimitHolds) {
  PaceWatch pace(0, 1e6, 200'000);
  long steps = 0;
  double t = 0;
  for (long lump = 64; steps + lump <= 200'000; lump *= 2) {
    steps += lump;
    t += 1;
    EXPECT_NO_THROW(pace.afterSteps(steps, t)) << steps << " steps at t = " << t;
  }
  EXPECT_THROW(pace.afterSteps(200'001, t + 1), std::runtime_error);
}

TEST(Events, FallingZeroIsLocatedToATenthOfANanosecond) {
  for (Method method : {Method::Rk4, Method::Dopri5, Method::Dop853}) {
    // y = cos t first falls through 0 at pi/2.
    std::vector<Event<2>> events{{.name = "zero", .g = [](double, const V2& y) { return y[0]; }, .direction = -1}};
    Trajectory trajectory(Oscillator{}, 0.0, V2(1, 0),
                          SolverConfig{.method = method, .rtol = 1e-13, .atol = 1e-15, .dt = 1e-3}, events);
    EXPECT_FALSE(trajectory.stateAt(3.0).has_value());
    ASSERT_TRUE(trajectory.stoppedBy().has_value());
    EXPECT_EQ(trajectory.stoppedBy()->name, "zero");
    EXPECT_TRUE(isNear(trajectory.stoppedBy()->t, std::numbers::pi / 2, 1e-10)) << nameOf(method);
  }
}

// An event whose g dips through zero and back inside one step shows no sign change at the step's
// ends: with its rate given, the dip's minimum is located and read, and the first crossing found.
// y = cos t: g = y + 0.995 dips to -0.005 at pi, under zero for |t - pi| < acos(0.995), inside one
// RK4 step from 3 to 3.5. Without the rate the dip is not seen at all.
TEST(Events, ADipInsideOneStepIsFoundFromTheRate) {
  for (const bool withRate : {false, true}) {
    Event<2> dip{.name = "dip", .g = [](double, const V2& y) { return y[0] + 0.995; }, .direction = -1};
    if (withRate) dip.rate = [](double, const V2& y) { return y[1]; };
    Trajectory trajectory(Oscillator{}, 0.0, V2(1, 0), SolverConfig{.method = Method::Rk4, .dt = 0.5}, {dip});
    const bool ran = trajectory.stateAt(5.0).has_value();
    if (!withRate) {
      EXPECT_TRUE(ran);
      continue;
    }
    ASSERT_FALSE(ran);
    ASSERT_TRUE(trajectory.stoppedBy().has_value());
    // The crossing on RK4's dense output of a step of 0.5 s: within its error of the exact one.
    EXPECT_TRUE(isNear(trajectory.stoppedBy()->t, std::numbers::pi - std::acos(0.995), 2e-2));
  }
}

TEST(Events, DirectionFilterSkipsTheOtherCrossing) {
  std::vector<Event<2>> events{{.name = "rising", .g = [](double, const V2& y) { return y[0]; }, .direction = +1}};
  Trajectory trajectory(Oscillator{}, 0.0, V2(1, 0), SolverConfig{.rtol = 1e-13, .atol = 1e-15}, events);
  trajectory.stateAt(10.0);
  ASSERT_TRUE(trajectory.stoppedBy().has_value());
  EXPECT_TRUE(isNear(trajectory.stoppedBy()->t, 1.5 * std::numbers::pi, 1e-10));
}

TEST(Events, NonTerminalEventsAreRecordedAndTheRunGoesOn) {
  std::vector<Event<2>> events{
      {.name = "maximum", .g = [](double, const V2& y) { return y[1]; }, .direction = -1, .terminal = false}};
  Trajectory trajectory(Oscillator{}, 0.0, V2(0, 1), SolverConfig{.rtol = 1e-13, .atol = 1e-15}, events);
  ASSERT_TRUE(trajectory.stateAt(20.0).has_value());
  // y = sin t has maxima (y' = cos t falling through 0) at pi/2 + 2 pi k.
  ASSERT_EQ(trajectory.nonTerminalHits().size(), 3u);  // pi/2, 5 pi/2, 9 pi/2 < 20 < 13 pi/2
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_TRUE(isNear(trajectory.nonTerminalHits()[k].t, std::numbers::pi / 2 + 2 * std::numbers::pi * k, 1e-10));
  }
}

TEST(Events, DirectionZeroCatchesARisingCrossing) {
  // y = -cos t rises through 0 at pi/2; an event of either direction must stop there.
  std::vector<Event<2>> events{{.name = "zero", .g = [](double, const V2& y) { return y[0]; }, .direction = 0}};
  Trajectory trajectory(Oscillator{}, 0.0, V2(-1, 0), SolverConfig{.rtol = 1e-13, .atol = 1e-15}, events);
  EXPECT_FALSE(trajectory.stateAt(3.0).has_value());
  ASSERT_TRUE(trajectory.stoppedBy().has_value());
  EXPECT_TRUE(isNear(trajectory.stoppedBy()->t, std::numbers::pi / 2, 1e-10));
}

TEST(Events, AGrazeInsideOneStepIsFoundOnlyWithInteriorChecks) {
  // g = (t - 0.5)^2 - 1e-4 dips below 0 on (0.49, 0.51), inside one RK4 step of 1 s whose ends
  // both have g = 0.2499: read at the ends the dip is missed; with three interior points (0.25,
  // 0.5, 0.75) the one at 0.5 finds it, and the root is located at 0.49 on the dense output.
  for (int checks : {0, 3}) {
    Event<2> graze{
        .name = "graze", .g = [](double t, const V2&) { return (t - 0.5) * (t - 0.5) - 1e-4; }, .direction = -1};
    graze.interiorChecks = checks;
    Trajectory trajectory(Oscillator{}, 0.0, V2(0, 1), SolverConfig{.method = Method::Rk4, .dt = 1.0}, {graze});
    const bool reachedTheEnd = trajectory.stateAt(1.0).has_value();
    if (checks == 0) {
      EXPECT_TRUE(reachedTheEnd);
      continue;
    }
    EXPECT_FALSE(reachedTheEnd);
    ASSERT_TRUE(trajectory.stoppedBy().has_value());
    EXPECT_TRUE(isNear(trajectory.stoppedBy()->t, 0.49, 1e-12));
  }
}

TEST(Events, TheEarliestOfTwoTerminalRootsInOneStepStopsTheRun) {
  // One RK4 step of 1 s holds both roots, t = 0.7 (listed first) and t = 0.3: the run ends at 0.3.
  std::vector<Event<2>> events{{.name = "late", .g = [](double t, const V2&) { return 0.7 - t; }, .direction = -1},
                               {.name = "early", .g = [](double t, const V2&) { return 0.3 - t; }, .direction = -1}};
  Trajectory trajectory(Oscillator{}, 0.0, V2(0, 1), SolverConfig{.method = Method::Rk4, .dt = 1.0}, events);
  EXPECT_FALSE(trajectory.stateAt(1.0).has_value());
  ASSERT_TRUE(trajectory.stoppedBy().has_value());
  EXPECT_EQ(trajectory.stoppedBy()->name, "early");
  EXPECT_TRUE(isNear(trajectory.stoppedBy()->t, 0.3, 1e-14));
}

TEST(EventRoot, IllinoisConvergesSuperlinearlyWhicheverEndRegulaFalsiWouldStickAt) {
  // Plain regula falsi keeps one end of the bracket for good on a convex or concave g and
  // converges linearly (here at 0.75 per iteration, over 100 evaluations to 1e-14); the Illinois
  // modification converges with order 1.44 (Dowell & Jarratt 1971): a dozen evaluations or so.
  struct Case {
    const char* name;
    double (*g)(double);
    double a, b, root;
  };
  const Case cases[] = {
      {"exp(t) - 2 (convex, rising)", [](double t) { return std::exp(t) - 2; }, 0.0, 3.0, std::log(2.0)},
      {"2 - exp(t) (concave, falling)", [](double t) { return 2 - std::exp(t); }, 0.0, 3.0, std::log(2.0)},
      {"t^3 - 0.001 (convex)", [](double t) { return t * t * t - 0.001; }, 0.0, 2.0, 0.1},
      {"log(t) (concave)", [](double t) { return std::log(t); }, 0.05, 20.0, 1.0},
  };
  for (const Case& c : cases) {
    int evaluations = 0;
    const double root = locateRoot(
        [&](double t) {
          ++evaluations;
          return c.g(t);
        },
        c.a, c.g(c.a), c.b, c.g(c.b));
    EXPECT_TRUE(isNear(root, c.root, 1e-13 * std::max(1.0, c.root))) << c.name;
    EXPECT_LE(evaluations, 30) << c.name;
  }
}

TEST(Trajectory, ANonFiniteInitialStateIsRefused) {
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    for (const Method method : {Method::Rk4, Method::Dopri5, Method::Dop853}) {
      EXPECT_THROW(Trajectory(Oscillator{}, 0.0, V2(bad, 1), SolverConfig{.method = method}), std::invalid_argument)
          << nameOf(method) << " from " << bad;
    }
  }
}

// The Riccati problem of the fixed-step tests as `copies` identical, uncoupled components.
template <int N>
struct RiccatiCopies {
  Vec<N> operator()(double t, const Vec<N>& y) const { return (-2 * t * y.array().square()).matrix(); }
};

TEST(Trajectory, AdaptiveStepsAreTheSameForAProblemAndItsDuplicate) {
  // HNW's error norm is a root mean square over the components: solving the same equation twice
  // over, as identical uncoupled components, leaves every error norm and so every step unchanged.
  for (const Method method : {Method::Dopri5, Method::Dop853}) {
    const SolverConfig config{.method = method, .rtol = 1e-9, .atol = 1e-12};
    Trajectory single(RiccatiCopies<1>{}, 0.0, Vec<1>(1.0), config);
    Trajectory doubled(RiccatiCopies<2>{}, 0.0, V2(1.0, 1.0), config);
    const double y1 = (*single.stateAt(10.0))[0];
    const V2 y2 = *doubled.stateAt(10.0);
    EXPECT_EQ(single.stats().acceptedSteps, doubled.stats().acceptedSteps) << nameOf(method);
    EXPECT_EQ(single.stats().rejectedSteps, doubled.stats().rejectedSteps) << nameOf(method);
    EXPECT_EQ(y2[0], y1) << nameOf(method);
    EXPECT_EQ(y2[1], y1) << nameOf(method);
    EXPECT_TRUE(isNear(y1, Riccati::exact(10.0), 1e-7)) << nameOf(method);
  }
}

TEST(Trajectory, BlowUpIsReportedNotReturned) {
  // y' = y^2 from y = 1 blows up at t = 1.
  auto blowUp = [](double, const V1& y) { return V1(y[0] * y[0]); };
  Trajectory trajectory(blowUp, 0.0, V1(1.0), SolverConfig{.method = Method::Dop853, .rtol = 1e-10, .atol = 1e-12});
  EXPECT_THROW(trajectory.stateAt(2.0), std::runtime_error);
}

TEST(Trajectory, QueriesBackInTimeAreRefused) {
  Trajectory trajectory(Oscillator{}, 0.0, V2(0, 1), SolverConfig{});
  trajectory.stateAt(1.0);
  EXPECT_THROW(trajectory.stateAt(0.5), std::logic_error);
}

}  // namespace
}  // namespace coinroll::integrate
