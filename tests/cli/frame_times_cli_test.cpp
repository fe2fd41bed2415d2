// `coinroll render --frame-times`: the sidecar lists the frames of the video actually written, at
// the times the program chose, so tools read them instead of repeating the time-remap rule. And the
// windows by video time (--from-video, --to-video, --last) and the dry run (--plan) that spare the
// user that arithmetic.

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli/run_command.h"
#include "csv_table.h"
#include "scratch_dir.h"
#include "video_probe.h"

namespace {

namespace fs = std::filesystem;

using coinroll::testing::CsvTable;
using coinroll::testing::readCsvTable;
using coinroll::testing::RunResult;

constexpr int kFps = 30;
constexpr double kTimeScale = 1;

RunResult run(const std::string& arguments, const std::string& environment = "") {
  return coinroll::testing::runCoinroll(arguments, environment);
}

class FrameTimesCliTest : public coinroll::testing::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    scene_ = dir_ / "scene.json";
    // phi-dot ~ 3.2 rad/s, above the remap's limit of 1: the clip plays at about 0.56 of real time,
    // the rate following the wobble, so frame steps differ from frame to frame.
    std::ofstream(scene_) << R"({"name": "toy", "coin": {"radius": 0.0375, "mass": 0.4},
      "initial": {"theta": 20, "omega_Y": 3.0, "omega_Z": 14.0}, "duration": 1.0,
      "render": {"width": 64, "height": 36, "fps": 30, "msaa": 1, "time_scale": 1,
                 "time_remap": {"precession_rate": 1, "growth": 0.5}}})";
  }

  // Renders with --frame-times and returns the sidecar, checking it lists the decoded video's frames.
  CsvTable render(const std::string& name, const std::string& window = "") {
    const fs::path video = dir_ / (name + ".mp4"), sidecar = dir_ / (name + ".csv");
    const RunResult r = run("render " + scene_.string() + " -q -o " + video.string() + " --frame-times " +
                            sidecar.string() + " " + window);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    const CsvTable table = readCsvTable(sidecar);
    EXPECT_EQ(table.headerLine, "frame,video_time_s,clip_frame,sim_time_s,playback_rate");
    EXPECT_EQ(static_cast<std::int64_t>(table.rows.size()), coinroll::video::readVideoInfo(video).frameCount);
    const std::vector<double> frame = table.column("frame"), videoTime = table.column("video_time_s");
    for (std::size_t k = 0; k < table.rows.size(); ++k) {
      EXPECT_EQ(frame[k], static_cast<double>(k));
      EXPECT_EQ(videoTime[k], static_cast<double>(k) / kFps) << "row " << k;
    }
    return table;
  }

  fs::path scene_;
};

TEST_F(FrameTimesCliTest, RowsAreTheVideosFramesAndTheirStepsFollowThePlaybackRate) {
  const CsvTable table = render("whole");
  const std::vector<double> t = table.column("sim_time_s"), rate = table.column("playback_rate"),
                            clipFrame = table.column("clip_frame");
  ASSERT_GT(t.size(), 40u);  // about 1 s / 0.56 * 30 fps
  EXPECT_EQ(t.front(), 0.0);
  EXPECT_LE(t.back(), 1.0);  // the run's duration
  double slowest = kTimeScale;
  for (std::size_t k = 0; k < t.size(); ++k) {
    EXPECT_EQ(clipFrame[k], static_cast<double>(k));
    EXPECT_LE(rate[k], kTimeScale) << "row " << k;
    slowest = std::min(slowest, rate[k]);
    if (k + 1 == t.size()) continue;
    EXPECT_GT(t[k + 1], t[k]) << "row " << k;
    EXPECT_NEAR(t[k + 1] - t[k], rate[k] / kFps, 1e-15) << "row " << k;
  }
  EXPECT_LT(slowest, 0.7 * kTimeScale) << "the time remap did not slow the clip";
}

TEST_F(FrameTimesCliTest, AWindowsRowsAreASliceOfTheFullRendersRows) {
  const CsvTable whole = render("whole");
  const CsvTable window = render("window", "--from 0.3 --to 0.6");
  const std::vector<double> t = whole.column("sim_time_s");
  std::size_t first = 0;
  while (first < t.size() && t[first] < 0.3 - 1e-9) ++first;
  std::size_t inWindow = 0;
  while (first + inWindow < t.size() && t[first + inWindow] <= 0.6 + 1e-9) ++inWindow;
  ASSERT_GT(inWindow, 10u);
  ASSERT_EQ(window.rows.size(), inWindow);
  for (const char* column : {"clip_frame", "sim_time_s", "playback_rate"}) {
    const std::vector<double> full = whole.column(column), part = window.column(column);
    for (std::size_t j = 0; j < inWindow; ++j) EXPECT_EQ(part[j], full[first + j]) << column << " row " << j;
  }
}

TEST_F(FrameTimesCliTest, AFailedRenderLeavesNeitherFile) {
  const fs::path video = dir_ / "clip.mp4", sidecar = dir_ / "clip.csv";
  // The video cannot be written: no sidecar either.
  EXPECT_EQ(run("render " + scene_.string() + " -q -o " + (dir_ / "no_dir" / "clip.mp4").string() + " --frame-times " +
                sidecar.string())
                .exitCode,
            1);
  EXPECT_FALSE(fs::exists(sidecar));
  // The sidecar cannot be written: no video either.
  EXPECT_EQ(run("render " + scene_.string() + " -q -o " + video.string() + " --frame-times " +
                (dir_ / "no_dir" / "clip.csv").string())
                .exitCode,
            1);
  EXPECT_FALSE(fs::exists(video));
  // The window holds no frame: neither.
  EXPECT_EQ(
      run("render " + scene_.string() + " -q -o " + video.string() + " --frame-times " + sidecar.string() + " --from 5")
          .exitCode,
      2);
  EXPECT_FALSE(fs::exists(video));
  EXPECT_FALSE(fs::exists(sidecar));
}

std::string contentOf(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

// A sidecar is an output of its run like the video: refused (exit 2, nothing written, the earlier
// files as they were) when it is the video's file under another spelling, or a name the frame
// pattern makes (which the frames would replace, or the stale-frame cleanup remove).
TEST_F(FrameTimesCliTest, TheSidecarIsRefusedAsAFrameOrTheVideoUnderAnySpelling) {
  const std::string earlier = "an earlier file, which must survive";
  for (const char* name : {"f_002.png", "f_007.png"}) std::ofstream(dir_ / name) << earlier;
  std::ofstream(dir_ / "v.mp4") << earlier;
  fs::create_symlink("v.mp4", dir_ / "link.csv");
  const std::string render = "render " + scene_.string() + " -q ";
  for (const char* arguments : {"-o f_%03d.png --frame-times f_002.png", "-o f_%03d.png --frame-times f_007.png",
                                "-o v.mp4 --frame-times ./v.mp4", "-o v.mp4 --frame-times link.csv"}) {
    const RunResult r = run(render + arguments, "cd " + dir_.string() + " &&");
    EXPECT_EQ(r.exitCode, 2) << arguments << ": " << r.output;
    EXPECT_NE(r.output.find("coinroll: error: --frame-times "), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "f_000.png")) << arguments;
    for (const char* name : {"f_002.png", "f_007.png", "v.mp4"})
      EXPECT_EQ(contentOf(dir_ / name), earlier) << arguments;
  }
  std::ofstream(dir_ / "o.csv") << earlier;
  for (const std::string& provenance : {std::string("./o.csv"), (dir_ / "o.csv").string(), std::string("")}) {
    const RunResult r = run("simulate " + scene_.string() + " --csv o.csv --provenance '" + provenance + "'",
                            "cd " + dir_.string() + " &&");
    EXPECT_EQ(r.exitCode, 2) << provenance << ": " << r.output;
    EXPECT_NE(r.output.find("coinroll: error: --provenance"), std::string::npos) << r.output;
    EXPECT_EQ(contentOf(dir_ / "o.csv"), earlier) << provenance;
  }
  const RunResult r = run("simulate " + scene_.string() + " --csv - --provenance -");
  EXPECT_EQ(r.exitCode, 2) << r.output;
}

// The run's outputs are published together or not at all: a video (or CSV) that fails at its end
// leaves the earlier sidecar as it was, and a failed simulate never replaces the earlier provenance.
TEST_F(FrameTimesCliTest, AFailedRunKeepsBothEarlierFiles) {
  const std::string earlier = "an earlier sidecar, which must survive";
  const fs::path sidecar = dir_ / "t.csv", provenance = dir_ / "p.json";
  std::ofstream(sidecar) << earlier;
  std::ofstream(provenance) << earlier;
  const RunResult rendered = run("render " + scene_.string() + " -q -o /dev/full --frame-times " + sidecar.string());
  EXPECT_EQ(rendered.exitCode, 1) << rendered.output;
  EXPECT_NE(rendered.output.find("/dev/full: writing the MP4 failed"), std::string::npos) << rendered.output;
  EXPECT_EQ(contentOf(sidecar), earlier);
  const RunResult simulated =
      run("simulate " + scene_.string() + " --csv /dev/full --provenance " + provenance.string());
  EXPECT_EQ(simulated.exitCode, 1) << simulated.output;
  EXPECT_EQ(contentOf(provenance), earlier);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 3) << "a temporary was left";
}

// A CSV name that is not UTF-8 is named in the provenance with U+FFFD in place of the bad bytes,
// instead of failing with the JSON library's text.
TEST_F(FrameTimesCliTest, AProvenanceNamesACsvWhoseNameIsNotUtf8) {
  const RunResult r = run("simulate " + scene_.string() + " --csv \"$(printf 'o\\377.csv')\" --provenance p.json",
                          "cd " + dir_.string() + " &&");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(contentOf(dir_ / "p.json").find("\"csv\": \"o\xef\xbf\xbd.csv\""), std::string::npos)
      << contentOf(dir_ / "p.json");
}

// The PNG files of a sequence rendered with `window`, in frame order, as bytes.
std::vector<std::string> pngSequence(const fs::path& scene, const fs::path& dir, const std::string& stem,
                                     const std::string& window) {
  const RunResult r =
      run("render " + scene.string() + " -q -o " + (dir / (stem + "_%03d.png")).string() + " " + window);
  EXPECT_EQ(r.exitCode, 0) << window << ": " << r.output;
  std::vector<std::string> frames;
  for (int k = 0; fs::exists(dir / fmt::format("{}_{:03d}.png", stem, k)); ++k)
    frames.push_back(contentOf(dir / fmt::format("{}_{:03d}.png", stem, k)));
  return frames;
}

// A window by video time is the window of simulated time between the same frames: the same PNG
// files byte for byte, under the time remap whose uneven steps make the one hard to find from the other.
TEST_F(FrameTimesCliTest, AWindowByVideoTimeWritesTheSameFramesAsTheSimulatedTimeWindowBetweenThem) {
  const std::vector<double> t = render("whole").column("sim_time_s");
  ASSERT_GT(t.size(), 40u);
  // Frame k plays at k / 30 s: 0.5 .. 1.0 s of video are frames 15 .. 30.
  const std::vector<std::string> byVideo = pngSequence(scene_, dir_, "v", "--from-video 0.5 --to-video 1.0");
  const std::vector<std::string> bySimulated =
      pngSequence(scene_, dir_, "s", fmt::format("--from {:.17g} --to {:.17g}", t[15], t[30]));
  ASSERT_EQ(byVideo.size(), 16u);
  EXPECT_TRUE(byVideo == bySimulated) << "the windows' frames differ";
  // The last 0.4 s of video are its last 12 frames, from the frame that plays 0.4 s before the end.
  const std::vector<std::string> last = pngSequence(scene_, dir_, "l", "--last 0.4");
  const std::vector<std::string> fromThere =
      pngSequence(scene_, dir_, "f", fmt::format("--from {:.17g}", t[t.size() - 12]));
  ASSERT_EQ(last.size(), 12u);
  EXPECT_TRUE(last == fromThere) << "the last 0.4 s differ from the simulated window";
}

// render --plan --json against what a render writes: its frames' times and rates (--frame-times), and
// the overlay's time line at each, computed here from those; with render.hud off, no overlay.
TEST_F(FrameTimesCliTest, ThePlanAsJsonHoldsTheRendersFramesAndTheirOverlay) {
  const CsvTable table = render("whole");
  const std::vector<double> t = table.column("sim_time_s"), rate = table.column("playback_rate");
  const RunResult r = run("render " + scene_.string() + " -q --plan --json", "cd " + dir_.string() + " &&");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json plan = nlohmann::json::parse(r.output);
  EXPECT_EQ(plan["fps"], kFps);
  EXPECT_EQ(plan["time_scale"], kTimeScale);
  EXPECT_EQ(plan["landed"], false);
  EXPECT_EQ(plan["end_time"], 1.0);
  const nlohmann::json& frames = plan["frames"];
  ASSERT_EQ(frames.size(), t.size());
  EXPECT_EQ(plan["simulated_frames"], t.size());
  EXPECT_EQ(plan["written"]["first"], 0);
  EXPECT_EQ(plan["written"]["last"], t.size() - 1);
  for (std::size_t k = 0; k < t.size(); ++k) {
    const nlohmann::json& frame = frames[k];
    EXPECT_EQ(frame["sim_time_s"].get<double>(), t[k]) << "frame " << k;
    EXPECT_EQ(frame["playback_rate"].get<double>(), rate[k]) << "frame " << k;
    const bool slowed = rate[k] < kTimeScale - 1e-9;
    EXPECT_EQ(frame["slowed_by"], slowed ? nlohmann::json("rate") : nlohmann::json(nullptr)) << "frame " << k;
    const std::vector<std::string> lines = frame["overlay_lines"];
    ASSERT_GE(lines.size(), 3u) << "frame " << k;
    EXPECT_EQ(lines.front(), fmt::format("t        {:9.3f} s", t[k])) << "frame " << k;
    EXPECT_EQ(lines.back().rfind("slow motion ×", 0) == 0, slowed) << lines.back();
    const nlohmann::json& camera = frame["camera"];
    const std::vector<double> eye = camera["eye"], target = camera["target"], up = camera["up"];
    ASSERT_EQ(eye.size(), 3u);
    EXPECT_GT(std::hypot(eye[0] - target[0], eye[1] - target[1], eye[2] - target[2]), 0.01) << "frame " << k;
    EXPECT_NEAR(std::hypot(up[0], up[1], up[2]), 1.0, 1e-6) << "frame " << k;
    EXPECT_GT(camera["fov_y_degrees"].get<double>(), 1.0);
  }
  const RunResult bare = run("render " + scene_.string() + " -q --plan --json --set render.hud=false");
  ASSERT_EQ(bare.exitCode, 0) << bare.output;
  const nlohmann::json barePlan = nlohmann::json::parse(bare.output);
  for (const nlohmann::json& frame : barePlan["frames"]) EXPECT_TRUE(frame["overlay_lines"].empty()) << frame.dump();
  // Without --plan there is no plan to print: refused naming both, nothing written.
  const RunResult alone = run("render " + scene_.string() + " -q --json -o " + (dir_ / "alone.mp4").string());
  EXPECT_EQ(alone.exitCode, 2) << alone.output;
  EXPECT_NE(alone.output.find("--json: prints the --plan as one JSON document"), std::string::npos) << alone.output;
  EXPECT_FALSE(fs::exists(dir_ / "alone.mp4"));
}

// One row of the plan's playback table.
struct PlanRow {
  long frame = 0;
  double videoTime = 0, simulatedTime = 0, rate = 0, contactHz = 0, turnsPerVideoSecond = 0;
};

// The lines of `render --plan`'s output, and its table's rows.
struct Plan {
  std::string text;
  long frames = 0;
  double videoSeconds = 0;
  std::vector<PlanRow> rows;
};

Plan parsePlan(const std::string& text) {
  Plan plan;
  plan.text = text;
  std::istringstream in(text);
  bool inTable = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("video: ", 0) == 0) {
      std::istringstream words(line.substr(7));
      std::string framesWord, at, fps, fpsWord;
      words >> plan.frames >> framesWord >> at >> fps >> fpsWord >> plan.videoSeconds;
    } else if (line.find("frame    video_s") != std::string::npos) {
      inTable = true;
    } else if (inTable) {
      PlanRow row;
      std::string speed, factor;  // "slow x1.08"
      std::istringstream(line) >> row.frame >> row.videoTime >> row.simulatedTime >> row.rate >> speed >> factor >>
          row.contactHz >> row.turnsPerVideoSecond;
      plan.rows.push_back(row);
    }
  }
  return plan;
}

// The plan against the time remap's rule computed here, on a steady circle whose contact rate Omega
// (phi-dot, printed by coinroll steady) is constant: the picture shows it at
// v = max(S, min(S (Omega / S)^g, pi fps / 2)) rad per video s (time_scale 1), so each frame advances
// v / Omega / fps simulated s, and a run of D s gives floor(D fps Omega / v) + 1 frames.
TEST_F(FrameTimesCliTest, ThePlanGivesTheFramesAndRatesOfTheTimeRemapRule) {
  constexpr double kLimit = 1.5, kGrowth = 0.5, kDuration = 2.0;  // rad/s, -, s
  const fs::path circle = dir_ / "circle.json";
  std::ofstream(circle) << fmt::format(
      R"({{"coin": {{"radius": 0.0375, "mass": 0.4}}, "initial": {{"steady": "circle", "theta": 20, "omega_Z": 10}},
      "duration": {}, "render": {{"width": 64, "height": 36, "fps": {}, "msaa": 1,
                                 "time_remap": {{"precession_rate": {}, "growth": {}}}}}}})",
      kDuration, kFps, kLimit, kGrowth);
  const RunResult steady = run("steady " + circle.string());
  ASSERT_EQ(steady.exitCode, 0) << steady.output;
  const std::size_t at = steady.output.find("phi-dot = ");
  ASSERT_NE(at, std::string::npos) << steady.output;
  const double omega = std::abs(std::stod(steady.output.substr(at + 10)));
  ASSERT_GT(omega, kLimit);
  const double visible =
      std::max(kLimit, std::min(kLimit * std::pow(omega / kLimit, kGrowth), std::numbers::pi * kFps / 2));
  const double rate = visible / omega;  // simulated s per video s, below time_scale 1
  const double intervals = kDuration * kFps / rate;
  ASSERT_GT(intervals - std::floor(intervals), 0.01) << "too near a whole frame to check the count";
  const long frames = static_cast<long>(std::floor(intervals)) + 1;
  const RunResult r = run("render " + circle.string() + " --plan", "cd " + dir_.string() + " &&");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const Plan plan = parsePlan(r.output);
  EXPECT_EQ(plan.frames, frames) << r.output;
  EXPECT_NEAR(plan.videoSeconds, static_cast<double>(frames) / kFps, 5e-4) << r.output;
  ASSERT_GE(plan.rows.size(), 2u) << r.output;
  for (const PlanRow& row : plan.rows) {
    EXPECT_NEAR(row.videoTime, static_cast<double>(row.frame) / kFps, 5e-4) << r.output;
    EXPECT_NEAR(row.simulatedTime, static_cast<double>(row.frame) * rate / kFps, 2e-6) << r.output;
    EXPECT_NEAR(row.rate, rate, 1e-6) << r.output;
    EXPECT_NEAR(row.contactHz, omega / (2 * std::numbers::pi), 1e-3) << r.output;
    EXPECT_NEAR(row.turnsPerVideoSecond, visible / (2 * std::numbers::pi), 1e-3) << r.output;
  }
  EXPECT_EQ(plan.rows.back().frame, frames - 1);
  // A dry run: nothing drawn, nothing written (not even circle.mp4, the default name it reports).
  EXPECT_NE(r.output.find("plan of circle.mp4"), std::string::npos) << r.output;
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 2) << "the plan wrote a file";
  // The window's line counts the frames a render with it writes, on both clocks.
  const RunResult last = run("render " + circle.string() + " --plan --last 0.5");
  ASSERT_EQ(last.exitCode, 0) << last.output;
  EXPECT_NE(last.output.find(fmt::format("written: 15 frames {} to {}, 0.500 s of video", frames - 15, frames - 1)),
            std::string::npos)
      << last.output;
}

}  // namespace
