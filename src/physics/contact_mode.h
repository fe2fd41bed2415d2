#pragma once
// The contact modes of one coin and the transitions between them (docs/sliding.md §4, docs/flight.md
// §1-§5): what each mode is, what ends it, and `next`, the table of where each transition leads.
// Box2D names the stages of every contact (begin touch, touching, end touch) once for all shapes; a
// coin has one contact, so its table is sized to it. A run that chains the modes
// (pipeline/hybrid_run.h) integrates one mode at a time, locates its end with the margins below,
// and starts what `next` names from what `handedOn` hands it.

#include <string_view>
#include <variant>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "physics/coin_model.h"
#include "physics/flight.h"
#include "physics/forward.h"
#include "physics/sliding.h"
#include "physics/validity.h"

namespace coinroll::physics {

enum class Mode {
  Rolling,   // the contact point at rest on the floor (docs/quaternion_formulation.md)
  Sliding,   // friction along the slip (docs/sliding.md §1)
  Creeping,  // friction along the slip's rest, while the slip is too small for its own direction to be
             // integrated (docs/sliding.md §4.6): from zero slip, or a slip that has fallen back to it
  Flight,    // no contact: the free coin (docs/flight.md §1)
  Impact,    // the rim strikes the floor, an instant whose outcome is the transition out (docs/flight.md §3)
};

enum class Transition {
  // Located on a held contact (rolling, sliding or creeping).
  SlideOnset,  // rolling: the rolling reaction reaches the static cone (docs/sliding.md §4.2)
  SlipStops,   // sliding or creeping: the slip falls to s_stop (docs/sliding.md eq. 4.18)
  SlipCreeps,  // sliding: the slip's direction would turn too fast to be integrated (docs/sliding.md §4.6)
  SlipFrees,   // creeping: the slip has grown enough for its own direction to be integrated (§4.6)
  LiftOff,     // with flight: N falls through zero (docs/flight.md §1)
  // With flight, a cornered rim passing upright: the other corner strikes the floor (docs/flight.md §4a).
  CornerLands,
  // Located on a flight: the rim reaches the floor (docs/flight.md §2).
  Touchdown,
  // An impact's outcomes (docs/flight.md §3-§5).
  Bounces,     // the rim rebounds at u_n' >= u_rest (eq. 4.1)
  BouncesEnd,  // the rebound is below u_rest, or the impacts come faster than the run resolves: the
               // impact is made plastic and the rim stays on the floor (§4)
  BandRests,   // a corner's landing after which both corners move slower than u_rest, or past that
               // bound of impacts: the flat band between them lies on the floor (§4a)
  LandsFlat,   // the tilt at touch is below face-down's (§5)
  Jams,        // the impact has no solution (§3, jam)
};

// "rolling", "slide onset", ...: for messages.
std::string_view modeName(Mode mode);
std::string_view transitionName(Transition transition);

// What a mode hands to the next at a transition: the coin there, as one state.
struct Handover {
  double t = 0;           // s
  SlidingState state;     // the attitude and the contact's slip (in flight: the rim's lowest point's)
  Forward forward;        // the ending mode's forward pass there: its centre, velocity and energy
  double dissipated = 0;  // J, since the run's start
};

// The free coin of `attitude` with the centre and velocity of a forward pass.
FlightState flightStateOf(const QuaternionState& attitude, const Forward& forward);
FlightState flightStateOf(const Handover& handover);

// The mode a transition leads to, or the event the run ends at there.
using Next = std::variant<Mode, ModelEvent>;

// The table: where `transition` leads from `mode`, from the physics of the handover's state. Throws
// std::logic_error for a transition `mode` never makes (a chain's mistake, not the coin's).
Next next(const CoinModel& model, Mode mode, Transition transition, const Handover& handover);

// The state the mode that `next` names starts from: after SlipStops the slip left is closed by
// friction at once, its kinetic energy dissipated (docs/sliding.md §4.5); after BouncesEnd the rim is
// held (heldContact); after any other transition the handover itself.
Handover handedOn(const CoinModel& model, Transition transition, const Handover& handover);

// The mode of a contact taken up where there was none (a run's start on the floor, a landing's last
// bounce): sliding with a slip above stoppedSlip(0); else rolling where the rolling reaction fits the
// static cone, else creeping from zero slip.
Mode heldMode(const CoinModel& model, const SlidingState& state);

// That contact: its slip dropped unless it slides, the forward pass of heldMode's mode.
Handover heldContact(const CoinModel& model, const Handover& handover);

// `model` holding the corner that a held contact starting at attitude q rolls or slides on
// (Rim::heldCorner): its equations then continue smoothly past upright, where CornerLands is located
// on them (docs/flight.md §4a).
CoinModel holdingCorner(CoinModel model, const Eigen::Quaterniond& q);

// A slide's slip stops at no less than this many times solver.atol (docs/sliding.md eq. 4.18): the
// integrator holds the slip's components to about atol, and a slip a few atol long chatters about
// zero, its direction flipping inside each step, on steps of its own |s| / (restoring rate). One
// landing's slide at the default atol of 1e-12 sat at 1.4e-11 m/s (14 atol) on steps of 8e-11 s,
// 2.2 million of them, and stopped at 20 atol or more; 100 leaves a factor of 7.
inline constexpr double kResolvedSlipPerAtol = 100;

// m/s: the slip speed at which sliding ends (a threshold growing with t, s; see contact_mode.cpp).
double stoppedSlip(double t);

// Rolling leaves for sliding when this falls through zero: the static cone's reserve.
double slideOnsetMargin(const CoinModel& model, const Forward& rolling);

// A free slide's slip stops when this falls through zero (t: s; slipRate: the slip's rate, m/s^2):
// at stoppedSlip(t), or earlier where the slip closes so fast that it would stop within
// slipStopLead(t) (a hard skid), and never below `resolvedSlip` (m/s, 100 atol: a slip the
// integrator's absolute tolerance cannot hold chatters about zero instead of reaching the stop; a
// scene at atol 1e-10 stalled there on steps of 2e-11 s, a landing at the default 1e-12 at 14 atol).
double slipStopMargin(double t, const Eigen::Vector2d& slip, const Eigen::Vector2d& slipRate, double resolvedSlip);

// A creeping slide's slip stops when this falls through zero: `rest` is friction's direction along
// the slip's rest (floor frame, unit, horizontal); the same rule along it.
double creepStopMargin(double t, const Eigen::Vector2d& slip, const Eigen::Vector2d& slipRate, double resolvedSlip,
                       const Eigen::Vector3d& rest);

// s: a slide also ends once its slip would stop within this at its present rate.
double slipStopLead(double t);

// m/s: the slip speed above which its direction is integrated, at a rest whose lag is pulled by
// `pull` (Creep::pull, m/s^2).
double freeSlipSpeed(const CoinModel& model, const Forward& sliding, double pull);

// A free slide hands friction's direction to the slip's rest when this falls through zero.
double slipCreepMargin(const CoinModel& model, const SlidingStateVec& y, const Forward& sliding);

// A creeping slide integrates its slip's direction again when this rises through zero.
double slipFreeMargin(const CoinModel& model, const SlidingStateVec& y, const Forward& sliding);

}  // namespace coinroll::physics
