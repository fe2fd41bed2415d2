#pragma once
// An event of a run, in the seed's variables and with its formulation's forward pass: what ends a
// run early, or a validity crossing it went on past.

#include "physics/coin_state.h"
#include "physics/forward.h"
#include "physics/validity.h"

namespace coinroll::pipeline {

// An event of a run: the one that ended it, or a crossing it went on past.
struct RunEvent {
  physics::ModelEvent event = physics::ModelEvent::CoinFlat;
  double t = 0;  // s
  physics::CoinState state;
  physics::Forward forward;
  double dissipated = 0;  // J
};

}  // namespace coinroll::pipeline
