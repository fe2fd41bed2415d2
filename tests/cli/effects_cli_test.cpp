// Dissipation through the program's contract (docs/contract.md §4), and the promise that a scene
// without effects is computed exactly as before effects existed: every example's CSV, PNG and MP4 hash to what the
// program wrote before the effects refactor (recorded with that build, overlay off: the overlay's labels changed
// deliberately since). The pictures follow the golden rule of every image test (docs/snapshot_testing.md): exact bytes,
// and under COINROLL_GOLDEN_TOLERANT=1 their hashes are not compared (see that test).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "cli/run_command.h"
#include "csv_table.h"
#include "golden_rule.h"
#include "image/image.h"
#include "scratch_dir.h"

namespace {

namespace fs = std::filesystem;

using coinroll::testing::runCoinroll;
using coinroll::testing::RunResult;

class EffectsCliTest : public coinroll::testing::ScratchDirTest {};

std::string example(const std::string& name) {
  return std::string(COINROLL_SOURCE_DIR) + "/examples/" + name + ".json";
}

std::uint64_t fnv1a(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::uint64_t hash = 1469598103934665603ull;
  for (std::istreambuf_iterator<char> it(in), end; it != end; ++it) {
    hash = (hash ^ static_cast<std::uint8_t>(*it)) * 1099511628211ull;
  }
  return hash;
}

// The CSV of a spin-down: its columns, power >= 0, and energy + dissipated = the initial energy;
// most of the energy above `restingEnergy` (the coin lying still) spent by the end.
// With sliding on, the slip columns follow.
std::vector<std::vector<double>> expectClosedEnergyBudget(const fs::path& csv, double restingEnergy,
                                                          double spentFraction, bool sliding = false) {
  coinroll::testing::CsvTable table = coinroll::testing::readCsvTable(csv);
  std::vector<std::vector<double>>& rows = table.rows;
  EXPECT_EQ(table.headerLine,
            std::string(
                "t,theta,phi,psi,omega_X,omega_Y,omega_Z,x,y,z,contact_x,contact_z,energy,normal_force,friction_force,"
                "power,dissipated") +
                (sliding ? ",slip_speed,sliding" : ""));
  EXPECT_GT(rows.size(), 100u);
  if (rows.empty()) return rows;
  const double E0 = rows.front()[12];
  for (const std::vector<double>& row : rows) {
    EXPECT_EQ(row.size(), sliding ? 19u : 17u);
    if (row.size() < 17) break;
    EXPECT_GE(row[15], 0);                                   // power
    EXPECT_LE(std::abs(row[12] + row[16] - E0), 1e-9 * E0);  // energy + dissipated
  }
  EXPECT_GT(rows.back()[16], spentFraction * (E0 - restingEnergy));
  EXPECT_GT(rows.back()[12], restingEnergy);
  return std::move(rows);
}

TEST_F(EffectsCliTest, TheThickToySlipsAndSpinsDownToFaceDownWithItsEnergyBudgetAndT0) {
  const fs::path csv = dir_ / "spin_down.csv";
  const RunResult r = runCoinroll("simulate " + example("euler_disk") + " --csv " + csv.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // Lying on its face the 0.449 kg, 13 mm toy keeps M g h / 2. Free to slide, its face no longer spins
  // up under the rolling constraint (docs/euler_disk.md §6): nearly all the rest is spent at the landing.
  const auto rows = expectClosedEnergyBudget(csv, 0.449 * 9.81 * 0.013 / 2, 0.98, true);
  std::size_t slidingRows = 0;
  for (const auto& row : rows) slidingRows += row.size() == 19 && row[18] == 1 ? 1 : 0;
  EXPECT_GT(slidingRows, 0u);
  EXPECT_NE(r.output.find("coinroll: slides at t = "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("coinroll: rolls at t = "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("stopped early: face-down at t = "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("89.9500 deg"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("singular time t0 = "), std::string::npos) << r.output;
  // Sliding carries the coin where rolling would leave the cone: no slip warning.
  EXPECT_EQ(r.output.find("slip at t = "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("note: initial.steady is a steady motion of the ideal model"), std::string::npos) << r.output;
}

TEST_F(EffectsCliTest, TheRollingOnlyToyWarnsWhereItLeavesItsFrictionCone) {
  const fs::path csv = dir_ / "rolling.csv";
  const RunResult r = runCoinroll("simulate " + example("euler_disk") + " --csv " + csv.string() +
                                  " --sample-dt 0.05 --set sliding=false");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // The face spin the rolling constraint pumps up and the last whirl keep 8 % of the rest at the
  // landing (docs/rim.md §7).
  expectClosedEnergyBudget(csv, 0.449 * 9.81 * 0.013 / 2, 0.85);
  EXPECT_NE(r.output.find("stopped early: face-down at t = "), std::string::npos) << r.output;
  // on_invalid "warn": the slip crossing is reported and the run goes on to flat.
  EXPECT_NE(r.output.find("warning: the ideal contact fails here (on_invalid: warn, going on): slip at t = "),
            std::string::npos)
      << r.output;
}

TEST_F(EffectsCliTest, AThinCoinSpinsDownToCoinFlatAtHalfADegree) {
  // The seed's thin coin (no thickness) has no face to land on: its spin-down ends at coin-flat.
  const fs::path scene = dir_ / "thin.json", csv = dir_ / "thin.csv";
  std::ofstream(scene) << R"({"coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4},
    "initial": {"steady": "spin-in-place", "theta": 60}, "duration": 200, "on_invalid": "warn",
    "effects": [{"type": "air_drag", "model": "boundary_layer"}, {"type": "rolling_resistance", "length": 3.75e-6}]})";
  const RunResult r = runCoinroll("simulate " + scene.string() + " --csv " + csv.string() + " --sample-dt 0.05");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  expectClosedEnergyBudget(csv, 0, 0.9);
  EXPECT_NE(r.output.find("stopped early: coin-flat at t = "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("89.5000 deg"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("singular time t0 = "), std::string::npos) << r.output;
}

TEST_F(EffectsCliTest, OnInvalidStopEndsTheSpinDownAtSlip) {
  const fs::path csv = dir_ / "stop.csv";
  const RunResult r = runCoinroll("simulate " + example("euler_disk") + " --csv " + csv.string() +
                                  " --sample-dt 0.5 --set sliding=false --set on_invalid=stop");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("stopped early: slip at t = "), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("face-down"), std::string::npos) << r.output;
}

TEST_F(EffectsCliTest, BadEffectsGetExitTwoNameTheKeyAndWriteNothing) {
  const std::string start = R"({"coin": {"radius": 0.0375, "mass": 0.4}, "initial": {"theta": 60}, "duration": 1, )";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"effects", R"("effects": {"type": "air_drag"}})"},
      {"effects[0]", R"("effects": ["air_drag"]})"},
      {"effects[0].type", R"("effects": [{"type": "magnetism"}]})"},
      {"effects[0].model", R"("effects": [{"type": "air_drag", "model": "turbulent"}]})"},
      {"effects[0].viscosity", R"("effects": [{"type": "air_drag", "viscosity": -1}]})"},
      {"effects[0].temperature", R"("effects": [{"type": "air_drag", "temperature": 20}]})"},
      {"effects[0].length", R"("effects": [{"type": "rolling_resistance", "length": -2e-6}]})"},
      {"effects[0].load_exponent", R"("effects": [{"type": "rolling_resistance", "load_exponent": 0}]})"},
      {"effects[1]", R"("effects": [{"type": "spin_friction"}, {"type": "spin_friction"}]})"},
      {"on_invalid", R"("on_invalid": "ignore"})"},
  };
  for (const auto& [key, tail] : cases) {
    const fs::path scene = dir_ / "scene.json", csv = dir_ / "out.csv";
    std::ofstream(scene) << start << tail;
    const RunResult r = runCoinroll("simulate " + scene.string() + " --csv " + csv.string());
    EXPECT_EQ(r.exitCode, 2) << key << ": " << r.output;
    EXPECT_NE(r.output.find(key), std::string::npos) << key << ": " << r.output;
    EXPECT_FALSE(fs::exists(csv)) << key;
  }
}

struct Recorded {
  const char* example;
  std::uint64_t csv, png, mp4;
};

TEST_F(EffectsCliTest, ScenesWithoutEffectsGiveTheBytesTheyGaveBeforeEffectsExisted) {
  // falling_flat integrates the quaternion formulation, whose CSV now reads its own forward pass (it
  // had read the Euler-angle equations; docs/physics.md "Formulations"): its state columns are those
  // of before, its derived columns (y, contact, energy, N, F) differ in the last digits, at most
  // 7e-12 of the weight in N where the Euler angles' tan(theta) had amplified round-off. Its still
  // and clip are unchanged.
  // The pictures' hashes were recorded again when the floor's grid took trilinear filtering (its
  // mipmap seams removed); the CSVs, which carry the claim, are the bytes of before effects.
  const Recorded recorded[] = {
      {"falling_flat", 0xecf06bcb75b7138bull, 0xae04cce0cea0315dull, 0x0309e5733693cfe1ull},
      {"perturbed_circle", 0xbcab92c1507693e1ull, 0x4b748375bbdb65dbull, 0x712375c5d4e4573dull},
      {"ring", 0x99f21397fcf14070ull, 0x95433bee32a9c482ull, 0xe2824c94f387243bull},
      {"spin_in_place", 0x686069e8237da8ddull, 0xb86034a53f4a2aa6ull, 0xe579bbba57ee8debull},
      {"steady_circle", 0xb7e55c2fc6a7506cull, 0xe3e6276de2b9eed6ull, 0xc25b8bd31f30fd30ull},
      {"straight_stable", 0x1676f7cb6562c2ffull, 0x3c5e0574b3096856ull, 0xbf1a107e8225f0a8ull},
      {"straight_unstable", 0x16ec4c380d8a2b17ull, 0xc0cf0331d36eeae2ull, 0xbfce3a7fae7de180ull},
  };
  // Provenance off: these bytes were recorded before files named their release and scene, and with
  // it on they would change with every release; the pictures and the stream are what is compared.
  // 4x MSAA named: the bytes were recorded with it, the default before anti-aliasing became `auto`
  // (docs/quality.md "Anti-aliasing"), and the claim is that effects changed no byte, not which
  // method draws.
  const std::string noProvenance = " --set render.provenance=false --set render.antialiasing=msaa";
  // A byte hash has no tolerance: on a CPU other than the recording one (COINROLL_GOLDEN_TOLERANT=1)
  // llvmpipe may round a few pixels differently and x264 then encodes other bytes, so there only the
  // CSVs are compared and the still is checked to decode at its size; the pictures' tolerant check
  // is tests/render's goldens. Exact mode (the default, and CI) compares every hash.
  const bool hashPictures = !coinroll::testing::goldenTolerant();
  for (const Recorded& r : recorded) {
    const std::string scene = example(r.example);
    const fs::path csv = dir_ / "run.csv", png = dir_ / "still.png", mp4 = dir_ / "clip.mp4";
    ASSERT_EQ(runCoinroll("simulate " + scene + " --csv " + csv.string()).exitCode, 0) << r.example;
    ASSERT_EQ(runCoinroll("still " + scene + " --time 0.5 -o " + png.string() +
                          " --set render.width=320 --set render.height=180 --set render.hud=false" + noProvenance)
                  .exitCode,
              0);
    ASSERT_EQ(runCoinroll("render " + scene + " -q -o " + mp4.string() +
                          " --set render.width=160 --set render.height=90 --set render.fps=10 --set render.hud=false" +
                          noProvenance)
                  .exitCode,
              0);
    EXPECT_EQ(fnv1a(csv), r.csv) << r.example << " CSV";
    if (hashPictures) {
      EXPECT_EQ(fnv1a(png), r.png) << r.example << " PNG";
      EXPECT_EQ(fnv1a(mp4), r.mp4) << r.example << " MP4";
    } else {
      const coinroll::image::Image still = coinroll::image::readPng(png);
      EXPECT_TRUE(still.width == 320 && still.height == 180)
          << r.example << " still " << still.width << "x" << still.height;
    }
  }
  const fs::path defaultCsv = dir_ / "default.csv";
  ASSERT_EQ(runCoinroll("simulate --csv " + defaultCsv.string()).exitCode, 0);
  EXPECT_EQ(fnv1a(defaultCsv), 0x953433f4ef16ee03ull) << "built-in default scene CSV";
  if (!hashPictures) {
    GTEST_SKIP() << "CSV bytes compared; PNG and MP4 hashes not compared under COINROLL_GOLDEN_TOLERANT=1 (exact "
                    "bytes only: docs/snapshot_testing.md)";
  }
}

}  // namespace

namespace {

TEST_F(EffectsCliTest, ASpinDownGivenAHugeDurationRunsToItsEnd) {
  // "duration": 1e5 s means "until it stops": the row and frame limits must not refuse it.
  const fs::path scene = dir_ / "long.json", csv = dir_ / "long.csv";
  std::ofstream(scene) << R"({"coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4},
    "initial": {"steady": "spin-in-place", "theta": 75}, "duration": 100000, "on_invalid": "warn",
    "effects": [{"type": "rolling_resistance", "length": 1e-4}, {"type": "air_drag", "model": "moffatt"}]})";
  const RunResult r = runCoinroll("simulate " + scene.string() + " --csv " + csv.string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("coin-flat at t = 1.55"), std::string::npos) << r.output;
  const RunResult video =
      runCoinroll("render " + scene.string() + " -q --set render.width=32 --set render.height=18 -o " +
                  (dir_ / "long.mp4").string());
  EXPECT_EQ(video.exitCode, 0) << video.output;
}

}  // namespace
