// The coin toss (docs/toss.md): how often a flipped coin shows the side it started on, from the
// program's own flight (physics/flight.h, integrated by DOP853), against Diaconis, Holmes and
// Montgomery's formula (2007) for a coin caught in the hand, and against the 0.508 that Bartos et
// al. (2023) measured over 350,757 human flips.
//
// Run: build/bench/toss_study [OUT_DIR]   (default docs/; writes toss_caught.csv)

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "integrate/trajectory.h"
#include "physics/coin_model.h"
#include "physics/flight.h"
#include "physics/solid_inertia.h"

namespace {

using namespace coinroll;

constexpr double kDeg = std::numbers::pi / 180;

// A US quarter: 24.26 mm across, 1.75 mm thick, 5.67 g.
physics::CoinModel quarter() {
  physics::CoinModel m = physics::diskModel(5.67e-3, 12.13e-3, 9.81);
  m.rim = {.thickness = 1.75e-3, .edgeRadius = 0.3e-3};
  const physics::PrincipalMoments moments = physics::filletedCylinderInertia(m.M, m.a, 0, 1.75e-3, 0.3e-3);
  m.I_X = moments.I_X;
  m.I_Z = moments.I_Z;
  return m;
}

// Heads up (e_Z along +y), spinning with angular momentum |L| at psi from the normal, in the x-y plane.
physics::FlightState launch(const physics::CoinModel& m, double psi, double spin, double upSpeed) {
  physics::FlightState s;
  s.q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY());
  const Eigen::Vector3d L = m.I_X * spin * Eigen::Vector3d(std::sin(psi), std::cos(psi), 0);
  s.omegaBody = (s.q.conjugate() * L).cwiseQuotient(Eigen::Vector3d(m.I_X, m.I_X, m.I_Z));
  s.centre = Eigen::Vector3d(0, 1.0, 0);
  s.velocity = Eigen::Vector3d(0, upSpeed, 0);
  return s;
}

struct FlightRhs {
  physics::CoinModel model;
  integrate::Vec<physics::kFlightStateSize> operator()(double, const integrate::Vec<physics::kFlightStateSize>& y) const {
    return physics::flightRhs(model, y);
  }
};

// Caught at the height it left the hand, 2 v / g later: does the same face look up?
bool caughtSameSide(const physics::CoinModel& m, const physics::FlightState& start) {
  const double flightTime = 2 * start.velocity.y() / m.g;
  integrate::Trajectory<physics::kFlightStateSize, FlightRhs> run(
      FlightRhs{m}, 0, physics::toVector(start), {.method = integrate::Method::Dop853, .rtol = 1e-10, .atol = 1e-12});
  const physics::FlightState end = physics::toFlightState(*run.stateAt(flightTime));
  return (end.q * Eigen::Vector3d::UnitZ()).y() > 0;
}

// Diaconis, Holmes and Montgomery (2007), eq. (1): the chance of the starting side over a flight
// time uniform over many precession periods, for angle psi between the normal and L.
double diaconisSameSide(double psi) {
  const double cot2 = std::pow(1 / std::tan(psi), 2);
  return cot2 >= 1 ? 1.0 : 0.5 + std::asin(cot2) / std::numbers::pi;
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path out = argc > 1 ? argv[1] : "docs";
  const physics::CoinModel m = quarter();
  std::ofstream csv(out / "toss_caught.csv");
  csv << "psi_deg,tosses,same_side,diaconis\n";
  // The normal goes round L once per precession period 2 pi I_X / |L|; flight times spread evenly over
  // a whole number of them make the fraction the formula's time average, to one toss in kTosses.
  const double spin = 38 * 2 * std::numbers::pi;
  const double period = 2 * std::numbers::pi / spin;
  constexpr int kPeriods = 8;
  fmt::print("Caught tosses: flight time uniform over {} precession periods from 0.4 s (to {:.3f} s), 38 turns/s\n",
             kPeriods, 0.4 + kPeriods * period);
  fmt::print("| psi (deg) | tosses | same side, simulated | Diaconis et al. | difference |\n|---|---|---|---|---|\n");
  constexpr int kTosses = 2000;
  for (const double psiDeg : {30.0, 45.5, 50.0, 60.0, 70.0, 80.0, 85.0, 90.0}) {
    int same = 0;
    for (int k = 0; k < kTosses; ++k) {
      const double flightTime = 0.4 + kPeriods * period * (k + 0.5) / kTosses;
      same += caughtSameSide(m, launch(m, psiDeg * kDeg, spin, 0.5 * m.g * flightTime)) ? 1 : 0;
    }
    const double simulated = static_cast<double>(same) / kTosses, formula = diaconisSameSide(psiDeg * kDeg);
    fmt::print("| {:.1f} | {} | {:.4f} | {:.4f} | {:+.4f} |\n", psiDeg, kTosses, simulated, formula, simulated - formula);
    csv << fmt::format("{},{},{},{}\n", psiDeg, kTosses, simulated, formula);
  }
  if (!csv) throw std::runtime_error("could not write toss_caught.csv");

  // Natural flips: the precession angle psi spread below 90 degrees (a flip hit exactly under its
  // diameter has psi = 90 degrees), spin and launch speed over a hand's range. Diaconis et al. report
  // about .51 for natural flips, Bartos et al. 0.508 measured; the spread that matches is the answer.
  fmt::print("\nNatural caught flips: 30-45 turns/s, launch 2-3 m/s up, psi uniform in [90 - spread, 90] deg\n");
  fmt::print("| spread (deg) | tosses | same side, simulated | Diaconis et al. averaged |\n|---|---|---|---|\n");
  std::mt19937 random(2007);
  std::uniform_real_distribution<double> unit(0, 1);
  constexpr int kNatural = 10000;
  for (const double spread : {5.0, 10.0, 15.0, 20.0}) {
    int same = 0;
    double formula = 0;
    for (int k = 0; k < kNatural; ++k) {
      const double psi = (90 - spread * unit(random)) * kDeg;
      const double turns = 30 + 15 * unit(random), up = 2 + unit(random);
      same += caughtSameSide(m, launch(m, psi, turns * 2 * std::numbers::pi, up)) ? 1 : 0;
      formula += diaconisSameSide(psi) / kNatural;
    }
    fmt::print("| {:.0f} | {} | {:.4f} | {:.4f} |\n", spread, kNatural, static_cast<double>(same) / kNatural, formula);
  }
}
