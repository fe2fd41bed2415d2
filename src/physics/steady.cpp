#include "physics/steady.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "physics/observables.h"

namespace coinroll::physics {

namespace {

void requireTiltBelowFlat(double theta) {
  if (!(std::abs(theta) < std::numbers::pi / 2)) {
    throw std::invalid_argument("steady state: theta must be in (-90, 90) degrees, got " +
                                std::to_string(theta * 180 / std::numbers::pi));
  }
}

}  // namespace

CoinState straightRolling(double omega_Z) { return {.omega_Z = omega_Z}; }

double criticalSpin(const CoinModel& m) {
  const double Ma2 = m.M * m.a * m.a;
  return std::sqrt(m.M * m.g * m.a * m.I_X / (m.I_Z * (m.I_Z + Ma2)));
}

CoinState spinInPlace(const CoinModel& m, double theta) {
  requireTiltBelowFlat(theta);
  if (theta == 0) {
    throw std::invalid_argument("steady state spin-in-place: theta must be non-zero (an upright coin cannot spin in place on its rim)");
  }
  return {.theta = theta, .omega_Y = std::sqrt(m.M * m.g * m.a * std::cos(theta) / m.I_X)};
}

CoinState steadyCircle(const CoinModel& m, double theta, double omega_Z, int branch) {
  requireTiltBelowFlat(theta);
  if (branch != 1 && branch != -1) {
    throw std::invalid_argument("steady state circle: branch must be +1 or -1, got " + std::to_string(branch));
  }
  // A w^2 + B w + C = 0 for w = omega_Y (seed 5.2, general inertia).
  const double A = m.I_X * std::tan(theta);
  const double B = (m.I_Z + m.M * m.a * m.a) * omega_Z;
  const double C = -m.M * m.g * m.a * std::sin(theta);
  if (A == 0) {
    if (branch == -1) {
      throw std::invalid_argument("steady state circle: the f- branch has no finite omega_Y at theta = 0 (use theta != 0 or branch +)");
    }
    return straightRolling(omega_Z);
  }
  // The textbook (-B +- sqrt(D)) / 2A cancels catastrophically for small tilts; pair each root
  // with its cancellation-free form (q = -(B + sign(B) sqrt(D)) / 2, roots q / A and C / q).
  const double sqrtD = std::sqrt(B * B - 4 * A * C);  // D >= 0 because A C <= 0 for |theta| < 90 deg
  const double q = -0.5 * (B + std::copysign(sqrtD, B));
  const double rootFromQ = q / A, rootFromC = C / q;
  // (-B + sqrt(D)) / 2A is the larger root when A > 0; f+ is the "+ sqrt" root by definition.
  const double plusSqrtRoot = (B >= 0) ? rootFromC : rootFromQ;
  const double minusSqrtRoot = (B >= 0) ? rootFromQ : rootFromC;
  return {.theta = theta, .omega_Y = branch == 1 ? plusSqrtRoot : minusSqrtRoot, .omega_Z = omega_Z};
}

double steadyResidual(const CoinModel& m, const CoinState& s) {
  return m.I_X * std::tan(s.theta) * s.omega_Y * s.omega_Y + (m.I_Z + m.M * m.a * m.a) * s.omega_Z * s.omega_Y -
         m.M * m.g * m.a * std::sin(s.theta);
}

double wobbleStiffness(const CoinModel& m, double theta0, double omega_Y0, double omega_Z0) {
  const double Ma2 = m.M * m.a * m.a, Mga = m.M * m.g * m.a;
  const double tanTheta = std::tan(theta0), cosTheta = std::cos(theta0);
  // Perturbations of omega_Y and omega_Z follow the tilt: d(omega_Y) = alpha d(theta),
  // d(omega_Z) = beta d(theta) (linearised eqs. 15, 16 with d(theta)-dot = d(omega_X)).
  const double alpha = (m.I_X * omega_Y0 * tanTheta + m.I_Z * omega_Z0) / m.I_X;       // (3.3)
  const double beta = Ma2 * omega_Y0 / (m.I_Z + Ma2);                                  // (3.4)
  // Linearised eq. (14): (I_X + M a^2) d(theta)'' = -K (I_X + M a^2) d(theta).
  return ((m.I_Z + Ma2) * (omega_Z0 * alpha + omega_Y0 * beta) + 2 * m.I_X * omega_Y0 * tanTheta * alpha +
          m.I_X * omega_Y0 * omega_Y0 / (cosTheta * cosTheta) - Mga * cosTheta) /
         (m.I_X + Ma2);                                                                 // (3.6)
}

CircleRadii circleRadii(const CoinModel& m, const CoinState& s) {
  const double phiDot = precessionRate(s);
  if (phiDot == 0) {
    return {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  }
  return {m.a * std::abs(s.omega_Z / phiDot), m.a * std::abs(spinRate(s) / phiDot)};
}

}  // namespace coinroll::physics
