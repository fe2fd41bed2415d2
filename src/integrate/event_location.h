#pragma once
// Root of a scalar function bracketed in [a, b] (g(a), g(b) of opposite sign or g(b) = 0):
// the Illinois variant of regula falsi, which keeps the bracket and converges superlinearly,
// with a bisection fallback when an iterate stalls at one end.

#include <algorithm>
#include <cmath>
#include <utility>

namespace coinroll::integrate {

template <class G>
double locateRoot(G&& g, double a, double ga, double b, double gb) {
  if (gb == 0) return b;
  const double tolerance = 1e-14 * std::max({1.0, std::abs(a), std::abs(b)});
  int side = 0;  // which end was kept last time (Illinois halves its value when repeated)
  for (int iteration = 0; iteration < 200 && std::abs(b - a) > tolerance; ++iteration) {
    double c = (a * gb - b * ga) / (gb - ga);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    const double gc = g(c);
    if (gc == 0) return c;
    if ((gc < 0) == (gb < 0)) {
      b = c, gb = gc;
      if (side == -1) ga *= 0.5;
      side = -1;
    } else {
      a = c, ga = gc;
      if (side == +1) gb *= 0.5;
      side = +1;
    }
  }
  // The earliest point known to be at or past the crossing.
  return b;
}

}  // namespace coinroll::integrate
