#include "pipeline/still.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/image.h"
#include "pipeline/motion_survey.h"
#include "pipeline/resources.h"
#include "pipeline/simulation.h"
#include "pipeline/snapshot.h"
#include "render/floor_tile.h"
#include "render/renderer.h"

namespace coinroll::pipeline {

StillResult renderStill(const scene::SceneConfig& scene, const StillRequest& request) {
  const StillPicture picture = drawStill(scene, request);
  image::writePng(picture.image, request.output, request.text);
  return picture.result;
}

StillPicture drawStill(const scene::SceneConfig& scene, const StillRequest& request) {
  if (!std::isfinite(request.time) || request.time < 0 || request.time > scene.duration) {
    throw std::invalid_argument(
        fmt::format("--time: must be within the scene's duration, 0 to {} s, got {}", scene.duration, request.time));
  }
  if (request.ghosts < 0 || request.ghosts > 500) {
    throw std::invalid_argument(fmt::format("--strobe: must be 0 to 500 copies, got {}", request.ghosts));
  }
  if (!(request.ghostsFrom >= 0 && request.ghostsFrom < request.time) && request.ghostsFrom != 0) {
    throw std::invalid_argument(
        fmt::format("--strobe-from: must be at least 0 and before --time ({} s), got {}", request.time, request.ghostsFrom));
  }
  Simulation simulation = buildSimulation(scene);
  simulation.cancel = request.cancel;
  render::RenderSettings settings = scene.render.picture;
  settings.reuseStaticBackground = false;  // one frame: nothing to reuse
  // llvmpipe does not check its allocations: short of memory, it crashes or hangs rather than
  // failing, so what it needs is checked first.
  requireRendererAddressSpace(settings);
  render::Renderer renderer(settings);  // before the physics: bad render settings fail fast
  const MotionSurvey survey = surveyMotion(simulation);
  StillResult result;
  result.shownTime = std::min(request.time, survey.endTime);
  if (survey.stoppedBy && survey.endTime < request.time) result.stopDescription = describeStop(*survey.stoppedBy);

  SnapshotMaker snapshots(scene, simulation, survey);
  // A run that stopped early shows its end; the ghosts then span [ghostsFrom, end) if it is long enough.
  const double from = std::min(request.ghostsFrom, result.shownTime);
  for (int i = 0; i < request.ghosts; ++i) snapshots.addGhost(from + (result.shownTime - from) * i / request.ghosts);
  // A strobe still is a figure: its overlay says how to read the copies and gives the scale.
  std::vector<std::string> legend;
  if (request.ghosts > 0) {
    legend = {fmt::format("copies   {:5d} every {:.4g} ms from t = {:.3f} s, blue first, yellow last", request.ghosts,
                          1e3 * (result.shownTime - from) / request.ghosts, from),
              fmt::format("grid     {:5g} mm squares", 1e3 * render::kFloorGridMetres)};
  }
  return {.image = renderer.draw(snapshots.makeSnapshot(result.shownTime, legend)), .result = result};
}

}  // namespace coinroll::pipeline
