// End to end `coinroll render` (10 s of the default scene at 30 fps, 1280x720, x264 veryfast crf
// 18) against its two stages alone, measured in the same run: render only (frames discarded),
// encode only (the same frames, kept in memory, into the same MP4 sink), and the pipeline (render
// on this thread, encode on the AsyncSink's), with the anti-aliasing `auto` chooses and with 4x
// MSAA (the default before `auto`, docs/quality.md "Performance"), paired in one run. Also the
// ffmpeg tool encoding its testsrc2 pattern with the same settings, so the figure compares across
// machines; the default scene's whole 12 s clip against real time; and the peak resident memory of
// a 10 s and a 60 s render (child processes, 640x360). Wall and CPU seconds (this process's
// threads, or the child's). Ratios matter; absolute seconds are noise.
// Run: build/bench/pipeline_bench [--no-memory]   (LP_NUM_THREADS sets llvmpipe's threads)
#include <fmt/format.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/video_frames.h"
#include "scene/scene_loader.h"
#include "video/async_sink.h"
#include "video/encoder_sink.h"

namespace {

using namespace coinroll;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// CPU seconds (user + system) of this process's threads, or of its waited-for children.
double cpuSeconds(int who) {
  rusage usage{};
  getrusage(who, &usage);
  const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * t.tv_usec; };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// `antialiasing`: empty for the scene's default (auto), else the method named.
scene::SceneConfig benchScene(const std::string& cameraMode, int encoderThreads, const std::string& antialiasing) {
  nlohmann::json doc = scene::builtInDefaultScene();
  doc["duration"] = 10.0;
  doc["render"]["time_scale"] = 1.0;
  doc["render"]["width"] = 1280;
  doc["render"]["height"] = 720;
  if (!antialiasing.empty()) doc["render"]["antialiasing"] = antialiasing;
  doc["render"]["camera"] = {{"mode", cameraMode}, {"orbit_period", 10.0}};
  doc["render"]["video"] = {{"preset", "veryfast"}, {"crf", 18}, {"threads", encoderThreads}};
  return scene::parseScene(doc, "pipeline_bench");
}

video::VideoOptions encoding(const scene::SceneConfig& s) {
  return s.render.mp4Options();
}  // no render.audio: no track

class DiscardSink final : public video::FrameSink {
 public:
  void push(const image::Image&) override {}
  void finish() override {}
};

class KeepSink final : public video::FrameSink {
 public:
  void push(const image::Image& frame) override { frames.push_back(frame); }
  void finish() override {}
  std::vector<image::Image> frames;
};

struct Timings {
  double renderOnly = 0, encodeOnly = 0, pipeline = 0, pipelineCpu = 0;
  long frames = 0;
};

Timings measure(const scene::SceneConfig& s, const std::filesystem::path& out) {
  Timings t;
  {
    DiscardSink discard;
    const auto start = Clock::now();
    t.frames = pipeline::renderVideo(s, discard).frames;
    t.renderOnly = secondsSince(start);
  }
  {
    KeepSink keep;
    pipeline::renderVideo(s, keep);
    video::EncoderSink sink(out, encoding(s));
    const auto start = Clock::now();
    for (const image::Image& frame : keep.frames) sink.push(frame);
    sink.finish();
    t.encodeOnly = secondsSince(start);
  }
  {
    const auto start = Clock::now();
    const double cpuStart = cpuSeconds(RUSAGE_SELF);
    {
      video::AsyncSink sink(std::make_unique<video::EncoderSink>(out, encoding(s)));
      pipeline::renderVideo(s, sink);
    }  // the encoder thread joined: its CPU time counted
    t.pipeline = secondsSince(start);
    t.pipelineCpu = cpuSeconds(RUSAGE_SELF) - cpuStart;
  }
  return t;
}

struct WallAndCpu {
  double wall = NAN, cpu = NAN;
};

WallAndCpu ffmpegTestPattern() {
  const auto start = Clock::now();
  const double cpuStart = cpuSeconds(RUSAGE_CHILDREN);
  const int status = std::system(
      "ffmpeg -hide_banner -loglevel error -nostdin -f lavfi -i testsrc2=size=1280x720:rate=30 -frames:v 300 "
      "-c:v libx264 -preset veryfast -crf 18 -f null -");
  if (status != 0) return {};
  return {secondsSince(start), cpuSeconds(RUSAGE_CHILDREN) - cpuStart};
}

// The built-in default scene's whole clip (12 s of video), encoded as `render` encodes it.
WallAndCpu defaultClip(const std::string& antialiasing, const std::filesystem::path& out) {
  nlohmann::json doc = scene::builtInDefaultScene();
  if (!antialiasing.empty()) doc["render"]["antialiasing"] = antialiasing;
  const scene::SceneConfig s = scene::parseScene(doc, "default");
  const auto start = Clock::now();
  const double cpuStart = cpuSeconds(RUSAGE_SELF);
  {
    video::AsyncSink sink(std::make_unique<video::EncoderSink>(out, encoding(s)));
    pipeline::renderVideo(s, sink);
  }
  return {secondsSince(start), cpuSeconds(RUSAGE_SELF) - cpuStart};
}

// Peak resident set of `coinroll render` for a clip of `seconds`, in MiB.
double peakMemoryMiB(const std::string& binary, double seconds, const std::filesystem::path& out) {
  const pid_t child = fork();
  if (child == 0) {
    const std::string duration = fmt::format("duration={}", seconds);
    execl(binary.c_str(), binary.c_str(), "render", "-q", "-o", out.c_str(), "--set", duration.c_str(), "--set",
          "render.time_scale=1", "--set", "render.width=640", "--set", "render.height=360",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(child, &status, 0, &usage);
  return usage.ru_maxrss / 1024.0;
}

}  // namespace

int main(int argc, char** argv) {
  const bool memory = !(argc > 1 && std::string(argv[1]) == "--no-memory");
  const char* lpThreads = std::getenv("LP_NUM_THREADS");
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "coinroll_pipeline_bench.mp4";
  fmt::print("pipeline_bench: 10 s at 30 fps, 1280x720, x264 veryfast crf 18; llvmpipe threads: {}\n\n",
             lpThreads ? lpThreads : "default");
  const WallAndCpu reference = ffmpegTestPattern();
  fmt::print(
      "| camera, anti-aliasing, x264 threads | render s | encode s | both s | both CPU s | both / slower | "
      "real time x | both / ffmpeg, wall | both / ffmpeg, CPU |\n|---|---|---|---|---|---|---|---|---|\n");
  struct Case {
    std::string camera, antialiasing;
    int threads;
  };
  for (const Case& c : {Case{"fixed", "msaa", 1}, Case{"fixed", "", 1}, Case{"fixed", "msaa", 2}, Case{"fixed", "", 2},
                        Case{"orbit", "", 1}}) {
    const Timings t = measure(benchScene(c.camera, c.threads, c.antialiasing), out);
    const double slower = std::max(t.renderOnly, t.encodeOnly);
    fmt::print("| {}, {}, {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} |\n", c.camera,
               c.antialiasing.empty() ? "auto" : "msaa 4x", c.threads, t.renderOnly, t.encodeOnly, t.pipeline,
               t.pipelineCpu, t.pipeline / slower, 10.0 / t.pipeline, t.pipeline / reference.wall,
               t.pipelineCpu / reference.cpu);
  }
  fmt::print(
      "\nffmpeg -f lavfi -i testsrc2=size=1280x720:rate=30 -frames:v 300 -c:v libx264 -preset veryfast -crf 18 "
      "-f null -: wall {:.2f} s, CPU {:.2f} s\n",
      reference.wall, reference.cpu);
  fmt::print("\n| default scene, 12 s clip | wall s | CPU s | faster than real time x |\n|---|---|---|---|\n");
  for (const std::string antialiasing : {"msaa", ""}) {
    const WallAndCpu clip = defaultClip(antialiasing, out);
    fmt::print("| {} | {:.2f} | {:.2f} | {:.2f} |\n", antialiasing.empty() ? "auto" : "msaa 4x", clip.wall, clip.cpu,
               12.0 / clip.wall);
  }
  std::filesystem::remove(out);
  if (memory) {
    const std::string binary = std::string(COINROLL_BINARY_DIR) + "/coinroll";
    const double short10 = peakMemoryMiB(binary, 10, out), long60 = peakMemoryMiB(binary, 60, out);
    fmt::print("peak resident memory, 640x360: 10 s clip {:.1f} MiB, 60 s clip {:.1f} MiB (ratio {:.3f})\n", short10,
               long60, long60 / short10);
    std::filesystem::remove(out);
  }
  return 0;
}
