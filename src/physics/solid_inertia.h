#pragma once
// Principal moments of a thick coin from its shape (docs/rim_inertia.md): the seed's thin-disk and
// annulus moments ignore the thickness, which for the toy (h / a ~ 1/3) is a percent-level error in I_X.

namespace coinroll::physics {

struct PrincipalMoments {
  double I_X = 0;  // kg m^2, about a diameter through the centre of mass (I_X = I_Y by symmetry)
  double I_Z = 0;  // kg m^2, about the symmetry axis
};

// Uniform solid of revolution: cylinder radius a, hole b, thickness h, outer rim rounded with radius rho
// (docs/rim_inertia.md). rho = 0 is the square-edged ring, M ((a^2 + b^2) / 4 + h^2 / 12), M (a^2 + b^2) / 2
// (I.12); rho = h/2 is a half-torus rim, matching Rim::fullyRounded(). h = 0 (with rho = 0) is the seed's
// thin lamina. Throws std::invalid_argument unless M > 0, a > 0, 0 <= b <= a, h >= 0 and
// 0 <= rho <= min(h/2, a - b).
PrincipalMoments filletedCylinderInertia(double M, double a, double b, double h, double rho);

}  // namespace coinroll::physics
