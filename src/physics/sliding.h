#pragma once
// The sliding coin (docs/sliding.md): the contact held on the floor (N from the unilateral
// constraint), its material point slipping, Coulomb friction F = -mu N s_hat along the slip, the
// centre of mass's horizontal velocity free. Carried by the quaternion formulation only: it is the
// one that reaches a spin-down's landing, where an Euler's disk slides (docs/sliding.md §1).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <optional>

#include "physics/coin_model.h"
#include "physics/forward.h"
#include "physics/quaternion_dynamics.h"

namespace coinroll::physics {

// The slip, not the centre's velocity, is state: near zero slip, where friction's direction is
// decided, it is then integrated to its own relative accuracy instead of being the small difference
// of two integrated velocities, v + omega x c, whose errors would turn its direction at random
// (docs/sliding.md §4).
struct SlidingState {
  QuaternionState attitude;                        // q, omegaBody, centre (x, z) on the floor plane
  Eigen::Vector2d slip = Eigen::Vector2d::Zero();  // m/s, (x, z) of the contact's material velocity
};

inline constexpr int kSlidingStateSize = kQuaternionStateSize + 2;
using SlidingStateVec = Eigen::Matrix<double, kSlidingStateSize, 1>;
enum SlidingStateIndex : int { kSlipX = kQuaternionStateSize, kSlipZ };

// The slip of a coin in `attitude` whose centre moves at (v_x, v_z) on the floor, m/s.
Eigen::Vector2d slipOf(const CoinModel& model, const QuaternionState& attitude, const Eigen::Vector2d& velocity);

SlidingStateVec toVector(const SlidingState& state);
SlidingState toSlidingState(const SlidingStateVec& y);

// The forward pass while sliding with kinetic coefficient `mu`. `slipDirection` (unit, horizontal,
// floor components) stands for s_hat while the slip speed is below round-off: at the switch from
// rolling, where s = 0 and the contract takes it opposite to the rolling friction force.
// Forward::slip, ::sliding and ::normalEffectiveMass are set.
Forward slidingForward(const CoinModel& model, const SlidingState& state, double mu,
                       const Eigen::Vector3d& slipDirection);

// The normal effective mass D at which a sliding run stops with `painleve` (docs/sliding.md §3.1).
// N = (N0 - ...) / D, so a slide driven towards D = 0 with a positive numerator meets an unbounded
// normal force before it: N ~ 1 / (t* - t), and the integrator's steps shrink to nothing short of
// t*. At D = 1e-3 the held contact already needs about a thousand times its static load.
inline constexpr double kPainleveMargin = 1e-3;

// dy/dt and the power dissipated (the effects' and friction's mu N |s|), W.
struct SlidingRates {
  SlidingStateVec dy;
  double power = 0;
};
SlidingRates slidingRates(const CoinModel& model, const SlidingStateVec& y, double mu,
                          const Eigen::Vector3d& slipDirection);

// The creeping slide (docs/sliding.md §4.6). Where the rolling reaction sits just outside the
// friction cone the slip stays tiny and its direction is slaved to the slow motion: it turns back
// to a rest at the rate restoring / |s|, far faster than anything else in the motion, which no
// explicit step can follow. While the slip is that small friction is taken along the rest instead
// of along the slip (a Tikhonov reduction to first order in the lag, (turn rate) |s| / restoring):
// the slip, the centre's velocity and the energy stay integrated from the forces, so momentum and
// the energy budget hold exactly, and only friction's direction is approximated.
struct Creep {
  Eigen::Vector3d slipHat;  // floor, unit, horizontal: friction is along -slipHat
  double restoring = 0;     // -d(s_perp . s-dot)/d(angle) at the rest, m/s^2 (positive: it attracts)
  double restRate = 0;      // rad/s, the rest's turn rate
  // m/s^2: restoring plus the slip's rate along the rest, which pulls on the lag as well: the lag is
  // |s| restRate / pull (docs/sliding.md eq. 4.17); positive wherever a Creep is found.
  double pull = 0;
};
// std::nullopt when there is no attracting rest next to the direction opposite the rolling friction
// force, or when the slip closes along it faster than the rest pulls (pull <= 0: no slow direction).
// Where rolling needs next to no friction (an upright coin rolling straight: every direction is
// neutral) the search starts from `neutralStart` when given, else from the slip's own direction:
// a creeping segment passes its own so that the rest keeps its side while the slip passes zero.
std::optional<Creep> findCreep(const CoinModel& model, const SlidingStateVec& y, double mu,
                               const std::optional<Eigen::Vector3d>& neutralStart = std::nullopt);

// The sliding coin with friction along -slipHat whatever the slip's own direction (the creeping slide).
SlidingRates slidingRatesAlong(const CoinModel& model, const SlidingStateVec& y, double mu,
                               const Eigen::Vector3d& slipHat);
Forward slidingForwardAlong(const CoinModel& model, const SlidingState& state, double mu,
                            const Eigen::Vector3d& slipHat);

// Creep::pull as if the rest were at the slip's own direction, m/s^2: -d(s_perp . s-dot)/d(angle)
// there plus s_hat . s-dot. Near a rest it is the rest's pull to a part in 1e5.
double slipDirectionPull(const CoinModel& model, const SlidingState& state, double mu);

// m/s: speeds below this are the slip's round-off, not a direction (docs/sliding.md §4).
inline constexpr double kSlipRoundOff = 1e-13;

}  // namespace coinroll::physics
