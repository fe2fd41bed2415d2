// coinroll sweep and sweep-merge through the command line (INTERFACE.md "Sweeps"): the same bytes
// for any thread count and for shards run as separate processes by GNU parallel, merge refusing
// missing or repeated points by number, failed points kept as rows, and the summary columns
// against an independent computation (the trajectory CSV of the same point).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/run_command.h"
#include "scratch_dir.h"

namespace {

namespace fs = std::filesystem;

using coinroll::testing::RunResult;
using coinroll::testing::runCoinroll;

class SweepCliTest : public coinroll::testing::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    std::ofstream(scene()) << R"({"name": "toy", "coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4},
                                  "initial": {"theta": 10, "omega_Z": 12}, "duration": 2})";
  }
  fs::path scene() const { return dir_ / "toy.json"; }
};

const std::string kGrid = " --grid initial.theta=5:40:8 --grid initial.omega_Z=4:16:7";

std::string slurp(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string f; std::getline(in, f, ',');) out.push_back(f);
  return out;
}

TEST_F(SweepCliTest, SameBytesForOneAndTwoThreadsAndForShardsRunByGnuParallel) {
  const fs::path one = dir_ / "one.csv", two = dir_ / "two.csv", merged = dir_ / "merged.csv";
  ASSERT_EQ(runCoinroll("sweep " + scene().string() + kGrid + " -q --threads 1 -o " + one.string()).exitCode, 0);
  ASSERT_EQ(runCoinroll("sweep " + scene().string() + kGrid + " -q --threads 2 -o " + two.string()).exitCode, 0);
  EXPECT_EQ(slurp(one), slurp(two));

  // Four shards as four processes, the way a cluster runs them (docs/sweeps.md).
  const std::string binary = std::string(COINROLL_BINARY_DIR) + "/coinroll";
  const std::string shardRun = "cd " + dir_.string() + " && parallel --will-cite --halt now,fail=1 " + binary + " sweep " +
                               scene().string() + kGrid + " -q --threads 1 --shard {}/4 -o part{}.csv ::: 1 2 3 4";
  ASSERT_EQ(std::system(shardRun.c_str()), 0) << shardRun;
  const std::string parts = (dir_ / "part1.csv").string() + " " + (dir_ / "part3.csv").string() + " " +
                            (dir_ / "part2.csv").string() + " " + (dir_ / "part4.csv").string();
  ASSERT_EQ(runCoinroll("sweep-merge -o " + merged.string() + " " + parts).exitCode, 0);
  EXPECT_EQ(slurp(merged), slurp(one));

  // A lost shard and a shard given twice are refused by point number, and nothing is written.
  const fs::path refused = dir_ / "refused.csv";
  RunResult r = runCoinroll("sweep-merge -o " + refused.string() + " " + (dir_ / "part1.csv").string() + " " +
                            (dir_ / "part2.csv").string() + " " + (dir_ / "part4.csv").string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("points missing: 2, 6, 10, 14"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(refused));
  r = runCoinroll("sweep-merge -o " + refused.string() + " " + parts + " " + (dir_ / "part2.csv").string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("points repeated: 1, 5, 9"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(refused));
}

TEST_F(SweepCliTest, DashWritesTheSameBytesToStandardOutputAndNoFile) {
  const fs::path file = dir_ / "file.csv", piped = dir_ / "piped.csv", merged = dir_ / "merged.csv";
  ASSERT_EQ(runCoinroll("sweep " + scene().string() + kGrid + " -q -o " + file.string()).exitCode, 0);
  ASSERT_EQ(runCoinroll("sweep " + scene().string() + kGrid + " -q -o - > " + piped.string()).exitCode, 0);
  EXPECT_EQ(slurp(piped), slurp(file));
  for (const char* shard : {"1", "2"}) {
    ASSERT_EQ(runCoinroll("sweep " + scene().string() + kGrid + " -q --shard " + shard + "/2 -o " +
                          (dir_ / (std::string("part") + shard + ".csv")).string()).exitCode, 0);
  }
  ASSERT_EQ(runCoinroll("sweep-merge -o - " + (dir_ / "part1.csv").string() + " " + (dir_ / "part2.csv").string() + " > " +
                        merged.string()).exitCode, 0);
  EXPECT_EQ(slurp(merged), slurp(file));
  EXPECT_FALSE(fs::exists(dir_ / "-"));
  EXPECT_FALSE(fs::exists(fs::current_path() / "-"));
}

TEST_F(SweepCliTest, RowsFollowTheGridLastAxisFastestAndMatchTheTrajectoryCsv) {
  const fs::path sweep = dir_ / "sweep.csv";
  ASSERT_EQ(runCoinroll("sweep " + scene().string() + kGrid + " -q -o " + sweep.string()).exitCode, 0);
  std::ifstream in(sweep);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "point,initial.theta,initial.omega_Z,end,t_end,theta_min,theta_max,energy_start,energy_end");
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) rows.push_back(fields(line));
  ASSERT_EQ(rows.size(), 56u);
  // Point 13 = theta index 1, omega_Z index 6: theta 10 degrees, omega_Z 16 rad/s.
  const std::vector<std::string>& row = rows[13];
  EXPECT_EQ(row[0], "13");
  EXPECT_EQ(row[1], "10");
  EXPECT_EQ(row[2], "16");
  EXPECT_EQ(row[3], "duration");

  // The same point through simulate: its CSV's theta extremes and energies are the summary's.
  const fs::path csv = dir_ / "point13.csv";
  ASSERT_EQ(runCoinroll("simulate " + scene().string() + " --set initial.theta=10 --set initial.omega_Z=16 --csv " +
                        csv.string()).exitCode, 0);
  std::ifstream trajectory(csv);
  std::getline(trajectory, line);
  double thetaMin = 1e9, thetaMax = -1e9, energyStart = 0, energyEnd = 0;
  for (bool first = true; std::getline(trajectory, line); first = false) {
    const std::vector<std::string> f = fields(line);
    thetaMin = std::min(thetaMin, std::stod(f[1]));
    thetaMax = std::max(thetaMax, std::stod(f[1]));
    if (first) energyStart = std::stod(f[12]);
    energyEnd = std::stod(f[12]);
  }
  EXPECT_EQ(std::stod(row[5]), thetaMin);
  EXPECT_EQ(std::stod(row[6]), thetaMax);
  EXPECT_EQ(std::stod(row[7]), energyStart);
  EXPECT_EQ(std::stod(row[8]), energyEnd);
}

TEST_F(SweepCliTest, AFailingPointKeepsItsRowAndItsReason) {
  const fs::path sweep = dir_ / "sweep.csv";
  const RunResult r = runCoinroll("sweep " + scene().string() + " --grid initial.theta=80:100:3 -o " + sweep.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::string text = slurp(sweep);
  EXPECT_NE(text.find("\n0,80,duration,2,"), std::string::npos) << text;
  EXPECT_NE(text.find("\n1,90,\"error: "), std::string::npos) << text;
  EXPECT_NE(text.find("initial.theta: must be in (-90, 90) degrees"), std::string::npos) << text;
  EXPECT_NE(r.output.find("3 points, 2 failed"), std::string::npos) << r.output;
}

TEST_F(SweepCliTest, BadGridsAndShardsExitTwoWithoutAFile) {
  const fs::path out = dir_ / "out.csv";
  for (const std::string& bad : {std::string(" --grid initial.theta=5:40"), std::string(" --grid initial.theta=5:40:0"),
                                 std::string(" --grid =5:40:3"), std::string(" --grid initial.theta=a:40:3"),
                                 std::string(kGrid + " --shard 4/3"), std::string(kGrid + " --shard 0/3"),
                                 std::string(kGrid + " --max-points 10"), std::string(kGrid + " --threads -1")}) {
    const RunResult r = runCoinroll("sweep " + scene().string() + bad + " -o " + out.string());
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.output;
    EXPECT_TRUE(r.output.find("--grid") != std::string::npos || r.output.find("--shard") != std::string::npos ||
                r.output.find("--max-points") != std::string::npos || r.output.find("--threads") != std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(out)) << bad;
  }
}

}  // namespace
