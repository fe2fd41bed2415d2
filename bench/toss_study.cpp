// The coin toss (docs/toss.md): how often a flipped coin shows the side it started on, from the
// program's own flight (physics/flight.h, its closed form), against Diaconis, Holmes and
// Montgomery's formula (2007) for a coin caught in the hand, and against the 0.508 that Bartos et
// al. (2023) measured over 350,757 human flips.
//
// The same natural flips landing on a table (flight, impacts, sliding and rolling: docs/flight.md)
// show how much the bounces change the fraction, and time a toss from the hand to its decided face
// and, for every tenth, to rest.
//
// Run: build/bench/toss_study [OUT_DIR [LANDED_TOSSES [RESTITUTIONS]]]   (default docs/, 2000 and 0.2,0.5,0.8;
// writes toss_caught.csv, toss_landed.csv). RESTITUTIONS, comma-separated, lets one process take each
// restitution of a long study, so that the cores share it.

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "physics/coin_model.h"
#include "physics/flight.h"
#include "physics/solid_inertia.h"
#include "physics/validity.h"
#include "pipeline/coin_run.h"
#include "pipeline/simulation.h"
#include "scene/scene_loader.h"

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

// Caught at the height it left the hand, 2 v / g later: does the same face look up? The flight is
// the program's closed form (physics::flightAfter; tests/physics/flight_test.cpp checks it against
// the integrated equations of motion).
bool caughtSameSide(const physics::CoinModel& m, const physics::FlightState& start) {
  const double flightTime = 2 * start.velocity.y() / m.g;
  const physics::FlightState end = physics::flightAfter(m, start, flightTime);
  return (end.q * Eigen::Vector3d::UnitZ()).y() > 0;
}

// Diaconis, Holmes and Montgomery (2007), eq. (1): the chance of the starting side over a flight
// time uniform over many precession periods, for angle psi between the normal and L.
double diaconisSameSide(double psi) {
  const double cot2 = std::pow(1 / std::tan(psi), 2);
  return cot2 >= 1 ? 1.0 : 0.5 + std::asin(cot2) / std::numbers::pi;
}

// The scene of a flip from the hand, heads up, landing on a hard table 0.3 m below the launch.
nlohmann::json landedFlip(double psi, double turns, double upSpeed, double restitution) {
  const physics::CoinModel m = quarter();
  const double L = m.I_X * turns * 2 * std::numbers::pi;
  return {{"coin", {{"radius", m.a}, {"mass", m.M}, {"thickness", 1.75e-3}, {"edge_radius", 0.3e-3}}},
          {"initial",
           {{"theta", -89.999},
            {"omega_X", L * std::sin(psi) / m.I_X},
            {"omega_Z", L * std::cos(psi) / m.I_Z},
            {"y", 0.3},
            {"v_y", upSpeed}}},
          {"friction", 0.3},
          {"sliding", true},
          {"flight", true},
          {"restitution", restitution},
          {"effects", {{{"type", "rolling_resistance"}, {"length", 2e-5}}}},
          {"duration", 300}};
}

// How a landed flip ended: the face up, the event, when, and its cost.
struct LandedOutcome {
  bool headsUp = false;
  bool onEdge = false;  // the event on-edge: no face up (docs/flight.md §4a)
  std::string end;      // the event's name, or "duration"
  double t = 0;         // s, simulated
  long evaluations = 0;
};

// `decided`: stop_when_decided, the run ends once its face is final (docs/flight.md §5a); else it
// runs to rest.
LandedOutcome landedFace(nlohmann::json flip, bool decided) {
  flip["stop_when_decided"] = decided;
  const pipeline::Simulation sim = pipeline::buildSimulation(scene::parseScene(flip, "toss"));
  pipeline::CoinRun run(sim);
  const double duration = flip["duration"].get<double>();
  double t = 0, theta = 0;
  for (double next = 0.01; next <= duration; next += 0.01) {
    const std::optional<pipeline::RunSample> sample = run.sampleAt(next);
    if (!sample) break;
    t = next;
    theta = sample->state.theta;
  }
  LandedOutcome outcome;
  outcome.evaluations = run.stats().rhsEvaluations;
  if (const std::optional<pipeline::RunEvent> stop = run.stoppedBy()) {
    outcome.headsUp = stop->state.theta < 0;
    outcome.onEdge = stop->event == physics::ModelEvent::OnEdge;
    outcome.end = physics::eventName(stop->event);
    outcome.t = stop->t;
  } else {
    outcome.headsUp = theta < 0;
    outcome.end = "duration";
    outcome.t = t;
  }
  return outcome;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
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
    fmt::print("| {:.1f} | {} | {:.4f} | {:.4f} | {:+.4f} |\n", psiDeg, kTosses, simulated, formula,
               simulated - formula);
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

  // The same flips landing on the table (spread 15 degrees): the bounces and the roll decide again.
  // Each is run to its decided face (stop_when_decided); every tenth also to rest, which must show
  // the same face, and whose cost against the decided run's is the ratio quoted.
  std::ofstream landedCsv(out / "toss_landed.csv");
  landedCsv << "restitution,tosses,same_side,caught_same_side,ms_per_toss,decided_at_s,to_rest_ms_per_toss\n";
  fmt::print("\nNatural flips (spread 15 deg) landing on a table 0.3 m below the hand, friction 0.3\n");
  fmt::print(
      "| restitution | tosses | same side, landed | same side, caught | ms per toss, decided | "
      "decided after (s) | ms per toss, to rest | endings |\n|---|---|---|---|---|---|---|---|\n");
  const int kLanded = argc > 2 ? std::stoi(argv[2]) : 2000;
  std::vector<double> restitutions = {0.2, 0.5, 0.8};
  if (argc > 3) {
    restitutions.clear();
    std::stringstream list(argv[3]);
    for (std::string item; std::getline(list, item, ',');) restitutions.push_back(std::stod(item));
  }
  // Each restitution's flips to rest: the median's wall time on one core and evaluations of the
  // right-hand side (the latter the same on any machine).
  std::vector<std::string> restLines;
  for (const double restitution : restitutions) {
    std::vector<double> restTimes, restEvaluations;
    std::mt19937 flips(2023);
    int same = 0, caught = 0, checked = 0, edges = 0;
    double decided = 0, decidedMs = 0, restMs = 0;
    std::map<std::string, int> endings;
    for (int k = 0; k < kLanded; ++k) {
      const double psi = (90 - 15 * unit(flips)) * kDeg;
      const double turns = 30 + 15 * unit(flips), up = 2 + unit(flips);
      const nlohmann::json flip = landedFlip(psi, turns, up, restitution);
      const auto begin = std::chrono::steady_clock::now();
      LandedOutcome landed;
      try {
        landed = landedFace(flip, true);
      } catch (const std::exception& e) {
        // Counted among the endings and shown with its scene, so that one refusal neither hides nor
        // ends the study.
        fmt::print(stderr, "flip {} (restitution {}): {}\n{}\n", k, restitution, e.what(), flip.dump());
        ++endings[fmt::format("error ({})", e.what())];
        continue;
      }
      decidedMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
      same += landed.headsUp && !landed.onEdge ? 1 : 0;
      edges += landed.onEdge ? 1 : 0;
      decided += landed.t / kLanded;
      ++endings[landed.end];
      caught += caughtSameSide(m, launch(m, psi, turns * 2 * std::numbers::pi, up)) ? 1 : 0;
      if (k % 10 == 0 && landed.end == "decided") {
        const auto restBegin = std::chrono::steady_clock::now();
        LandedOutcome atRest;
        try {
          atRest = landedFace(flip, false);
        } catch (const std::exception& e) {
          fmt::print(stderr, "flip {} to rest (restitution {}): {}\n{}\n", k, restitution, e.what(), flip.dump());
          ++endings[fmt::format("error to rest ({})", e.what())];
          continue;
        }
        restTimes.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - restBegin).count());
        restMs += restTimes.back();
        restEvaluations.push_back(static_cast<double>(atRest.evaluations));
        ++checked;
        if (atRest.headsUp != landed.headsUp) {
          throw std::runtime_error(fmt::format("flip {}: decided {} but rests {}", k, landed.headsUp, atRest.headsUp));
        }
      }
    }
    // Of the flips that show a face: one left standing on its edge shows neither.
    const double landedFraction = static_cast<double>(same) / std::max(kLanded - edges, 1);
    const double caughtFraction = static_cast<double>(caught) / kLanded;
    std::string endingText;
    for (const auto& [name, count] : endings)
      endingText += fmt::format("{}{} {}", endingText.empty() ? "" : ", ", count, name);
    fmt::print("| {} | {} | {:.4f} | {:.4f} | {:.2f} | {:.2f} | {:.1f} ({} flips) | {} |\n", restitution, kLanded,
               landedFraction, caughtFraction, decidedMs / kLanded, decided, restMs / std::max(checked, 1), checked,
               endingText);
    landedCsv << fmt::format("{},{},{},{},{},{},{}\n", restitution, kLanded, landedFraction, caughtFraction,
                             decidedMs / kLanded, decided, restMs / std::max(checked, 1));
    restLines.push_back(fmt::format("| {} | {} | {:.1f} | {:.0f} |", restitution, restTimes.size(), median(restTimes),
                                    median(restEvaluations)));
  }
  fmt::print(
      "\nFlips to rest (every tenth decided flip)\n| restitution | flips | median ms | median evaluations |\n"
      "|---|---|---|---|\n{}\n",
      fmt::join(restLines, "\n"));
  if (!landedCsv) throw std::runtime_error("could not write toss_landed.csv");
}
