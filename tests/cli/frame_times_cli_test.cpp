// `coinroll render --frame-times`: the sidecar lists the frames of the video actually written, at
// the times the program chose, so tools read them instead of repeating the time-remap rule.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
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

RunResult run(const std::string& arguments) { return coinroll::testing::runCoinroll(arguments); }

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
                sidecar.string()).exitCode, 1);
  EXPECT_FALSE(fs::exists(sidecar));
  // The sidecar cannot be written: no video either.
  EXPECT_EQ(run("render " + scene_.string() + " -q -o " + video.string() + " --frame-times " +
                (dir_ / "no_dir" / "clip.csv").string()).exitCode, 1);
  EXPECT_FALSE(fs::exists(video));
  // The window holds no frame: neither.
  EXPECT_EQ(run("render " + scene_.string() + " -q -o " + video.string() + " --frame-times " + sidecar.string() +
                " --from 5").exitCode, 2);
  EXPECT_FALSE(fs::exists(video));
  EXPECT_FALSE(fs::exists(sidecar));
}

}  // namespace
