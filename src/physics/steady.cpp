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

double degrees(double radians) { return radians * 180 / std::numbers::pi; }

bool hasCorners(const Rim& rim) { return !rim.thin() && !rim.fullyRounded(); }

// Upright, a cornered rim stands on its flat band and the contact jumps between the two corners, so
// nothing steady lives there (docs/rim.md eq. 5.4).
void refuseUprightCorner(const Rim& rim, const std::string& what) {
  if (hasCorners(rim)) {
    throw std::invalid_argument(what + ": a rim with corners (edge radius " + std::to_string(rim.edgeRadius) +
                                " m < thickness / 2 = " + std::to_string(0.5 * rim.thickness) +
                                " m) cannot roll upright: at theta = 0 the contact switches from one corner to the "
                                "other (docs/rim.md eq. 5.4)");
  }
}

// The root omega_Y of A w^2 + B w + C = 0 (A != 0, D >= 0) that branch +1 (f+, the "+ sqrt(D)" root by
// definition) or -1 names. The textbook (-B +- sqrt(D)) / 2A cancels catastrophically for small
// tilts; each root is paired with its cancellation-free form (q = -(B + sign(B) sqrt(D)) / 2, roots
// q / A and C / q), which holds for either sign of A.
double steadyOmegaY(double A, double B, double C, int branch) {
  const double q = -0.5 * (B + std::copysign(std::sqrt(B * B - 4 * A * C), B));
  // B = C = 0: balanced on a corner, at rest. With C != 0, a q that underflowed to 0 gives C / q =
  // inf, which the caller refuses as rates beyond any number.
  if (q == 0 && C == 0) return 0;
  const double rootFromQ = q / A, rootFromC = C / q;
  const double plusSqrtRoot = (B >= 0) ? rootFromC : rootFromQ;
  const double minusSqrtRoot = (B >= 0) ? rootFromQ : rootFromC;
  return branch == 1 ? plusSqrtRoot : minusSqrtRoot;
}

// The rim's geometry at one tilt, in the combinations docs/rim.md §5 is written in.
struct RimTilt {
  double sinTheta = 0, cosTheta = 0, tanTheta = 0;
  double A = 0;       // m, -c . e_Y (eq. 1.3)
  double B = 0;       // m, c . e_Z
  double L = 0;       // m, H / cos(theta) = A + B tan(theta), H the height of G (eq. 1.4)
  double Lambda = 0;  // m, gravity's lever arm about the contact, c x e_y = Lambda e_X (eq. 1.7)
};

RimTilt rimTilt(const CoinModel& m, double theta) {
  const double sinTheta = std::sin(theta), cosTheta = std::cos(theta);
  const ContactOffset c = contactOffset(m.rim, m.a, sinTheta, cosTheta);
  // A sin - B cos in the form without the rho sin cos terms that cancel: a tiny tilt's lever keeps its digits.
  const double side = sinTheta < 0 ? -1.0 : 1.0;
  return {.sinTheta = sinTheta,
          .cosTheta = cosTheta,
          .tanTheta = sinTheta / cosTheta,
          .A = c.reach,
          .B = c.lift,
          .L = centreHeight(c, sinTheta, cosTheta) / cosTheta,
          .Lambda = (m.a - m.rim.edgeRadius) * sinTheta - side * m.rim.cornerOffset() * cosTheta};
}

// P and Q of P omega_Y^2 + Q omega_Z omega_Y - M g Lambda = 0 (docs/rim.md eq. 5.1).
double rimP(const CoinModel& m, const RimTilt& r) { return m.I_X * r.tanTheta + m.M * r.B * r.L; }
double rimQ(const CoinModel& m, const RimTilt& r) { return m.I_Z + m.M * r.A * r.L; }

CoinState rimSteadyCircle(const CoinModel& m, double theta, double omega_Z, int branch) {
  if (theta == 0) refuseUprightCorner(m.rim, "steady state circle");
  const RimTilt r = rimTilt(m, theta);
  const double A = rimP(m, r), B = rimQ(m, r) * omega_Z, C = -m.M * m.g * r.Lambda;
  if (A == 0) {  // fully rounded and upright: straight rolling, as for the thin coin
    if (branch == -1) {
      throw std::invalid_argument(
          "steady state circle: the f- branch has no finite omega_Y at theta = 0 (use theta != 0 or branch +)");
    }
    return straightRolling(omega_Z);
  }
  // Below a corner's balance angle gravity rights the coin (Lambda < 0) and only enough spin holds it (eq. 5.2).
  const double D = B * B - 4 * A * C;
  if (!(D >= 0)) {
    throw std::invalid_argument("steady state circle: no steady circle at theta = " + std::to_string(degrees(theta)) +
                                " degrees with omega_Z = " + std::to_string(omega_Z) +
                                " rad/s: the rim's corner holds the coin up (docs/rim.md eq. 5.2, discriminant < 0); "
                                "spin faster or tilt beyond the balance angle");
  }
  return {.theta = theta, .omega_Y = steadyOmegaY(A, B, C, branch), .omega_Z = omega_Z};
}

CoinState rimSpinInPlace(const CoinModel& m, double theta) {
  const RimTilt r = rimTilt(m, theta);
  // (5.3): v = 0 puts omega along c, omega_Z = -B/A omega_Y; for a fully rounded rim both Lambda and the
  // denominator carry a factor sin(theta), so small tilts lose nothing.
  const double omegaSquared = m.M * m.g * r.A * r.Lambda / (m.I_X * r.A * r.tanTheta - m.I_Z * r.B);
  if (!(omegaSquared >= 0) || !std::isfinite(omegaSquared)) {
    throw std::invalid_argument(
        "steady state spin-in-place: this rim has no spin in place at theta = " + std::to_string(degrees(theta)) +
        " degrees (docs/rim.md eq. 5.3: between a corner's balance angle and the root of "
        "I_X A tan(theta) = I_Z B the required omega_Y^2 is negative)");
  }
  const double omega_Y = std::sqrt(omegaSquared);
  return {.theta = theta, .omega_Y = omega_Y, .omega_Z = -r.B / r.A * omega_Y};
}

double rimWobbleStiffness(const CoinModel& m, double theta0, double omega_Y0, double omega_Z0) {
  if (theta0 == 0) refuseUprightCorner(m.rim, "wobble stiffness");
  const RimTilt r = rimTilt(m, theta0);
  const double rho = m.rim.edgeRadius, M = m.M;
  const double A = r.A, B = r.B, L = r.L, s = r.sinTheta, co = r.cosTheta, t = r.tanTheta;
  const double H = L * co;
  const double V = A * omega_Z0 + B * omega_Y0;                            // speed of G (eq. 2.4)
  const double G_X = omega_Y0 * (m.a - rho + B * t) + rho * s * omega_Z0;  // f_Y, f_Z per omega_X (eq. 2.9)
  // The rate perturbations follow the tilt, d(omega_Y) = alpha d(theta), d(omega_Z) = beta d(theta):
  // the Y-Z block of the mass matrix (2.8) solved for d(f_Y, f_Z)/d(omega_X).
  const double k = m.I_X * t * omega_Y0 + m.I_Z * omega_Z0;
  const double det = m.I_X * m.I_Z + M * (m.I_X * A * A + m.I_Z * B * B);
  const double alpha = ((m.I_Z + M * A * A) * k + M * m.I_Z * B * G_X) / det;  // (5.6)
  const double beta = M * A * (m.I_X * G_X - B * k) / det;
  const double dfdTheta = -m.I_X * omega_Y0 * omega_Y0 / (co * co) -
                          M * omega_Y0 * (B * V / (co * co) + L * rho * (omega_Y0 * co - omega_Z0 * s)) +
                          M * m.g * (H - rho);  // (5.7)
  const double dfdOmega_Y = -m.I_Z * omega_Z0 - 2 * m.I_X * t * omega_Y0 - M * L * (A * omega_Z0 + 2 * B * omega_Y0);
  const double dfdOmega_Z = -(m.I_Z + M * A * L) * omega_Y0;
  return -(dfdTheta + alpha * dfdOmega_Y + beta * dfdOmega_Z) / (m.I_X + M * (A * A + B * B));  // (5.8)
}

}  // namespace

CoinState straightRolling(double omega_Z) { return {.omega_Z = omega_Z}; }

CoinState straightRolling(const CoinModel& m, double omega_Z) {
  refuseUprightCorner(m.rim, "steady state straight");
  return straightRolling(omega_Z);
}

double criticalSpin(const CoinModel& m) {
  if (!m.rim.thin()) {
    refuseUprightCorner(m.rim, "critical spin");
    // (5.9): near upright G rises like (a - rho) cos(theta) + rho, so gravity's lever is a - rho.
    const double Ma2 = m.M * m.a * m.a;
    return std::sqrt(m.M * m.g * (m.a - m.rim.edgeRadius) * m.I_X / (m.I_Z * (m.I_Z + Ma2)));
  }
  const double Ma2 = m.M * m.a * m.a;
  return std::sqrt(m.M * m.g * m.a * m.I_X / (m.I_Z * (m.I_Z + Ma2)));
}

CoinState spinInPlace(const CoinModel& m, double theta) {
  requireTiltBelowFlat(theta);
  if (theta == 0) {
    throw std::invalid_argument(
        "steady state spin-in-place: theta must be non-zero (an upright coin cannot spin in place on its rim)");
  }
  if (!m.rim.thin()) return rimSpinInPlace(m, theta);
  return {.theta = theta, .omega_Y = std::sqrt(m.M * m.g * m.a * std::cos(theta) / m.I_X)};
}

CoinState steadyCircle(const CoinModel& m, double theta, double omega_Z, int branch) {
  requireTiltBelowFlat(theta);
  if (branch != 1 && branch != -1) {
    throw std::invalid_argument("steady state circle: branch must be +1 or -1, got " + std::to_string(branch));
  }
  if (!m.rim.thin()) return rimSteadyCircle(m, theta, omega_Z, branch);
  // A w^2 + B w + C = 0 for w = omega_Y (seed 5.2, general inertia).
  const double A = m.I_X * std::tan(theta);
  const double B = (m.I_Z + m.M * m.a * m.a) * omega_Z;
  const double C = -m.M * m.g * m.a * std::sin(theta);
  if (A == 0) {
    if (branch == -1) {
      throw std::invalid_argument(
          "steady state circle: the f- branch has no finite omega_Y at theta = 0 (use theta != 0 or branch +)");
    }
    return straightRolling(omega_Z);
  }
  // D >= 0 because A C <= 0 for |theta| < 90 deg.
  return {.theta = theta, .omega_Y = steadyOmegaY(A, B, C, branch), .omega_Z = omega_Z};
}

double steadyResidual(const CoinModel& m, const CoinState& s) {
  if (!m.rim.thin()) {
    const RimTilt r = rimTilt(m, s.theta);
    return rimP(m, r) * s.omega_Y * s.omega_Y + rimQ(m, r) * s.omega_Z * s.omega_Y - m.M * m.g * r.Lambda;  // (5.1)
  }
  return m.I_X * std::tan(s.theta) * s.omega_Y * s.omega_Y + (m.I_Z + m.M * m.a * m.a) * s.omega_Z * s.omega_Y -
         m.M * m.g * m.a * std::sin(s.theta);
}

double wobbleStiffness(const CoinModel& m, double theta0, double omega_Y0, double omega_Z0) {
  if (!m.rim.thin()) return rimWobbleStiffness(m, theta0, omega_Y0, omega_Z0);
  const double Ma2 = m.M * m.a * m.a, Mga = m.M * m.g * m.a;
  const double tanTheta = std::tan(theta0), cosTheta = std::cos(theta0);
  // Perturbations of omega_Y and omega_Z follow the tilt: d(omega_Y) = alpha d(theta),
  // d(omega_Z) = beta d(theta) (linearised eqs. 15, 16 with d(theta)-dot = d(omega_X)).
  const double alpha = (m.I_X * omega_Y0 * tanTheta + m.I_Z * omega_Z0) / m.I_X;  // (3.3)
  const double beta = Ma2 * omega_Y0 / (m.I_Z + Ma2);                             // (3.4)
  // Linearised eq. (14): (I_X + M a^2) d(theta)'' = -K (I_X + M a^2) d(theta).
  return ((m.I_Z + Ma2) * (omega_Z0 * alpha + omega_Y0 * beta) + 2 * m.I_X * omega_Y0 * tanTheta * alpha +
          m.I_X * omega_Y0 * omega_Y0 / (cosTheta * cosTheta) - Mga * cosTheta) /
         (m.I_X + Ma2);  // (3.6)
}

CircleRadii circleRadii(const CoinModel& m, const CoinState& s) {
  const double phiDot = precessionRate(s);
  if (phiDot == 0) {
    return {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  }
  if (!m.rim.thin()) {
    // (5.10): G moves at |A omega_Z + B omega_Y|, the contact point at A |psi-dot|.
    const RimTilt r = rimTilt(m, s.theta);
    return {std::abs(r.A * s.omega_Z + r.B * s.omega_Y) / std::abs(phiDot), r.A * std::abs(spinRate(s) / phiDot)};
  }
  return {m.a * std::abs(s.omega_Z / phiDot), m.a * std::abs(spinRate(s) / phiDot)};
}

TiltStability tiltStability(double K) {
  if (K > 0)
    return {.kind = TiltStability::Kind::Stable, .rate = std::sqrt(K), .time = 2 * std::numbers::pi / std::sqrt(K)};
  if (K < 0) return {.kind = TiltStability::Kind::Unstable, .rate = std::sqrt(-K), .time = 1 / std::sqrt(-K)};
  return {};
}

std::string_view verdictName(TiltStability::Kind kind) {
  switch (kind) {
    case TiltStability::Kind::Stable: return "stable";
    case TiltStability::Kind::Unstable: return "unstable";
    case TiltStability::Kind::Marginal: break;
  }
  return "marginal";
}

SteadyReport steadyReport(const CoinModel& model, const CoinState& s) {
  const bool cornered = !model.rim.thin() && !model.rim.fullyRounded();
  const double K = wobbleStiffness(model, s.theta, s.omega_Y, s.omega_Z);
  return {.naturalRate = naturalRate(model),
          .criticalSpin = cornered ? std::nullopt : std::optional(criticalSpin(model)),
          .precessionRate = precessionRate(s),
          .spinRate = spinRate(s),
          .radii = circleRadii(model, s),
          .reaction = reaction(model, s),
          .stiffness = K,
          .stability = tiltStability(K)};
}

}  // namespace coinroll::physics
