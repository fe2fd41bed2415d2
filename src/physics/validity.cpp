#include "physics/validity.h"

#include <cmath>

namespace coinroll::physics {

std::string_view eventName(ModelEvent event) {
  switch (event) {
    case ModelEvent::CoinFlat: return "coin-flat";
    case ModelEvent::FaceDown: return "face-down";
    case ModelEvent::CornerSwitch: return "corner-switch";
    case ModelEvent::LiftOff: return "lift-off";
    case ModelEvent::Slip: return "slip";
    case ModelEvent::Painleve: return "painleve";
    case ModelEvent::StickSlip: return "stick-slip";
    case ModelEvent::Rest: return "rest";
    case ModelEvent::ImpactJam: return "impact-jam";
    case ModelEvent::Decided: return "decided";
    case ModelEvent::OnEdge: return "on-edge";
  }
  return "event";
}

FaceUp faceUp(double theta) { return theta < 0 ? FaceUp::Heads : FaceUp::Tails; }

std::string_view faceName(FaceUp face) { return face == FaceUp::Heads ? "heads" : "tails"; }

FlatStop flatStopFor(const CoinModel& model, Formulation formulation) {
  // Only the quaternion reaches a thick coin's landing; the Euler angles stop where they must.
  if (!model.rim.thin() && formulation == Formulation::Quaternion) return {ModelEvent::FaceDown, kFaceDownTilt};
  if (!model.effects.empty()) return {ModelEvent::CoinFlat, kSpinDownFlatTilt};
  return {ModelEvent::CoinFlat, formulation == Formulation::Quaternion ? kQuaternionFlatTilt : kFlatTilt};
}

bool hasCorners(const CoinModel& model) { return !model.rim.thin() && !model.rim.fullyRounded(); }

double liftOffMargin(const CoinModel& model, const Forward& f) { return f.reaction.N / (model.M * model.g); }

double slipMargin(const CoinModel& model, const Forward& f, double mu) {
  return (mu * f.reaction.N - f.reaction.F) / (model.M * model.g);
}

double flatMargin(double theta, double flatTilt) { return flatTilt - std::abs(theta); }

}  // namespace coinroll::physics
