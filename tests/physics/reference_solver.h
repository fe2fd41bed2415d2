#pragma once
// What the physics tests integrate with when they compare a run against an analytic result or a
// second formulation: DOP853 at tolerances far below every bound they assert, so a failure is the
// model's and not the solver's.

#include <numbers>

#include "integrate/solver_config.h"

namespace coinroll::physics::reference {

inline constexpr double kDeg = std::numbers::pi / 180;

inline const integrate::SolverConfig kTight{.method = integrate::Method::Dop853, .rtol = 1e-12, .atol = 1e-14};

}  // namespace coinroll::physics::reference
