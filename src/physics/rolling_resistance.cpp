#include "physics/rolling_resistance.h"

#include <algorithm>
#include <cmath>

namespace coinroll::physics {

Loads loads(const RollingResistance& law, const ContactKinematics& k) {
  // Without load there is no contact to deform: the couple vanishes with N (lift-off is an event).
  if (!(k.N > 0)) return {};
  double couple = law.loadExponent == 1
                      ? law.length * k.N
                      : law.length * kRollingReferenceLoad * std::pow(k.N / kRollingReferenceLoad, law.loadExponent);
  const Eigen::Vector3d h = rollingAxis(k);
  const double rollingRate = k.omega.dot(h);  // psi-dot cos(theta), eq. (2.9)
  const double cosTheta = k.e_Y.y();
  if (law.rateExponent != 1)
    couple *= std::pow(std::abs(rollingRate / cosTheta) / kRollingReferenceRate, law.rateExponent - 1);
  // The couple about h that does the work delta N |psi-dot| while the face turns about h only
  // at psi-dot cos(theta) (eq. 2.10). It puts the normal force's centre delta / cos(theta) ahead of
  // the contact, which near flat would lie off the coin: there it stays at the coin's edge (2.11d),
  // where an unbounded lever made the couple, and the steps, ever stiffer as the coin lay down.
  const double magnitude =
      std::min(couple / cosTheta, k.N * k.outerRadius) * smoothSign(rollingRate, kRollingRegularisationRate);
  return {.torque = -magnitude * h, .power = magnitude * rollingRate};
}

}  // namespace coinroll::physics
