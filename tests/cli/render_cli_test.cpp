// `coinroll render` and `coinroll still` from outside: the MP4 read back with libavformat,
// byte-identical reruns, PNG determinism across llvmpipe thread counts, clean failures and
// Ctrl-C leaving nothing under the output name.

#include <gtest/gtest.h>

#include "cli/run_command.h"
#include "scratch_dir.h"
#include "temporaries.h"
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include "image/image.h"
#include "video_probe.h"

// GCC says __SANITIZE_ADDRESS__, clang (the sanitizer stage's compiler) __has_feature.
#if defined(__has_feature)
#define COINROLL_CLANG_ASAN __has_feature(address_sanitizer)
#else
#define COINROLL_CLANG_ASAN 0
#endif

namespace {

namespace fs = std::filesystem;

using coinroll::testing::RunResult;

RunResult run(const std::string& arguments, const std::string& environment = "") {
  return coinroll::testing::runCoinroll(arguments, environment);
}

std::string bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

class RenderCliTest : public coinroll::testing::ScratchDirTest {
 protected:
  void SetUp() override {
    ScratchDirTest::SetUp();
    scene_ = dir_ / "scene.json";
    std::ofstream(scene_) << R"({"name": "toy", "coin": {"radius": 0.0375, "mass": 0.4},
      "initial": {"theta": 20, "omega_Y": 3.0, "omega_Z": 14.0}, "duration": 1.0,
      "render": {"width": 160, "height": 90, "fps": 30, "msaa": 4}})";
  }
  // Everything in the directory but the scene: what a command left behind.
  std::vector<std::string> leftovers() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      if (entry.path() != scene_) names.push_back(entry.path().filename().string());
    }
    return names;
  }
  fs::path scene_;
};

TEST_F(RenderCliTest, Mp4ReadsBackWithTheAskedFramesSizeAndTags) {
  const fs::path out = dir_ / "clip.mp4";
  const RunResult r = run("render " + scene_.string() + " -o " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const coinroll::video::VideoInfo info = coinroll::video::readVideoInfo(out);
  EXPECT_EQ(info.codecName, "h264");
  EXPECT_EQ(info.pixelFormat, "yuv420p");
  EXPECT_EQ(info.width, 160);
  EXPECT_EQ(info.height, 90);
  EXPECT_EQ(info.frameCount, 31);  // t = 0, 1/30, ..., 1 s
  EXPECT_NEAR(info.durationSeconds, 31.0 / 30, 1e-9);
  EXPECT_EQ(info.colorSpace, "bt709");
  EXPECT_TRUE(info.moovBeforeMdat);

  const fs::path again = dir_ / "again.mp4";
  ASSERT_EQ(run("render " + scene_.string() + " -o " + again.string()).exitCode, 0);
  EXPECT_EQ(bytesOf(out), bytesOf(again)) << "a rerun gave different MP4 bytes";
}

TEST_F(RenderCliTest, DefaultOutputIsNamedAfterTheScene) {
  const RunResult r = run("render " + scene_.string() + " -q --set duration=0.1", "cd " + dir_.string() + " &&");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "toy.mp4"));
  EXPECT_TRUE(r.output.empty()) << "--quiet printed: " << r.output;
}

TEST_F(RenderCliTest, PngSequenceHasOneFilePerFrame) {
  const RunResult r =
      run("render " + scene_.string() + " -o " + (dir_ / "f_%03d.png").string() + " --set duration=0.2");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (int k = 0; k <= 6; ++k) EXPECT_TRUE(fs::exists(dir_ / ("f_00" + std::to_string(k) + ".png"))) << k;
  EXPECT_FALSE(fs::exists(dir_ / "f_007.png"));
}

TEST_F(RenderCliTest, BadRequestsExitTwoAndLeaveNothing) {
  struct Case {
    std::string arguments, mustMention;
    int exitCode;  // 2: a bad scene or command line; 1: a failure the request could not foresee
  };
  const Case cases[] = {
      {"-o " + (dir_ / "bad.mp4").string() + " --set render.width=-5", "render.width", 2},
      {"-o " + (dir_ / "bad.mp4").string() + " --set render.msaa=3", "render.msaa", 2},
      {"-o " + (dir_ / "bad.mp4").string() + " --set render.video.preset=\\\"warp\\\"", "preset", 2},
      {"-o " + (dir_ / "bad.avi").string(), ".mp4", 2},
      {"-o " + (dir_ / "missing_dir/bad.mp4").string(), "missing_dir", 1},
      {"-o " + (dir_ / "bad.mp4").string() + " --size 4k", "--size", 2},
      {"-o " + (dir_ / "bad.mp4").string() + " --from 0.8 --to 0.2", "--from", 2},
      {"-o " + (dir_ / "bad.mp4").string() + " --from 5", "--from", 2},
      {"-o " + (dir_ / "bad.mp4").string() + " --from -1", "--from", 2},
      {"-o " + (dir_ / "bad.mp4").string() + " --from 0.51 --to 0.52", "no frame", 2},
      {"-o " + (dir_ / "bad.mp4").string() + " --set render.background=\\\"transparent\\\"", "render.background", 2},
      {"-o " + (dir_ / "bad.GIF").string() + " --set render.background=\\\"transparent\\\"", "render.background", 2},
      {"-o " + (dir_ / "bad.mov").string() + " --set render.background=\\\"clear\\\"", "render.background", 2},
      {"-o " + (dir_ / "bad.gif").string() + " --set render.audio=true", "render.audio", 2},
      {"-o " + (dir_ / "bad.gif").string() + " --set render.fps=60", "render.fps", 2},
  };
  for (const Case& c : cases) {
    const RunResult r = run("render " + scene_.string() + " " + c.arguments);
    EXPECT_EQ(r.exitCode, c.exitCode) << c.arguments << ": " << r.output;
    EXPECT_NE(r.output.find(c.mustMention), std::string::npos) << c.arguments << ": " << r.output;
    EXPECT_TRUE(leftovers().empty()) << c.arguments << " left " << leftovers().front();
  }
  const RunResult still = run("still " + scene_.string() + " --time 7 -o " + (dir_ / "late.png").string());
  EXPECT_EQ(still.exitCode, 2);
  EXPECT_NE(still.output.find("--time"), std::string::npos) << still.output;
  EXPECT_TRUE(leftovers().empty());
}

// A scene with sound cannot make a GIF; the refusal names the way out, and that way works: --set
// render.audio=null removes the key, so the scene takes its default (no sound track).
TEST_F(RenderCliTest, TheAudioRefusalsWayOutMakesTheGif) {
  const fs::path gif = dir_ / "quiet.gif";
  const std::string render =
      "render " + scene_.string() + " -q --to 0.2 -o " + gif.string() + " --set render.audio=true";
  const RunResult refused = run(render);
  ASSERT_EQ(refused.exitCode, 2) << refused.output;
  const std::string fix = "--set render.audio=null";
  ASSERT_NE(refused.output.find(fix), std::string::npos) << refused.output;
  const RunResult made = run(render + " " + fix);
  EXPECT_EQ(made.exitCode, 0) << made.output;
  EXPECT_TRUE(fs::is_regular_file(gif));
}

TEST_F(RenderCliTest, EachExtensionGivesItsKindInAnyCase) {
  struct Kind {
    const char* name;
    const char* codec;
  };
  for (const Kind& kind : {Kind{"clip.GIF", "gif"}, Kind{"clip.webm", "vp9"}, Kind{"clip.Mov", "prores"}}) {
    const fs::path out = dir_ / kind.name;
    const RunResult r = run("render " + scene_.string() + " -q -o " + out.string());
    ASSERT_EQ(r.exitCode, 0) << kind.name << ": " << r.output;
    const coinroll::video::VideoInfo info = coinroll::video::readVideoInfo(out);
    EXPECT_EQ(info.codecName, kind.codec) << kind.name;
    EXPECT_EQ(info.frameCount, 31) << kind.name;
    EXPECT_EQ(info.width, 160) << kind.name;
  }
}

TEST_F(RenderCliTest, SizeSetsTheRenderWidthAndHeight) {
  const fs::path out = dir_ / "small.mp4";
  ASSERT_EQ(run("render " + scene_.string() + " -q --size 480p --set duration=0.1 -o " + out.string()).exitCode, 0);
  const coinroll::video::VideoInfo info = coinroll::video::readVideoInfo(out);
  EXPECT_EQ(info.width, 854);
  EXPECT_EQ(info.height, 480);
}

TEST_F(RenderCliTest, AWindowWritesTheFullRendersFramesForItsSimulatedTimes) {
  ASSERT_EQ(run("render " + scene_.string() + " -q -o " + (dir_ / "all_%02d.png").string()).exitCode, 0);
  const RunResult r =
      run("render " + scene_.string() + " -q --from 0.5 --to 1.0 -o " + (dir_ / "win_%02d.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  // 0.5 s is frame 15 of 0 .. 30; the window holds 15 .. 30, renumbered from 0.
  for (int k = 0; k <= 15; ++k) {
    const auto name = [](const char* prefix, int n) {
      return prefix + std::string(n < 10 ? "0" : "") + std::to_string(n) + ".png";
    };
    const std::string window = name("win_", k), whole = name("all_", k + 15);
    ASSERT_TRUE(fs::exists(dir_ / window)) << window;
    EXPECT_EQ(bytesOf(dir_ / window), bytesOf(dir_ / whole)) << window << " is not " << whole;
  }
  EXPECT_FALSE(fs::exists(dir_ / "win_16.png"));
  const fs::path clip = dir_ / "window.mp4";
  ASSERT_EQ(run("render " + scene_.string() + " -q --from 0.5 --to 1.0 -o " + clip.string()).exitCode, 0);
  EXPECT_EQ(coinroll::video::readVideoInfo(clip).frameCount, 16);
}

TEST_F(RenderCliTest, ATransparentBackgroundReachesThePngsAlpha) {
  const fs::path opaque = dir_ / "opaque.png", clear = dir_ / "clear.png";
  // No overlay: at 160x90 its translucent panel covers a third of the picture.
  const std::string still = "still " + scene_.string() + " --time 0.5 --set render.hud=false -o ";
  ASSERT_EQ(run(still + opaque.string()).exitCode, 0);
  const RunResult r = run(still + clear.string() + " --set render.background=\\\"transparent\\\"");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const coinroll::image::Image a = coinroll::image::readPng(opaque), b = coinroll::image::readPng(clear);
  long transparent = 0, opaquePixels = 0;
  for (std::size_t i = 3; i < b.rgba.size(); i += 4) {
    EXPECT_EQ(a.rgba[i], 255);
    transparent += b.rgba[i] == 0 ? 1 : 0;
    opaquePixels += b.rgba[i] == 255 ? 1 : 0;
  }
  const long pixels = static_cast<long>(b.rgba.size() / 4);
  EXPECT_GT(transparent, pixels / 2) << "the sky and the floor should be gone";
  EXPECT_GT(opaquePixels, 0) << "the coin should be there";
  EXPECT_EQ(b.pixel(b.width - 1, b.height - 1)[3], 0);  // a corner: nothing at all
}

TEST_F(RenderCliTest, ProvenanceNamesTheReleaseAndSceneUnlessTurnedOff) {
  const fs::path tagged = dir_ / "tagged.png", again = dir_ / "again.png", plain = dir_ / "plain.png";
  ASSERT_EQ(run("still " + scene_.string() + " --time 0.5 -o " + tagged.string()).exitCode, 0);
  ASSERT_EQ(run("still " + scene_.string() + " --time 0.5 -o " + again.string()).exitCode, 0);
  ASSERT_EQ(
      run("still " + scene_.string() + " --time 0.5 -o " + plain.string() + " --set render.provenance=false").exitCode,
      0);
  const std::string bytes = bytesOf(tagged);
  EXPECT_NE(bytes.find(std::string("tEXtSoftware\0coinroll ", 22)), std::string::npos);
  EXPECT_NE(bytes.find("coinroll-scene-digest"), std::string::npos);
  EXPECT_EQ(bytes, bytesOf(again)) << "the same release and scene must give the same bytes";
  EXPECT_EQ(bytesOf(plain).find("tEXt"), std::string::npos);
  // Another scene, another digest.
  const fs::path other = dir_ / "other.png";
  ASSERT_EQ(run("still " + scene_.string() + " --time 0.5 -o " + other.string() + " --set initial.theta=21").exitCode,
            0);
  const auto digestOf = [](const std::string& png) { return png.substr(png.find("fnv1a64:"), 24); };
  EXPECT_NE(digestOf(bytes), digestOf(bytesOf(other)));

  const fs::path clip = dir_ / "tagged.mov";
  ASSERT_EQ(run("render " + scene_.string() + " -q -o " + clip.string()).exitCode, 0);  // the still's scene, unchanged
  const coinroll::video::VideoInfo info = coinroll::video::readVideoInfo(clip);
  EXPECT_EQ(info.tags.at("encoder").rfind("coinroll ", 0), 0u) << info.tags.at("encoder");
  EXPECT_EQ(info.tags.at("comment"), info.tags.at("encoder") + ", scene " + digestOf(bytes));
}

// The CSV's header is the contract's, so its provenance is a sidecar: the same digest a picture of
// the same scene carries, and how the run it describes was sampled and ended.
TEST_F(RenderCliTest, SimulatesProvenanceSidecarNamesTheSceneAsItsPicturesDo) {
  const fs::path png = dir_ / "still.png", csv = dir_ / "run.csv", json = dir_ / "run.json";
  ASSERT_EQ(run("still " + scene_.string() + " --time 0.5 -o " + png.string()).exitCode, 0);
  ASSERT_EQ(
      run("simulate " + scene_.string() + " --csv " + csv.string() + " --sample-dt 0.1 --provenance " + json.string())
          .exitCode,
      0);
  const std::string picture = bytesOf(png), sidecar = bytesOf(json);
  const std::string digest = picture.substr(picture.find("fnv1a64:"), 24);
  EXPECT_NE(sidecar.find("\"scene_digest\": \"" + digest + "\""), std::string::npos) << sidecar;
  EXPECT_NE(sidecar.find("\"program\": \"coinroll\""), std::string::npos) << sidecar;
  EXPECT_NE(sidecar.find("\"sample_dt\": 0.1"), std::string::npos) << sidecar;
  EXPECT_NE(sidecar.find("\"end\": \"duration\""), std::string::npos) << sidecar;
  const std::string rows = bytesOf(csv);
  const long lines = static_cast<long>(std::count(rows.begin(), rows.end(), '\n'));
  EXPECT_NE(sidecar.find("\"rows\": " + std::to_string(lines - 1)), std::string::npos) << sidecar;

  // A CSV that cannot be written leaves no sidecar either.
  const fs::path missing = dir_ / "no_such_dir" / "run.csv", orphan = dir_ / "orphan.json";
  EXPECT_EQ(
      run("simulate " + scene_.string() + " --csv " + missing.string() + " --provenance " + orphan.string()).exitCode,
      1);
  EXPECT_FALSE(fs::exists(orphan));
}

TEST_F(RenderCliTest, InterruptLeavesNoFileAndExitsOne) {
  const fs::path out = dir_ / "long.mp4";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const std::string binary = std::string(COINROLL_BINARY_DIR) + "/coinroll";
    std::freopen("/dev/null", "w", stderr);
    execl(binary.c_str(), binary.c_str(), "render", scene_.c_str(), "-o", out.c_str(), "--set", "duration=60", "--set",
          "render.width=320", "--set", "render.height=180", static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait until the encoder has started writing its temporary file (unnamed, io/temporary.h: seen
  // among the run's descriptors), then press Ctrl-C.
  for (int i = 0; i < 200 && coinroll::testing::temporariesBeingWritten(child, dir_) < 1; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const bool writing = coinroll::testing::temporariesBeingWritten(child, dir_) >= 1;
  if (!writing) kill(child, SIGKILL);  // not left running for ever
  ASSERT_TRUE(writing) << "the render never started writing";
  kill(child, SIGINT);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal instead of stopping cleanly";
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_TRUE(leftovers().empty()) << "left " << leftovers().front();
}

TEST_F(RenderCliTest, StillIsByteIdenticalAcrossRerunsAndLlvmpipeThreadCounts) {
  const fs::path a = dir_ / "a.png", b = dir_ / "b.png", c = dir_ / "c.png";
  ASSERT_EQ(run("still " + scene_.string() + " --time 0.5 -o " + a.string(), "LP_NUM_THREADS=2").exitCode, 0);
  ASSERT_EQ(run("still " + scene_.string() + " --time 0.5 -o " + b.string(), "LP_NUM_THREADS=1").exitCode, 0);
  ASSERT_EQ(run("still " + scene_.string() + " --time 0.5 -o " + c.string(), "LP_NUM_THREADS=4").exitCode, 0);
  EXPECT_EQ(bytesOf(a), bytesOf(b)) << "LP_NUM_THREADS=1 and 2 drew different pictures";
  EXPECT_EQ(bytesOf(a), bytesOf(c)) << "LP_NUM_THREADS=4 and 2 drew different pictures";
  const fs::path strobe = dir_ / "strobe.png";
  ASSERT_EQ(run("still " + scene_.string() + " --time 1 --strobe 8 -o " + strobe.string()).exitCode, 0);
  EXPECT_NE(bytesOf(strobe), bytesOf(a));
}

TEST_F(RenderCliTest, AFullDiskFailsEveryWriterWithoutLeavingAFile) {
  // A file-size limit of 512 bytes stands in for a full disk: with SIGXFSZ ignored, writes past
  // it fail with EFBIG, as they would with ENOSPC.
  const std::string fullDisk = "ulimit -f 1; trap '' XFSZ; ";
  const std::vector<std::string> commands = {
      "still " + scene_.string() + " --time 0.5 -o " + (dir_ / "still.png").string(),
      "render " + scene_.string() + " -q -o " + (dir_ / "clip.mp4").string(),
      "render " + scene_.string() + " -q -o " + (dir_ / "f_%03d.png").string(),
      "simulate " + scene_.string() + " --csv " + (dir_ / "run.csv").string(),
      "sweep " + scene_.string() + " --grid initial.theta=1:20:40 -q -o " + (dir_ / "sweep.csv").string()};
  for (const std::string& command : commands) {
    const coinroll::testing::RunResult r = coinroll::testing::runCoinroll(command, fullDisk);
    EXPECT_EQ(r.exitCode, 1) << command << ": " << r.output;
    EXPECT_NE(r.output.find("coinroll: error:"), std::string::npos) << r.output;
    EXPECT_TRUE(leftovers().empty()) << command << " left " << leftovers().front();
  }
}

}  // namespace

namespace {

// As a user's shell sets the limit, SIGXFSZ at its default: the signal used to kill coinroll and
// leave its temporary; now the write fails, naming the limit, and nothing is left.
TEST_F(RenderCliTest, AFileSizeLimitIsAWriteErrorEvenWithSigxfszAtItsDefault) {
  const std::string limit = "ulimit -f 1; ";
  for (const std::string& command : {"still " + scene_.string() + " --time 0.5 -o " + (dir_ / "still.png").string(),
                                     "render " + scene_.string() + " -q -o " + (dir_ / "clip.mp4").string(),
                                     "render " + scene_.string() + " -q -o " + (dir_ / "f_%03d.png").string(),
                                     "simulate " + scene_.string() + " --csv " + (dir_ / "run.csv").string()}) {
    const RunResult r = run(command, limit);
    EXPECT_EQ(r.exitCode, 1) << command << ": " << r.output;
    // (In bytes: "ulimit -f 1" is 512 bytes to dash, which popen runs, and 1024 to bash.)
    EXPECT_NE(r.output.find("File too large (the file-size limit, ulimit -f, is "), std::string::npos)
        << command << ": " << r.output;
    EXPECT_TRUE(leftovers().empty()) << command << " left " << leftovers().front();
  }
}

// OpenGL on llvmpipe does not check its allocations: under an address-space limit too small for
// the picture it segfaulted or hung. The need is checked first and the message names it; a
// 7680x4320 picture needs about 2 GiB, more than a 1.5 GB limit leaves beside the binary.
TEST_F(RenderCliTest, UnderAnAddressSpaceLimitTooSmallRenderingIsRefusedNamingIt) {
#if defined(__SANITIZE_ADDRESS__) || COINROLL_CLANG_ASAN
  GTEST_SKIP() << "AddressSanitizer cannot start under an address-space limit (it reserves terabytes of shadow)";
#endif
  const std::string limit = "ulimit -v 1500000; ";
  const std::string big = " --set render.width=7680 --set render.height=4320";
  for (const std::string& command :
       {"still " + scene_.string() + " --time 0.5 -o " + (dir_ / "still.png").string() + big,
        "render " + scene_.string() + " -q -o " + (dir_ / "clip.mp4").string() + big}) {
    const RunResult r = run(command, limit);
    EXPECT_EQ(r.exitCode, 1) << command << ": " << r.output;
    EXPECT_NE(r.output.find("not enough memory for drawing"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("7680x4320 pictures"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("(ulimit -v 1500000)"), std::string::npos) << r.output;
    EXPECT_TRUE(leftovers().empty()) << command << " left " << leftovers().front();
  }
}

}  // namespace
