// coinroll sweep and sweep-merge through the command line (docs/contract.md §7): the same bytes
// for any thread count and for shards run as separate processes by GNU parallel (the Slurm array of
// docs/sweeps.md: tests/slurm/slurm_test.py), listed and geometric axes, --shard auto/N, merge refusing
// missing or repeated points by number, failed points kept as rows, and the summary columns
// against an independent computation (the trajectory CSV of the same point).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli/run_command.h"
#include "scratch_dir.h"

namespace {

namespace fs = std::filesystem;

using coinroll::testing::runCoinroll;
using coinroll::testing::RunResult;

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
  const std::string shardRun = "cd " + dir_.string() + " && parallel --will-cite --halt now,fail=1 " + binary +
                               " sweep " + scene().string() + kGrid +
                               " -q --threads 1 --shard {}/4 -o part{}.csv ::: 1 2 3 4";
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
  EXPECT_NE(r.output.find("points missing (of 56 in the grid): 2, 6, 10, 14"), std::string::npos) << r.output;
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
                          (dir_ / (std::string("part") + shard + ".csv")).string())
                  .exitCode,
              0);
  }
  ASSERT_EQ(runCoinroll("sweep-merge -q -o - " + (dir_ / "part1.csv").string() + " " + (dir_ / "part2.csv").string() +
                        " > " + merged.string())
                .exitCode,
            0);
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
  EXPECT_EQ(line,
            "point,initial.theta,initial.omega_Z,end,t_end,theta_min,theta_max,energy_start,energy_end,"
            "theta_end,grid_points,sweep");
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) rows.push_back(fields(line));
  ASSERT_EQ(rows.size(), 56u);
  // Point 13 = theta index 1, omega_Z index 6: theta 10 degrees, omega_Z 16 rad/s.
  const std::vector<std::string>& row = rows[13];
  EXPECT_EQ(row[0], "13");
  EXPECT_EQ(row[1], "10");
  EXPECT_EQ(row[2], "16");
  EXPECT_EQ(row[3], "duration");

  // The same point through simulate: its CSV's theta extremes, energies and last theta are the summary's.
  const fs::path csv = dir_ / "point13.csv";
  ASSERT_EQ(runCoinroll("simulate " + scene().string() + " --set initial.theta=10 --set initial.omega_Z=16 --csv " +
                        csv.string())
                .exitCode,
            0);
  std::ifstream trajectory(csv);
  std::getline(trajectory, line);
  double thetaMin = 1e9, thetaMax = -1e9, energyStart = 0, energyEnd = 0, thetaEnd = 0;
  for (bool first = true; std::getline(trajectory, line); first = false) {
    const std::vector<std::string> f = fields(line);
    thetaMin = std::min(thetaMin, std::stod(f[1]));
    thetaMax = std::max(thetaMax, std::stod(f[1]));
    if (first) energyStart = std::stod(f[12]);
    energyEnd = std::stod(f[12]);
    thetaEnd = std::stod(f[1]);
  }
  EXPECT_EQ(std::stod(row[5]), thetaMin);
  EXPECT_EQ(std::stod(row[6]), thetaMax);
  EXPECT_EQ(std::stod(row[7]), energyStart);
  EXPECT_EQ(std::stod(row[8]), energyEnd);
  EXPECT_EQ(std::stod(row[9]), thetaEnd);
}

// A sweep of tosses tells each one's face: where a toss is decided (docs/flight.md §5a), theta_end's
// sign (heads < 0) is the face `simulate` reports for the same point. A toss that ends otherwise
// (this coin's cornered rim stops one at corner-switch, passing upright) has no face in either.
TEST_F(SweepCliTest, ATossSweepsThetaEndIsTheFaceSimulateReports) {
  const std::string toss = std::string(COINROLL_SOURCE_DIR) + "/examples/coin_toss.json --set stop_when_decided=true";
  const fs::path sweep = dir_ / "tosses.csv";
  const RunResult r =
      runCoinroll("sweep " + toss + " --grid initial.omega_X=30:45:4 --grid initial.v_y=1:3:3 -q -o " + sweep.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::stringstream rows(slurp(sweep));
  std::string line;
  std::getline(rows, line);
  ASSERT_EQ(fields(line).at(9), "theta_end") << line;
  std::map<std::string, int> faces;
  while (std::getline(rows, line)) {
    const std::vector<std::string> f = fields(line);
    ASSERT_EQ(f.size(), 12u) << line;
    const RunResult point = runCoinroll("simulate " + toss + " --set initial.omega_X=" + f[1] +
                                        " --set initial.v_y=" + f[2] + " --csv " + (dir_ / "point.csv").string());
    ASSERT_EQ(point.exitCode, 0) << point.output;
    if (f[3] != "decided") {
      EXPECT_NE(point.output.find("stopped early: " + f[3] + " "), std::string::npos) << line << "\n" << point.output;
      EXPECT_EQ(point.output.find("coinroll: heads"), std::string::npos) << point.output;
      EXPECT_EQ(point.output.find("coinroll: tails"), std::string::npos) << point.output;
      continue;
    }
    const double thetaEnd = std::stod(f[9]);
    ASSERT_NE(thetaEnd, 0.0) << line;
    const std::string face = thetaEnd < 0 ? "heads" : "tails";
    ++faces[face];
    EXPECT_NE(point.output.find("coinroll: " + face + " "), std::string::npos) << line << "\n" << point.output;
  }
  EXPECT_GE(faces["heads"] + faces["tails"], 10);  // measured: 11 of the 12 decided
  EXPECT_GT(faces["heads"], 0);                    // both faces come up, so a sign taken the wrong way round fails
  EXPECT_GT(faces["tails"], 0);
}

// A run's end lies at its duration, not at the last summary point before it: a toss whose duration
// fell between a bounce's touchdown and the next point ended `stick-slip` at that touchdown.
TEST_F(SweepCliTest, ARunEndsAtItsDurationWhereverTheSummaryPointsFall) {
  const std::string toss = std::string(COINROLL_SOURCE_DIR) + "/examples/coin_toss.json --set duration=0.5147";
  const fs::path sweep = dir_ / "short.csv";
  const RunResult r = runCoinroll("sweep " + toss + " --grid initial.v_x=0.1:0.1:1 -q -o " + sweep.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::stringstream rows(slurp(sweep));
  std::string line;
  std::getline(rows, line);
  ASSERT_TRUE(std::getline(rows, line));
  const std::vector<std::string> f = fields(line);
  EXPECT_EQ(f.at(2), "duration") << line;
  EXPECT_EQ(f.at(3), "0.5147") << line;
  const RunResult point = runCoinroll("simulate " + toss + " --csv " + (dir_ / "point.csv").string());
  ASSERT_EQ(point.exitCode, 0) << point.output;
  EXPECT_EQ(point.output.find("stopped early"), std::string::npos) << point.output;
}

// Every row ends with the sweep's identity: the grid's size and a digest of the scene and the grid,
// equal in every shard and the unsharded file, different for another scene, --set or grid. A merge
// refuses a mixture and a shard cut after a whole row, and reads shards from pipes.
TEST_F(SweepCliTest, ShardsKnowTheirSweep) {
  const auto identities = [](const std::string& text) {
    std::vector<std::string> found;
    std::stringstream in(text);
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      const std::vector<std::string> f = fields(line);
      found.push_back(f[f.size() - 2] + "," + f.back());
    }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
  };
  const std::string sweep = "sweep " + scene().string() + kGrid + " -q --set duration=0.5";
  const fs::path whole = dir_ / "whole.csv", other = dir_ / "other.csv";
  ASSERT_EQ(runCoinroll(sweep + " -o " + whole.string()).exitCode, 0);
  const std::vector<std::string> identity = identities(slurp(whole));
  ASSERT_EQ(identity.size(), 1u);
  EXPECT_TRUE(identity[0].starts_with("56,")) << identity[0];
  EXPECT_EQ(identity[0].size(), 3u + 16u) << identity[0];
  for (const char* shard : {"1", "2", "3"}) {
    const fs::path part = dir_ / (std::string("part") + shard + ".csv");
    ASSERT_EQ(runCoinroll(sweep + " --shard " + shard + "/3 -o " + part.string()).exitCode, 0);
    EXPECT_EQ(identities(slurp(part)), identity) << shard;
  }
  // Another scene value gives another digest, another grid another size and digest.
  ASSERT_EQ(runCoinroll(sweep + " --set gravity=9.8 --shard 3/3 -o " + other.string()).exitCode, 0);
  EXPECT_NE(identities(slurp(other)), identity);
  ASSERT_EQ(runCoinroll("sweep " + scene().string() +
                        " --grid initial.theta=5:40:8 --grid initial.omega_Z=4:16:8 -q "
                        "--set duration=0.5 --shard 3/3 -o " +
                        (dir_ / "bigger.csv").string())
                .exitCode,
            0);
  EXPECT_TRUE(identities(slurp(dir_ / "bigger.csv"))[0].starts_with("64,"));

  const std::string part1 = (dir_ / "part1.csv").string(), part2 = (dir_ / "part2.csv").string();
  const fs::path merged = dir_ / "merged.csv";
  RunResult r = runCoinroll("sweep-merge -o " + merged.string() + " " + part1 + " " + part2 + " " + other.string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("from another sweep than"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(merged));

  // Shard 3 of 56 points holds 2, 5, ..., 53, 18 rows: cut after its 17th, point 53 is named missing.
  const std::string text3 = slurp(dir_ / "part3.csv");
  std::ofstream(dir_ / "cut3.csv") << text3.substr(0, text3.rfind('\n', text3.size() - 2) + 1);
  r = runCoinroll("sweep-merge -o " + merged.string() + " " + part1 + " " + part2 + " " + (dir_ / "cut3.csv").string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("points missing (of 56 in the grid): 53"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(merged));

  // From a pipe, a process substitution and standard input: the unsharded bytes.
  const std::string fromPipes = "bash -c '" + std::string(COINROLL_BINARY_DIR) + "/coinroll sweep-merge -o " +
                                merged.string() + " <(cat " + part1 + ") - " + (dir_ / "part3.csv").string() + " < " +
                                part2 + "'";
  ASSERT_EQ(std::system(fromPipes.c_str()), 0) << fromPipes;
  EXPECT_EQ(slurp(merged), slurp(whole));
}

// A listed axis keeps its order; a geometric one is even in log10, so decades read as typed.
TEST_F(SweepCliTest, ListedAndGeometricAxesGiveTheirValuesInOrder) {
  const fs::path sweep = dir_ / "sweep.csv";
  ASSERT_EQ(runCoinroll("sweep " + scene().string() +
                        " --grid initial.theta=20,5,10 --grid solver.rtol=1e-3:1e-9:7:log "
                        "--set duration=0.2 -q -o " +
                        sweep.string())
                .exitCode,
            0);
  std::ifstream in(sweep);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> theta, rtol;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = fields(line);
    if (rtol.size() < 7) rtol.push_back(f[2]);
    if (theta.empty() || theta.back() != f[1]) theta.push_back(f[1]);
  }
  EXPECT_EQ(theta, (std::vector<std::string>{"20", "5", "10"}));
  EXPECT_EQ(rtol, (std::vector<std::string>{"0.001", "0.0001", "1e-05", "1e-06", "1e-07", "1e-08", "1e-09"}));
}

// --shard auto/N is --shard K/N with K the Slurm array task's number, and refuses to guess
// outside an array task or for a task number that is no shard.
TEST_F(SweepCliTest, ShardAutoTakesKFromTheSlurmArrayTask) {
  const fs::path automatic = dir_ / "auto.csv", given = dir_ / "given.csv";
  const std::string sweep = "sweep " + scene().string() + kGrid + " -q --set duration=0.2";
  ASSERT_EQ(runCoinroll(sweep + " --shard auto/3 -o " + automatic.string(), "SLURM_ARRAY_TASK_ID=2").exitCode, 0);
  ASSERT_EQ(runCoinroll(sweep + " --shard 2/3 -o " + given.string(), "SLURM_ARRAY_TASK_ID=1").exitCode, 0);
  EXPECT_EQ(slurp(automatic), slurp(given));

  const fs::path refused = dir_ / "refused.csv";
  RunResult r = runCoinroll(sweep + " --shard auto/3 -o " + refused.string(), "env -u SLURM_ARRAY_TASK_ID");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("$SLURM_ARRAY_TASK_ID, which is not set"), std::string::npos) << r.output;
  r = runCoinroll(sweep + " --shard auto/3 -o " + refused.string(), "SLURM_ARRAY_TASK_ID=4");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("$SLURM_ARRAY_TASK_ID is \"4\", not a shard number 1 to 3"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(refused));
}

// Where stderr is a file (a batch job's log), progress comes as whole lines naming points: one per
// tenth of the work, never a carriage return that would pile up into one endless line.
TEST_F(SweepCliTest, ABatchLogGetsProgressLinesNamingPoints) {
  const RunResult r = runCoinroll("sweep " + scene().string() + kGrid + " --set duration=0.2 --shard 2/2 -o " +
                                  (dir_ / "part.csv").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find('\r'), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("frame"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("coinroll: sweep shard 2/2: 28/28 points (100 %) after "), std::string::npos) << r.output;
  const long lines = std::count(r.output.begin(), r.output.end(), '\n');
  EXPECT_GE(lines, 10 + 1) << r.output;  // ten tenths and the summary
  EXPECT_LE(lines, 28 + 1) << r.output;
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
  for (const std::string& bad :
       {std::string(" --grid initial.theta=5:40"), std::string(" --grid initial.theta=5:40:0"),
        std::string(" --grid =5:40:3"), std::string(" --grid initial.theta=a:40:3"),
        std::string(" --grid initial.theta=5,10,5"), std::string(" --grid initial.theta=0:10:3:log"),
        std::string(" --grid initial.theta=1:10:3:lin"), std::string(kGrid + " --shard 4/3"),
        std::string(kGrid + " --shard 0/3"), std::string(kGrid + " --max-points 10"),
        std::string(kGrid + " --threads -1")}) {
    const RunResult r = runCoinroll("sweep " + scene().string() + bad + " -o " + out.string());
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.output;
    EXPECT_TRUE(r.output.find("--grid") != std::string::npos || r.output.find("--shard") != std::string::npos ||
                r.output.find("--max-points") != std::string::npos || r.output.find("--threads") != std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(out)) << bad;
  }
}

// A sweep whose runs end in different ways says so in its summary, counted as the CSV's end
// column counts them: "0 failed" alone let spin-downs that only reached their duration pass for
// landed ones.
TEST_F(SweepCliTest, TheSummaryCountsTheRunsByHowTheyEnded) {
  const fs::path out = dir_ / "ends.csv";
  // Without spin the toy falls (the seed's lift-off as theta-dot grows); at 12 rad/s it rolls on.
  const RunResult r = runCoinroll("sweep " + scene().string() + " --grid initial.omega_Z=0:12:4 -o " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::map<std::string, int> ends;
  std::stringstream rows(slurp(out));
  std::string line;
  std::getline(rows, line);
  while (std::getline(rows, line)) ++ends[fields(line).at(2)];
  ASSERT_GE(ends.size(), 2u) << "the grid should end in more than one way";
  std::string expected = "0 failed";
  for (const auto& [end, count] : ends) expected += ", " + std::to_string(count) + " " + end;
  EXPECT_NE(r.output.find("(4 points, " + expected + ";"), std::string::npos) << r.output;
}

}  // namespace
