// Rolling and sliding (docs/sliding.md) against truths computed another way: the skid's closed
// form, pure rolling as friction grows without bound, the energy budget across switches, and the
// rolling run's own slip event for the instant sliding begins.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "physics/contact_mode.h"
#include "physics/quaternion_dynamics.h"
#include "physics/sliding.h"
#include "pipeline/coin_run.h"
#include "pipeline/run_record.h"
#include "pipeline/snapshot.h"
#include "pipeline/simulation.h"
#include "pipeline/trajectory_csv.h"
#include "scene/scene_loader.h"
#include "scene_simulation.h"
#include "tolerance.h"

namespace {

using namespace coinroll;
using coinroll::testing::isBelow;
using coinroll::testing::isNear;

using coinroll::testing::kTightSolver;
using coinroll::testing::simulationOf;

nlohmann::json skid(const nlohmann::json& coin, double v0, double mu, const nlohmann::json& solver = kTightSolver) {
  return {{"coin", coin},  {"friction", mu},  {"sliding", true}, {"initial", {{"theta", 0}, {"v_x", v0}}},
          {"duration", 1}, {"solver", solver}};
}

TEST(Sliding, AnUprightSkidRollsAtTheClosedFormTimeSpeedAndWork) {
  // v0 / (mu g (1 + M a^2 / I_Z)) and v0 M a^2 / (I_Z + M a^2): a disk, a ring, and a thick disk whose
  // fully rounded rim touches at radius a when upright, with the I_Z of its solid.
  const double v0 = 1.3, mu = 0.25, g = 9.81;
  for (const nlohmann::json& coin :
       {nlohmann::json{{"radius", 0.0375}, {"mass", 0.4}},
        nlohmann::json{{"shape", "ring"}, {"radius", 0.04}, {"inner_radius", 0.03}, {"mass", 0.2}},
        nlohmann::json{{"radius", 0.0375}, {"mass", 0.449}, {"thickness", 0.013}}}) {
    const pipeline::Simulation sim = simulationOf(skid(coin, v0, mu));
    const double M = sim.model.M, a = sim.model.a, I_Z = sim.model.I_Z;
    const double tStar = v0 / (mu * g * (1 + M * a * a / I_Z));
    const double vAfter = v0 * M * a * a / (I_Z + M * a * a);
    const double work = 0.5 * M * v0 * v0 - 0.5 * (M + I_Z / (a * a)) * vAfter * vAfter;
    pipeline::CoinRun run(sim);
    const pipeline::RunSample end = *run.sampleAt(1.0);
    // The start off the rolling constraint (t = 0, to sliding), then the stop.
    ASSERT_EQ(run.switches().size(), 2u) << coin.dump();
    EXPECT_TRUE(run.switches()[0].toSliding);
    EXPECT_EQ(run.switches()[0].t, 0.0);
    EXPECT_FALSE(run.switches()[1].toSliding);
    EXPECT_TRUE(isNear(run.switches()[1].t, tStar, 1e-9)) << coin.dump();
    EXPECT_FALSE(end.forward.sliding);
    EXPECT_TRUE(isNear(end.forward.velocity.x() / vAfter, 1, 1e-9)) << coin.dump();
    EXPECT_TRUE(isNear(end.dissipated / work, 1, 1e-9)) << coin.dump();
    EXPECT_TRUE(
        isBelow(std::abs(end.forward.energy + end.dissipated - 0.5 * M * v0 * v0 - M * g * end.forward.centre.y()) /
                    (0.5 * M * v0 * v0),
                1e-9));
  }
}

TEST(Sliding, AHardShortSkidEndsAtItsClosedFormInsteadOfStalling) {
  // mu = 2000, and mu = 1000 from 0.1 m/s: the slip closes at 3 mu g (3e4-6e4 m/s^2) and stops within
  // 1.7-34 us. At the default tolerances these runs stalled a few 1e-16 s short of the stop
  // ("integration stalled", steps of 8e-15 s; docs/sliding.md §4.5, "Hard skids"); the slide now ends
  // where the slip would stop within physics::slipStopLead (1e-13 s), and the coin rolls on at the
  // closed form's speed (docs/sliding.md §5).
  const double g = 9.81;
  for (const auto& [mu, v0] : {std::pair{2000.0, 1.0}, std::pair{2000.0, 0.1}, std::pair{1000.0, 0.1}}) {
    const pipeline::Simulation sim =
        simulationOf(skid({{"radius", 0.0375}, {"mass", 0.4}}, v0, mu, nlohmann::json::object()));
    const double M = sim.model.M, a = sim.model.a, I_Z = sim.model.I_Z;
    const double tStar = v0 / (mu * g * (1 + M * a * a / I_Z));
    const double vAfter = v0 * M * a * a / (I_Z + M * a * a);
    const double work = 0.5 * M * v0 * v0 - 0.5 * (M + I_Z / (a * a)) * vAfter * vAfter;
    pipeline::CoinRun run(sim);
    const std::optional<pipeline::RunSample> end = run.sampleAt(1.0);
    ASSERT_TRUE(end.has_value()) << "mu " << mu << ", v0 " << v0;
    ASSERT_EQ(run.switches().size(), 2u) << "mu " << mu << ", v0 " << v0;
    const double early = tStar - run.switches()[1].t;  // s: the lead, and the event's location
    EXPECT_TRUE(early >= -1e-15 && early <= 2 * physics::slipStopLead(tStar)) << early;
    EXPECT_FALSE(end->forward.sliding);
    // The last lead of sliding is applied as one increment, so the roll starts on the closed form
    // (measured 3e-15; dropping that slip instead cost 2.4e-7 of the work).
    EXPECT_TRUE(isNear(end->forward.velocity.x() / vAfter, 1, 1e-12)) << end->forward.velocity.x() - vAfter;
    EXPECT_TRUE(isNear(end->dissipated / work, 1, 1e-12)) << end->dissipated - work;
  }
}

TEST(Sliding, AnUprightSkidAtTheDefaultTolerancesCreepsToItsStop) {
  // The default tolerances hand the last millimetres per second of slip to the creeping slide, where
  // the upright coin's rest is neutral: friction must keep its side while a trial step passes zero
  // slip (it once flipped with the slip, and the step shrank without end).
  const double v0 = 0.5, mu = 0.3, g = 9.81;
  const pipeline::Simulation sim =
      simulationOf(skid({{"radius", 0.0375}, {"mass", 0.4}}, v0, mu, nlohmann::json::object()));
  const double tStar = v0 / (mu * g * (1 + sim.model.M * sim.model.a * sim.model.a / sim.model.I_Z));
  pipeline::CoinRun run(sim);
  const pipeline::RunSample end = *run.sampleAt(1.0);
  ASSERT_EQ(run.switches().size(), 2u);  // slides at t = 0, rolls at t*
  EXPECT_TRUE(isNear(run.switches()[1].t, tStar, 1e-9));
  EXPECT_FALSE(end.forward.sliding);
}

std::vector<pipeline::RunSample> samples(const pipeline::Simulation& sim, double dt) {
  pipeline::CoinRun run(sim);
  std::vector<pipeline::RunSample> out;
  for (int k = 0; k * dt <= sim.duration + 1e-12; ++k) {
    const std::optional<pipeline::RunSample> s = run.sampleAt(k * dt);
    if (!s) break;
    out.push_back(*s);
  }
  return out;
}

TEST(Sliding, WithFrictionWithoutBoundItIsPureRolling) {
  nlohmann::json doc = {{"coin", {{"radius", 0.0375}, {"mass", 0.4}, {"thickness", 0.004}}},
                        {"initial", {{"theta", 25}, {"omega_X", 0.4}, {"omega_Y", 4.0}, {"omega_Z", 11.0}}},
                        {"duration", 3},
                        {"solver", {{"formulation", "quaternion"}, {"rtol", 1e-12}, {"atol", 1e-14}}}};
  const std::vector<pipeline::RunSample> rolling = samples(simulationOf(doc), 0.01);
  doc["friction"] = 1e6;
  doc["sliding"] = true;
  const pipeline::Simulation sim = simulationOf(doc);
  const std::vector<pipeline::RunSample> hybrid = samples(sim, 0.01);
  ASSERT_EQ(rolling.size(), hybrid.size());
  double worst = 0;
  for (std::size_t i = 0; i < rolling.size(); ++i) {
    worst = std::max({worst, std::abs(rolling[i].state.theta - hybrid[i].state.theta),
                      (rolling[i].forward.centre - hybrid[i].forward.centre).norm() / 0.0375});
    EXPECT_FALSE(hybrid[i].forward.sliding);
  }
  EXPECT_TRUE(isBelow(worst, 1e-12));
}

TEST(Sliding, SlidingBeginsWhereTheRollingRunFirstNeedsMuN) {
  // A coin let go tilted with a slow spin falls; rolling, its contact needs more and more friction.
  // The rolling run's slip event (on_invalid stop) is the truth for the instant sliding begins.
  nlohmann::json doc = {{"coin", {{"radius", 0.0375}, {"mass", 0.4}}},
                        {"initial", {{"theta", 20}, {"omega_Z", 1.0}}},
                        {"friction", 0.5},
                        {"duration", 0.5},
                        {"solver", {{"formulation", "quaternion"}, {"rtol", 1e-12}, {"atol", 1e-14}}}};
  pipeline::CoinRun rolling(simulationOf(doc));
  rolling.sampleAt(0.5);
  ASSERT_TRUE(rolling.stoppedBy().has_value());
  ASSERT_EQ(rolling.stoppedBy()->event, physics::ModelEvent::Slip);
  doc["sliding"] = true;
  pipeline::CoinRun hybrid(simulationOf(doc));
  hybrid.sampleAt(rolling.stoppedBy()->t + 1e-3);
  ASSERT_FALSE(hybrid.switches().empty());
  EXPECT_TRUE(hybrid.switches()[0].toSliding);
  EXPECT_TRUE(isNear(hybrid.switches()[0].t, rolling.stoppedBy()->t, 1e-12));
}

TEST(Sliding, ASlideDrivenIntoPainlevesBandStopsWithPainleveAtTheClosedFormTilt) {
  // A thin disk at 60 deg, no spin, slipping sideways at 3 m/s under mu 2: the motion stays in one
  // plane with the slip along -h, friction tips it upright, and the normal force grows like
  // 1 / (t* - t) as D falls. D = (k + sin^2 theta - mu sin theta cos theta) / k (docs/sliding.md
  // (3.3)-(3.5), k = 1/4) reaches kPainleveMargin at the upper root of
  // sin^2 theta - mu sin theta cos theta + k (1 - margin) = 0, the truth for the stop's tilt. (The
  // run once stalled there, its steps shrinking to 1e-14 s.)
  const double mu = 2, k = 0.25;
  const nlohmann::json doc = {{"coin", {{"radius", 0.0375}, {"mass", 0.4}}},
                              {"initial", {{"theta", 60}, {"omega_Z", 0}, {"v_z", -3}}},
                              {"sliding", true},
                              {"friction", mu},
                              {"duration", 1},
                              {"solver", kTightSolver}};
  const pipeline::Simulation sim = simulationOf(doc);
  pipeline::CoinRun run(sim);
  EXPECT_FALSE(run.sampleAt(1.0).has_value());
  ASSERT_TRUE(run.stoppedBy().has_value());
  EXPECT_EQ(run.stoppedBy()->event, physics::ModelEvent::Painleve);
  const auto residual = [&](double theta) {
    return std::sin(theta) * std::sin(theta) - mu * std::sin(theta) * std::cos(theta) +
           k * (1 - physics::kPainleveMargin);
  };
  double lo = 45 * std::numbers::pi / 180, hi = 60 * std::numbers::pi / 180;  // residual < 0 at lo, > 0 at hi
  ASSERT_LT(residual(lo), 0);
  ASSERT_GT(residual(hi), 0);
  for (int i = 0; i < 100; ++i) (residual(0.5 * (lo + hi)) < 0 ? lo : hi) = 0.5 * (lo + hi);
  EXPECT_TRUE(isNear(run.stoppedBy()->state.theta, lo, 1e-9)) << run.stoppedBy()->state.theta * 180 / std::numbers::pi;
  pipeline::CoinRun again(sim);  // a run answers forward in time only
  const pipeline::RunSample last = *again.sampleAt(run.stoppedBy()->t);
  EXPECT_TRUE(last.forward.sliding);
  EXPECT_GT(last.forward.reaction.N, 100 * sim.model.M * sim.model.g);  // the normal force running away
}

TEST(Sliding, TheEnergyBudgetClosesAcrossSwitches) {
  // A tilted spinning coin set down skidding sideways: it slides, rolls, and may switch again; energy
  // + dissipated (friction's mu N |s| and the air's) stays the initial energy.
  const nlohmann::json doc = {
      {"coin", {{"radius", 0.0375}, {"mass", 0.4}, {"thickness", 0.003}}},
      {"initial", {{"theta", 20}, {"omega_Y", 5.0}, {"omega_Z", 12.0}, {"v_x", 0.3}, {"v_z", -0.2}}},
      {"friction", 0.3},
      {"sliding", true},
      {"effects", {{{"type", "air_drag"}}}},
      {"duration", 1},
      {"solver", {{"rtol", 1e-10}}}};
  const pipeline::Simulation sim = simulationOf(doc);
  pipeline::CoinRun run(sim);
  const double E0 = run.sampleAt(0)->forward.energy;
  double worst = 0;
  bool slid = false, rolled = false;
  for (int k = 1; k <= 100; ++k) {
    const std::optional<pipeline::RunSample> s = run.sampleAt(0.01 * k);
    if (!s) break;
    worst = std::max(worst, std::abs(s->forward.energy + s->dissipated - E0) / E0);
    (s->forward.sliding ? slid : rolled) = true;
  }
  EXPECT_TRUE(slid && rolled);
  EXPECT_GE(run.switches().size(), 4u);  // rolls, slides, rolls, ... (10 in this second)
  EXPECT_TRUE(isBelow(worst, 1e-9));
}

TEST(Sliding, TheCreepingDirectionFollowsAClosingFreeSlipToSecondOrder) {
  // The coin toss's first slide, closing freely towards its stop: its slip's own direction against the
  // reduced one of the creeping slide (docs/sliding.md eq. 4.17) at the same state. With the slip's
  // rate in the lag the angle between them falls as |s|^2 (5.3 s^2/m^2 here); without it, as 0.58 |s|.
  std::ifstream in(std::string(COINROLL_SOURCE_DIR) + "/examples/coin_toss.json");
  nlohmann::json doc = nlohmann::json::parse(in);
  doc["duration"] = 1.85;  // to the first slide's end (1.797 s), before the second
  const pipeline::Simulation sim = pipeline::buildSimulation(scene::parseScene(doc, "test"));
  double slideEnd = 0;
  {
    pipeline::CoinRun run(sim);
    run.sampleAt(sim.duration);
    ASSERT_GE(run.switches().size(), 2u);
    ASSERT_FALSE(run.switches()[1].toSliding);
    slideEnd = run.switches()[1].t;
  }
  pipeline::CoinRun run(sim);
  std::vector<double> ratios;
  constexpr double kLeastSlip = 3e-4, kMostSlip = 1.5e-3;  // m/s: free (the creep takes over below 1e-4)
  for (double t = slideEnd - 3e-3; t < slideEnd; t += 1e-5) {
    const std::optional<pipeline::RunSample> s = run.sampleAt(t);
    ASSERT_TRUE(s);
    const Eigen::Vector2d slip(s->forward.slip.x(), s->forward.slip.z());
    if (!s->forward.sliding || slip.norm() < kLeastSlip || slip.norm() > kMostSlip) continue;
    const physics::SlidingState state{.attitude = physics::fromEulerState(s->state), .slip = slip};
    const std::optional<physics::Creep> creep =
        physics::findCreep(sim.model, physics::toVector(state), sim.model.friction.kinetic);
    ASSERT_TRUE(creep);
    const double angle = std::acos(
        std::clamp(slip.normalized().dot(Eigen::Vector2d(creep->slipHat.x(), creep->slipHat.z())), -1.0, 1.0));
    EXPECT_LT(angle, 0.05 * slip.norm()) << "t = " << t;  // a first-order lag leaves 0.58 |s|
    ratios.push_back(angle / slip.squaredNorm());
  }
  ASSERT_GE(ratios.size(), 10u);
  const auto [least, most] = std::minmax_element(ratios.begin(), ratios.end());
  EXPECT_LT(*most / *least, 1.2);  // second order: angle / |s|^2 steady as |s| falls five-fold
}

TEST(Sliding, LiftOffEndsASlidingRunEvenWhenTheSceneSaysWarn) {
  // A thick coin thrown down spinning and wobbling hard: it rolls, slides, and its normal force
  // falls through zero 11 ms in. Integrated on as a contact, N < 0 turned the sliding friction
  // -mu N s_hat into a push along the slip (power -59 W, the energy up 4 % in 5 ms;
  // docs/sliding.md §4.5). Free flight is not modelled, so the run must end there: every sample
  // before it holds the contact (N >= 0) with friction taking energy (power >= 0), and no energy
  // comes from nowhere.
  const nlohmann::json doc = {
      {"coin", {{"radius", 0.0375}, {"mass", 0.4}, {"thickness", 0.013}, {"edge_radius", 0.0015}}},
      {"initial",
       {{"theta", 18.19115672673155},
        {"omega_X", 17.323401068130792},
        {"omega_Y", -48.73684958709181},
        {"omega_Z", -56.59830281735924}}},
      {"friction", 0.5178825519599348},
      {"friction_static", 0.6214590623519217},
      {"sliding", true},
      {"on_invalid", "warn"},
      {"duration", 0.05}};
  const pipeline::Simulation sim = simulationOf(doc);
  pipeline::CoinRun run(sim);
  const double E0 = run.sampleAt(0)->forward.energy;
  double lowestN = INFINITY, lowestPower = INFINITY, highestEnergy = 0, t = 0;
  for (; t <= 0.05; t += 1e-5) {
    const std::optional<pipeline::RunSample> s = run.sampleAt(t);
    if (!s) break;
    lowestN = std::min(lowestN, s->forward.reaction.N);
    lowestPower = std::min(lowestPower, s->forward.loads.power);
    highestEnergy = std::max(highestEnergy, s->forward.energy);
  }
  ASSERT_TRUE(run.stoppedBy().has_value()) << "ran to t = " << t << " s past the lift-off";
  EXPECT_EQ(run.stoppedBy()->event, physics::ModelEvent::LiftOff);
  EXPECT_TRUE(isNear(run.stoppedBy()->t, 0.011042468, 1e-6)) << run.stoppedBy()->t;
  EXPECT_TRUE(run.warnings().empty());
  EXPECT_GE(lowestN, -1e-6 * sim.model.M * sim.model.g);
  EXPECT_GE(lowestPower, 0);
  EXPECT_LE(highestEnergy, E0 * (1 + 1e-12));
}

TEST(Sliding, AWobbleThatGrazesTheConeBetweenTwoStepEndsSlides) {
  // A wobbling thin coin whose rolling reaction leaves the cone (F/N up to 0.27137 in a cone of 0.27)
  // for a few milliseconds at t = 2.167 s, inside one step whose ends are both in the cone: read at
  // the step ends only, the run rolled on through it (docs/sliding.md §4.5). Every rolling sample
  // must lie in the cone, as the switch rule says.
  const nlohmann::json doc = {{"coin", {{"radius", 0.0375}, {"mass", 0.4}, {"thickness", 0.002}}},
                              {"initial",
                               {{"theta", 23.649907572148113},
                                {"omega_X", -9.36372926770362},
                                {"omega_Y", 15.814515079174889},
                                {"omega_Z", 10.738334504205813}}},
                              {"friction", 0.27},
                              {"sliding", true},
                              {"duration", 3}};
  const pipeline::Simulation sim = simulationOf(doc);
  pipeline::CoinRun run(sim);
  double worst = 0, worstAt = 0;
  for (int k = 0; k <= 30000; ++k) {
    const std::optional<pipeline::RunSample> s = run.sampleAt(1e-4 * k);
    ASSERT_TRUE(s.has_value()) << "stopped at " << 1e-4 * k;
    if (s->forward.sliding) continue;
    const double ratio = s->forward.reaction.F / s->forward.reaction.N;
    if (ratio > worst) worst = ratio, worstAt = 1e-4 * k;
  }
  EXPECT_TRUE(isBelow(worst / 0.27 - 1, 1e-7)) << "F/N = " << worst << " while rolling at t = " << worstAt << " s";
}

TEST(Sliding, TheCsvCarriesTheSlipAndTheSwitches) {
  const pipeline::Simulation sim = simulationOf(skid({{"radius", 0.0375}, {"mass", 0.4}}, 1.0, 0.3));
  std::ostringstream csv;
  const pipeline::TrajectoryReport result = pipeline::writeTrajectoryCsv(sim, 0.05, csv);
  std::istringstream lines(csv.str());
  std::string header, first;
  std::getline(lines, header);
  std::getline(lines, first);
  EXPECT_EQ(header,
            "t,theta,phi,psi,omega_X,omega_Y,omega_Z,x,y,z,contact_x,contact_z,energy,normal_force,friction_force,"
            "power,dissipated,slip_speed,sliding");
  EXPECT_EQ(first.substr(first.rfind(',') - 1), "1,1");  // slip speed 1 m/s, sliding
  ASSERT_EQ(result.switches.size(), 2u);                 // slides at t = 0, rolls at t*
}

}  // namespace

namespace {

std::string hudLineStartingWith(const std::vector<std::string>& lines, std::string_view start) {
  for (const std::string& line : lines) {
    if (line.starts_with(start)) return line;
  }
  return {};
}

}  // namespace

TEST(Sliding, TheOverlayShowsTheSlipWhileSlidingAndOnlyThen) {
  // The upright skid's slip falls as v0 - mu g (1 + M a^2 / I_Z) t, 3 mu g t for a disk.
  const double v0 = 0.5, mu = 0.3, g = 9.81, t = 0.01;
  const scene::SceneConfig scene = scene::parseScene(skid({{"radius", 0.0375}, {"mass", 0.4}}, v0, mu), "test");
  const pipeline::Simulation sim = pipeline::buildSimulation(scene);
  pipeline::FixedFrameTimes at({t, 0.2});
  const pipeline::RunRecord record = pipeline::recordRun(sim, at);
  pipeline::SnapshotMaker maker(scene, sim.model, record);
  const std::string slip = hudLineStartingWith(maker.makeSnapshot(record.frames.at(0)).hudLines, "sliding");
  EXPECT_EQ(slip, fmt::format("sliding  {:9.2f} mm/s slip", 1e3 * (v0 - 3 * mu * g * t)));
  EXPECT_EQ(hudLineStartingWith(maker.makeSnapshot(record.frames.at(1)).hudLines, "sliding"),
            "");  // rolling from t = 0.0566 s
}
