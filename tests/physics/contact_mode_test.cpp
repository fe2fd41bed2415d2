// The table of contact modes (physics/contact_mode.h): every mode and transition leads where
// docs/sliding.md §4 and docs/flight.md §1-§5 say, and a transition a mode never makes is refused.

#include "physics/contact_mode.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "physics/quaternion_dynamics.h"
#include "physics/validity.h"
#include "tolerance.h"

namespace coinroll::physics {
namespace {

using coinroll::testing::isNear;

constexpr double kDeg = std::numbers::pi / 180;

// "creeping", "on-edge": a mode's name or an ending event's, for readable failures.
std::string nameOf(const Next& next) {
  if (const auto* mode = std::get_if<Mode>(&next)) return std::string(modeName(*mode));
  return std::string(eventName(std::get<ModelEvent>(next)));
}

CoinModel disk() {
  CoinModel m = diskModel(0.4, 0.0375, 9.81);
  m.friction = {.cone = 0.4, .kinetic = 0.3};
  return m;
}

// A coin tilted 25 degrees and at rest on the floor: it falls, and holding its contact point needs
// friction F / N = neededFriction.
Handover tiltedAtRest() {
  const QuaternionState q = fromEulerState(CoinState{.theta = 25 * kDeg});
  return {.t = 0.5, .state = {.attitude = q}, .forward = forward(disk(), q), .dissipated = 0.01};
}

double neededFriction(const CoinModel& m, const Handover& h) {
  const Forward rolling = forward(m, h.state.attitude);
  return rolling.reaction.F / rolling.reaction.N;
}

constexpr Mode kModes[] = {Mode::Rolling, Mode::Sliding, Mode::Creeping, Mode::Flight, Mode::Impact};
constexpr Transition kTransitions[] = {Transition::SlideOnset, Transition::SlipStops, Transition::SlipCreeps,
                                       Transition::SlipFrees,  Transition::LiftOff,   Transition::CornerLands,
                                       Transition::Touchdown,  Transition::Bounces,   Transition::BouncesEnd,
                                       Transition::BandRests,  Transition::LandsFlat, Transition::Jams};

struct Row {
  Mode mode;
  Transition transition;
  const char* leadsTo;  // nameOf the answer
};

// The rows whose answer the transition alone decides, with the reason.
const std::vector<Row> kFixedRows = {
    // A slide that starts from rolling starts creeping from zero slip (docs/sliding.md §4.5).
    {Mode::Rolling, Transition::SlideOnset, "creeping"},
    // The slip's direction too fast to integrate: friction along its rest; slow enough: along itself (§4.6).
    {Mode::Sliding, Transition::SlipCreeps, "creeping"},
    {Mode::Creeping, Transition::SlipFrees, "sliding"},
    // N through zero: the coin leaves the floor from every held contact (docs/flight.md §1).
    {Mode::Rolling, Transition::LiftOff, "flight"},
    {Mode::Sliding, Transition::LiftOff, "flight"},
    {Mode::Creeping, Transition::LiftOff, "flight"},
    // The other corner reaches the floor at upright with a finite normal velocity: an impact (§4a).
    {Mode::Rolling, Transition::CornerLands, "impact"},
    {Mode::Sliding, Transition::CornerLands, "impact"},
    {Mode::Creeping, Transition::CornerLands, "impact"},
    // The rim reaching the floor in flight strikes it (§2, §3).
    {Mode::Flight, Transition::Touchdown, "impact"},
    // A rebound at u_rest or faster leaves the floor again (§4).
    {Mode::Impact, Transition::Bounces, "flight"},
    // The band lies on the floor, and rolling on it is not modelled: the coin stands on its edge (§4a).
    {Mode::Impact, Transition::BandRests, "on-edge"},
    // Flat on a face at touch: it lies there (§5).
    {Mode::Impact, Transition::LandsFlat, "rest"},
    // No impact of this kind exists: the run cannot go on (§3, jam).
    {Mode::Impact, Transition::Jams, "impact-jam"},
};

// The rows whose answer the physics of the handover decides (the tests below).
bool decidedByPhysics(Mode mode, Transition transition) {
  return (transition == Transition::SlipStops && (mode == Mode::Sliding || mode == Mode::Creeping)) ||
         (transition == Transition::BouncesEnd && mode == Mode::Impact);
}

TEST(ContactModes, EachFixedRowLeadsWhereTheDocsSay) {
  for (const Row& row : kFixedRows) {
    EXPECT_EQ(nameOf(next(disk(), row.mode, row.transition, tiltedAtRest())), row.leadsTo)
        << modeName(row.mode) << " x " << transitionName(row.transition);
  }
}

TEST(ContactModes, ATransitionAModeNeverMakesIsRefused) {
  int refused = 0;
  for (const Mode mode : kModes) {
    for (const Transition transition : kTransitions) {
      const bool listed = std::any_of(kFixedRows.begin(), kFixedRows.end(),
                                      [&](const Row& row) { return row.mode == mode && row.transition == transition; });
      if (listed || decidedByPhysics(mode, transition)) continue;
      EXPECT_THROW(next(disk(), mode, transition, tiltedAtRest()), std::logic_error)
          << modeName(mode) << " x " << transitionName(transition);
      ++refused;
    }
  }
  // 5 modes x 12 transitions, less 14 fixed rows and 3 decided by the physics.
  EXPECT_EQ(refused, 60 - 14 - 3);
}

TEST(ContactModes, ASlideWhoseSlipStopsRollsWhereTheRollingReactionFitsTheStaticConeAndElseCreepsOn) {
  CoinModel m = disk();
  const Handover stopped = tiltedAtRest();
  const double needed = neededFriction(m, stopped);
  ASSERT_GT(needed, 0);
  for (const Mode slide : {Mode::Sliding, Mode::Creeping}) {
    m.friction.cone = 2 * needed;
    EXPECT_EQ(nameOf(next(m, slide, Transition::SlipStops, stopped)), "rolling") << modeName(slide);
    m.friction.cone = 0.5 * needed;
    EXPECT_EQ(nameOf(next(m, slide, Transition::SlipStops, stopped)), "creeping") << modeName(slide);
  }
}

TEST(ContactModes, BouncesEndInTheModeAStartOnTheFloorTakes) {
  CoinModel m = disk();
  Handover landed = tiltedAtRest();
  const double needed = neededFriction(m, landed);
  // A slip above the stopping slip slides, whatever the cone (docs/flight.md §4).
  landed.state.slip = Eigen::Vector2d(0.1, 0);
  EXPECT_EQ(nameOf(next(m, Mode::Impact, Transition::BouncesEnd, landed)), "sliding");
  // Below it the slip is dropped: rolling inside the static cone, creeping outside it.
  landed.state.slip = Eigen::Vector2d(0.5 * stoppedSlip(0), 0);
  m.friction.cone = 2 * needed;
  EXPECT_EQ(nameOf(next(m, Mode::Impact, Transition::BouncesEnd, landed)), "rolling");
  m.friction.cone = 0.5 * needed;
  EXPECT_EQ(nameOf(next(m, Mode::Impact, Transition::BouncesEnd, landed)), "creeping");
}

TEST(ContactModes, BouncesEndInFlightWhereTheFloorCannotHoldTheRim) {
  // Tipping over at 200 rad/s, the centre is swung up faster than gravity pulls it: the held contact
  // would need N < 0, so the coin flies on at once (docs/flight.md §4).
  const CoinModel m = disk();
  const QuaternionState tipping = fromEulerState(CoinState{.theta = 25 * kDeg, .omega_X = 200});
  const Handover landed{.t = 0.5, .state = {.attitude = tipping}, .forward = forward(m, tipping)};
  ASSERT_LE(liftOffMargin(m, heldContact(m, landed).forward), 0);
  EXPECT_EQ(nameOf(next(m, Mode::Impact, Transition::BouncesEnd, landed)), "flight");
}

TEST(ContactModes, AStoppedSlipsKineticEnergyIsDissipatedAndTheRollStartsWithoutIt) {
  const CoinModel m = disk();
  Handover sliding = tiltedAtRest();
  sliding.state.slip = Eigen::Vector2d(0.05, 0);  // a stop far coarser than s_stop, for the energy to show
  sliding.forward = slidingForward(m, sliding.state, m.friction.kinetic, Eigen::Vector3d::UnitX());
  const Handover rolling = handedOn(m, Transition::SlipStops, sliding);
  EXPECT_EQ(rolling.state.slip, Eigen::Vector2d::Zero());
  EXPECT_EQ(rolling.t, sliding.t);
  // Energy plus dissipated is kept across the stop (docs/sliding.md §4.5).
  EXPECT_TRUE(isNear(rolling.forward.energy + rolling.dissipated, sliding.forward.energy + sliding.dissipated, 1e-15));
  EXPECT_GT(rolling.dissipated, sliding.dissipated);
  // Other transitions hand the state on as it is.
  const Handover freed = handedOn(m, Transition::SlipFrees, sliding);
  EXPECT_EQ(freed.state.slip, sliding.state.slip);
  EXPECT_EQ(freed.dissipated, sliding.dissipated);
}

}  // namespace
}  // namespace coinroll::physics
