#pragma once
// When the contact rolls and when it slides (docs/sliding.md §4): the rules of the switches between
// contact modes, as functions of the model (its friction) and the state or its forward pass. A run
// that chains the modes (pipeline/hybrid_run.h) integrates one mode at a time and asks these where
// each one ends and which comes next.

#include <Eigen/Core>

#include "physics/coin_model.h"
#include "physics/forward.h"
#include "physics/sliding.h"

namespace coinroll::physics {

// Sliding: friction along the slip. Creeping: along the slip's rest, while the slip is too small for
// its own direction to be integrated (Creep): from zero slip, or a slip that has fallen back to it.
enum class ContactMode { Rolling, Sliding, Creeping };

// m/s: the slip speed at which sliding ends (a threshold growing with t, s; see contact_mode.cpp).
double stoppedSlip(double t);

// The mode of a contact at t = 0: sliding with a slip above stoppedSlip(0); creeping from zero slip
// where the rolling reaction does not fit the static cone; else rolling. `rolling` and `slipping`:
// the forward passes of the start rolling and sliding with its slip.
ContactMode startingMode(const CoinModel& model, const Forward& rolling, const Forward& slipping);

// Rolling leaves for sliding when this falls through zero: the static cone's reserve.
double slideOnsetMargin(const CoinModel& model, const Forward& rolling);

// Where a slide goes on once its slip has stopped: rolling when the rolling reaction at zero slip
// fits the static cone, else creeping on from zero slip, its direction at its rest.
ContactMode modeAfterSlipStops(const CoinModel& model, const Forward& rolling);

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
