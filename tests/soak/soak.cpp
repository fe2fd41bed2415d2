// Soak: many short clips (MP4 with sound, PNG sequences) and stills rendered in one process, as a
// long-lived user of the library would. Prints, after each round, the heap in use, resident memory,
// threads and open file descriptors, and fails when the heap, the threads or the descriptors keep
// growing once the process has warmed up: a leaked GL context, encoder, frame, thread or file shows
// up here long before a user's batch job runs out.
//
// Resident memory is printed but not judged. It also counts glibc's cache of freed thread stacks
// (up to 40 MiB) and its per-thread arenas, and llvmpipe starts one rasteriser thread per core for
// every context, so on a many-core runner it climbs for the first rounds and then wobbles by tens
// of MiB with no leak at all (CI saw 498-581 MiB alternating). The bytes malloc has handed out and
// not taken back are what a leak adds to, whatever the core count.
//
//   soak [rounds] [scratch dir]      (defaults: 20 rounds, a fresh directory under /tmp)

#include <fmt/format.h>
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

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

double heapInUseMiB() {
  const struct mallinfo2 heap = mallinfo2();  // summed over all arenas
  return static_cast<double>(heap.uordblks + heap.hblkhd) / (1 << 20);
}

long threadCount() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.starts_with("Threads:")) return std::stol(line.substr(8));
  }
  return -1;
}

long openDescriptors() { return std::distance(fs::directory_iterator("/proc/self/fd"), fs::directory_iterator{}); }

SceneConfig smallScene() {
  nlohmann::json document = coinroll::scene::builtInDefaultScene();
  for (const char* assignment :
       {"duration=1", "render.width=160", "render.height=120", "render.fps=24", "render.audio.timbre=clicks"}) {
    coinroll::scene::applyOverride(document, assignment);
  }
  return coinroll::scene::parseScene(document, "soak");
}

void renderClip(const SceneConfig& scene, const fs::path& output) {
  coinroll::video::VideoOptions encoding = scene.render.mp4Options();
  encoding.audio = output.extension() == ".mp4";
  coinroll::video::AsyncSink sink(coinroll::video::makeSinkForPath(output, encoding));
  coinroll::pipeline::renderVideo(scene, sink);
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::max(4, std::atoi(argv[1])) : 20;
  const fs::path scratch =
      argc > 2 ? fs::path(argv[2]) : fs::temp_directory_path() / fmt::format("coinroll_soak_{}", getpid());
  fs::create_directories(scratch);
  const SceneConfig scene = smallScene();

  // Warm-up rounds load llvmpipe, compile shaders and fill the allocator's pools; growth is
  // measured from the end of the warm-up to the end of the run.
  const int warmup = std::max(2, rounds / 5);
  std::vector<double> heap;
  std::vector<long> threads, descriptors;
  fmt::print("{:>5} {:>12} {:>10} {:>7} {:>5}\n", "round", "heap MiB", "RSS MiB", "threads", "fds");
  for (int round = 0; round < rounds; ++round) {
    renderClip(scene, scratch / "clip.mp4");
    renderClip(scene, scratch / "frames_%04d.png");
    coinroll::pipeline::renderStill(scene, {.time = 0.5, .output = scratch / "still.png"});
    coinroll::pipeline::renderStill(scene,
                                    {.time = 0.9, .ghosts = 4, .ghostsFrom = 0.1, .output = scratch / "strobe.png"});
    heap.push_back(heapInUseMiB());
    threads.push_back(threadCount());
    descriptors.push_back(openDescriptors());
    fmt::print("{:>5} {:>12.4f} {:>10.1f} {:>7} {:>5}\n", round + 1, heap.back(), residentMiB(), threads.back(),
               descriptors.back());
  }
  fs::remove_all(scratch);

  const int measuredRounds = rounds - warmup;
  const double heapGrowthPerRound = (heap.back() - heap[warmup - 1]) / measuredRounds;
  const long threadGrowth = threads.back() - threads[warmup - 1];
  const long descriptorGrowth = descriptors.back() - descriptors[warmup - 1];
  fmt::print("after warm-up ({} rounds, 2 clips and 2 stills each): heap {:+.1f} KiB/round, threads {:+d}, fds {:+d}\n",
             measuredRounds, heapGrowthPerRound * 1024, threadGrowth, descriptorGrowth);
  // Mesa itself keeps about 0.3-7 KiB per context created and destroyed (measured with a bare
  // OSMesa loop), so four renders a round may add a few KiB; one leaked frame (160x120 RGBA) is
  // 75 KiB, a leaked context or encoder megabytes. Threads and descriptors never legitimately stay.
  const double heapBoundPerRound = 32.0 / 1024;
  const bool leaks = heapGrowthPerRound > heapBoundPerRound || threadGrowth > 0 || descriptorGrowth > 0;
  if (leaks) fmt::print(stderr, "soak: resources grow round after round\n");
  return leaks ? 1 : 0;
}
