// The thick coin's moments (docs/rim_inertia.md) against integrals computed another way: 2-D Gauss-Legendre
// quadrature over the (r, z) cross-section, bounded by the fillet arc itself rather than by the page's
// square-minus-quarter-disc bookkeeping, and a brute-force midpoint rule over an indicator of the section that
// guards the quadrature's own geometry. Also the square-edged ring (I.12), the sphere (I.13), the lamina and
// the argument checks.

#include "physics/solid_inertia.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "tolerance.h"

namespace coinroll::physics {
namespace {

using coinroll::testing::isNear;

constexpr double kPi = std::numbers::pi;

struct Shape {
  double M, a, b, h, rho;
};

// Integrals of 1, r^2 and z^2 over the solid (weight 2 pi r over the section).
struct Integrals {
  double V = 0, Jr = 0, Jz = 0;
  PrincipalMoments moments(double M) const { return {.I_X = M * (Jr / 2 + Jz) / V, .I_Z = M * Jr / V}; }
};

// n-point Gauss-Legendre on [-1, 1] by Newton's method on P_n (Abramowitz & Stegun 25.4.29).
struct GaussRule {
  std::vector<double> x, w;
};

GaussRule gaussLegendre(int n) {
  GaussRule rule{std::vector<double>(n), std::vector<double>(n)};
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1);
      const double step = p1 / dp;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    rule.x[i] = x;
    rule.w[i] = 2 / ((1 - x * x) * dp * dp);
  }
  return rule;
}

// Adds the integrals over r in [r0, r1], |z| <= top(r), with Gauss-Legendre in both directions. The section's
// outer boundary r = c + rho sin(t), |z| = d + rho cos(t) is smooth in t, so the arc strip is integrated in t,
// not r (the r-parametrised arc has a square-root edge at r = a that would spoil Gauss' convergence).
Integrals gaussSection(const Shape& s, int n) {
  const GaussRule g = gaussLegendre(n);
  const double c = s.a - s.rho, d = s.h / 2 - s.rho;
  Integrals sum;
  const auto addColumn = [&](double r, double top, double weight) {  // weight: dr quadrature weight
    for (int j = 0; j < n; ++j) {
      const double z = top * g.x[j];
      const double w = weight * top * g.w[j] * 2 * kPi * r;
      sum.V += w;
      sum.Jr += w * r * r;
      sum.Jz += w * z * z;
    }
  };
  for (int i = 0; i < n; ++i) {  // the flat part b <= r <= c
    const double half = (c - s.b) / 2;
    addColumn(s.b + half * (1 + g.x[i]), s.h / 2, half * g.w[i]);
  }
  if (s.rho > 0) {
    for (int i = 0; i < n; ++i) {  // the rounded strip c <= r <= a, r = c + rho sin(t), t in [0, pi/2]
      const double t = kPi / 4 * (1 + g.x[i]);
      addColumn(c + s.rho * std::sin(t), d + s.rho * std::cos(t), kPi / 4 * g.w[i] * s.rho * std::cos(t));
    }
  }
  return sum;
}

// Midpoint rule on an N x N grid over [b, a] x [0, h/2] (doubled for the mirror half) with the section's
// indicator: crude, O(1/N) at the boundary, but it knows nothing of arcs' parametrisations.
Integrals midpointSection(const Shape& s, int N) {
  const double c = s.a - s.rho, d = s.h / 2 - s.rho;
  const double dr = (s.a - s.b) / N, dz = s.h / 2 / N;
  Integrals sum;
  for (int i = 0; i < N; ++i) {
    const double r = s.b + (i + 0.5) * dr;
    for (int j = 0; j < N; ++j) {
      const double z = (j + 0.5) * dz;
      const bool inCorner = r > c && z > d;
      if (inCorner && (r - c) * (r - c) + (z - d) * (z - d) > s.rho * s.rho) continue;
      const double w = 2 * 2 * kPi * r * dr * dz;
      sum.V += w;
      sum.Jr += w * r * r;
      sum.Jz += w * z * z;
    }
  }
  return sum;
}

PrincipalMoments closedForm(const Shape& s) { return filletedCylinderInertia(s.M, s.a, s.b, s.h, s.rho); }

// 40 Gauss points each way: the integrands are polynomials in z and r on the flat part and trigonometric
// polynomials in t on the arc strip, so the quadrature is exact to rounding.
constexpr int kGaussPoints = 40;
constexpr double kGaussRelTol = 1e-13;

void expectMatchesQuadrature(const Shape& s) {
  const PrincipalMoments exact = closedForm(s);
  const PrincipalMoments numeric = gaussSection(s, kGaussPoints).moments(s.M);
  EXPECT_TRUE(isNear(exact.I_X, numeric.I_X, kGaussRelTol * numeric.I_X)) << "I_X";
  EXPECT_TRUE(isNear(exact.I_Z, numeric.I_Z, kGaussRelTol * numeric.I_Z)) << "I_Z";
}

const Shape kToy{.M = 0.4, .a = 0.0375, .b = 0, .h = 0.013, .rho = 0.0016};  // the Euler's-disk toy

TEST(SolidInertia, SquareEdgedDiskMatchesQuadrature) { expectMatchesQuadrature({0.4, 0.0375, 0, 0.013, 0}); }
TEST(SolidInertia, FullyRoundedDiskMatchesQuadrature) { expectMatchesQuadrature({0.4, 0.0375, 0, 0.013, 0.0065}); }
TEST(SolidInertia, RingWithSmallFilletMatchesQuadrature) { expectMatchesQuadrature({0.05, 0.03, 0.012, 0.01, 0.003}); }
TEST(SolidInertia, EulersDiskToyMatchesQuadrature) { expectMatchesQuadrature(kToy); }
TEST(SolidInertia, SphereLimitMatchesQuadrature) { expectMatchesQuadrature({2.0, 0.02, 0, 0.04, 0.02}); }
// rho = a - b: the fillet's arc starts right at the hole's edge, no flat part left on the faces.
TEST(SolidInertia, FilletReachingTheHoleMatchesQuadrature) {
  expectMatchesQuadrature({0.1, 0.02, 0.015, 0.012, 0.005});
}
TEST(SolidInertia, ThickRoundedWasherMatchesQuadrature) { expectMatchesQuadrature({1.0, 0.01, 0.002, 0.012, 0.006}); }

// The Gauss integrator's geometry checked by brute force: 4000 x 4000 midpoint cells, whose boundary error
// for these shapes is measured at <= 2.3e-6 relative (2e-5 allowed).
TEST(SolidInertia, QuadratureAgreesWithIndicatorMidpointRule) {
  for (const Shape& s : {kToy, Shape{0.4, 0.0375, 0, 0.013, 0.0065}, Shape{0.05, 0.03, 0.012, 0.01, 0.003},
                         Shape{2.0, 0.02, 0, 0.04, 0.02}}) {
    const PrincipalMoments gauss = gaussSection(s, kGaussPoints).moments(s.M);
    const PrincipalMoments brute = midpointSection(s, 4000).moments(s.M);
    EXPECT_TRUE(isNear(brute.I_X, gauss.I_X, 2e-5 * gauss.I_X)) << "I_X, rho = " << s.rho;
    EXPECT_TRUE(isNear(brute.I_Z, gauss.I_Z, 2e-5 * gauss.I_Z)) << "I_Z, rho = " << s.rho;
  }
}

// (I.12): no fillet, the square-edged ring, to rounding.
TEST(SolidInertia, NoFilletIsTheSquareEdgedRing) {
  for (const Shape& s : {Shape{0.4, 0.0375, 0, 0.013, 0}, Shape{0.05, 0.03, 0.012, 0.01, 0},
                         Shape{3.0, 1.0, 0.999, 0.2, 0}, Shape{1.0, 0.01, 0, 0.5, 0}}) {
    const PrincipalMoments m = closedForm(s);
    const double I_X = s.M * ((s.a * s.a + s.b * s.b) / 4 + s.h * s.h / 12);
    const double I_Z = s.M * (s.a * s.a + s.b * s.b) / 2;
    EXPECT_TRUE(isNear(m.I_X, I_X, 1e-15 * I_X)) << "a = " << s.a << ", b = " << s.b;
    EXPECT_TRUE(isNear(m.I_Z, I_Z, 1e-15 * I_Z)) << "a = " << s.a << ", b = " << s.b;
  }
}

// (I.13): a = rho = h/2, b = 0 is a ball, 2/5 M a^2 about every axis.
TEST(SolidInertia, SphereLimitIsTwoFifthsMaSquared) {
  const double M = 2.0, a = 0.02;
  const PrincipalMoments m = filletedCylinderInertia(M, a, 0, 2 * a, a);
  EXPECT_TRUE(isNear(m.I_X, 0.4 * M * a * a, 1e-14 * M * a * a));
  EXPECT_TRUE(isNear(m.I_Z, 0.4 * M * a * a, 1e-14 * M * a * a));
}

// h = 0 is the seed's lamina (coin_model.h's diskModel / ringModel), even though its section has no area.
TEST(SolidInertia, ZeroThicknessIsTheLamina) {
  const PrincipalMoments disk = filletedCylinderInertia(0.4, 0.0375, 0, 0, 0);
  EXPECT_EQ(disk.I_X, 0.4 * 0.0375 * 0.0375 / 4);
  EXPECT_EQ(disk.I_Z, 0.4 * 0.0375 * 0.0375 / 2);
  const PrincipalMoments hoop = filletedCylinderInertia(1.0, 0.02, 0.02, 0, 0);
  EXPECT_TRUE(std::isfinite(hoop.I_X) && std::isfinite(hoop.I_Z));
  EXPECT_TRUE(isNear(hoop.I_Z, 1.0 * 0.02 * 0.02, 1e-18));
}

// A vanishing fillet changes the moments by O(rho^2) (its area), so continuity at rho = 0 is smooth.
TEST(SolidInertia, TinyFilletIsContinuousWithSquareEdge) {
  const PrincipalMoments square = filletedCylinderInertia(0.4, 0.0375, 0, 0.013, 0);
  const PrincipalMoments tiny = filletedCylinderInertia(0.4, 0.0375, 0, 0.013, 1e-7);
  EXPECT_TRUE(isNear(tiny.I_X, square.I_X, 1e-9 * square.I_X));
  EXPECT_TRUE(isNear(tiny.I_Z, square.I_Z, 1e-9 * square.I_Z));
  EXPECT_LT(tiny.I_Z, square.I_Z);  // the fillet removes mass from the largest radius
}

TEST(SolidInertia, RejectsImpossibleShapes) {
  EXPECT_THROW(filletedCylinderInertia(0.4, 0.0375, 0, 0.013, 0.0066), std::invalid_argument);     // rho > h/2
  EXPECT_THROW(filletedCylinderInertia(0.4, 0.0375, 0.035, 0.013, 0.003), std::invalid_argument);  // rho > a - b
  EXPECT_THROW(filletedCylinderInertia(0.4, 0.0375, 0.04, 0.013, 0), std::invalid_argument);       // b > a
  EXPECT_THROW(filletedCylinderInertia(0.4, 0.0375, 0, -0.013, 0), std::invalid_argument);
  EXPECT_THROW(filletedCylinderInertia(0.4, 0.0375, 0, 0.013, -1e-4), std::invalid_argument);
  EXPECT_THROW(filletedCylinderInertia(0, 0.0375, 0, 0.013, 0), std::invalid_argument);
  EXPECT_THROW(filletedCylinderInertia(0.4, 0.0375, 0, 0.013, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace coinroll::physics
