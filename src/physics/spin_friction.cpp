#include "physics/spin_friction.h"

namespace coinroll::physics {

Loads loads(const SpinFriction& law, const ContactKinematics& k) {
  if (!(k.N > 0)) return {};  // no load, no patch
  const double pivotRate = k.omega.dot(floorNormal());
  const double magnitude = law.length * k.N * smoothSign(pivotRate, kPivotRegularisationRate);
  return {.torque = -magnitude * floorNormal(), .power = magnitude * pivotRate};
}

}  // namespace coinroll::physics
