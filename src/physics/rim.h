#pragma once
// The coin's rim as the dynamics see it (docs/contract.md §5, docs/rim.md §1): a torus
// of tube radius rho whose centre circle, of radius a - rho, lies h/2 - rho from the mid-plane on
// the side of the lower face. Thickness 0 is the seed's thin coin, touching the floor at radius a
// in its mid-plane. The one place that knows where the contact point sits on the body.

#include <cmath>

namespace coinroll::physics {

struct Rim {
  double thickness = 0;   // m, h; 0: the seed's thin coin
  double edgeRadius = 0;  // m, rho in [0, h/2]: the tube radius rounding the outer rim
  // +1 or -1: the corner a contact segment rolls or slides on, held past upright, where the contact's
  // continuation on it stays smooth, so that an integrator's trial stages across theta = 0 see no
  // jump and the corner-switch event is located on accepted steps (docs/rim.md §7); 0: the lower one.
  double heldCorner = 0;

  bool thin() const { return thickness == 0; }
  // rho = h/2: the rim is a half-torus, smooth through upright; below it two corners meet there.
  bool fullyRounded() const { return edgeRadius >= 0.5 * thickness; }
  // m, h/2 - rho: how far the torus' centre circle sits from the mid-plane.
  double cornerOffset() const { return fullyRounded() ? 0.0 : 0.5 * thickness - edgeRadius; }
};

// The contact vector c from the centre of mass to the contact point in the seed's frame XYZ,
//   c = -reach e_Y + lift e_Z,                                                      (docs/rim.md eq. 1.3)
// reach = a - rho + rho cos(theta), lift = sign(theta) (h/2 - rho) + rho sin(theta),
// with the derivatives d/dtheta (away from theta = 0 for a cornered rim, where lift jumps).
struct ContactOffset {
  double reach = 0;   // m, -c . e_Y
  double lift = 0;    // m, c . e_Z
  double dReach = 0;  // m/rad, d(reach)/d(theta)
  double dLift = 0;   // m/rad, d(lift)/d(theta)
};

inline ContactOffset contactOffset(const Rim& rim, double a, double sinTheta, double cosTheta) {
  const double rho = rim.edgeRadius;
  const double side = rim.heldCorner != 0 ? rim.heldCorner : sinTheta < 0 ? -1.0 : 1.0;
  return {.reach = a - rho + rho * cosTheta,
          .lift = side * rim.cornerOffset() + rho * sinTheta,
          .dReach = -rho * sinTheta,
          .dLift = rho * cosTheta};
}

// m, height of the centre of mass above the floor: (a - rho) cos(theta) + (h/2 - rho) |sin(theta)| + rho,
// = reach cos(theta) - lift (-sin(theta)) since e_y = cos(theta) e_Y - sin(theta) e_Z.
inline double centreHeight(const ContactOffset& c, double sinTheta, double cosTheta) {
  return c.reach * cosTheta + c.lift * sinTheta;
}

}  // namespace coinroll::physics
