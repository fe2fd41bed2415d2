#pragma once
// Where the model stops describing the real coin, as events with margins. Each margin is positive
// while the model holds and crosses zero where it fails, so an integrator can locate the crossing
// on its dense output instead of clamping or producing NaNs. The margins read the forward pass of
// the formulation that integrates the run (forward.h), never another formulation's equations.

#include <numbers>
#include <string_view>

#include "physics/coin_model.h"
#include "physics/formulation.h"
#include "physics/forward.h"

namespace coinroll::physics {

// Why a run ended early, or a crossing it went on past (docs/contract.md).
enum class ModelEvent {
  CoinFlat,      // the formulation's own limit near flat (or a thin coin's spin-down end)
  FaceDown,      // a coin with thickness lies on its face
  CornerSwitch,  // a cornered rim passes upright: the contact would jump to the other corner
  LiftOff,       // N falls through 0
  Slip,          // friction needed reaches mu N
  Painleve,      // sliding, the held contact has no unique normal force (docs/sliding.md §3)
  StickSlip,     // more rolling/sliding switches than the run allows per simulated second (docs/sliding.md §4)
  Rest,          // flight: the coin landed flat on a face and lies there (docs/flight.md §5)
  ImpactJam,     // flight: an impact whose friction stops the normal impulse from ending it (docs/flight.md §3)
  Decided,       // flight, stop_when_decided: too little energy left to pass upright, the face up is final (§5a)
  OnEdge,        // flight, a cornered rim: the rocking between its corners died away, it stands on its band (§4a)
};

// The contract's name: "coin-flat", "face-down", "corner-switch", "lift-off", "slip", "painleve", "stick-slip",
// "rest", "impact-jam", "decided", "on-edge".
std::string_view eventName(ModelEvent event);

// rad. The Euler-angle equations carry tan(theta) and 1 / cos(theta); at 89 degrees the coin's
// face is within 1 degree of the floor, 1 / cos(theta) is 57 and the step sizes of an ideal
// (energy-conserving) fall collapse, so the seed's formulation stops an ideal run here.
inline constexpr double kFlatTilt = 89.0 * std::numbers::pi / 180.0;

// rad. The quaternion formulation stops an ideal run of a thin coin here: cos(theta) = 1.7e-4, the
// contact point runs round the rim at psi-dot ~ omega / cos(theta) and is undefined at 90 degrees.
inline constexpr double kQuaternionFlatTilt = 89.99 * std::numbers::pi / 180.0;

// rad. A thin coin's run with effects (a spin-down) ends at 0.5 degrees above the floor in either
// formulation (docs/euler_disk.md §5): there the far rim of the 75 mm toy is 0.65 mm above the
// floor, t0 - t is milliseconds, and both formulations still agree.
inline constexpr double kSpinDownFlatTilt = 89.5 * std::numbers::pi / 180.0;

// rad. A coin with thickness lies on its face once its tilt above the floor is below 0.05 degrees
// (docs/rim.md §7): the far rim of the toy is then 65 micrometres up, and the landing's last
// milliseconds are the slap the model leaves out.
inline constexpr double kFaceDownDegrees = 0.05;  // tilt above the floor
inline constexpr double kFaceDownTilt = (90.0 - kFaceDownDegrees) * std::numbers::pi / 180.0;

// Which face is up once a coin lies on the floor: heads, the face with +e_Z up (theta < 0), or tails.
enum class FaceUp { Heads, Tails };
FaceUp faceUp(double theta);
std::string_view faceName(FaceUp face);

// How a run of `model` in `formulation` ends near flat: the event and the |theta| it fires at.
struct FlatStop {
  ModelEvent event = ModelEvent::CoinFlat;
  double tilt = kFlatTilt;  // rad, |theta|
};
FlatStop flatStopFor(const CoinModel& model, Formulation formulation);

// True when the rim has two corners that meet at upright (0 < rho < h/2 or rho = 0 with thickness).
bool hasCorners(const CoinModel& model);

// N / (M g): the normal force in units of the weight; below zero the coin would lift off.
double liftOffMargin(const CoinModel& model, const Forward& forward);

// (mu N - F) / (M g): static friction reserve; below zero the contact would slip.
double slipMargin(const CoinModel& model, const Forward& forward, double mu);

// flatTilt - |theta|, rad.
double flatMargin(double theta, double flatTilt);

}  // namespace coinroll::physics
