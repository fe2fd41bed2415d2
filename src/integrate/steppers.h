#pragma once
// Single steps of each method, written once for any right-hand side f(t, y) -> dy/dt, and the
// dense output of one step. No allocation: every vector is fixed-size.

#include <cmath>
#include <stdexcept>
#include <string>

#include "integrate/solver_config.h"

namespace coinroll::integrate {

// Out of line: a message is built only when the check fails.
[[noreturn]] inline void throwOutsideStep(double t, double t0, double h) {
  throw std::logic_error("dense output asked for t = " + std::to_string(t) + " s outside its step [" +
                         std::to_string(t0) + ", " + std::to_string(t0 + h) + "] s: a caller picked the wrong step");
}

// The solution inside one step [t0, t0 + h] in Hairer's nested form, with s = (t - t0) / h:
//   y = r1 + s (r2 + (1 - s) (r3 + s (r4 + (1 - s) (r5 + s (r6 + (1 - s) (r7 + s r8)))))).
// r1..r4 alone are the cubic Hermite interpolant of the end values and slopes; DOPRI5's r5 lifts
// it to order 4, DOP853's r5..r8 to order 7. Explicit Euler uses the chord (r3 = ... = 0).
template <int N>
struct DenseInterval {
  double t0 = 0, h = 0;  // s
  Vec<N> r1, r2, r3, r4, r5, r6, r7, r8;

  double tEnd() const { return t0 + h; }

  Vec<N> at(double t) const {
    // Dense output is only valid inside its own step (round-off at the ends allowed); outside it
    // the polynomial extrapolates without a sign of trouble, into frames, CSV rows and event
    // times. Checked in every build, not as an assert (CI builds with NDEBUG): two comparisons
    // beside the eight vector updates below.
    if (t < t0 - 1e-12 * (1 + std::abs(t0)) || t > t0 + h + 1e-12 * (1 + std::abs(t0 + h))) throwOutsideStep(t, t0, h);
    const double s = (t - t0) / h, s1 = 1 - s;
    const Vec<N> high = r5 + s * (r6 + s1 * (r7 + s * r8));
    return r1 + s * (r2 + s1 * (r3 + s * (r4 + s1 * high)));
  }
};

// Cubic Hermite interval from the end values and slopes (order 3 between step points).
template <int N>
DenseInterval<N> hermiteInterval(double t0, double h, const Vec<N>& y0, const Vec<N>& f0, const Vec<N>& y1,
                                 const Vec<N>& f1) {
  DenseInterval<N> d;
  d.t0 = t0;
  d.h = h;
  d.r1 = y0;
  d.r2 = y1 - y0;
  d.r3 = h * f0 - d.r2;
  d.r4 = d.r2 - h * f1 - d.r3;
  d.r5.setZero();
  d.r6.setZero();
  d.r7.setZero();
  d.r8.setZero();
  return d;
}

template <int N, class Rhs>
Vec<N> eulerStep(Rhs& f, double t, const Vec<N>& y, const Vec<N>& f0, double h) {
  (void)f;
  (void)t;
  return y + h * f0;
}

// Classic RK4; f0 = f(t, y) is passed in so the driver evaluates it once per step.
template <int N, class Rhs>
Vec<N> rk4Step(Rhs& f, double t, const Vec<N>& y, const Vec<N>& f0, double h) {
  const Vec<N> k2 = f(t + h / 2, Vec<N>(y + (h / 2) * f0));
  const Vec<N> k3 = f(t + h / 2, Vec<N>(y + (h / 2) * k2));
  const Vec<N> k4 = f(t + h, Vec<N>(y + h * k3));
  return y + (h / 6) * (f0 + 2 * k2 + 2 * k3 + k4);
}

// Dormand & Prince (1980) 5(4) pair with Shampine's dense output as in Hairer, Norsett & Wanner,
// Solving ODEs I, II.5-II.6 (DOPRI5). FSAL: k7 = f(t + h, y1) is the next step's k1.
namespace dopri5 {
inline constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
inline constexpr double a21 = 1.0 / 5;
inline constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
inline constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
inline constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
inline constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                        a65 = -5103.0 / 18656;
inline constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784, b6 = 11.0 / 84;
// e = b - b_hat (5th minus embedded 4th-order weights).
inline constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                        e6 = 22.0 / 525, e7 = -1.0 / 40;
inline constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                        d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                        d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;
}  // namespace dopri5

template <int N>
struct Dopri5Result {
  Vec<N> y1, f1;          // solution and slope at t + h
  Vec<N> error;           // local error estimate (5th minus 4th order)
  Vec<N> k3, k4, k5, k6;  // kept for the dense output of an accepted step
};

template <int N, class Rhs>
Dopri5Result<N> dopri5Step(Rhs& f, double t, const Vec<N>& y, const Vec<N>& k1, double h) {
  using namespace dopri5;
  Dopri5Result<N> r;
  const Vec<N> k2 = f(t + c2 * h, Vec<N>(y + h * (a21 * k1)));
  r.k3 = f(t + c3 * h, Vec<N>(y + h * (a31 * k1 + a32 * k2)));
  r.k4 = f(t + c4 * h, Vec<N>(y + h * (a41 * k1 + a42 * k2 + a43 * r.k3)));
  r.k5 = f(t + c5 * h, Vec<N>(y + h * (a51 * k1 + a52 * k2 + a53 * r.k3 + a54 * r.k4)));
  r.k6 = f(t + h, Vec<N>(y + h * (a61 * k1 + a62 * k2 + a63 * r.k3 + a64 * r.k4 + a65 * r.k5)));
  r.y1 = y + h * (b1 * k1 + b3 * r.k3 + b4 * r.k4 + b5 * r.k5 + b6 * r.k6);
  r.f1 = f(t + h, r.y1);
  r.error = h * (e1 * k1 + e3 * r.k3 + e4 * r.k4 + e5 * r.k5 + e6 * r.k6 + e7 * r.f1);
  return r;
}

template <int N>
DenseInterval<N> dopri5Interval(double t0, double h, const Vec<N>& y0, const Vec<N>& k1, const Dopri5Result<N>& r) {
  using namespace dopri5;
  DenseInterval<N> d = hermiteInterval<N>(t0, h, y0, k1, r.y1, r.f1);
  d.r5 = h * (d1 * k1 + d3 * r.k3 + d4 * r.k4 + d5 * r.k5 + d6 * r.k6 + d7 * r.f1);
  return d;
}

}  // namespace coinroll::integrate
