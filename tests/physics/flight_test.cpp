// Flight and impact (docs/flight.md) against closed forms and conserved quantities: the torque-free
// top's exact motion (1.4), the lowest point's height (2.1), and the impact law's energy (3.6).

#include "physics/flight.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "integrate/trajectory.h"
#include "physics/coin_model.h"
#include "physics/impact.h"
#include "physics/observables.h"
#include "physics/solid_inertia.h"
#include "tolerance.h"

namespace coinroll::physics {
namespace {

using coinroll::testing::isBelow;
using coinroll::testing::isNear;

constexpr double kDeg = std::numbers::pi / 180;

CoinModel thickCoin() {
  CoinModel m = diskModel(0.0075, 0.0125, 9.81);
  m.rim = {.thickness = 0.002, .edgeRadius = 0.0005};
  return m;
}

// A tumbling, spinning coin high above the floor.
FlightState toss() {
  return {.q = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized())),
          .omegaBody = Eigen::Vector3d(180, -40, 25),
          .centre = Eigen::Vector3d(0.1, 1.2, -0.2),
          .velocity = Eigen::Vector3d(0.3, 2.5, -0.1)};
}

struct FlightRhs {
  CoinModel model;
  integrate::Vec<kFlightStateSize> operator()(double, const integrate::Vec<kFlightStateSize>& y) const {
    return flightRhs(model, y);
  }
};

FlightState integrateFlight(const CoinModel& m, const FlightState& start, double t) {
  integrate::Trajectory<kFlightStateSize, FlightRhs> run(
      FlightRhs{m}, 0, toVector(start), {.method = integrate::Method::Dop853, .rtol = 1e-13, .atol = 1e-15});
  return toFlightState(*run.stateAt(t));
}

// The program's flight is the closed form (1.4) with G's parabola (flightAfter); the equations of
// motion (1.1)-(1.3) integrated tightly are the independent second formulation it must match.
TEST(Flight, ClosedFormMatchesTheIntegratedEquationsOfMotion) {
  for (const CoinModel& m : {diskModel(0.0075, 0.0125, 9.81), ringModel(0.01, 0.02, 0.012, 9.81), thickCoin()}) {
    const FlightState start = toss();
    for (const double t : {0.05, 0.31, 0.6}) {
      const FlightState integrated = integrateFlight(m, start, t);
      const FlightState exact = flightAfter(m, start, t);
      EXPECT_TRUE(isBelow((integrated.q.toRotationMatrix() - exact.q.toRotationMatrix()).norm(), 1e-10)) << t;
      EXPECT_TRUE(isBelow((integrated.omegaBody - exact.omegaBody).norm() / start.omegaBody.norm(), 1e-10)) << t;
      EXPECT_TRUE(isBelow((integrated.centre - exact.centre).norm(), 1e-12)) << t;
      EXPECT_TRUE(isBelow((integrated.velocity - exact.velocity).norm(), 1e-12)) << t;
    }
  }
}

TEST(Flight, ClosedFormConservesMomentumAndEnergyOverManyTurns) {
  for (const CoinModel& m : {diskModel(0.0075, 0.0125, 9.81), ringModel(0.01, 0.02, 0.012, 9.81), thickCoin()}) {
    const FlightState start = toss();
    const Eigen::Vector3d L0 = angularMomentum(m, start);
    const double E0 = flightForward(m, start).energy;
    // 100 s is about 3000 turns: an integration's error would have grown; the closed form's does not.
    for (const double t : {0.6, 100.0}) {
      const FlightState end = flightAfter(m, start, t);
      EXPECT_TRUE(isBelow((angularMomentum(m, end) - L0).norm() / L0.norm(), 1e-12)) << t;
      EXPECT_TRUE(
          isNear(flightForward(m, end).energy, E0, 1e-12 * (std::abs(E0) + m.M * m.g * std::abs(end.centre.y()))))
          << t;
    }
  }
}

TEST(Flight, SymmetryAxisPrecessesAboutTheMomentumAtItsOverInertia) {
  const CoinModel m = thickCoin();
  const FlightState start = toss();
  const Eigen::Vector3d Lhat = angularMomentum(m, start).normalized();
  const Eigen::Vector3d axis0 = start.q * Eigen::Vector3d::UnitZ();
  const double rate = angularMomentum(m, start).norm() / m.I_X;
  // After a quarter of the precession's period the axis has turned a right angle about L, keeping its cone.
  const double quarter = 0.5 * std::numbers::pi / rate;
  for (const FlightState& end : {integrateFlight(m, start, quarter), flightAfter(m, start, quarter)}) {
    const Eigen::Vector3d axis = end.q * Eigen::Vector3d::UnitZ();
    EXPECT_TRUE(isNear(axis.dot(Lhat), axis0.dot(Lhat), 1e-11));
    const Eigen::Vector3d across0 = (axis0 - axis0.dot(Lhat) * Lhat).normalized();
    const Eigen::Vector3d across = (axis - axis.dot(Lhat) * Lhat).normalized();
    EXPECT_TRUE(isNear(across0.cross(across).dot(Lhat), 1.0, 1e-11));
  }
}

// No attitude puts the rim deeper below G than reachBelowCentre, and some come within 2 % of it.
TEST(Flight, NoAttitudeReachesBelowTheCoinsSphere) {
  for (const CoinModel& m : {diskModel(0.0075, 0.0125, 9.81), thickCoin()}) {
    double deepest = 0;
    std::mt19937 random(38);
    std::normal_distribution<double> normal;
    for (int k = 0; k < 2000; ++k) {
      const Eigen::Quaterniond q = Eigen::Quaterniond(normal(random), normal(random), normal(random), normal(random));
      deepest = std::max(deepest, lowestPointDepth(m, q.normalized()));
    }
    EXPECT_TRUE(isBelow(deepest, reachBelowCentre(m)));
    EXPECT_GT(deepest, 0.98 * reachBelowCentre(m));
  }
}

TEST(Flight, LowestPointDepthIsTheRollingCentreHeight) {
  const CoinModel m = thickCoin();
  for (const double theta : {-80.0, -30.0, 0.0, 10.0, 45.0, 89.0}) {
    const CoinState s{.theta = theta * kDeg, .phi = 0.4, .psi = 1.1};
    const double depth = lowestPointDepth(m, attitude(s));
    EXPECT_TRUE(isNear(depth, centreOfMass(m, s).y(), 1e-15)) << theta;
    // The lowest point is the rolling contact point, and no rim point of the torus lies lower.
    const Eigen::Vector3d r = lowestPointVector(m, attitude(s));
    EXPECT_TRUE(isNear(r.y(), -depth, 1e-15)) << theta;
  }
  // Flat, on either face: the face's half thickness.
  for (const double theta : {-90.0, 90.0}) {
    const Eigen::Quaterniond q = attitude(CoinState{.theta = theta * kDeg});
    EXPECT_TRUE(isNear(lowestPointDepth(m, q), 0.5 * m.rim.thickness, 1e-15)) << theta;
    EXPECT_TRUE(isNear(lowestPointVector(m, q).y(), -0.5 * m.rim.thickness, 1e-9)) << theta;
  }
}

// Random approaching states, friction and restitution: the energy booked is the kinetic energy's
// fall (computed from the velocities, not from eq. 3.3) and never negative.
TEST(Impact, NeverCreatesEnergy) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1, 1), positive(0, 1);
  int resolved = 0;
  for (const CoinModel& m : {diskModel(0.0075, 0.0125, 9.81), ringModel(0.01, 0.02, 0.012, 9.81), thickCoin()}) {
    for (int k = 0; k < 400; ++k) {
      FlightState s;
      s.q = Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random)).normalized();
      s.omegaBody = 100 * Eigen::Vector3d(unit(random), unit(random), unit(random));
      s.velocity = 2 * Eigen::Vector3d(unit(random), unit(random), unit(random));
      const Eigen::Vector3d r = lowestPointVector(m, s.q);
      if (pointVelocity(s, r).y() >= -1e-3) continue;
      const ImpactLaw law{.restitution = positive(random), .friction = positive(random)};
      const ImpactOutcome out = resolveImpact(m, s, law);
      // Up to mu = 1 no landing of these coins jams (at 1.5 a third do: docs/flight.md §3).
      ASSERT_FALSE(out.jammed) << k;
      ++resolved;
      const double before = kineticEnergy(m, s), after = kineticEnergy(m, out.after);
      EXPECT_TRUE(isNear(out.energyLost, before - after, 1e-12 * before)) << k;
      EXPECT_GE(out.energyLost, -1e-13 * before) << k;
      // The impulse pushes: its normal part is positive and friction keeps to its cone.
      EXPECT_GT(out.impulse.y(), 0) << k;
      EXPECT_TRUE(isBelow(std::hypot(out.impulse.x(), out.impulse.z()), law.friction * out.impulse.y() * (1 + 1e-9)))
          << k;
      EXPECT_GE(pointVelocity(out.after, r).y(), -1e-12 * out.approachSpeed) << k;
    }
  }
  EXPECT_GT(resolved, 550);
}

// A landing found by a sweep of tosses (examples/coin_toss.json at omega_X 33.158 rad/s, v_y 2.579 m/s)
// whose slip, during restitution, spirals into zero: its direction turns about 170 times faster than
// it shrinks, and steps of half its distance took 6400 steps to cover 7 decades, so the impact
// "did not end". It ends, and keeps the energy books of every impact.
CoinModel tossedQuarter() {
  CoinModel m = diskModel(0.00567, 0.01213, 9.81);
  m.rim = {.thickness = 0.00175, .edgeRadius = 0.0003};
  const PrincipalMoments moments = filletedCylinderInertia(m.M, m.a, 0, m.rim.thickness, m.rim.edgeRadius);
  m.I_X = moments.I_X;
  m.I_Z = moments.I_Z;
  return m;
}

// The books every impact keeps (3.3, 3.6): the energy booked is the kinetic energy's fall, positive;
// the impulse inside its cone; the rim leaves the floor no faster than it came.
void expectTheBooksOfAnImpact(const CoinModel& m, const FlightState& s, const ImpactLaw& law) {
  const ImpactOutcome out = resolveImpact(m, s, law);
  ASSERT_FALSE(out.jammed);
  const double before = kineticEnergy(m, s), after = kineticEnergy(m, out.after);
  EXPECT_TRUE(isNear(out.energyLost, before - after, 1e-12 * before));
  EXPECT_GT(out.energyLost, 0);
  EXPECT_TRUE(isBelow(std::hypot(out.impulse.x(), out.impulse.z()), law.friction * out.impulse.y() * (1 + 1e-9)));
  EXPECT_GT(out.reboundSpeed, 0);
  EXPECT_TRUE(isBelow(out.reboundSpeed, out.approachSpeed));
}

TEST(Impact, ASlipSpirallingIntoZeroEnds) {
  const FlightState s{
      .q = Eigen::Quaterniond(0.19795497007678289, 0.8074850170554666, 0.47718579572028763, -0.2847375869386215),
      .omegaBody = Eigen::Vector3d(83.091424835864373, 103.57637717160461, -4.6151036009108157),
      .centre = Eigen::Vector3d(0.13582806773868678, 0.01017921264718355, 0.22094149168231511),
      .velocity = Eigen::Vector3d(0.46951827786838873, -0.77698323018712978, 1.4063432116250474)};
  expectTheBooksOfAnImpact(tossedQuarter(), s, {.restitution = 0.4, .friction = 0.5});
}

// The first landing of the toss at omega_X 30 rad/s, v_y 2.111 m/s: the slip's direction settles at
// once and closes at 0.27 m/s per N s, a thousandth of what (3.7) lets a step span, so the impact
// crawled 1 % a step and "did not end". A settled slip reaches its stop in one step.
TEST(Impact, ASlipClosingSlowlyAtTheConesEdgeEnds) {
  const FlightState s{
      .q = Eigen::Quaterniond(0.33765720215836265, 0.55068910778423841, 0.74564042357415661, -0.16355267998580347),
      .omegaBody = Eigen::Vector3d(-0.80011649511590166, 29.989328328494512, 2.9999999999999996),
      .centre = Eigen::Vector3d(0.053991429420728924, 0.0099750473854340882, 0),
      .velocity = Eigen::Vector3d(0.10000000000000001, -3.1854481150623966, 0)};
  expectTheBooksOfAnImpact(tossedQuarter(), s, {.restitution = 0.4, .friction = 0.5});
}

// (3.4) integrated the plain way, independently of resolveImpact's shortcuts (no settled step, no ray
// taken whole): the classical Runge-Kutta method at steps a twentieth of (3.7)'s bound and at most a
// millionth of the compression's impulse, friction's direction read afresh at every stage, each end
// placed by linear interpolation within its step. For an impact whose slip keeps away from zero.
Eigen::Vector3d impulseByFineSteps(const Eigen::Matrix3d& K, const Eigen::Vector3d& u0, const ImpactLaw& law) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  const auto rate = [&](const Eigen::Vector3d& u) {
    const Eigen::Vector3d slip(u.x(), 0, u.z());
    return Eigen::Vector3d(up - law.friction * slip / slip.norm());
  };
  Eigen::Matrix2d Ktt;
  Ktt << K(0, 0), K(0, 2), K(2, 0), K(2, 2);
  const double stiffness = law.friction * Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(Ktt).eigenvalues().maxCoeff();
  const double largest = -u0.y() / K(1, 1) * 1e-6;
  Eigen::Vector3d u = u0, P = Eigen::Vector3d::Zero();
  double work = 0, target = 0;
  bool compressing = true;
  for (long steps = 0; steps < 100'000'000; ++steps) {
    const double h = std::min(largest, 0.05 * std::hypot(u.x(), u.z()) / stiffness);
    const Eigen::Vector3d r1 = rate(u), r2 = rate(u + 0.5 * h * K * r1), r3 = rate(u + 0.5 * h * K * r2),
                          r4 = rate(u + h * K * r3);
    const Eigen::Vector3d dP = h / 6 * (r1 + 2 * r2 + 2 * r3 + r4);
    const Eigen::Vector3d next = u + K * dP;
    const double nextWork = work + 0.5 * h * (u.y() + next.y());
    if (compressing && next.y() >= 0) {
      const double f = -u.y() / (next.y() - u.y());
      compressing = false;
      target = (1 - law.restitution * law.restitution) * (work + 0.5 * f * h * u.y());
    } else if (!compressing && nextWork >= target) {
      return P + dP * (target - work) / (nextWork - work);
    }
    u = next;
    P += dP;
    work = nextWork;
  }
  ADD_FAILURE() << "impulseByFineSteps: the impact did not end";
  return P;
}

// The third landing of a natural flip in the toss study (docs/toss.md, e = 0.5, flip 3926): the slip
// passes close to zero, turns, and grows along its ray from 1e-5 m/s. Held to (3.7)'s steps it grew
// 0.05 % a step and the impact "did not end" after 6,400; on its ray (docs/flight.md 3.9) it ends
// in a few dozen steps, with the impulse of (3.4) integrated the plain way and the books of an impact.
TEST(Impact, ASlipGrowingAlongItsRayEnds) {
  const FlightState s{
      .q = Eigen::Quaterniond(0.55622017580019623, -0.5520433563933862, -0.43773033387971966, -0.44074868518949983),
      .omegaBody = Eigen::Vector3d(51.063648289725585, 190.89489626971181, -1.5501147091525187),
      .centre = Eigen::Vector3d(-3.9009044079330676e-06, 0.00096119923847959201, -3.6499078108763222e-06),
      .velocity = Eigen::Vector3d(-0.023605630481098996, 0.43131647670241197, 0.16612822709209446)};
  const CoinModel m = tossedQuarter();
  const ImpactLaw law{.restitution = 0.5, .friction = 0.3};
  expectTheBooksOfAnImpact(m, s, law);
  const Eigen::Vector3d r = lowestPointVector(m, s.q);
  const Eigen::Vector3d fine = impulseByFineSteps(contactCompliance(m, s.q, r), pointVelocity(s, r), law);
  const Eigen::Vector3d impulse = resolveImpact(m, s, law).impulse;
  EXPECT_TRUE(isBelow((impulse - fine).norm(), 1e-6 * fine.norm())) << impulse.transpose() << " | " << fine.transpose();
}

// A planar impact (the coin's axis, the contact and the velocities in one vertical plane, so the slip
// keeps to one line) solved in closed form, independently of resolveImpact's path: along the line
// (3.4) is piecewise linear in p, with phases of slip, of stick, and of slip reversed, each ending
// where the slip reaches zero, compression ends (u_n = 0) or the normal work reaches (3.5). `t` is
// the line's horizontal unit vector.
struct PlanarImpulse {
  double tangential = 0, normal = 0;  // N s, along t and e_y
};

PlanarImpulse planarImpact(const Eigen::Matrix3d& K, const Eigen::Vector3d& t, const Eigen::Vector3d& u0,
                           const ImpactLaw& law) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  const double Ktt = t.dot(K * t), Ktn = t.dot(K * up), Knn = up.dot(K * up), mu = law.friction;
  double slip = t.dot(u0), un = u0.y(), work = 0, Pt = 0, p = 0;
  bool compressing = true;
  double target = 0;
  const double stickRatio = -Ktn / Ktt;
  for (int phase = 0; phase < 8; ++phase) {
    // This phase's tangential impulse per normal impulse, and what it does to the slip and u_n.
    const bool sticks = slip == 0 && std::abs(stickRatio) <= mu;
    // A slip restarting from zero grows the way K_tn pushes it: K_tn - mu sign(K_tn) K_tt has K_tn's sign.
    const double ratio = sticks ? stickRatio : -mu * (slip != 0 ? (slip > 0 ? 1 : -1) : (Ktn > 0 ? 1 : -1));
    const double slipRate = Ktn + ratio * Ktt, unRate = Knn + ratio * Ktn;
    double dp = std::numeric_limits<double>::infinity();
    bool stops = false;
    if (slip != 0 && slip * slipRate < 0 && -slip / slipRate < dp) {
      dp = -slip / slipRate;
      stops = true;
    }
    double end;
    if (compressing) {
      end = -un / unRate;
    } else {  // work + un dp + unRate dp^2 / 2 = target
      end = (-un + std::sqrt(un * un + 2 * unRate * (target - work))) / unRate;
    }
    const bool ends = end <= dp;
    if (ends) {
      dp = end;
      stops = false;
    }
    work += un * dp + 0.5 * unRate * dp * dp;
    un += unRate * dp;
    slip = stops || sticks ? 0.0 : slip + slipRate * dp;
    Pt += ratio * dp;
    p += dp;
    if (ends) {
      if (!compressing) return {Pt, p};
      compressing = false;
      target = (1 - law.restitution * law.restitution) * work;
      if (work >= target) return {Pt, p};
    }
  }
  ADD_FAILURE() << "planarImpact: more than 8 phases";
  return {Pt, p};
}

// Random planar impacts, stopping, sticking or reversing their slip, against their closed form to
// 1e-9 of the impulse: the step that reaches a stop keeps the slip's direction to its end (docs/flight.md
// eq. 3.8). Before, its last stage read the rate at zero slip, frictionless, and a sticking impact at
// e = 1 gained up to 0.6 % of its energy.
TEST(Impact, PlanarImpactsMatchTheirPiecewiseLinearSolution) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1, 1), positive(0, 1);
  int sticking = 0, reversing = 0, compared = 0;
  for (const CoinModel& m : {diskModel(0.01, 0.02, 9.81), thickCoin(), tossedQuarter()}) {
    for (int k = 0; k < 300; ++k) {
      FlightState s;
      s.q = attitude(CoinState{.theta = 85 * kDeg * unit(random)});
      s.omegaBody = Eigen::Vector3d(60 * unit(random), 0, 0);
      s.velocity = Eigen::Vector3d(0, -1.5 * positive(random), unit(random));
      const Eigen::Vector3d r = lowestPointVector(m, s.q);
      const Eigen::Vector3d u0 = pointVelocity(s, r);
      if (u0.y() >= -1e-3) continue;
      const Eigen::Matrix3d K = contactCompliance(m, s.q, r);
      // The plane is x = 0: nothing couples the x direction to the other two.
      ASSERT_TRUE(isBelow(std::abs(u0.x()) + std::abs(K(0, 1)) + std::abs(K(0, 2)), 1e-12 * K.norm())) << k;
      const ImpactLaw law{.restitution = k % 3 == 0 ? 1.0 : positive(random), .friction = 1.2 * positive(random)};
      const ImpactOutcome out = resolveImpact(m, s, law);
      if (out.jammed) continue;
      const PlanarImpulse exact = planarImpact(K, Eigen::Vector3d::UnitZ(), u0, law);
      const double size = std::hypot(exact.tangential, exact.normal);
      EXPECT_TRUE(isNear(out.impulse.z(), exact.tangential, 1e-9 * size)) << k;
      EXPECT_TRUE(isNear(out.impulse.y(), exact.normal, 1e-9 * size)) << k;
      const double before = kineticEnergy(m, s);
      EXPECT_GE(out.energyLost, -1e-13 * before) << k;
      const double stickRatio = std::abs(K(2, 1) / K(2, 2));
      sticking += out.slipAfter.norm() <= 1e-9 * out.approachSpeed && stickRatio <= law.friction;
      reversing += u0.z() * out.slipAfter.z() < 0;
      ++compared;
    }
  }
  // Every kind of path was taken.
  EXPECT_GT(compared, 400);
  EXPECT_GT(sticking, 50);
  EXPECT_GT(reversing, 20);
}

TEST(Impact, WithoutFrictionReboundsAtEItsApproach) {
  const CoinModel m = thickCoin();
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int k = 0; k < 200; ++k) {
    FlightState s;
    s.q = Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random)).normalized();
    s.omegaBody = 50 * Eigen::Vector3d(unit(random), unit(random), unit(random));
    s.velocity = Eigen::Vector3d(unit(random), -1.5, unit(random));
    if (pointVelocity(s, lowestPointVector(m, s.q)).y() >= -1e-3) continue;
    for (const double e : {0.0, 0.37, 1.0}) {
      const ImpactOutcome out = resolveImpact(m, s, {.restitution = e, .friction = 0});
      EXPECT_TRUE(isNear(out.reboundSpeed, e * out.approachSpeed, 1e-12 * out.approachSpeed)) << k << " e " << e;
      EXPECT_TRUE(isBelow(std::hypot(out.impulse.x(), out.impulse.z()), 1e-15)) << k;
      if (e == 1.0) {
        EXPECT_TRUE(isBelow(std::abs(out.energyLost), 1e-12 * kineticEnergy(m, s))) << k;
      }
    }
  }
}

TEST(Impact, EdgeDownDropReboundsAtE) {
  // A disk upright (theta = 0), falling without spin: the impulse passes through G, friction has
  // nothing to do, and the centre's vertical speed is reversed and scaled by e.
  const CoinModel m = diskModel(0.0075, 0.0125, 9.81);
  const FlightState s{.velocity = Eigen::Vector3d(0, -1.3, 0)};
  const ImpactOutcome out = resolveImpact(m, s, {.restitution = 0.6, .friction = 0.4});
  EXPECT_TRUE(isNear(out.after.velocity.y(), 0.6 * 1.3, 1e-14));
  EXPECT_TRUE(isBelow(out.after.omegaBody.norm(), 1e-15));
  EXPECT_TRUE(isNear(out.energyLost, 0.5 * m.M * 1.3 * 1.3 * (1 - 0.36), 1e-14 * m.M));
}

TEST(Impact, HighFrictionEndsSticking) {
  // A tilted coin landing while skidding: with mu large the slip is stopped during compression and
  // the contact sticks, so the contact point leaves the floor without slipping.
  const CoinModel m = thickCoin();
  FlightState s;
  s.q = attitude(CoinState{.theta = 40 * kDeg, .phi = 0.3});
  s.velocity = Eigen::Vector3d(0.05, -1.0, -0.02);
  s.omegaBody = Eigen::Vector3d(1, -1, 2);
  const ImpactOutcome out = resolveImpact(m, s, {.restitution = 0.5, .friction = 1});
  ASSERT_FALSE(out.jammed);
  EXPECT_TRUE(isBelow(out.slipAfter.norm(), 1e-12 * out.approachSpeed));
  // and with little friction it slips throughout, losing less.
  const ImpactOutcome slippery = resolveImpact(m, s, {.restitution = 0.5, .friction = 0.05});
  EXPECT_GT(slippery.slipAfter.norm(), 0.1);
  EXPECT_LT(slippery.energyLost, out.energyLost);
}

}  // namespace
}  // namespace coinroll::physics
