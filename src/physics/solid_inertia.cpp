#include "physics/solid_inertia.h"

#include <numbers>
#include <stdexcept>
#include <string>

namespace coinroll::physics {

PrincipalMoments filletedCylinderInertia(double M, double a, double b, double h, double rho) {
  // Written as !(ok) so that NaN inputs are rejected too.
  if (!(M > 0) || !(a > 0) || !(b >= 0 && b <= a) || !(h >= 0)) {
    throw std::invalid_argument(
        "filletedCylinderInertia: need M > 0, a > 0, 0 <= b <= a, h >= 0; got M = " + std::to_string(M) +
        ", a = " + std::to_string(a) + ", b = " + std::to_string(b) + ", h = " + std::to_string(h));
  }
  // Beyond h/2 the two fillets overlap; beyond a - b the fillet would cut into the (square) hole edge.
  if (!(rho >= 0 && rho <= 0.5 * h && rho <= a - b)) {
    throw std::invalid_argument("filletedCylinderInertia: edge radius rho must be in [0, min(h/2, a - b)], got " +
                                std::to_string(rho));
  }
  constexpr double pi = std::numbers::pi;
  const double c = a - rho;        // m, radius of the fillet arcs' centre circle
  const double d = 0.5 * h - rho;  // m, its distance from the mid-plane
  const double rho2 = rho * rho;
  const double rho3 = rho2 * rho;
  const double rho4 = rho3 * rho;
  const double rho5 = rho4 * rho;
  const double kappa = 1 - pi / 4;  // fillet area / rho^2 (I.4)

  // One fillet's integrals of r, r^3 and r z^2 over the area it removes; the two fillets are mirror images in z.
  const double cornerV = kappa * c * rho2 + rho3 / 6;  // (I.6)
  const double cornerR =
      kappa * c * c * c * rho2 + c * c * rho3 / 2 + (1 - 3 * pi / 16) * c * rho4 + 7 * rho5 / 60;  // (I.7)
  const double cornerZ = c * (kappa * d * d * rho2 + d * rho3 / 3 + (1.0 / 3 - pi / 16) * rho4) + d * d * rho3 / 6 +
                         d * rho4 / 4 + rho5 / 10;  // (I.8)

  // Everything is divided by the square-edged volume / pi so that rho = 0 gives the ring's moments exactly
  // (the corner terms vanish identically) and small fillets appear as small corrections. (a - b)(a + b) rather
  // than a^2 - b^2 keeps a thin ring's section accurate. A zero section (lamina h = 0, or hoop b = a) forces
  // rho = 0 and hence zero corner terms, so its share is taken as 0 instead of dividing by zero.
  const double section = h * (a - b) * (a + b);
  const double share = section > 0 ? 4 / section : 0.0;
  const double sumOfSquares = a * a + b * b;
  const double volumeFraction = 1 - share * cornerV;  // V / (pi h (a^2 - b^2)), (I.9)
  return {.I_X = M * (sumOfSquares / 4 + h * h / 12 - share * (cornerR / 2 + cornerZ)) / volumeFraction,  // (I.11)
          .I_Z = M * (sumOfSquares / 2 - share * cornerR) / volumeFraction};                              // (I.11)
}

}  // namespace coinroll::physics
