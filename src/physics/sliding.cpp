#include "physics/sliding.h"

#include <cmath>
#include <limits>
#include <string>
#include <optional>
#include <utility>

#include "physics/body_contact.h"
#include "physics/effects.h"

namespace coinroll::physics {

namespace {

// Sherman-Morrison's passes converge in one or two for a couple that changes N by a part in 1e4;
// the cap only guards a law whose couple is steep in N.
constexpr int kMaxNormalForcePasses = 6;

struct Sliding {
  ContactGeometry geo;
  Eigen::Vector3d spinAtContact;    // floor: omega x c
  Eigen::Vector3d cDot;             // material derivative of c
  Eigen::Vector3d velocity;         // floor: (v_x, from the held contact, v_z)  (docs/sliding.md eq. 1.2)
  Eigen::Vector3d slip;             // floor, horizontal: v + omega x c          (1.3)
  Eigen::Vector3d slipHat;          // floor, unit
  double N0 = 0;                    // N, the normal force without omega-dot's part (1.5)
  Eigen::Vector3d m, k;             // body: c x e_y and c x (e_y - mu s_hat)     (1.6)
  Eigen::Vector3d inverseInertiaK;  // body: I_G^-1 k
  double D = 1;                     // the normal effective mass (3.2)
};

// The terms the friction's direction leaves alone: everything but slipHat and k.
Sliding undirectedTerms(const CoinModel& model, const SlidingState& state) {
  const QuaternionState& s = state.attitude;
  Sliding t;
  t.geo = contactGeometry(model, s.q);
  const Eigen::Matrix3d& R = t.geo.floorFromBody;
  const Eigen::Vector3d& w = s.omegaBody;
  const Eigen::Vector3d& c = t.geo.c;
  t.cDot = contactDrift(model, t.geo, w);
  const Eigen::Vector3d& spinAtContact = t.spinAtContact = R * w.cross(c);
  t.slip = Eigen::Vector3d(state.slip.x(), 0, state.slip.y());  // horizontal: the held contact (1.2)
  t.velocity = t.slip - spinAtContact;
  const Eigen::Vector3d& u = t.geo.up;
  t.N0 = model.M * model.g - model.M * w.cross(t.cDot + w.cross(c)).dot(u);
  t.m = c.cross(u);
  return t;
}

void directFriction(const CoinModel& model, Sliding& t, double mu, const Eigen::Vector3d& slipHat) {
  t.slipHat = slipHat;
  t.k = t.geo.c.cross(t.geo.up - mu * t.geo.floorFromBody.transpose() * slipHat);
  t.inverseInertiaK = Eigen::Vector3d(t.k.x() / model.I_X, t.k.y() / model.I_X, t.k.z() / model.I_Z);
  t.D = 1 + model.M * t.m.dot(t.inverseInertiaK);
}

Sliding slidingTerms(const CoinModel& model, const SlidingState& state, double mu,
                     const Eigen::Vector3d& slipDirection) {
  Sliding t = undirectedTerms(model, state);
  const double speed = t.slip.norm();
  directFriction(model, t, mu, speed > kSlipRoundOff ? Eigen::Vector3d(t.slip / speed) : slipDirection);
  return t;
}

// (1.7): [I_G + M k m^t] omega-dot = -omega x I_G omega + N0 k + tau is a rank-one update of the
// diagonal I_G, solved by Sherman-Morrison (3.2): with b its right-hand side, m . omega-dot =
// m . I_G^-1 b / D, so N = N0 - M m . I_G^-1 b / D (1.5) and omega-dot = I_G^-1 (b - M k (m . omega-dot)).
void solve(const CoinModel& model, const Sliding& t, const Eigen::Vector3d& w, const Eigen::Vector3d& torqueBody,
           Eigen::Vector3d& dOmega, double& N) {
  const Eigen::Vector3d inertia(model.I_X, model.I_X, model.I_Z);
  const Eigen::Vector3d b = -w.cross(inertia.cwiseProduct(w)) + t.N0 * t.k + torqueBody;
  const double mOmegaDot = t.m.dot(b.cwiseQuotient(inertia)) / t.D;
  dOmega = b.cwiseQuotient(inertia) - model.M * mOmegaDot * t.inverseInertiaK;
  N = t.N0 - model.M * mOmegaDot;
}

struct Accelerations {
  Eigen::Vector3d dOmega;
  double N = 0;
  Loads loads;  // the effects' torque and power at N
};

// The effects' loads of a state: everything the laws read but N is fixed by the attitude.
NormalForceLoads effectLoadsOf(const CoinModel& model, const SlidingState& state, const Sliding& t) {
  const Eigen::Matrix3d& R = t.geo.floorFromBody;
  return {model.effects,
          {.e_X = R * t.geo.e_X,
           .e_Y = R * t.geo.e_Y,
           .e_Z = R.col(2),
           .omega = R * state.attitude.omegaBody,
           .faceRadius = model.a - model.rim.edgeRadius,
           .outerRadius = model.a,
           .holeRadius = model.holeRadius,
           .N = 0}};
}

Accelerations accelerations(const CoinModel& model, const SlidingState& state, const Sliding& t,
                            const NormalForceLoads& effectLoads) {
  const QuaternionState& s = state.attitude;
  const Eigen::Matrix3d& R = t.geo.floorFromBody;
  Accelerations a;
  solve(model, t, s.omegaBody, Eigen::Vector3d::Zero(), a.dOmega, a.N);
  if (!model.effects.empty()) {
    for (int pass = 0; pass < kMaxNormalForcePasses; ++pass) {
      const double triedN = a.N;
      a.loads = effectLoads.at(triedN);
      solve(model, t, s.omegaBody, R.transpose() * a.loads.torque, a.dOmega, a.N);
      if (a.N == triedN) break;
    }
  }
  return a;
}

// ds/dt = a_G + d(omega x c)/dt, the latter in the turning body frame (docs/sliding.md eq. 4.1);
// horizontally a_G is friction's alone (1.8).
Eigen::Vector2d slipRate(const CoinModel& model, const Sliding& t, const Eigen::Vector3d& w,
                         const Eigen::Vector3d& dOmega, double N, double mu) {
  const Eigen::Vector3d friction = N * (Eigen::Vector3d::UnitY() - mu * t.slipHat);
  const ContactGeometry& geo = t.geo;
  const Eigen::Vector3d spinRate =
      geo.floorFromBody * (dOmega.cross(geo.c) + w.cross(t.cDot) + w.cross(w.cross(geo.c)));
  return {friction.x() / model.M + spinRate.x(), friction.z() / model.M + spinRate.z()};
}

Forward forwardFrom(const CoinModel& model, const SlidingState& state, double mu, const Sliding& t) {
  const QuaternionState& s = state.attitude;
  Forward f;
  const NormalForceLoads effectLoads = effectLoadsOf(model, state, t);
  const Accelerations a = accelerations(model, state, t, effectLoads);
  f.dOmega = a.dOmega;
  f.loads = a.loads;
  const double N = a.N;
  f.normalEffectiveMass = t.D;
  f.reaction.R = N * (Eigen::Vector3d::UnitY() - mu * t.slipHat);
  f.reaction.N = N;
  f.reaction.F = mu * std::abs(N);
  f.slip = t.slip;
  f.sliding = true;
  f.loads.power += mu * N * t.slipHat.dot(t.slip);  // friction's work rate -F . s (2.1)
  setAttitudeKinematics(model, s.q, s.omegaBody, s.x, s.z, t.geo, t.velocity, f);
  return f;
}

SlidingRates ratesFrom(const CoinModel& model, const SlidingStateVec& y, const SlidingState& state,
                       const Sliding& terms, double mu) {
  const Eigen::Quaterniond stored(y[kQw], y[kQx], y[kQy], y[kQz]);
  const Forward f = forwardFrom(model, state, mu, terms);
  SlidingRates rates;
  SlidingStateVec& dy = rates.dy;
  // q-dot as in the rolling formulation (docs/quaternion_formulation.md eq. 4.1), norm pulled back to 1.
  const Eigen::Quaterniond& q = state.attitude.q;
  const Eigen::Vector3d& w = state.attitude.omegaBody;
  const Eigen::Quaterniond spin = q * Eigen::Quaterniond(0, w.x(), w.y(), w.z());
  const double restoring = naturalRate(model) * (1 - stored.squaredNorm());
  dy[kQw] = 0.5 * spin.w() + restoring * q.w();
  dy[kQx] = 0.5 * spin.x() + restoring * q.x();
  dy[kQy] = 0.5 * spin.y() + restoring * q.y();
  dy[kQz] = 0.5 * spin.z() + restoring * q.z();
  dy.segment<3>(kOmegaBody1) = f.dOmega;
  dy[kCentreX] = f.velocity.x();
  dy[kCentreZ] = f.velocity.z();
  dy.tail<2>() = slipRate(model, terms, w, f.dOmega, f.reaction.N, mu);
  rates.power = f.loads.power;
  return rates;
}

}  // namespace

SlidingStateVec toVector(const SlidingState& s) {
  SlidingStateVec y;
  y << toVector(s.attitude), s.slip;
  return y;
}

SlidingState toSlidingState(const SlidingStateVec& y) {
  return {.attitude = toQuaternionState(y.head<kQuaternionStateSize>()), .slip = y.tail<2>()};
}

Eigen::Vector2d slipOf(const CoinModel& model, const QuaternionState& attitude, const Eigen::Vector2d& velocity) {
  const ContactGeometry geo = contactGeometry(model, attitude.q);
  const Eigen::Vector3d spinAtContact = geo.floorFromBody * attitude.omegaBody.cross(geo.c);
  return velocity + Eigen::Vector2d(spinAtContact.x(), spinAtContact.z());
}

SlidingRates slidingRates(const CoinModel& model, const SlidingStateVec& y, double mu,
                          const Eigen::Vector3d& slipDirection) {
  const SlidingState state = toSlidingState(y);
  return ratesFrom(model, y, state, slidingTerms(model, state, mu, slipDirection), mu);
}

Forward slidingForward(const CoinModel& model, const SlidingState& state, double mu,
                       const Eigen::Vector3d& slipDirection) {
  return forwardFrom(model, state, mu, slidingTerms(model, state, mu, slipDirection));
}

namespace {

// Newton on the direction's angle converges in three or four passes from the rolling friction's
// direction; more means the rest has gone (the caller is told).
constexpr int kMaxCreepPasses = 12;
constexpr double kAngleStep = 1e-7;        // rad, for the central difference in the angle
constexpr double kAngleConverged = 1e-13;  // rad
// s: the step along the motion for the rest's turn rate; its error is (turn rate x step)^2 ~ 1e-7.
constexpr double kFlowStep = 1e-6;
// A pull on the direction below this part of mu g is round-off, not a rest: an upright coin rolling
// straight needs no friction and leaves every direction neutral.
constexpr double kLeastRestoring = 1e-9;

Eigen::Vector3d floorDirection(double angle) { return {std::cos(angle), 0, std::sin(angle)}; }
double angleOf(const Eigen::Vector2d& slip) { return std::atan2(slip.y(), slip.x()); }

// The terms with friction along -slipHat whatever the slip's own direction.
Sliding termsAlong(const CoinModel& model, const SlidingState& state, double mu, const Eigen::Vector3d& slipHat) {
  Sliding terms = undirectedTerms(model, state);
  directFriction(model, terms, mu, slipHat);
  return terms;
}

SlidingRates ratesAlong(const CoinModel& model, const SlidingStateVec& y, double mu, double angle) {
  const SlidingState state = toSlidingState(y);
  return ratesFrom(model, y, state, termsAlong(model, state, mu, floorDirection(angle)), mu);
}

// s_perp . s-dot with friction along -s_hat(angle), of one state at any angle: the slip's turn rate
// times |s|. The search for the rest asks it at some twenty angles, so what the angle leaves alone
// (the contact's geometry, N0) is computed once, and of the rates only the slip's.
class Turning {
 public:
  Turning(const CoinModel& model, const SlidingStateVec& y, double mu)
      : model_(model),
        state_(toSlidingState(y)),
        undirected_(undirectedTerms(model, state_)),
        effectLoads_(effectLoadsOf(model, state_, undirected_)),
        mu_(mu) {}

  double operator()(double angle) const {
    const Eigen::Vector2d rate = slipRateAt(angle);
    return -std::sin(angle) * rate.x() + std::cos(angle) * rate.y();
  }

  // s-dot (floor x, z) with friction along -s_hat(angle).
  Eigen::Vector2d slipRateAt(double angle) const {
    Sliding terms = undirected_;
    directFriction(model_, terms, mu_, floorDirection(angle));
    const Accelerations a = accelerations(model_, state_, terms, effectLoads_);
    return slipRate(model_, terms, state_.attitude.omegaBody, a.dOmega, a.N, mu_);
  }

  double restoringAt(double angle) const {
    return -((*this)(angle + kAngleStep) - (*this)(angle - kAngleStep)) / (2 * kAngleStep);
  }

  double mu() const { return mu_; }
  const CoinModel& model() const { return model_; }

 private:
  const CoinModel& model_;
  SlidingState state_;
  Sliding undirected_;
  NormalForceLoads effectLoads_;
  double mu_;
};

// Newton for turning(angle) = target from `angle`: the angle and the restoring there, or nothing when
// it finds no attracting rest. `lastChange` is the step that brought the angle there, when known.
//
// Converged once the next change would be below kAngleConverged: by the change itself, or, in
// Newton's quadratic regime (a change a hundredth of the last or less), by the next change it
// predicts, change^2 x (change / lastChange^2): the pass that only confirms a change of 1e-9 rad
// costs three evaluations and moves the angle by 1e-16.
std::optional<std::pair<double, double>> solveTurning(const Turning& turning, double angle, double target,
                                                      double lastChange = std::numeric_limits<double>::infinity()) {
  for (int pass = 0; pass <= kMaxCreepPasses && std::isfinite(angle); ++pass) {
    const double restoring = turning.restoringAt(angle);
    const double change = (turning(angle) - target) / restoring;
    angle += change;
    const double ratio = std::isfinite(lastChange) ? std::abs(change / lastChange) : 1.0;
    const double nextChange = ratio < 1e-2 ? std::abs(change) * ratio * ratio : std::abs(change);
    if (nextChange < kAngleConverged && restoring > kLeastRestoring * turning.mu() * turning.model().g)
      return std::pair{angle, restoring};
    lastChange = change;
  }
  return std::nullopt;
}

}  // namespace

std::optional<Creep> findCreep(const CoinModel& model, const SlidingStateVec& y, double mu,
                               const std::optional<Eigen::Vector3d>& neutralStart) {
  // Newton starts against the rolling friction force (the contract's direction at a slide's onset);
  // where rolling needs next to no friction that direction is noise, and the caller's or the slip's
  // own is taken.
  const Forward rolling = forward(model, toQuaternionState(y.head<kQuaternionStateSize>()));
  const Eigen::Vector3d& rollingFriction = rolling.reaction.R;
  const Eigen::Vector2d slip = y.tail<2>();
  const bool neutral = Eigen::Vector2d(rollingFriction.x(), rollingFriction.z()).norm() <
                       kLeastRestoring * mu * std::abs(rolling.reaction.N);
  double start = std::atan2(-rollingFriction.z(), -rollingFriction.x());
  if (neutral && neutralStart) {
    start = std::atan2(neutralStart->z(), neutralStart->x());
  } else if (neutral && slip.norm() > kSlipRoundOff) {
    start = angleOf(slip);
  }
  const Turning turning(model, y, mu);
  const auto rest = solveTurning(turning, start, 0);
  if (!rest) return std::nullopt;
  const auto [restAngle, restoring] = *rest;
  // The rest turns with the motion; a slip that keeps up with it must turn at the same rate, which
  // takes turning(angle) = |s| x (its rate): the rest to first order in the lag (docs/sliding.md eq. 4.14).
  const SlidingStateVec flow = ratesAlong(model, y, mu, restAngle).dy;
  const double restRate =
      (Turning(model, y + kFlowStep * flow, mu)(restAngle) - Turning(model, y - kFlowStep * flow, mu)(restAngle)) /
      (2 * kFlowStep * restoring);
  // The lag grows or shrinks with the slip, at the slip's own rate along the rest, which is a friction
  // acceleration like `restoring`, not a small correction: the slow direction trails the rest by
  // |s| restRate / (restoring + slipRate) (docs/sliding.md eq. 4.17), and exists only while that sum
  // pulls. Without the slip's rate the lag was wrong at first order in |s| (1.2e-4 rad at the hand-over
  // on the coin toss, against 2e-7 rad with it).
  const double slipRate = std::cos(restAngle) * flow[kSlipX] + std::sin(restAngle) * flow[kSlipZ];
  const double pull = restoring + slipRate;
  if (!(pull > 0)) return std::nullopt;
  // The slip along the rest, signed: the lag shrinks to zero with it and changes sign past it, smoothly,
  // where |s| put a kink into a creeping slide's right-hand side at its stop.
  const double slipAlong = slip.x() * std::cos(restAngle) + slip.y() * std::sin(restAngle);
  double angle = restAngle;
  if (slipAlong != 0) {
    const double target = slipAlong * restRate * restoring / pull;
    // Newton's first step costs nothing: at the rest turning is 0 and its slope is -restoring.
    const double lag = -target / restoring;
    const auto lagging = solveTurning(turning, restAngle + lag, target, lag);
    if (!lagging) return std::nullopt;
    angle = lagging->first;
  }
  return Creep{.slipHat = floorDirection(angle), .restoring = restoring, .restRate = restRate, .pull = pull};
}

SlidingRates slidingRatesAlong(const CoinModel& model, const SlidingStateVec& y, double mu,
                               const Eigen::Vector3d& slipHat) {
  const SlidingState state = toSlidingState(y);
  return ratesFrom(model, y, state, termsAlong(model, state, mu, slipHat), mu);
}

Forward slidingForwardAlong(const CoinModel& model, const SlidingState& state, double mu,
                            const Eigen::Vector3d& slipHat) {
  return forwardFrom(model, state, mu, termsAlong(model, state, mu, slipHat));
}

double slipDirectionPull(const CoinModel& model, const SlidingState& state, double mu) {
  const double angle = angleOf(state.slip);
  const Turning turning(model, toVector(state), mu);
  const Eigen::Vector2d rate = turning.slipRateAt(angle);
  return turning.restoringAt(angle) + std::cos(angle) * rate.x() + std::sin(angle) * rate.y();
}

}  // namespace coinroll::physics
