// A coin with a rim through the command line (docs/contract.md §5): the CSV follows the
// solid's geometry, a cornered rim stops where it would switch corners, a spin-down lands on its face
// and the clip then holds still in silence.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <iterator>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "cli/run_command.h"
#include "csv_table.h"
#include "scratch_dir.h"
#include "tolerance.h"
#include "video_probe.h"

namespace {

namespace fs = std::filesystem;

using coinroll::testing::isBelow;
using coinroll::testing::isNear;
using coinroll::testing::runCoinroll;

class RimCliTest : public coinroll::testing::ScratchDirTest {};

std::vector<std::vector<double>> readRows(const fs::path& csv) { return coinroll::testing::readCsvTable(csv).rows; }

constexpr double kRadius = 0.0375, kThickness = 0.013;

TEST_F(RimCliTest, TheCsvHeightIsTheSolidsAndTheContactIsOnTheFloorUnderTheRim) {
  // y = (a - rho) cos(theta) + (h/2 - rho) |sin(theta)| + rho (docs/contract.md), written here from the
  // contract; the contact point is |c_h| from the centre's floor point, c from the contract's vector.
  for (const double rho : {0.0065, 0.0016, 0.0}) {
    const fs::path scene = dir_ / "rim.json", csv = dir_ / "rim.csv";
    std::ofstream(scene) << R"({"coin": {"radius": 0.0375, "mass": 0.45, "thickness": 0.013, "edge_radius": )" << rho
                         << R"(}, "initial": {"theta": 25, "omega_Y": 3, "omega_Z": 9}, "duration": 1})";
    const coinroll::testing::RunResult r = runCoinroll("simulate " + scene.string() + " --csv " + csv.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::vector<std::vector<double>> rows = readRows(csv);
    ASSERT_EQ(rows.size(), 101u);
    for (const std::vector<double>& row : rows) {
      const double theta = row[1], phi = row[2];
      const double y = (kRadius - rho) * std::cos(theta) + (kThickness / 2 - rho) * std::abs(std::sin(theta)) + rho;
      EXPECT_TRUE(isNear(row[8], y, 1e-15)) << "rho " << rho << ", t " << row[0];
      // c's horizontal part: -(a - rho) e_Y + sign(theta) (h/2 - rho) e_Z projected, with e_Y, e_Z of seed eq. (7).
      const double side = theta < 0 ? -1 : 1;
      const double along = -(kRadius - rho) * std::sin(theta) + side * (kThickness / 2 - rho) * std::cos(theta);
      EXPECT_TRUE(isNear(row[10], row[7] + along * std::sin(phi), 1e-15));
      EXPECT_TRUE(isNear(row[11], row[9] + along * std::cos(phi), 1e-15));
    }
  }
}

TEST_F(RimCliTest, ACornerOfOneNanometreStillStopsAtUpright) {
  // The corner's impact at upright shrinks with its offset e = h/2 - rho but exists for every e > 0
  // (docs/rim.md (7.0b)): a toy rounded to 1 nm short of fully still stops there.
  const fs::path scene = dir_ / "tiny_corner.json";
  std::ofstream(scene) << R"({"coin": {"radius": 0.0375, "mass": 0.45, "thickness": 0.013,
    "edge_radius": 0.006499999}, "initial": {"theta": 2, "omega_X": -1.5, "omega_Z": 20}, "duration": 5})";
  const coinroll::testing::RunResult r = runCoinroll("simulate " + scene.string() + " --csv /dev/null");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("stopped early: corner-switch at t = "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("0.0000 deg)"), std::string::npos) << r.output;
}

TEST_F(RimCliTest, ACorneredRimStopsWhereItWouldSwitchCorners) {
  // A fast straight roll with a wobble that carries it through upright.
  const fs::path scene = dir_ / "corner.json", csv = dir_ / "corner.csv";
  std::ofstream(scene) << R"({"coin": {"radius": 0.0375, "mass": 0.45, "thickness": 0.013, "edge_radius": 0.0016},
    "initial": {"theta": 2, "omega_X": -1.5, "omega_Z": 20}, "duration": 5})";
  const coinroll::testing::RunResult r =
      runCoinroll("simulate " + scene.string() + " --csv " + csv.string() + " --sample-dt 0.001");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("stopped early: corner-switch at t = "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("0.0000 deg)"), std::string::npos) << r.output;  // located at upright
  const std::vector<std::vector<double>> rows = readRows(csv);
  ASSERT_GT(rows.size(), 2u);
  EXPECT_GT(rows.back()[1], 0);  // every row before the stop on the side it started
  EXPECT_LT(rows.size(), 5001u);
  // Rounded fully, the same coin rolls through upright to the end.
  const coinroll::testing::RunResult rounded =
      runCoinroll("simulate " + scene.string() + " --csv " + csv.string() + " --set coin.edge_radius=0.0065");
  ASSERT_EQ(rounded.exitCode, 0) << rounded.output;
  EXPECT_EQ(rounded.output.find("stopped early"), std::string::npos) << rounded.output;
  double lowest = 1;
  for (const std::vector<double>& row : readRows(csv)) lowest = std::min(lowest, row[1]);
  EXPECT_LT(lowest, 0);
}

TEST_F(RimCliTest, ASpinDownLandsOnItsFaceAndTheClipHoldsStillInSilence) {
  // A fast spin-down (rolling resistance 0.1 mm), played in real time at the real pitch, so audio time
  // is simulated time; a 2 mm rounded rim so it lands on its face.
  const fs::path scene = dir_ / "land.json", csv = dir_ / "land.csv", mp4 = dir_ / "land.mp4";
  std::ofstream(scene) << R"({"coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4, "thickness": 0.002},
    "initial": {"steady": "spin-in-place", "theta": 75}, "duration": 10,
    "effects": [{"type": "rolling_resistance", "length": 1e-4}, {"type": "air_drag"}],
    "render": {"width": 64, "height": 36, "fps": 30, "hud": false,
               "audio": {"timbre": "tone", "frequency_scale": 10, "pitch": "real"}}})";
  const coinroll::testing::RunResult run = runCoinroll("simulate " + scene.string() + " --csv " + csv.string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const std::size_t at = run.output.find("stopped early: face-down at t = ");
  ASSERT_NE(at, std::string::npos) << run.output;
  const double landing = std::stod(run.output.substr(at + std::string("stopped early: face-down at t = ").size()));
  ASSERT_GT(landing, 1.0);
  ASSERT_EQ(runCoinroll("render " + scene.string() + " -q -o " + mp4.string()).exitCode, 0);

  const coinroll::video::VideoInfo info = coinroll::video::readVideoInfo(mp4);
  // Frames k / 30 s up to the landing, then the landing itself (it falls between two frames).
  const long simulatedFrames = static_cast<long>(std::floor(landing * 30)) + 2;
  EXPECT_EQ(info.frameCount, simulatedFrames + 45);  // 1.5 s of hold at 30 fps
  // The hold shows the landing's picture: a PNG sequence of the same clip, losslessly.
  const fs::path frames = dir_ / "frames";
  fs::create_directory(frames);
  ASSERT_EQ(runCoinroll("render " + scene.string() + " -q -o " + (frames / "f_%05d.png").string()).exitCode, 0);
  const auto bytes = [](const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const auto frame = [&frames](long k) {
    char name[32];
    std::snprintf(name, sizeof name, "f_%05ld.png", k);
    return frames / name;
  };
  ASSERT_TRUE(fs::exists(frame(simulatedFrames + 44)));
  EXPECT_FALSE(fs::exists(frame(simulatedFrames + 45)));
  EXPECT_EQ(bytes(frame(simulatedFrames - 1)), bytes(frame(simulatedFrames + 44)));
  EXPECT_NE(bytes(frame(simulatedFrames - 2)), bytes(frame(simulatedFrames - 1)));  // it moved until then

  // With the overlay, the hold says that time stands still ("landed, held 1.5 s") in each of its frames.
  const fs::path hud = dir_ / "hud";
  fs::create_directory(hud);
  ASSERT_EQ(runCoinroll("render " + scene.string() +
                        " -q --set render.hud=true --set render.width=320 --set render.height=180 -o " +
                        (hud / "f_%05d.png").string())
                .exitCode,
            0);
  const auto hudFrame = [&](long k) { return hud / frame(k).filename(); };
  EXPECT_TRUE(bytes(hudFrame(simulatedFrames - 1)) != bytes(hudFrame(simulatedFrames)));
  EXPECT_TRUE(bytes(hudFrame(simulatedFrames)) == bytes(hudFrame(simulatedFrames + 44)));

  const coinroll::video::DecodedAudio audio = coinroll::video::decodeAudio(mp4);
  const auto loudest = [&audio](double from, double to) {
    float peak = 0;
    for (auto i = static_cast<std::size_t>(from * 48000);
         i < std::min(audio.samples.size(), static_cast<std::size_t>(to * 48000)); ++i) {
      peak = std::max(peak, std::abs(audio.samples[i]));
    }
    return peak;
  };
  EXPECT_GT(loudest(landing - 0.5, landing - 0.1), 0.2);              // the chirp up to the landing
  EXPECT_TRUE(isBelow(loudest(landing + 0.1, landing + 1.4), 1e-3));  // then silence
}

}  // namespace
