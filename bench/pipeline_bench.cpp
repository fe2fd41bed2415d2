// End to end `coinroll render` (10 s of the default scene at 30 fps, 1280x720, 4x MSAA, x264
// veryfast) against its two stages alone, measured in the same run: render only (frames
// discarded), encode only (the same frames, kept in memory, into the same MP4 sink), and the
// pipeline (render on this thread, encode on the AsyncSink's). Also the ffmpeg tool encoding its
// testsrc2 pattern, so the figure compares across machines, and the peak resident memory of a
// 10 s and a 60 s render (child processes, 640x360). Ratios matter; absolute seconds are noise.
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

scene::SceneConfig benchScene(const std::string& cameraMode, int encoderThreads) {
  nlohmann::json doc = scene::builtInDefaultScene();
  doc["duration"] = 10.0;
  doc["render"]["time_scale"] = 1.0;
  doc["render"]["width"] = 1280;
  doc["render"]["height"] = 720;
  doc["render"]["msaa"] = 4;
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
  double renderOnly = 0, encodeOnly = 0, pipeline = 0;
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
    video::AsyncSink sink(std::make_unique<video::EncoderSink>(out, encoding(s)));
    const auto start = Clock::now();
    pipeline::renderVideo(s, sink);
    t.pipeline = secondsSince(start);
  }
  return t;
}

double ffmpegTestPatternSeconds() {
  const auto start = Clock::now();
  const int status = std::system(
      "ffmpeg -hide_banner -loglevel error -nostdin -f lavfi -i testsrc2=size=1280x720:rate=30 -frames:v 300 "
      "-c:v libx264 -preset veryfast -f null -");
  if (status != 0) return NAN;
  return secondsSince(start);
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
  fmt::print("pipeline_bench: 10 s at 30 fps, 1280x720, 4x MSAA, x264 veryfast crf 18; llvmpipe threads: {}\n\n",
             lpThreads ? lpThreads : "default");
  const double reference = ffmpegTestPatternSeconds();
  fmt::print("{:<28} {:>9} {:>9} {:>9} {:>14} {:>12} {:>14}\n", "camera, x264 threads", "render s", "encode s",
             "both s", "both / slower", "real time x", "both / ffmpeg");
  for (const std::string camera : {"fixed", "orbit"}) {
    for (int threads : {1, 2}) {
      const Timings t = measure(benchScene(camera, threads), out);
      const double slower = std::max(t.renderOnly, t.encodeOnly);
      fmt::print("{:<28} {:>9.2f} {:>9.2f} {:>9.2f} {:>14.2f} {:>12.2f} {:>14.2f}\n",
                 fmt::format("{}, {}", camera, threads), t.renderOnly, t.encodeOnly, t.pipeline, t.pipeline / slower,
                 10.0 / t.pipeline, t.pipeline / reference);
    }
  }
  fmt::print(
      "\nffmpeg -f lavfi -i testsrc2=size=1280x720:rate=30 -frames:v 300 -c:v libx264 -preset veryfast -f null -: "
      "{:.2f} s\n",
      reference);
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
