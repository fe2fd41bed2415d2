// Cost of one right-hand-side evaluation of the seed's equations: ours (physics::rhs on an Eigen
// state) against a plain-double probe of the same formulas written inline, in the same run, so
// the ratio is meaningful on any machine; and of the quaternion formulation's. Run: build/bench/rhs_bench
#include <benchmark/benchmark.h>

#include <cmath>

#include "physics/coin_model.h"
#include "physics/dynamics.h"
#include "physics/quaternion_dynamics.h"

namespace {

using coinroll::physics::StateVec;

const coinroll::physics::CoinModel kDisk = coinroll::physics::diskModel(0.4, 0.0375, 9.81);

StateVec typicalState() {
  StateVec y;
  y << 0.35, 0.2, 1.0, 0.5, 3.0, 14.0, 0.01, -0.02;
  return y;
}

void BM_RhsEval(benchmark::State& state) {
  StateVec y = typicalState();
  for (auto _ : state) {
    const StateVec dy = coinroll::physics::rhs(kDisk, 0.0, y);
    benchmark::DoNotOptimize(dy);
    y[0] += 1e-12;  // theta and phi change every call, so no sin or cos can be hoisted
    y[1] += 1e-12;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RhsEval);

// The quaternion formulation at the same physical state: its 3x3 solve and rotation matrix
// against the seed's closed forms.
void BM_QuaternionRhsEval(benchmark::State& state) {
  coinroll::physics::QuaternionStateVec y =
      coinroll::physics::toVector(coinroll::physics::fromEulerState(coinroll::physics::toState(typicalState())));
  for (auto _ : state) {
    const coinroll::physics::QuaternionStateVec dy = coinroll::physics::quaternionRhs(kDisk, 0.0, y);
    benchmark::DoNotOptimize(dy);
    y[0] += 1e-12;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_QuaternionRhsEval);

// The baseline: the same equations on eight doubles, no Eigen, no struct.
void BM_RhsPlainDoubleProbe(benchmark::State& state) {
  double y[8] = {0.35, 0.2, 1.0, 0.5, 3.0, 14.0, 0.01, -0.02}, dy[8];
  const double M = kDisk.M, a = kDisk.a, g = kDisk.g, IX = kDisk.I_X, IZ = kDisk.I_Z;
  for (auto _ : state) {
    const double st = std::sin(y[0]), ct = std::cos(y[0]), sp = std::sin(y[1]), cp = std::cos(y[1]);
    const double tt = st / ct, Ma2 = M * a * a;
    dy[0] = y[3];
    dy[1] = y[4] / ct;
    dy[2] = y[5] + tt * y[4];
    dy[3] = (-(IZ + Ma2) * y[4] * y[5] - IX * y[4] * y[4] * tt + M * g * a * st) / (IX + Ma2);
    dy[4] = y[3] * y[4] * tt + IZ / IX * y[5] * y[3];
    dy[5] = Ma2 * y[3] * y[4] / (IZ + Ma2);
    dy[6] = a * (-y[5] * cp + y[3] * ct * sp);
    dy[7] = a * (y[5] * sp + y[3] * ct * cp);
    benchmark::DoNotOptimize(dy);
    y[0] += 1e-12;
    y[1] += 1e-12;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_RhsPlainDoubleProbe);

}  // namespace

BENCHMARK_MAIN();
