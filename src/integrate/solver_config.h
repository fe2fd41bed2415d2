#pragma once
// Choice of method and its tolerances, independent of any particular right-hand side.

#include <Eigen/Core>

#include <limits>
#include <optional>
#include <span>
#include <string_view>

namespace coinroll::integrate {

template <int N>
using Vec = Eigen::Matrix<double, N, 1>;

enum class Method {
  Euler,   // explicit Euler, fixed step: the first-order baseline that fails
  Rk4,     // classic Runge-Kutta, fixed step, order 4
  Dopri5,  // Dormand-Prince 5(4), adaptive, 4th-order dense output
  Dop853,  // Dormand-Prince 8(5,3), adaptive, 7th-order dense output
  Gauss4,  // 2-stage Gauss-Legendre, implicit, fixed step, order 4, symplectic (no energy drift)
};

std::optional<Method> methodFromName(std::string_view name);
std::string_view nameOf(Method method);
std::span<const std::string_view> methodNames();  // in the order of the enum
bool isAdaptive(Method method);
int errorEstimateOrder(Method method);  // adaptive methods: the order of the local error estimate (DOP853: 8)

// The ranges a scene's solver block may take (scene files, docs/scene.md). Below 1e-14 the
// steps a tolerance asks for are lost in round-off (double precision is 2e-16); above 1e-2 the
// dense output and the events it locates are no longer worth reading. A pure relative tolerance
// (atol = 0) cannot control a component that is or passes through 0: its error weight is 1 / 0.
// More than 10^7 fixed steps per simulated second, or steps longer than the coin's own time scale
// sqrt(a/g) ~ 0.06 s many times over, are typos rather than choices.
inline constexpr double kMinRtol = 1e-14, kMaxRtol = 1e-2;
inline constexpr double kMaxAtol = 1e-2;            // atol in (0, kMaxAtol]
inline constexpr double kMinDt = 1e-7, kMaxDt = 1;  // s

struct SolverConfig {
  Method method = Method::Dop853;
  double rtol = 1e-10;  // relative tolerance per step (adaptive methods)
  double atol = 1e-12;  // absolute tolerance per step, in the state's units (adaptive methods)
  double dt = 1e-3;     // s, step of the fixed-step methods
  double maxStep = std::numeric_limits<double>::infinity();  // s, cap on adaptive steps
  long maxSteps = 50'000'000;  // a run needing more steps throws, naming t, h and the state
  // s, where the run will be asked to end, if known: a run whose pace so far would need more than
  // maxSteps to get there fails early instead of after maxSteps steps.
  double endTime = std::numeric_limits<double>::infinity();
};

struct Stats {
  long rhsEvaluations = 0;
  long acceptedSteps = 0;
  long rejectedSteps = 0;

  // A run made of several integrations (HybridRun's segments) reports their sum.
  Stats& operator+=(const Stats& other) {
    rhsEvaluations += other.rhsEvaluations;
    acceptedSteps += other.acceptedSteps;
    rejectedSteps += other.rejectedSteps;
    return *this;
  }
};

}  // namespace coinroll::integrate
