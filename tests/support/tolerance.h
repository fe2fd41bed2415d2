#pragma once
// One place for test tolerances: each claim states its bound beside it, and
// COINROLL_TOL_SCALE scales them all (0 makes every comparison fail so the real residuals print).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

namespace coinroll::testing {

inline double toleranceScale() {
  const char* text = std::getenv("COINROLL_TOL_SCALE");
  return text == nullptr ? 1.0 : std::atof(text);
}

// |actual - expected| <= tolerance * COINROLL_TOL_SCALE, with both values in the message.
inline ::testing::AssertionResult isNear(double actual, double expected, double tolerance) {
  const double error = std::abs(actual - expected);
  if (error <= tolerance * toleranceScale() && std::isfinite(actual)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "actual " << actual << ", expected " << expected << ", |error| " << error
                                       << " > tolerance " << tolerance * toleranceScale();
}

// value <= bound * COINROLL_TOL_SCALE.
inline ::testing::AssertionResult isBelow(double value, double bound) {
  if (value <= bound * toleranceScale() && std::isfinite(value)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "value " << value << " > bound " << bound * toleranceScale();
}

}  // namespace coinroll::testing
