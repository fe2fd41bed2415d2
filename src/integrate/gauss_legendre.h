#pragma once
// Two-stage Gauss-Legendre collocation (Hairer, Lubich & Wanner, Geometric Numerical
// Integration, II.1.3; Hairer & Wanner, Solving ODEs II, IV.8): order 4, A-stable and
// symplectic, so on a conservative system its energy error stays bounded instead of drifting.
// Fixed step; the implicit stages are solved by simplified Newton.
//
// Why Newton and not fixed-point iteration: fixed point contracts only for h L < ~1 (L the
// Lipschitz constant), which is the explicit methods' step limit again; simplified Newton keeps
// the A-stable method usable at steps where RK4 has blown up (tests/physics/stability_test.cpp,
// Gauss4.StaysBoundedAtTwiceRk4sStepLimit).
// The Jacobian comes from forward differences (N right-hand-side evaluations, counted) and,
// with the LU of the iteration matrix, is reused across steps while Newton contracts fast:
// the step is fixed, so only a slow contraction says the Jacobian has gone stale.

#include <Eigen/Core>
#include <Eigen/LU>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "integrate/solver_config.h"

namespace coinroll::integrate {

namespace gauss4 {
inline constexpr double r = std::numbers::sqrt3 / 6;
inline constexpr double c1 = 0.5 - r, c2 = 0.5 + r;
inline constexpr double a11 = 0.25, a12 = 0.25 - r, a21 = 0.25 + r, a22 = 0.25;
// y1 = y0 + h (b1 k1 + b2 k2) with b = (1/2, 1/2) equals y0 + d1 Z1 + d2 Z2 with d = b^T A^-1 =
// (-sqrt 3, sqrt 3) in the stage increments Z_i = h sum_j a_ij k_j: no extra evaluations.
inline constexpr double d1 = -std::numbers::sqrt3, d2 = std::numbers::sqrt3;
}  // namespace gauss4

template <int N>
class GaussLegendre4 {
 public:
  // One step of size h from (t, y), with f0 = f(t, y). Returns y(t + h); adds the right-hand-
  // side evaluations it made (stages and Jacobian columns) to `rhsEvaluations`.
  template <class Rhs>
  Vec<N> step(Rhs& f, double t, const Vec<N>& y, const Vec<N>& f0, double h, long& rhsEvaluations) {
    if (!isSameStep(h)) isJacobianStale_ = true;  // the iteration matrix holds h
    Stages Z = startingGuess(f0, h);
    for (int attempt = 0; attempt < 2; ++attempt) {
      if (isJacobianStale_) refreshIterationMatrix(f, t, y, f0, h, rhsEvaluations);
      if (solveStages(f, t, y, h, Z, rhsEvaluations)) {
        rememberCollocation(Z, h);
        return y + gauss4::d1 * Z.template head<N>() + gauss4::d2 * Z.template tail<N>();
      }
      if (isJacobianFresh_) break;
      isJacobianStale_ = true;  // Newton failed on an old Jacobian: retry with a fresh one
      Z = startingGuess(f0, h);
    }
    throw std::runtime_error(
        fmt::format("gauss4: Newton iteration diverges at t = {} s with step {} s; "
                    "the step is too large for this right-hand side",
                    t, h));
  }

 private:
  using Stages = Eigen::Matrix<double, 2 * N, 1>;
  using IterationMatrix = Eigen::Matrix<double, 2 * N, 2 * N>;

  static constexpr int kMaxIterations = 10;
  // Converged when the next correction (estimated from the contraction rate as in HW IV.8)
  // is below a few ulps of the state: symplecticity holds only for converged stages.
  static constexpr double kNewtonTolerance = 1e-15;
  // Stagnation at round-off: the correction stopped shrinking while already this small.
  static constexpr double kRoundOffFloor = 1e-13;
  // A step whose Newton contracted slower than this asks for a fresh Jacobian next step.
  static constexpr double kSlowContraction = 0.1;

  // Grid steps t0 + k dt differ from dt by round-off; a real change of step is far larger.
  bool isSameStep(double h) const { return std::abs(h - lastH_) <= 1e-9 * std::abs(h); }

  // Extrapolates the previous step's collocation polynomial (a quadratic through the stage
  // increments) into this step; the first step starts from Euler's increments.
  Stages startingGuess(const Vec<N>& f0, double h) const {
    Stages Z;
    if (!hasPreviousStep_ || !isSameStep(h)) {
      Z.template head<N>() = gauss4::c1 * h * f0;
      Z.template tail<N>() = gauss4::c2 * h * f0;
      return Z;
    }
    const Vec<N> atOne = previousCollocation(1.0);
    Z.template head<N>() = previousCollocation(1 + gauss4::c1) - atOne;
    Z.template tail<N>() = previousCollocation(1 + gauss4::c2) - atOne;
    return Z;
  }

  // u(t0 + s h) - y0 of the previous step: the quadratic through 0, Z1 at c1 and Z2 at c2.
  Vec<N> previousCollocation(double s) const {
    using namespace gauss4;
    const double l1 = s * (s - c2) / (c1 * (c1 - c2)), l2 = s * (s - c1) / (c2 * (c2 - c1));
    return l1 * previousZ_.template head<N>() + l2 * previousZ_.template tail<N>();
  }

  void rememberCollocation(const Stages& Z, double h) {
    previousZ_ = Z;
    lastH_ = h;
    hasPreviousStep_ = true;
  }

  template <class Rhs>
  void refreshIterationMatrix(Rhs& f, double t, const Vec<N>& y, const Vec<N>& f0, double h, long& rhsEvaluations) {
    Eigen::Matrix<double, N, N> J;
    for (int j = 0; j < N; ++j) {
      // HNW's increment: sqrt(eps) relative, floored for components near zero.
      const double delta = std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(1e-5, std::abs(y[j]));
      Vec<N> shifted = y;
      shifted[j] += delta;
      J.col(j) = (f(t, shifted) - f0) / delta;
    }
    rhsEvaluations += N;
    using namespace gauss4;
    IterationMatrix M = IterationMatrix::Identity();
    M.template topLeftCorner<N, N>() -= h * a11 * J;
    M.template topRightCorner<N, N>() -= h * a12 * J;
    M.template bottomLeftCorner<N, N>() -= h * a21 * J;
    M.template bottomRightCorner<N, N>() -= h * a22 * J;
    lu_.compute(M);
    lastH_ = h;
    isJacobianStale_ = false;
    isJacobianFresh_ = true;
  }

  // Simplified Newton on Z - h (A x I) F(Z) = 0. True when converged; Z then holds the stages.
  template <class Rhs>
  bool solveStages(Rhs& f, double t, const Vec<N>& y, double h, Stages& Z, long& rhsEvaluations) {
    using namespace gauss4;
    const Vec<N> scale = (1 + y.cwiseAbs().array()).matrix();
    double previousNorm = 0, rate = 0;
    for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
      const Vec<N> k1 = f(t + c1 * h, Vec<N>(y + Z.template head<N>()));
      const Vec<N> k2 = f(t + c2 * h, Vec<N>(y + Z.template tail<N>()));
      rhsEvaluations += 2;
      Stages residual;
      residual.template head<N>() = Z.template head<N>() - h * (a11 * k1 + a12 * k2);
      residual.template tail<N>() = Z.template tail<N>() - h * (a21 * k1 + a22 * k2);
      const Stages correction = lu_.solve(-residual);
      if (!correction.allFinite()) return false;
      Z += correction;
      const double norm = std::max(correction.template head<N>().cwiseQuotient(scale).cwiseAbs().maxCoeff(),
                                   correction.template tail<N>().cwiseQuotient(scale).cwiseAbs().maxCoeff());
      double nextCorrection = norm;  // no rate yet after the first correction: assume no contraction
      if (iteration > 0) {
        rate = norm / previousNorm;
        if (rate >= 1) return norm < kRoundOffFloor && finishSolve(rate);  // else diverging
        nextCorrection = rate / (1 - rate) * norm;
      }
      if (nextCorrection <= kNewtonTolerance) return finishSolve(rate);
      previousNorm = norm;
    }
    return false;
  }

  bool finishSolve(double rate) {
    isJacobianFresh_ = false;
    if (rate > kSlowContraction) isJacobianStale_ = true;
    return true;
  }

  Eigen::PartialPivLU<IterationMatrix> lu_;
  Stages previousZ_ = Stages::Zero();
  double lastH_ = 0;  // s, the step the iteration matrix and previousZ_ belong to
  bool hasPreviousStep_ = false;
  bool isJacobianStale_ = true;
  bool isJacobianFresh_ = false;  // computed at the start of the current step
};

}  // namespace coinroll::integrate
