#include "physics/coin_model.h"

#include <cmath>

namespace coinroll::physics {

CoinModel diskModel(double M, double a, double g) {
  return {.M = M, .a = a, .g = g, .I_X = M * a * a / 4, .I_Z = M * a * a / 2, .rim = {}, .effects = {}};
}

CoinModel ringModel(double M, double a, double b, double g) {
  const double sumOfSquares = a * a + b * b;
  return {.M = M,
          .a = a,
          .g = g,
          .I_X = M * sumOfSquares / 4,
          .I_Z = M * sumOfSquares / 2,
          .rim = {},
          .holeRadius = b,
          .effects = {}};
}

double naturalTime(const CoinModel& model) { return std::sqrt(model.a / model.g); }

double naturalRate(const CoinModel& model) { return std::sqrt(model.g / model.a); }

}  // namespace coinroll::physics
