// What the page's run costs beyond the run itself (docs/web.md "Speed"): the WebAssembly core's
// visualRun is simulateScene on the renderer's trace grid, plus the visual track's overlay per row
// (VisualTrackBuilder::add) and its cameras and clip (finish). Each part timed alone and together,
// on the built-in default scene and on the Euler's disk's first 20 s, natively (the module's code is
// the same C++; its ratios are what a page's slider waits for).
#include <benchmark/benchmark.h>

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pipeline/motion_survey.h"
#include "pipeline/playback_clock.h"
#include "pipeline/scene_run.h"
#include "pipeline/visual_track.h"
#include "scene/scene_loader.h"

namespace {

using namespace coinroll;

enum class Part { Run, RunAndOverlay, Track, Clip };

scene::SceneConfig sceneFor(int which) {
  if (which == 0) return scene::parseScene(scene::builtInDefaultScene(), "built-in default scene");
  const std::vector<std::string> first20s = {"duration=20"};
  return scene::loadScene(std::string(COINROLL_SOURCE_DIR) + "/examples/euler_disk.json", first20s);
}

void visualRun(benchmark::State& state, Part part) {
  const scene::SceneConfig scene = sceneFor(static_cast<int>(state.range(0)));
  pipeline::SceneRunRequest request;
  request.sampleDt = pipeline::traceInterval(scene.duration);
  request.sampleDtName = "sampleDt";
  for (auto _ : state) {
    if (part == Part::Clip) {
      benchmark::DoNotOptimize(pipeline::planClip(scene));
      continue;
    }
    std::optional<pipeline::VisualTrackBuilder> builder;
    pipeline::SampleObserver sample;
    if (part != Part::Run) sample = [&](double t, const pipeline::RunSample& s, bool row) { builder->add(t, s, row); };
    pipeline::simulateScene(scene, request,
                            {.begin = [&](const pipeline::RunStart& start) { builder.emplace(scene, *start.model); },
                             .row = [](std::span<const double>) {},
                             .sample = sample});
    if (part == Part::Track) benchmark::DoNotOptimize(std::move(*builder).finish(nullptr));
  }
}

BENCHMARK_CAPTURE(visualRun, run_on_trace_grid, Part::Run)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(visualRun, run_and_overlay, Part::RunAndOverlay)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(visualRun, whole_track, Part::Track)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(visualRun, clip_plan_alone, Part::Clip)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
