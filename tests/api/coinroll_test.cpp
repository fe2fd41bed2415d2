// The library's doors keep the command's rules (docs/contract.md §9): an output never replaces the
// scene it was read from, a run's size is refused before any work, and messages name what a C++
// caller types (the header's parameters), never a command-line flag or an internal struct.
#include <coinroll/coinroll.h>

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include "scratch_dir.h"
#include "temporaries.h"

namespace {

using coinroll::testing::ScratchDirTest;

// The issue's s.json: a 0.5 s toy run, small pictures.
constexpr const char* kScene =
    R"({"name": "s", "coin": {"shape": "disk", "radius": 0.0375, "mass": 0.4},
        "initial": {"theta": 10, "omega_Z": 12}, "duration": 0.5, "render": {"width": 160, "height": 90}})";

std::string contentsOf(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The message of the std::invalid_argument `call` throws; fails the test if it throws none.
template <class Call>
std::string refusal(Call call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "no std::invalid_argument";
  return {};
}

class ApiOutputs : public ScratchDirTest {};

TEST_F(ApiOutputs, RenderVideoNeverWritesOverItsSceneFile) {
  const std::filesystem::path scene = dir_ / "scene.mp4";
  std::ofstream(scene) << kScene;
  try {
    coinroll::renderVideo(coinroll::Scene::fromFile(scene), scene);
    ADD_FAILURE() << "rendered over the scene file";
  } catch (const coinroll::ArgumentError& e) {
    EXPECT_EQ(e.argument(), "output");
    EXPECT_EQ(std::string(e.what()),
              "output " + scene.string() + ": that is the input " + scene.string() + "; choose another output name");
  }
  EXPECT_EQ(contentsOf(scene), kScene);
}

TEST_F(ApiOutputs, RenderVideoNeverWritesAPngSequenceOverItsSceneFile) {
  const std::filesystem::path scene = dir_ / "frame_00001.png";
  std::ofstream(scene) << kScene;
  const std::string message =
      refusal([&] { coinroll::renderVideo(coinroll::Scene::fromFile(scene), dir_ / "frame_%05d.png"); });
  EXPECT_NE(message.find("one of its frames would be the input " + scene.string()), std::string::npos) << message;
  EXPECT_EQ(contentsOf(scene), kScene);
  EXPECT_EQ(scratch_->fileCount(), 1);
}

// A process using the library that ends unseen leaves nothing beside the output (docs/outputs.md
// "Temporaries have no name while they are written"): SIGKILL, and SIGTERM, for which the library
// installs no handler (multiprocessing's Pool.terminate sends it to workers that forked from the
// caller, as this child does). Each left `.x.mp4.partial-PID-0`.
TEST_F(ApiOutputs, ARenderKilledMidWriteLeavesNoFile) {
  const coinroll::Scene scene = coinroll::Scene::fromJson(kScene, {"duration=60"});
  for (const int signal : {SIGKILL, SIGTERM}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      try {
        coinroll::renderVideo(scene, dir_ / "x.mp4");
      } catch (...) {
      }
      ::_exit(0);
    }
    for (int i = 0; i < 1000 && coinroll::testing::temporariesBeingWritten(child, dir_) == 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const bool writing = coinroll::testing::temporariesBeingWritten(child, dir_) > 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // well into the video
    ::kill(child, signal);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(writing) << "the render never started writing";
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << "ended before the signal " << signal;
    EXPECT_EQ(scratch_->fileCount(), 0) << "signal " << signal;
  }
}

TEST(ApiRows, SimulateRefusesMoreRowsThanTheCommandsLimitBeforeAnyWork) {
  const coinroll::Scene scene = coinroll::Scene::fromJson(kScene);
  // Set from the start, so that a run which is not refused stops at its first sample (Cancelled)
  // instead of filling the machine's memory.
  const std::atomic<bool> cancel{true};
  const auto start = std::chrono::steady_clock::now();
  try {
    coinroll::simulate(scene, 1e-10, &cancel);
    ADD_FAILURE() << "5e9 rows were accepted";
  } catch (const coinroll::ArgumentError& e) {
    EXPECT_EQ(std::string(e.what()),
              "sampleDt 1e-10: duration 0.5 s gives 5000000006 rows, more than the limit 100000000; raise sampleDt");
    EXPECT_EQ(e.naming("sample_dt"),
              "sample_dt 1e-10: duration 0.5 s gives 5000000006 rows, more than the limit 100000000; raise sample_dt");
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

// What a C++ caller types: the header's parameter names and the scene's keys.
TEST(ApiMessages, NameTheCallersArgumentsAndNoCommandLineFlag) {
  const coinroll::Scene scene = coinroll::Scene::fromJson(kScene);
  EXPECT_EQ(refusal([&] { coinroll::simulate(scene, -1); }), "sampleDt: must be a finite number > 0 s, got -1");
  EXPECT_EQ(refusal([&] { coinroll::renderStill(scene, 7); }),
            "time: must be within the scene's duration, 0 to 0.5 s, got 7");
  EXPECT_EQ(refusal([&] { coinroll::renderVideo(scene, ""); }),
            "output: the file name is empty; give the file to write, e.g. \"clip.mp4\" (or \"frame_%05d.png\" for a "
            "PNG sequence)");
  const std::string transparent = refusal([] {
    coinroll::renderVideo(coinroll::Scene::fromJson(kScene, {"render.background=\"transparent\""}), "clip.mp4");
  });
  EXPECT_EQ(transparent.rfind("render.background: \"transparent\" needs an output with alpha", 0), 0) << transparent;
  const std::string audio =
      refusal([] { coinroll::renderVideo(coinroll::Scene::fromJson(kScene, {"render.audio={}"}), "clip.webm"); });
  EXPECT_NE(audio.find("leave the sound out with \"audio\": false in the scene's render block"), std::string::npos)
      << audio;
  const std::string frames =
      refusal([] { coinroll::renderVideo(coinroll::Scene::fromJson(kScene, {"duration=1e9"}), "clip.mp4"); });
  EXPECT_NE(frames.find("shorten the duration, raise time_scale or lower fps"), std::string::npos) << frames;
  for (const std::string& message : {transparent, audio, frames}) {
    EXPECT_EQ(message.find("--"), std::string::npos) << message;
    EXPECT_EQ(message.find("VideoOptions"), std::string::npos) << message;
  }
}

}  // namespace
