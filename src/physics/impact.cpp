#include "physics/impact.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

namespace coinroll::physics {

namespace {

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitY();

// The impact's steps per the frictionless compression's impulse: the slip's direction turns over
// an impact by at most a right angle or so, which the classical Runge-Kutta method follows to
// ~1e-9 in 64 steps (docs/flight.md §3; the energy booked does not depend on it, eq. 3.3).
constexpr int kStepsPerCompression = 64;
constexpr int kMaxSteps = 100 * kStepsPerCompression;
// Bisections locating an end inside a step: the step's fraction to 2^-60.
constexpr int kBisections = 60;
// A slip below this fraction of the approach speed has stopped: reached by halving steps towards
// the stop, about 40 of them from a slip the size of the approach.
constexpr double kStoppedSlip = 1e-13;
// The slip's direction counts as settled when it turns at most this fraction of the rate its length
// closes at: the rest of the way to zero is then a straight line.
constexpr double kSettledTurn = 1e-9;
// Directions tried when the slip restarts from zero, before the ray's own is bisected.
constexpr int kRayDirections = 720;

Eigen::Matrix3d skew(const Eigen::Vector3d& r) {
  Eigen::Matrix3d s;
  s << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return s;
}

Eigen::Vector3d horizontal(const Eigen::Vector3d& u) { return {u.x(), 0, u.z()}; }

// The contact point's stages within one impulse (eq. 3.4), not the run's contact modes (contact_mode.h).
enum class ImpactContact { Slipping, Sticking, Ray };

// How the tangential impulse grows with the normal one (eq. 3.4): along -mu s_hat while slipping,
// at the fixed ratio tau* while sticking or slipping along a ray.
struct ImpulseMode {
  ImpactContact contact = ImpactContact::Slipping;
  Eigen::Vector3d ratio = Eigen::Vector3d::Zero();  // tau, horizontal, for Sticking and Ray
};

// At normal impulse p along the impact.
struct ImpulsePath {
  Eigen::Vector3d u = Eigen::Vector3d::Zero();  // m/s, the contact point's velocity
  Eigen::Vector3d P = Eigen::Vector3d::Zero();  // N s, impulse so far
  double work = 0;                              // J, W_n: the normal impulse's work so far
};

Eigen::Vector3d impulseRate(const ImpulseMode& mode, const Eigen::Vector3d& u, double mu) {
  if (mode.contact != ImpactContact::Slipping) return kUp + mode.ratio;
  const Eigen::Vector3d slip = horizontal(u);
  const double speed = slip.norm();
  return speed > 0 ? Eigen::Vector3d(kUp - mu * slip / speed) : kUp;
}

ImpulsePath step(const ImpulsePath& s, double dp, const ImpulseMode& mode, const Eigen::Matrix3d& K, double mu) {
  const auto rate = [&](const Eigen::Vector3d& u) { return impulseRate(mode, u, mu); };
  const Eigen::Vector3d r1 = rate(s.u);
  const Eigen::Vector3d u2 = s.u + 0.5 * dp * K * r1;
  const Eigen::Vector3d r2 = rate(u2);
  const Eigen::Vector3d u3 = s.u + 0.5 * dp * K * r2;
  const Eigen::Vector3d r3 = rate(u3);
  const Eigen::Vector3d u4 = s.u + dp * K * r3;
  const Eigen::Vector3d r4 = rate(u4);
  const Eigen::Vector3d dP = dp / 6 * (r1 + 2 * r2 + 2 * r3 + r4);
  return {.u = s.u + K * dP, .P = s.P + dP, .work = s.work + dp / 6 * (s.u.y() + 2 * u2.y() + 2 * u3.y() + u4.y())};
}

// K_tt: K's block between the floor's two horizontal directions, x and z.
Eigen::Matrix2d tangentialBlock(const Eigen::Matrix3d& K) {
  Eigen::Matrix2d Ktt;
  Ktt << K(0, 0), K(0, 2), K(2, 0), K(2, 2);
  return Ktt;
}

// tau* = -K_tt^-1 K_tn: the tangential impulse per normal impulse that keeps the slip at zero.
Eigen::Vector3d stickingRatio(const Eigen::Matrix3d& K) {
  const Eigen::Vector2d tau = -tangentialBlock(K).inverse() * Eigen::Vector2d(K(0, 1), K(2, 1));
  return {tau.x(), 0, tau.y()};
}

// The direction s_hat along which a slip restarting from zero grows as a ray: the horizontal part
// of K (e_y - mu s_hat) along +s_hat (docs/flight.md §3). std::nullopt when there is none.
std::optional<Eigen::Vector3d> rayDirection(const Eigen::Matrix3d& K, double mu) {
  const auto direction = [](double beta) { return Eigen::Vector3d(std::cos(beta), 0, std::sin(beta)); };
  const auto growth = [&](double beta) { return horizontal(K * (kUp - mu * direction(beta))); };
  const auto across = [&](double beta) {
    const Eigen::Vector3d s = direction(beta), g = growth(beta);
    return s.x() * g.z() - s.z() * g.x();
  };
  std::optional<Eigen::Vector3d> best;
  double bestGrowth = 0;
  const double delta = 2 * std::numbers::pi / kRayDirections;
  for (int k = 0; k < kRayDirections; ++k) {
    double lo = k * delta, hi = lo + delta;
    if ((across(lo) > 0) == (across(hi) > 0)) continue;
    for (int i = 0; i < kBisections; ++i) {
      const double mid = 0.5 * (lo + hi);
      ((across(mid) > 0) == (across(lo) > 0) ? lo : hi) = mid;
    }
    const double along = growth(lo).dot(direction(lo));
    // Where several rays exist the fastest-growing is taken (docs/flight.md §3).
    if (along > bestGrowth) {
      bestGrowth = along;
      best = direction(lo);
    }
  }
  return best;
}

// The mode at zero slip: sticking when tau* fits the cone, else slipping along the ray.
std::optional<ImpulseMode> modeFromRest(const Eigen::Matrix3d& K, double mu) {
  const Eigen::Vector3d tau = stickingRatio(K);
  if (tau.norm() <= mu) return ImpulseMode{.contact = ImpactContact::Sticking, .ratio = tau};
  const std::optional<Eigen::Vector3d> ray = rayDirection(K, mu);
  if (!ray) return std::nullopt;
  return ImpulseMode{.contact = ImpactContact::Ray, .ratio = -mu * *ray};
}

}  // namespace

Eigen::Matrix3d contactCompliance(const CoinModel& m, const Eigen::Quaterniond& unitQ, const Eigen::Vector3d& r) {
  const Eigen::Matrix3d R = unitQ.toRotationMatrix();
  const Eigen::Matrix3d inverseInertia =
      R * Eigen::Vector3d(1 / m.I_X, 1 / m.I_X, 1 / m.I_Z).asDiagonal() * R.transpose();
  return Eigen::Matrix3d::Identity() / m.M - skew(r) * inverseInertia * skew(r);  // (3.2)
}

ImpactOutcome resolveImpact(const CoinModel& m, const FlightState& state, const ImpactLaw& law) {
  const Eigen::Vector3d r = lowestPointVector(m, state.q);
  const Eigen::Matrix3d K = contactCompliance(m, state.q, r);
  const Eigen::Vector3d u0 = pointVelocity(state, r);
  if (!(u0.y() < 0)) {
    throw std::logic_error("resolveImpact: the contact point does not approach (u_n = " + std::to_string(u0.y()) + ")");
  }
  const double mu = law.friction, e = law.restitution;
  ImpactOutcome outcome;
  outcome.approachSpeed = -u0.y();

  ImpulsePath s{.u = u0};
  // A slip below round-off of the approach has no direction of its own: the impact starts at rest.
  const double slipRoundOff = 1e-12 * u0.norm();
  ImpulseMode mode;
  if (horizontal(u0).norm() <= slipRoundOff) {
    s.u = Eigen::Vector3d(0, u0.y(), 0);
    const std::optional<ImpulseMode> rest = modeFromRest(K, mu);
    if (!rest) {
      outcome.jammed = true;
      return outcome;
    }
    mode = *rest;
  }
  const double dp = outcome.approachSpeed / K(1, 1) / kStepsPerCompression;
  const double directionStiffness =
      mu * Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(tangentialBlock(K)).eigenvalues().maxCoeff();
  bool compressing = true;
  double target = 0;  // W_n at which restitution ends, eq. (3.5)
  for (int steps = 0;; ++steps) {
    if (steps > kMaxSteps) throw std::runtime_error("resolveImpact: the impact did not end");
    if (compressing && (K * impulseRate(mode, s.u, mu)).y() <= 0) {
      outcome.jammed = true;
      return outcome;
    }
    // While slipping the step is at most half the slip's distance from zero at its rate of change,
    // so no step crosses zero, where friction's direction jumps: near a stop the steps shrink
    // geometrically and the slip is located at its zero to kStoppedSlip. The slip's direction turns
    // towards the one it stops along at a rate up to mu |K_tt| / |s|, stiff as |s| shrinks: a step of
    // more than |s| / (mu |K_tt|) leaves the direction oscillating about it, stuck at the bound of the
    // method's stability, and the slip shrinking by 0.3 % a step instead of converging (docs/flight.md §3).
    // Once the direction has settled (its turn rate below kSettledTurn of the closing rate) friction
    // keeps it, du/dp is constant, and one step reaches the stop exactly: near the cone's edge the slip
    // closes hundreds of times slower than (3.7) lets steps grow.
    double stepSize = dp;
    bool settled = false;
    ImpulseMode stepMode = mode;
    if (mode.contact == ImpactContact::Slipping) {
      const double slip = horizontal(s.u).norm();
      const Eigen::Vector3d slipRate = horizontal(K * impulseRate(mode, s.u, mu));
      const Eigen::Vector3d direction = horizontal(s.u) / slip;
      const double closing = -slipRate.dot(direction);
      const double turning = (slipRate + closing * direction).norm();
      settled = closing > 0 && turning <= kSettledTurn * closing;
      if (closing < 0 && turning <= kSettledTurn * -closing) {
        // A growing slip whose direction has settled is on a ray: friction along -s_hat makes the
        // slip's rate K (e_y - mu s_hat) point along s_hat, so the slip keeps s_hat for the rest of the
        // impact (docs/flight.md 3.9), exactly and at full steps. Held to (3.7) instead, a slip that
        // left zero behind (a reversal that passed close by) grew 0.05 % a step from 1e-5 m/s and the
        // impact "did not end".
        mode = ImpulseMode{.contact = ImpactContact::Ray, .ratio = -mu * direction};
        stepMode = mode;
      } else if (settled) {
        // Friction keeps the settled direction all the way to the stop, so the step holds it: the
        // rate re-read at the stop, where the slip has no direction, would drop up to a sixth of the
        // step's friction impulse, and an impact that sticks would gain energy (docs/flight.md 3.8).
        stepSize = std::min(dp, slip / closing);
        stepMode = ImpulseMode{.contact = ImpactContact::Ray, .ratio = -mu * direction};
      } else {
        if (slipRate.norm() > 0) stepSize = std::min(dp, 0.5 * slip / slipRate.norm());
        if (directionStiffness > 0) stepSize = std::min(stepSize, slip / directionStiffness);
      }
    }
    const auto ended = [&](const ImpulsePath& x) {
      return compressing ? x.u.y() >= 0 : x.work >= target || x.u.y() < 0;
    };
    ImpulsePath next = step(s, stepSize, stepMode, K, mu);
    const bool reachesTheStop = settled && stepSize < dp && !ended(next);
    if (ended(next)) {
      double lo = 0, hi = 1;
      for (int i = 0; i < kBisections; ++i) {
        const double mid = 0.5 * (lo + hi);
        (ended(step(s, mid * stepSize, stepMode, K, mu)) ? hi : lo) = mid;
      }
      next = step(s, hi * stepSize, stepMode, K, mu);
    }
    s = next;
    if (mode.contact == ImpactContact::Slipping &&
        (reachesTheStop || horizontal(s.u).norm() <= kStoppedSlip * u0.norm())) {
      s.u = Eigen::Vector3d(0, s.u.y(), 0);
      const std::optional<ImpulseMode> rest = modeFromRest(K, mu);
      if (!rest) {
        outcome.jammed = true;
        return outcome;
      }
      mode = *rest;
    }
    if (compressing && s.u.y() >= 0) {
      compressing = false;
      target = (1 - e * e) * s.work;
    }
    if (!compressing && (s.work >= target || s.u.y() < 0)) break;
  }
  const Eigen::Matrix3d R = state.q.toRotationMatrix();
  const Eigen::Vector3d inertia(m.I_X, m.I_X, m.I_Z);
  outcome.impulse = s.P;
  outcome.after = state;
  outcome.after.velocity += s.P / m.M;  // (3.1)
  outcome.after.omegaBody += (R.transpose() * r.cross(s.P)).cwiseQuotient(inertia);
  const Eigen::Vector3d uAfter = u0 + K * s.P;
  outcome.reboundSpeed = std::max(0.0, uAfter.y());
  outcome.slipAfter = horizontal(uAfter);
  outcome.energyLost = -(s.P.dot(u0) + 0.5 * s.P.dot(K * s.P));  // (3.3)
  return outcome;
}

}  // namespace coinroll::physics
