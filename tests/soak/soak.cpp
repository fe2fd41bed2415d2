// Soak: many short clips (MP4 with sound, PNG sequences) and stills rendered in one process, as a
// long-lived user of the library would. Prints resident memory and open file descriptors after
// each round and fails when either keeps growing once the process has warmed up: a leaked GL
// context, encoder, thread or file shows up here long before a user's batch job runs out.
//
//   soak [rounds] [scratch dir]      (defaults: 20 rounds, a fresh directory under /tmp)

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "integrate/solver_config.h"
#include "pipeline/still.h"
#include "pipeline/video_frames.h"
#include "scene/scene_loader.h"
#include "video/async_sink.h"
#include "video/make_sink.h"

namespace {

namespace fs = std::filesystem;
using coinroll::scene::SceneConfig;

double residentMiB() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1 << 20);
}

long openDescriptors() {
  return std::distance(fs::directory_iterator("/proc/self/fd"), fs::directory_iterator{});
}

SceneConfig smallScene() {
  nlohmann::json document = coinroll::scene::builtInDefaultScene();
  for (const char* assignment : {"duration=1", "render.width=160", "render.height=120", "render.fps=24",
                                 "render.audio.timbre=clicks"}) {
    coinroll::scene::applyOverride(document, assignment);
  }
  return coinroll::scene::parseScene(document, "soak", {.solverMethods = coinroll::integrate::methodNames()});
}

void renderClip(const SceneConfig& scene, const fs::path& output) {
  coinroll::video::Mp4Options encoding = scene.render.mp4Options();
  encoding.audio = output.extension() == ".mp4";
  coinroll::video::AsyncSink sink(coinroll::video::makeSinkForPath(output, encoding));
  coinroll::pipeline::renderVideo(scene, sink);
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::max(4, std::atoi(argv[1])) : 20;
  const fs::path scratch = argc > 2 ? fs::path(argv[2]) : fs::temp_directory_path() / fmt::format("coinroll_soak_{}", getpid());
  fs::create_directories(scratch);
  const SceneConfig scene = smallScene();

  // Warm-up rounds load llvmpipe, compile shaders and fill the allocator's pools; growth is
  // measured from the end of the warm-up to the end of the run.
  const int warmup = std::max(2, rounds / 5);
  std::vector<double> resident;
  std::vector<long> descriptors;
  fmt::print("{:>5} {:>10} {:>5}\n", "round", "RSS MiB", "fds");
  for (int round = 0; round < rounds; ++round) {
    renderClip(scene, scratch / "clip.mp4");
    renderClip(scene, scratch / "frames_%04d.png");
    coinroll::pipeline::renderStill(scene, {.time = 0.5, .output = scratch / "still.png"});
    coinroll::pipeline::renderStill(scene, {.time = 0.9, .ghosts = 4, .ghostsFrom = 0.1, .output = scratch / "strobe.png"});
    resident.push_back(residentMiB());
    descriptors.push_back(openDescriptors());
    fmt::print("{:>5} {:>10.1f} {:>5}\n", round + 1, resident.back(), descriptors.back());
  }
  fs::remove_all(scratch);

  const double residentGrowth = resident.back() - resident[warmup - 1];
  const long descriptorGrowth = descriptors.back() - descriptors[warmup - 1];
  const int measuredRounds = rounds - warmup;
  fmt::print("after warm-up ({} rounds, {} clips and {} stills each): RSS {:+.2f} MiB ({:+.3f} MiB/round), fds {:+d}\n",
             measuredRounds, 2, 2, residentGrowth, residentGrowth / measuredRounds, descriptorGrowth);
  // A descriptor never legitimately stays open; memory may wobble by allocator pages but not climb
  // by a frame's worth (160x120 RGBA is 0.07 MiB) every round.
  const bool leaks = descriptorGrowth > 0 || residentGrowth / measuredRounds > 0.25;
  if (leaks) fmt::print(stderr, "soak: resources grow round after round\n");
  return leaks ? 1 : 0;
}
