// The built program from outside, as scripts use it: exit codes, messages naming the key,
// and no output file after bad input (docs/contract.md).

#include <gtest/gtest.h>

#include "cli/run_command.h"
#include "csv_table.h"
#include "image/image.h"
#include "scratch_dir.h"
#include "temporaries.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

using coinroll::testing::RunResult;

RunResult run(const std::string& arguments, const std::string& environment = "") {
  return coinroll::testing::runCoinroll(arguments, environment);
}

class CliTest : public coinroll::testing::ScratchDirTest {
 protected:
  fs::path writeScene(const std::string& json) const {
    const fs::path path = dir_ / "scene.json";
    std::ofstream(path) << json;
    return path;
  }
};

const std::string kCoin = R"("coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4})";
const std::string kValid = "{" + kCoin + R"(, "initial": {"theta": 10, "omega_Z": 12}, "duration": 0.5})";

struct BadScene {
  const char* key;  // the message must name it
  std::string json;
};

TEST_F(CliTest, EveryBadSceneGetsExitTwoANamedKeyAndNoFile) {
  const BadScene cases[] = {
      {"line 3", "{\n  \"coin\": {\"radius\": 0.0375,\n  , \"mass\": 0.4}}"},
      {"colour", "{" + kCoin + R"(, "initial": {"theta": 10}, "duration": 1, "colour": "red"})"},
      {"duration", "{" + kCoin + R"(, "initial": {"theta": 10}, "duration": "long"})"},
      {"initial", "{" + kCoin + R"(, "duration": 1})"},
      {"coin.radius", R"({"coin": {"radius": -1, "mass": 0.4}, "initial": {}, "duration": 1})"},
      {"coin.mass", R"({"coin": {"radius": 0.03, "mass": 0}, "initial": {}, "duration": 1})"},
      {"theta", "{" + kCoin + R"(, "initial": {"theta": 95}, "duration": 1})"},
      {"I_X", R"({"coin": {"shape": "custom", "radius": 0.03, "mass": 0.4}, "initial": {}, "duration": 1})"},
      {"I_Z", R"({"coin": {"shape": "custom", "radius": 0.03, "mass": 0.4, "I_X": 1e-5, "I_Z": 3e-5}, )"
              R"("initial": {}, "duration": 1})"},
      {"duration", "{" + kCoin + R"(, "initial": {}, "duration": -3})"},
      {"solver.dt", "{" + kCoin + R"(, "initial": {}, "duration": 1, "solver": {"method": "rk4", "dt": -0.1}})"},
      {"method", "{" + kCoin + R"(, "initial": {}, "duration": 1, "solver": {"method": "magic"}})"},
      {"solver.formulation", "{" + kCoin + R"(, "initial": {}, "duration": 1, "solver": {"formulation": "matrix"}})"},
      {"1e400", "{" + kCoin + R"(, "initial": {}, "duration": 1, "gravity": 1e400})"},
      {"shape", R"({"coin": {"shape": "triangle", "radius": 0.03, "mass": 0.4}, "initial": {}, "duration": 1})"},
  };
  for (const BadScene& c : cases) {
    const fs::path csv = dir_ / "out.csv";
    const RunResult r = run("simulate " + writeScene(c.json).string() + " --csv " + csv.string());
    EXPECT_EQ(r.exitCode, 2) << c.key << ": " << r.output;
    EXPECT_NE(r.output.find(c.key), std::string::npos) << "message should name '" << c.key << "': " << r.output;
    EXPECT_FALSE(fs::exists(csv)) << c.key;
  }
}

// FFmpeg and Mesa (with LLVM, some 140 libraries) are opened by the first render call, not at
// start-up: linked, they cost every command 50 ms before main. The loader's own log says which
// files a run opened.
TEST_F(CliTest, OnlyARenderLoadsFfmpegAndMesa) {
  const fs::path scene = writeScene(kValid);
  const auto loaded = [](const RunResult& r, const std::string& soname) {
    return r.output.find("file=" + soname) != std::string::npos;
  };
  const std::string simulate = "simulate " + scene.string() + " --csv " + (dir_ / "a.csv").string();
  for (const std::string& arguments : {std::string("--version"), simulate}) {
    const RunResult r = run(arguments, "LD_DEBUG=files");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    ASSERT_TRUE(loaded(r, "libfmt.so")) << "the loader's log is missing: " << r.output.substr(0, 400);
    for (const char* soname : {"libavcodec.so", "libavformat.so", "libswscale.so", "libOSMesa.so", "libEGL.so"}) {
      EXPECT_FALSE(loaded(r, soname)) << arguments << " loaded " << soname;
    }
  }
  const RunResult still =
      run("still " + scene.string() + " --time 0.1 --set render.width=64 --set render.height=48 -o " +
              (dir_ / "a.png").string(),
          "LD_DEBUG=files");
  ASSERT_EQ(still.exitCode, 0) << still.output;
  EXPECT_TRUE(loaded(still, "libOSMesa.so") || loaded(still, "libEGL.so"));
  const RunResult video =
      run("render " + scene.string() + " --set duration=0.1 --set render.width=64 --set render.height=48 -o " +
              (dir_ / "a.mp4").string(),
          "LD_DEBUG=files");
  ASSERT_EQ(video.exitCode, 0) << video.output;
  EXPECT_TRUE(loaded(video, "libavcodec.so"));
}

TEST_F(CliTest, BadCommandLinesGetExitTwo) {
  const fs::path scene = writeScene(kValid), csv = dir_ / "out.csv";
  EXPECT_EQ(run("simulate " + scene.string() + " --csv " + csv.string() + " --sample-dt 0").exitCode, 2);
  EXPECT_EQ(run("simulate " + (dir_ / "missing.json").string() + " --csv " + csv.string()).exitCode, 2);
  EXPECT_EQ(run("simulate " + scene.string() + " --csv " + csv.string() + " --set initial.theta=100").exitCode, 2);
  EXPECT_EQ(run("simulate " + scene.string()).exitCode, 2);  // --csv is required
  EXPECT_EQ(run("frobnicate").exitCode, 2);
  EXPECT_FALSE(fs::exists(csv));
}

// One set of conventions (docs/usage.md "Commands"): `coinroll help COMMAND` is
// `coinroll COMMAND --help`, and a misspelt command is answered with the command it is a slip of.
TEST_F(CliTest, HelpCommandIsTheCommandsHelpAndAMisspeltCommandGetsASuggestion) {
  const RunResult help = run("help render"), flag = run("render --help");
  EXPECT_EQ(help.exitCode, 0) << help.output;
  EXPECT_EQ(help.output, flag.output);
  EXPECT_NE(help.output.find("--frame-times"), std::string::npos) << help.output;
  EXPECT_EQ(run("help").output, run("--help").output);
  for (const auto& [given, meant] : {std::pair{"rendr", "render"}, std::pair{"Simulate", "simulate"},
                                     std::pair{"stil", "still"}, std::pair{"sweep-marge", "sweep-merge"}}) {
    const RunResult r = run(given);
    EXPECT_EQ(r.exitCode, 2) << given;
    EXPECT_NE(r.output.find(std::string("(coinroll --help); did you mean '") + meant + "'?"), std::string::npos)
        << r.output;
  }
  const RunResult far = run("frobnicate");
  EXPECT_EQ(far.exitCode, 2);
  EXPECT_EQ(far.output.find("did you mean"), std::string::npos) << far.output;
  const RunResult helpMisspelt = run("help rendr");
  EXPECT_EQ(helpMisspelt.exitCode, 2);
  EXPECT_NE(helpMisspelt.output.find("unknown command 'rendr'"), std::string::npos) << helpMisspelt.output;
}

// The argument parser's refusals read like every other one: "coinroll: error: ...", naming the
// option and where the command's options are listed, instead of the parser's own two lines.
TEST_F(CliTest, ParseErrorsComeInTheProgramsOwnStyle) {
  const fs::path scene = writeScene(kValid);
  for (const auto& [arguments, message] :
       {std::pair{"simulate " + scene.string(),
                  std::string("coinroll: error: --csv is required (coinroll simulate --help)\n")},
        std::pair{"render " + scene.string() + " --max-frames 0",
                  std::string(
                      "coinroll: error: --max-frames: must be a whole number >= 1, got 0 (coinroll render --help)\n")},
        std::pair{std::string(""), std::string("coinroll: error: A subcommand is required (coinroll --help)\n")}}) {
    const RunResult r = run(arguments);
    EXPECT_EQ(r.exitCode, 2) << arguments;
    EXPECT_EQ(r.output, message) << arguments;
  }
}

// Two scene files without a name rendered without -o in one directory each get their own video,
// named after the file, instead of both writing coinroll.mp4, the second replacing the first.
TEST_F(CliTest, RenderWithoutANameOrOutputNamesTheVideoAfterTheSceneFile) {
  const std::string small = " -q --set render.width=64 --set render.height=48 --set duration=0.1";
  for (const char* name : {"first.json", "second.json"}) {
    std::ofstream(dir_ / name) << kValid;
    const RunResult r = run(std::string("render ") + name + small, "cd " + dir_.string() + " &&");
    ASSERT_EQ(r.exitCode, 0) << r.output;
  }
  EXPECT_TRUE(fs::exists(dir_ / "first.mp4"));
  EXPECT_TRUE(fs::exists(dir_ / "second.mp4"));
  EXPECT_FALSE(fs::exists(dir_ / "coinroll.mp4"));
  // A name in the scene still names the video.
  const RunResult named = run("render first.json" + small + " --set 'name=\"toy\"'", "cd " + dir_.string() + " &&");
  ASSERT_EQ(named.exitCode, 0) << named.output;
  EXPECT_TRUE(fs::exists(dir_ / "toy.mp4"));
}

TEST_F(CliTest, UnwritableOutputFailsWithoutLeavingFiles) {
  const RunResult r =
      run("simulate " + writeScene(kValid).string() + " --csv " + (dir_ / "no/such/dir/out.csv").string());
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("out.csv"), std::string::npos) << r.output;
}

TEST_F(CliTest, SimulateWritesTheContractHeaderAndRowsAtMultiplesOfTheSampleStep) {
  const fs::path csv = dir_ / "out.csv";
  const RunResult r = run("simulate " + writeScene(kValid).string() + " --csv " + csv.string() + " --sample-dt 0.05");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const coinroll::testing::CsvTable table = coinroll::testing::readCsvTable(csv);
  EXPECT_EQ(table.headerLine,
            "t,theta,phi,psi,omega_X,omega_Y,omega_Z,x,y,z,contact_x,contact_z,energy,normal_force,friction_force");
  const std::vector<double> t = table.column("t");
  for (std::size_t k = 0; k < t.size(); ++k) EXPECT_NEAR(t[k], 0.05 * static_cast<double>(k), 1e-12);
  EXPECT_EQ(t.size(), 11u);                                                             // t = 0, 0.05, ..., 0.5
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}), 2);  // scene + csv, no temp
}

TEST_F(CliTest, SetOverridesAFieldAndStdoutGetsTheCsv) {
  const RunResult r =
      run("simulate " + writeScene(kValid).string() + " --csv - --set duration=0.02 --set initial.theta=0");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("\n0.02,0,"), std::string::npos) << r.output;  // upright stays upright
}

TEST_F(CliTest, CoinFallingFlatStopsWithANamedEvent) {
  // Below the critical spin from a large tilt the coin falls: the run must end with the
  // coin-flat event, not NaNs.
  const fs::path csv = dir_ / "out.csv";
  const RunResult r =
      run("simulate " + writeScene("{" + kCoin + R"(, "initial": {"theta": 60}, "duration": 5})").string() + " --csv " +
          csv.string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("coin-flat"), std::string::npos) << r.output;
  std::ifstream in(csv);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("nan"), std::string::npos);
}

// One column of a trajectory CSV, by header name.
std::vector<double> csvColumn(const fs::path& csv, const std::string& name) {
  return coinroll::testing::readCsvTable(csv).column(name);
}

TEST_F(CliTest, QuaternionFormulationRunsPastTheEulerAnglesFlatStop) {
  // Let go at 60 degrees with a slow spin, the coin falls past 89.9 degrees and rights itself.
  const fs::path scene = writeScene("{" + kCoin + R"(, "initial": {"theta": 60, "omega_Z": 0.1}, "duration": 0.3})");
  const fs::path eulerCsv = dir_ / "euler.csv", quaternionCsv = dir_ / "quaternion.csv";
  const RunResult euler = run("simulate " + scene.string() + " --csv " + eulerCsv.string());
  EXPECT_EQ(euler.exitCode, 0) << euler.output;
  EXPECT_NE(euler.output.find("coin-flat"), std::string::npos) << euler.output;

  const RunResult quaternion = run("simulate " + scene.string() + " --csv " + quaternionCsv.string() +
                                   " --sample-dt 0.0005 --set solver.formulation=quaternion");
  EXPECT_EQ(quaternion.exitCode, 0) << quaternion.output;
  EXPECT_EQ(quaternion.output.find("stopped early"), std::string::npos) << quaternion.output;
  const std::vector<double> theta = csvColumn(quaternionCsv, "theta"), energy = csvColumn(quaternionCsv, "energy");
  EXPECT_EQ(theta.size(), 601u);
  EXPECT_GT(*std::max_element(theta.begin(), theta.end()), 89.9 * std::numbers::pi / 180);
  const auto [low, high] = std::minmax_element(energy.begin(), energy.end());
  EXPECT_LT((*high - *low) / energy.front(), 1e-8);  // default tolerances, rtol 1e-10
}

// The verdict switches at the classical critical spin of a thin disk rolling straight,
// omega_c = sqrt(g / 3a) (Routh; for the built-in coin a = 0.0375 m, g = 9.81: 9.3381 rad/s),
// computed here, not read from the program.
TEST_F(CliTest, SteadyVerdictSwitchesAtTheThinDiskCriticalSpin) {
  const double omega_c = std::sqrt(9.81 / (3 * 0.0375));
  const RunResult stable = run("steady --kind straight --omega-Z " + std::to_string(1.01 * omega_c));
  EXPECT_EQ(stable.exitCode, 0) << stable.output;
  EXPECT_NE(stable.output.find("verdict: STABLE"), std::string::npos) << stable.output;
  EXPECT_EQ(stable.output.find("UNSTABLE"), std::string::npos) << stable.output;
  const RunResult unstable = run("steady --kind straight --omega-Z " + std::to_string(0.99 * omega_c));
  EXPECT_EQ(unstable.exitCode, 0) << unstable.output;
  EXPECT_NE(unstable.output.find("verdict: UNSTABLE"), std::string::npos) << unstable.output;
  EXPECT_EQ(run("steady --theta 20").exitCode, 2);
}

// The number printed after `label` in a report ("omega_c = 9.33809 rad/s" -> 9.33809); NaN if absent.
double numberAfter(const std::string& output, const std::string& label) {
  const std::size_t at = output.find(label);
  if (at == std::string::npos) return std::nan("");
  return std::stod(output.substr(at + label.size()));
}

// A thick coin (docs/rim.md §5): the built-in 37.5 mm toy at h = 13 mm, fully rounded by default (rho = h/2).
// Straight rolling is steady and its critical spin is eq. 5.9, omega_c^2 = M g (a - rho) I_X / (I_Z (I_Z + M a^2)),
// computed here from the inertia the report says it used; the shorter lever a - rho puts it below the thin coin's.
TEST_F(CliTest, SteadyOfAFullyRoundedThickCoinPrintsItsRimAndALowerCriticalSpin) {
  const RunResult thin = run("steady --kind straight --omega-Z 12");
  ASSERT_EQ(thin.exitCode, 0) << thin.output;
  const RunResult thick = run("steady --kind straight --omega-Z 12 --set coin.thickness=0.013");
  ASSERT_EQ(thick.exitCode, 0) << thick.output;
  EXPECT_NE(thick.output.find("rim: thickness h = 0.013 m, edge radius rho = 0.0065 m"), std::string::npos)
      << thick.output;
  EXPECT_NE(thick.output.find("inertia used:"), std::string::npos) << thick.output;
  EXPECT_NE(thick.output.find("docs/rim.md eq. 5.8"), std::string::npos) << thick.output;
  EXPECT_EQ(thick.output.find("docs/derivations.md"), std::string::npos) << thick.output;
  EXPECT_NE(thick.output.find("verdict: STABLE"), std::string::npos) << thick.output;
  EXPECT_EQ(thin.output.find("rim:"), std::string::npos) << thin.output;

  const double thinSpin = numberAfter(thin.output, "omega_c = "), thickSpin = numberAfter(thick.output, "omega_c = ");
  EXPECT_NEAR(thinSpin, std::sqrt(9.81 / (3 * 0.0375)), 1e-4);
  EXPECT_LT(thickSpin, thinSpin);
  const double M = 0.4, a = 0.0375, g = 9.81, rho = 0.0065;
  const double I_X = numberAfter(thick.output, "I_X = "), I_Z = numberAfter(thick.output, "I_Z = ");
  EXPECT_NEAR(thickSpin, std::sqrt(M * g * (a - rho) * I_X / (I_Z * (I_Z + M * a * a))), 1e-5 * thickSpin)
      << thick.output;
  // The thick coin's verdict switches at its own critical spin.
  for (const auto& [factor, verdict] : {std::pair{0.99, "verdict: UNSTABLE"}, std::pair{1.01, "verdict: STABLE"}}) {
    const RunResult near =
        run("steady --kind straight --omega-Z " + std::to_string(factor * thickSpin) + " --set coin.thickness=0.013");
    EXPECT_NE(near.output.find(verdict), std::string::npos) << factor << ": " << near.output;
  }
}

// A cornered rim (rho < h/2) has no upright steady motion, so no critical spin: the report says why instead of
// failing, and still gives a circle's K and verdict; asking for straight rolling is a bad request naming the key.
TEST_F(CliTest, SteadyOfACorneredRimHasAVerdictButNoCriticalSpin) {
  const std::string rim = " --set coin.thickness=0.013 --set coin.edge_radius=0.0016";
  const RunResult r = run("steady --kind circle --theta 20 --omega-Z 10" + rim);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("verdict: "), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("omega_c"), std::string::npos) << r.output;
  EXPECT_NE(
      r.output.find("straight rolling is not a steady motion of a coin whose rim has corners (it switches corners "
                    "at upright)"),
      std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("edge radius rho = 0.0016 m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("docs/rim.md eq. 5.8"), std::string::npos) << r.output;

  const RunResult straight = run("steady --kind straight --omega-Z 12" + rim);
  EXPECT_EQ(straight.exitCode, 2) << straight.output;
  EXPECT_NE(straight.output.find("initial.steady"), std::string::npos) << straight.output;
  EXPECT_EQ(straight.output.find("verdict"), std::string::npos) << straight.output;
}

TEST_F(CliTest, HelpTeachesAndExitsZero) {
  const RunResult r = run("--help");
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_NE(r.output.find("simulate"), std::string::npos);
  EXPECT_NE(r.output.find("Examples"), std::string::npos);
}

}  // namespace

namespace {

// The names of the files in `dir` (temporaries are ".NAME.partial-...").
std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  return names;
}

TEST_F(CliTest, InterruptedSimulateExitsOneAndLeavesNothing) {
  const fs::path scene = writeScene(kValid), csv = dir_ / "out.csv";
  for (const int signal : {SIGINT, SIGTERM}) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      const std::string binary = std::string(COINROLL_BINARY_DIR) + "/coinroll";
      std::freopen("/dev/null", "w", stderr);
      execl(binary.c_str(), binary.c_str(), "simulate", scene.c_str(), "--csv", csv.c_str(), "--sample-dt", "0.0001",
            "--set", "duration=1e6", "--max-rows", "100000000000", static_cast<char*>(nullptr));
      _exit(127);
    }
    // The signal guard is installed before any output exists, so the signal may come as soon as
    // the temporary file does: no window in which it would kill the process. The temporary has no
    // name (io/temporary.h), so it is seen among the run's descriptors.
    for (int i = 0; i < 400 && coinroll::testing::temporariesBeingWritten(child, dir_) < 1; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const bool writing = coinroll::testing::temporariesBeingWritten(child, dir_) >= 1;
    if (!writing) kill(child, SIGKILL);  // not left running for ever
    ASSERT_TRUE(writing) << "the run never started writing";
    kill(child, signal);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << signal << " instead of stopping cleanly";
    EXPECT_EQ(WEXITSTATUS(status), 1);
    EXPECT_EQ(filesIn(dir_), std::vector<std::string>{"scene.json"});
  }
}

TEST_F(CliTest, AnOutputThatIsTheInputIsRefusedAndTheInputKept) {
  const fs::path scene = writeScene(kValid);
  const std::string before = [&] {
    std::ifstream in(scene);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  for (const std::string& command : {"simulate " + scene.string() + " --csv " + scene.string(),
                                     "simulate " + scene.string() + " --csv " + (dir_ / "." / "scene.json").string(),
                                     "sweep " + scene.string() + " --grid initial.theta=1:2:2 -o " + scene.string(),
                                     "still " + scene.string() + " --time 0.1 -o " + scene.string()}) {
    const RunResult r = run(command);
    EXPECT_EQ(r.exitCode, 2) << command << ": " << r.output;
    std::ifstream in(scene);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), before) << command;
  }
  const RunResult r = run("simulate " + scene.string() + " --csv " + scene.string());
  EXPECT_NE(r.output.find("that is the input"), std::string::npos) << r.output;
}

TEST_F(CliTest, AFailedWriteToStdoutIsAnError) {
  // stderr to the pipe we read, stdout to the full device (runCoinroll would send both there).
  const std::string command = std::string(COINROLL_BINARY_DIR) + "/coinroll simulate " + writeScene(kValid).string() +
                              " --csv - 2>&1 >/dev/full";
  FILE* pipe = popen(command.c_str(), "r");
  std::string output;
  for (std::array<char, 4096> buffer{}; std::fgets(buffer.data(), buffer.size(), pipe) != nullptr;)
    output += buffer.data();
  const int status = pclose(pipe);
  EXPECT_EQ(WEXITSTATUS(status), 1) << output;
  EXPECT_NE(output.find("writing the CSV to stdout failed: No space left on device"), std::string::npos) << output;
}

TEST_F(CliTest, ToleranceOutsideItsMeaningfulRangeIsRefused) {
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"atol", "0"}, {"atol", "1"}, {"rtol", "0.5"}, {"rtol", "1e-16"}, {"dt", "1e-9"}, {"dt", "10"}}) {
    const RunResult r = run("simulate " + writeScene(kValid).string() + " --csv " + (dir_ / "o.csv").string() +
                            " --set solver." + key + "=" + value);
    EXPECT_EQ(r.exitCode, 2) << key << "=" << value << ": " << r.output;
    EXPECT_NE(r.output.find("solver." + key), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "o.csv"));
  }
}

}  // namespace

namespace {

TEST_F(CliTest, AbsurdRequestsAreRefusedUpFrontNamingWhatAndTheLimit) {
  const fs::path scene = writeScene(kValid);
  struct Case {
    std::string arguments, mustSay;
  };
  const std::vector<Case> cases = {
      {"simulat " + scene.string(), "unknown command 'simulat'; the commands are simulate, "},
      {"simulate " + dir_.string() + " --csv " + (dir_ / "o.csv").string(), "is a directory"},
      {"simulate /dev/zero --csv " + (dir_ / "o.csv").string(), "more than 16777216 bytes"},
      {"simulate " + scene.string() + " --sample-dt 1e-10 --csv " + (dir_ / "o.csv").string(), "--max-rows"},
      {"render " + scene.string() + " --set duration=1e7 --set render.fps=240 -o " + (dir_ / "o.mp4").string(),
       "2.4e+09 frames, more than the limit 1000000"},
      {"render " + scene.string() + " --max-frames 10 -o " + (dir_ / "o.mp4").string(),  // a limit the user set
       "16 frames, more than the limit 10"},
  };
  for (const Case& c : cases) {
    const auto start = std::chrono::steady_clock::now();
    const RunResult r = run(c.arguments);
    EXPECT_EQ(r.exitCode, 2) << c.arguments << ": " << r.output;
    EXPECT_NE(r.output.find(c.mustSay), std::string::npos) << c.arguments << ": " << r.output;
    EXPECT_EQ(filesIn(dir_), std::vector<std::string>{"scene.json"}) << c.arguments;
    // Refused before the work, not after it (the render above would integrate for minutes).
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20)) << c.arguments;
  }
}

}  // namespace

namespace {

TEST_F(CliTest, AFixedStepPastTheDurationReportsNoEventAfterTheEnd) {
  // The fall reaches the 89-degree stop at t = 0.073 s; a 0.05 s RK4 step from 0.05 lands at 0.1,
  // past the 0.07 s duration, and finds it there. The run ended at 0.07 s, before the event.
  const fs::path scene = std::string(COINROLL_SOURCE_DIR) + "/examples/falling_flat.json";
  const RunResult r = run("simulate " + scene.string() + " --csv " + (dir_ / "o.csv").string() +
                          " --set solver.formulation=euler-angles --set solver.method=rk4 --set solver.dt=0.05 "
                          "--set duration=0.07");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("stopped early"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("coinroll: 8 rows"), std::string::npos) << r.output;
}

TEST_F(CliTest, ALegalLongFileNameIsWritten) {
  const std::string name(251, 'a');  // + ".csv" = 255 bytes, the longest name Linux allows
  const RunResult r = run("simulate " + writeScene(kValid).string() + " --csv " + (dir_ / (name + ".csv")).string());
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / (name + ".csv")));
}

TEST_F(CliTest, ADegenerateCameraIsRefused) {
  for (const std::string& camera : {std::string(R"({"eye": [0, 0.2, 0], "target": [0, 0.2, 0]})"),
                                    std::string(R"({"eye": [0, 1, 0], "target": [0, 0, 0]})")}) {
    const RunResult r = run("still " + writeScene(kValid).string() + " --time 0.1 -o " + (dir_ / "o.png").string() +
                            " --set 'render.camera=" + camera + "'");
    EXPECT_EQ(r.exitCode, 2) << camera << ": " << r.output;
    EXPECT_NE(r.output.find("render.camera.target"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "o.png"));
  }
}

std::string contentOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// A small scene of a coin tilted by `theta` degrees, quick to draw.
std::string smallScene(int theta) {
  return "{" + kCoin + R"(, "initial": {"theta": )" + std::to_string(theta) +
         R"(, "omega_Z": 12}, "duration": 0.3, "render": {"width": 64, "height": 48, "fps": 10, "msaa": 1}})";
}

// A page template with the scene's placeholder, as tools/build_page.sh leaves it (export fills it).
fs::path fakePage(const fs::path& dir) {
  const fs::path page = dir / "template.html";
  std::ofstream(page) << R"(<html><script type="application/json" id="coinroll-scene">null</script>)"
                         R"(<script type="application/json" id="coinroll-page-options">null</script>)"
                         R"(<script type="application/json" id="coinroll-controls">[]</script></html>)";
  return page;
}

// The default output name (no -o) of render, still and export is the scene file's name; a file
// there made from another scene (its provenance names another digest) or by something else is
// never replaced silently: exit 2 naming -o and --force, the file kept. The same scene replaces its
// own output, and -o and --force replace as asked.
TEST_F(CliTest, ADefaultOutputNameIsNeverTakenOverByAnotherScenesOutput) {
  fs::create_directories(dir_ / "other");
  std::ofstream(dir_ / "a.json") << smallScene(10);
  std::ofstream(dir_ / "other" / "a.json") << smallScene(15);  // another scene whose default names are a.*
  const std::string in = "cd " + dir_.string() + " && COINROLL_PAGE=" + fakePage(dir_).string();
  struct Command {
    const char* arguments;  // after the scene
    const char* output;     // its default output name
  };
  for (const Command& command :
       {Command{"render -q", "a.mp4"}, Command{"still --time 0.1 -q", "a.png"}, Command{"export -q", "a.html"}}) {
    const std::string verb = command.arguments;
    const std::string name = verb.substr(0, verb.find(' '));
    const std::string options = verb.substr(name.size());
    const auto runOn = [&](const std::string& scene, const std::string& extra = "") {
      return run(name + " " + scene + options + extra, in);
    };
    ASSERT_EQ(runOn("a.json").exitCode, 0) << command.arguments;
    const std::string first = contentOf(dir_ / command.output);
    ASSERT_FALSE(first.empty()) << command.output;
    EXPECT_EQ(runOn("a.json").exitCode, 0) << command.arguments << ": the same scene replaces its own output";
    const RunResult other = runOn("other/a.json");
    EXPECT_EQ(other.exitCode, 2) << other.output;
    EXPECT_NE(other.output.find(std::string(command.output) + ": exists, made from another scene"), std::string::npos)
        << other.output;
    EXPECT_NE(other.output.find("give -o NAME to write elsewhere, or --force to replace it"), std::string::npos)
        << other.output;
    EXPECT_EQ(contentOf(dir_ / command.output), first) << command.arguments;
    EXPECT_EQ(runOn("other/a.json", " -o " + std::string(command.output)).exitCode, 0) << "an -o name is replaced";
    EXPECT_NE(contentOf(dir_ / command.output), first) << command.arguments;
    EXPECT_EQ(runOn("a.json", " --force").exitCode, 0) << command.arguments;
    EXPECT_EQ(contentOf(dir_ / command.output), first) << command.arguments << ": --force replaces it";
    // A file coinroll did not make under the default name.
    std::ofstream(dir_ / command.output) << "the user's own file";
    const RunResult foreign = runOn("a.json");
    EXPECT_EQ(foreign.exitCode, 2) << foreign.output;
    EXPECT_NE(foreign.output.find("does not say which scene made it"), std::string::npos) << foreign.output;
    EXPECT_EQ(contentOf(dir_ / command.output), "the user's own file");
  }
}

// -q on every command that prints notes, progress or a summary on stderr: silent where nothing went
// wrong, while a warning and an early stop (which change what the output means) still show.
TEST_F(CliTest, QuietSilencesNotesAndSummariesOnEveryCommand) {
  // A steady start with effects: every command that loads it notes that the state is only a start.
  std::ofstream(dir_ / "s.json") << "{" + kCoin + R"(, "initial": {"steady": "spin-in-place", "theta": 30},
      "effects": [{"type": "rolling_resistance", "length": 1e-4}], "duration": 0.2,
      "render": {"width": 64, "height": 48, "fps": 10, "msaa": 1}})";
  const std::string in = "cd " + dir_.string() + " && COINROLL_PAGE=" + fakePage(dir_).string();
  for (const std::string& command :
       {std::string("simulate s.json --csv o.csv"), std::string("steady s.json"),
        std::string("still s.json --time 0.1"), std::string("render s.json"), std::string("export s.json --force"),
        std::string("sweep s.json --grid "
                    "duration=0.1,0.2 -o w.csv")}) {
    // Standard output holds only steady's report, whose lines never start "coinroll:".
    const RunResult loud = run(command, in);
    ASSERT_EQ(loud.exitCode, 0) << command << ": " << loud.output;
    EXPECT_NE(loud.output.find("coinroll: "), std::string::npos) << command << " says nothing without -q";
    const RunResult quiet = run(command + " -q", in);
    ASSERT_EQ(quiet.exitCode, 0) << command << ": " << quiet.output;
    EXPECT_EQ(quiet.output.find("coinroll: "), std::string::npos) << command << " -q: " << quiet.output;
  }
  // What -q keeps: the early stop of a coin that falls flat (at 89 degrees in Euler angles).
  const fs::path falling = std::string(COINROLL_SOURCE_DIR) + "/examples/falling_flat.json";
  const RunResult stopped =
      run("simulate " + falling.string() + " --csv o.csv -q --set solver.formulation=euler-angles", in);
  EXPECT_EQ(stopped.exitCode, 0) << stopped.output;
  EXPECT_NE(stopped.output.find("coinroll: stopped early: coin-flat"), std::string::npos) << stopped.output;
}

// still --strobe N --panels: the N + 1 times side by side instead of copies piled over one picture,
// each panel the still at its time (compared here without the overlay, whose labels differ), with a
// gutter of white paper between them; two rows, 4 + 3 panels, for seven.
TEST_F(CliTest, AStrobesPanelsAreTheStillsAtItsTimesSideBySide) {
  constexpr int kWidth = 200, kHeight = 100, kGutter = 2;  // pixels; the gutter is max(2, width / 100)
  std::ofstream(dir_ / "s.json") << "{" + kCoin + R"(, "initial": {"theta": 20, "omega_Y": 3, "omega_Z": 14},
      "duration": 1, "render": {"width": 200, "height": 100, "msaa": 1, "hud": false,
                                "camera": {"eye": [0, 0.15, 0.3], "target": [0, 0, 0]}}})";
  const std::string in = "cd " + dir_.string() + " &&";
  const RunResult r = run("still s.json --time 0.6 --strobe 6 --strobe-from 0.3 --panels -q -o panels.png", in);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const coinroll::image::Image figure = coinroll::image::readPng(dir_ / "panels.png");
  ASSERT_EQ(figure.width, 4 * kWidth + 3 * kGutter);
  ASSERT_EQ(figure.height, 2 * kHeight + kGutter);
  for (int i = 0; i < 7; ++i) {
    const double t = 0.3 + 0.05 * i;  // six copies over [0.3, 0.6), then 0.6
    const std::string name = "at" + std::to_string(i) + ".png";
    ASSERT_EQ(run("still s.json --time " + std::to_string(t) + " -q -o " + name, in).exitCode, 0);
    const coinroll::image::Image still = coinroll::image::readPng(dir_ / name);
    const int left = (i % 4) * (kWidth + kGutter), top = (i / 4) * (kHeight + kGutter);
    int differing = 0;
    for (int y = 0; y < kHeight; ++y) {
      differing += std::equal(still.pixel(0, y), still.pixel(0, y) + 4 * kWidth, figure.pixel(left, top + y)) ? 0 : 1;
    }
    EXPECT_EQ(differing, 0) << "panel " << i << " (t = " << t << " s): rows differing from the still";
  }
  EXPECT_EQ(figure.pixel(kWidth, 0)[0], 255) << "the gutter is white";
  EXPECT_EQ(figure.pixel(figure.width - 1, figure.height - 1)[0], 255) << "the empty eighth cell is white";
  // The summary gives the figure's size, not one panel's.
  const RunResult told = run("still s.json --time 0.6 --strobe 6 --strobe-from 0.3 --panels -o told.png", in);
  ASSERT_EQ(told.exitCode, 0) << told.output;
  const std::string size = std::to_string(figure.width) + "x" + std::to_string(figure.height);
  EXPECT_NE(told.output.find("wrote told.png (" + size + ", t = 0.6 s)"), std::string::npos) << told.output;
  // Panels lay out the copies: without --strobe there are none.
  const RunResult alone = run("still s.json --time 0.6 --panels -q -o p.png", in);
  EXPECT_EQ(alone.exitCode, 2) << alone.output;
  EXPECT_NE(alone.output.find("--panels: lays out the --strobe copies side by side, and there are none"),
            std::string::npos)
      << alone.output;
}

}  // namespace
