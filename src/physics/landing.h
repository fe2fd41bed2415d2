#pragma once
// The rim's landings with flight (docs/flight.md §3-§5): a flight's touchdown, or a cornered rim's
// other corner striking the floor as the coin passes upright, resolved by the model's impact law
// into the transition out of the impact (contact_mode.h: Bounces, BouncesEnd, BandRests, LandsFlat
// or Jams).

#include "physics/coin_model.h"
#include "physics/contact_mode.h"
#include "physics/flight.h"
#include "physics/sliding.h"

namespace coinroll::physics {

// m/s, u_rest of docs/flight.md eq. (4.1): bounces end at a rebound that would lift the rim 1e-6 a.
double restSpeed(const CoinModel& model);

// `state` with its centre at the height where the rim's lowest point touches the floor: where a
// bounce or a lift-off starts a flight (the touchdown was located a root tolerance either side of it,
// the contact's height carries round-off), moved by at most 1e-12 a.
FlightState onTheFloor(const CoinModel& model, FlightState state);

// The held contact of a coin whose rim touches the floor: its attitude and rates, and the slip of
// the contact point.
SlidingState contactStateOf(const CoinModel& model, const FlightState& state);

// The handover of a free coin at t: its contact's state and its flight's forward pass.
Handover flightHandover(const CoinModel& model, double t, const FlightState& state, double dissipated);

// Whether the coin has less energy than standing still upright on its rim (docs/flight.md §5a): it can
// no longer turn over, its face up is decided.
bool belowUpright(const CoinModel& model, const FlightState& state);

// A landing: the transition out of its impact and the coin after it.
struct Landing {
  Transition transition = Transition::Bounces;  // Bounces, BouncesEnd, BandRests, LandsFlat or Jams
  // After the impact, its loss dissipated (BouncesEnd, BandRests: the rim's normal velocity zero);
  // LandsFlat, Jams: at touch.
  Handover handover;
  double normalSpeed = 0;   // m/s, how fast the rim closed on the floor
  double reboundSpeed = 0;  // m/s, how fast it left; 0 where the bounces end
  double energyLost = 0;    // J
  bool bouncesEnd = false;  // the last impact of a bounce sequence (the event bounce-end)
};

// The impact of a flight's touchdown, handed over at touch. `plastic`: end the bounces here whatever
// the rebound (a run past its bound of impacts per second).
Landing touchdown(const CoinModel& model, const Handover& atTouch, bool plastic);

// The impact of the other corner of a cornered rim whose held contact passed upright, handed over
// there (docs/flight.md §4a): the corner the tilt moves towards lands. Where the bounces end and both
// corners move slower than restSpeed, or `plastic`, the band lies on the floor: BandRests.
Landing cornerLanding(const CoinModel& model, const Handover& leaving, bool plastic);

}  // namespace coinroll::physics
