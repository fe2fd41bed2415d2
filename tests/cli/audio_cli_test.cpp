// render.audio through the command line: the sound track decoded back with libavcodec and its
// pitch measured by zero crossings against Omega = |phi-dot| from `simulate`'s CSV of the same
// scene (an independent path: the CSV comes from the trajectory, the pitch from the encoded file).

#include <gtest/gtest.h>

#include <cmath>
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

using coinroll::testing::isNear;
using coinroll::testing::runCoinroll;

class AudioCliTest : public coinroll::testing::ScratchDirTest {
 protected:
};

constexpr int kRate = 48000;
constexpr double kPitchBound = 0.01;  // the issue's bound; steady motions measure 1e-6

// Omega(t) = |omega_Y / cos(theta)| at each CSV row, rad/s.
std::vector<std::pair<double, double>> omegaFromCsv(const fs::path& csv) {
  const coinroll::testing::CsvTable table = coinroll::testing::readCsvTable(csv);
  const std::vector<double> t = table.column("t"), theta = table.column("theta"), omega_Y = table.column("omega_Y");
  std::vector<std::pair<double, double>> rows;
  for (std::size_t i = 0; i < t.size(); ++i) rows.emplace_back(t[i], std::abs(omega_Y[i] / std::cos(theta[i])));
  return rows;
}

// The mean frequency between the first and the last upward zero crossing in samples [begin, end),
// crossings interpolated to sub-sample time; `from` and `to` get their times, s.
double zeroCrossingFrequency(const std::vector<float>& x, std::size_t begin, std::size_t end, double* from = nullptr,
                             double* to = nullptr) {
  std::vector<double> crossings;
  for (std::size_t i = begin; i + 1 < end; ++i) {
    if (x[i] < 0 && x[i + 1] >= 0) crossings.push_back(static_cast<double>(i) + x[i] / (x[i] - x[i + 1]));
  }
  if (crossings.size() < 3) return 0;
  if (from != nullptr) *from = crossings.front() / kRate;
  if (to != nullptr) *to = crossings.back() / kRate;
  return static_cast<double>(crossings.size() - 1) * kRate / (crossings.back() - crossings.front());
}

TEST_F(AudioCliTest, SteadyCircleSoundsAtItsContactRateAndSlowMotionLowersIt) {
  const std::string scene = std::string(COINROLL_SOURCE_DIR) + "/examples/steady_circle.json";
  const fs::path csv = dir_ / "circle.csv";
  ASSERT_EQ(runCoinroll("simulate " + scene + " --csv " + csv.string()).exitCode, 0);
  const double Omega = omegaFromCsv(csv).front().second;
  const double k = 200;  // the circle's 0.98 Hz brought to 195 Hz, so 0.25 s windows hold 49 periods
  for (const double timeScale : {1.0, 0.5}) {
    const fs::path mp4 = dir_ / "circle.mp4";
    const std::string audio = R"(--set 'render.audio={"timbre": "tone", "frequency_scale": 200, "pitch": "video"}')";
    ASSERT_EQ(
        runCoinroll("render " + scene + " -q -o " + mp4.string() + " --set render.width=64 --set render.height=36 " +
                    "--set render.time_scale=" + std::to_string(timeScale) + " " + audio)
            .exitCode,
        0);
    const coinroll::video::DecodedAudio decoded = coinroll::video::decodeAudio(mp4);
    EXPECT_EQ(decoded.codecName, "aac");
    EXPECT_EQ(decoded.sampleRate, kRate);
    // The track lasts as long as the video, to within one AAC frame of 1024 samples.
    const coinroll::video::VideoInfo info = coinroll::video::readVideoInfo(mp4);
    EXPECT_LE(std::abs(decoded.durationSeconds - info.durationSeconds), 1024.0 / kRate);
    // Pitch "video": slow motion at time_scale 0.5 halves the pitch, as a slowed recording would.
    const double expected = k * Omega / (2 * std::numbers::pi) * timeScale;
    int windows = 0;
    for (std::size_t begin = kRate / 10; begin + kRate / 4 < decoded.samples.size() - kRate / 5; begin += kRate / 4) {
      const double measured = zeroCrossingFrequency(decoded.samples, begin, begin + kRate / 4);
      EXPECT_TRUE(isNear(measured / expected, 1, kPitchBound)) << "time_scale " << timeScale << ", window at " << begin;
      ++windows;
    }
    EXPECT_GE(windows, 10);
  }
}

TEST_F(AudioCliTest, SpinDownChirpFollowsOmegaToTheEnd) {
  // A fast spin-down (rolling resistance 0.1 mm: 1.5 s from 15 degrees), played in real time with
  // the real pitch, so audio time is simulated time.
  const fs::path scene = dir_ / "chirp.json", csv = dir_ / "chirp.csv", mp4 = dir_ / "chirp.mp4";
  std::ofstream(scene) << R"({"coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4},
    "initial": {"steady": "spin-in-place", "theta": 75}, "duration": 10,
    "effects": [{"type": "rolling_resistance", "length": 1e-4}, {"type": "air_drag"}],
    "render": {"width": 64, "height": 36, "fps": 30,
               "audio": {"timbre": "tone", "frequency_scale": 10, "pitch": "real"}}})";
  ASSERT_EQ(runCoinroll("simulate " + scene.string() + " --csv " + csv.string() + " --sample-dt 0.001").exitCode, 0);
  ASSERT_EQ(runCoinroll("render " + scene.string() + " -q -o " + mp4.string()).exitCode, 0);
  const std::vector<std::pair<double, double>> omega = omegaFromCsv(csv);
  const coinroll::video::DecodedAudio decoded = coinroll::video::decodeAudio(mp4);
  const double end = omega.back().first;
  ASSERT_GT(end, 1.0);
  // 50 ms windows up to 0.2 s before the stop. Zero crossings count the phase advanced, so the
  // truth is the mean of k Omega / (2 pi) over the CSV's 1 ms rows between the first and the last
  // crossing. (Measured against Omega at the window's middle instead, the chirp's curvature alone
  // adds up to 0.9 %.)
  double lowest = 1e9, highest = 0;
  for (double start = 0.05; start + 0.05 < end - 0.2; start += 0.05) {
    const auto begin = static_cast<std::size_t>(start * kRate), stop = static_cast<std::size_t>((start + 0.05) * kRate);
    double from = 0, to = 0;
    const double measured = zeroCrossingFrequency(decoded.samples, begin, stop, &from, &to);
    double sum = 0;
    int count = 0;
    for (const auto& [t, Omega] : omega) {
      if (t >= from && t <= to) sum += Omega, ++count;
    }
    ASSERT_GT(count, 30);
    const double expected = 10 * sum / count / (2 * std::numbers::pi);
    EXPECT_TRUE(isNear(measured / expected, 1, kPitchBound)) << "window at " << start << " s";
    lowest = std::min(lowest, expected);
    highest = std::max(highest, expected);
  }
  EXPECT_GT(highest, 1.5 * lowest);  // it is a chirp
}

TEST_F(AudioCliTest, EachImpactKnocksAtItsTimeAsLoudAsTheSquareRootOfItsLoss) {
  // A disk dropped edge-down from 1 cm without spin (docs/flight.md): no contact rate, so the track
  // is silent but for the knocks, played in real time. Each rebound takes e^2 = 1/4 of the energy the
  // impact before took, so each knock is e = 1/2 as loud; the times come from `simulate`'s stderr.
  const fs::path scene = dir_ / "drop.json", mp4 = dir_ / "drop.mp4";
  std::ofstream(scene) << R"({"coin": {"radius": 0.0125, "mass": 0.0075}, "friction": 0.3, "sliding": true,
    "flight": true, "restitution": 0.5, "initial": {"theta": 0, "y": 0.0225}, "duration": 0.4,
    "render": {"width": 64, "height": 36, "fps": 30, "audio": {"timbre": "tone", "pitch": "real"}}})";
  const auto simulated = runCoinroll("simulate " + scene.string() + " --csv " + (dir_ / "drop.csv").string());
  ASSERT_EQ(simulated.exitCode, 0);
  std::vector<double> impacts;
  for (std::size_t at = 0; (at = simulated.output.find("impact at t = ", at)) != std::string::npos; ++at) {
    impacts.push_back(std::stod(simulated.output.substr(at + 14)));
  }
  ASSERT_GE(impacts.size(), 4u);
  ASSERT_EQ(runCoinroll("render " + scene.string() + " -q -o " + mp4.string()).exitCode, 0);
  const std::vector<float>& x = coinroll::video::decodeAudio(mp4).samples;
  // The loudest sample within 3 ms after each impact, and nothing before the first.
  const auto peakAfter = [&](double t, double window) {
    float peak = 0;
    const auto end = std::min(static_cast<std::size_t>((t + window) * kRate), x.size());
    for (auto i = static_cast<std::size_t>(t * kRate); i < end; ++i) {
      peak = std::max(peak, std::abs(x[i]));
    }
    return peak;
  };
  EXPECT_LT(peakAfter(0, impacts[0] - 0.002), 0.01);
  for (std::size_t k = 0; k + 1 < 3; ++k) {
    const double ratio = peakAfter(impacts[k + 1], 0.003) / peakAfter(impacts[k], 0.003);
    EXPECT_TRUE(isNear(ratio, 0.5, 0.05)) << "knock " << k + 1 << " to " << k + 2 << ": " << ratio;
  }
}

TEST_F(AudioCliTest, ARerunWritesTheSameBytes) {
  const std::string scene = std::string(COINROLL_SOURCE_DIR) + "/examples/euler_disk.json";
  const std::string options =
      " -q --set render.width=64 --set render.height=36 --set render.fps=10 --set duration=3 "
      "--set 'render.audio=true'";
  const fs::path a = dir_ / "a.mp4", b = dir_ / "b.mp4";
  ASSERT_EQ(runCoinroll("render " + scene + options + " -o " + a.string()).exitCode, 0);
  ASSERT_EQ(runCoinroll("render " + scene + options + " -o " + b.string()).exitCode, 0);
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  const std::string bytesA{std::istreambuf_iterator<char>(fa), {}}, bytesB{std::istreambuf_iterator<char>(fb), {}};
  EXPECT_EQ(bytesA, bytesB);
  EXPECT_EQ(coinroll::video::decodeAudio(a).codecName, "aac");
}

}  // namespace
