#include "pipeline/still.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "image/image.h"
#include "pipeline/coin_run.h"
#include "pipeline/framing.h"
#include "pipeline/simulation.h"
#include "render/renderer.h"

namespace coinroll::pipeline {

namespace {

// What one query of the trajectory is for; queries run in time order (the trajectory streams).
enum class Use { Trace, Ghost, Shown };

struct Query {
  double t;
  Use use;
};

}  // namespace

StillResult renderStill(const scene::SceneConfig& scene, const StillRequest& request) {
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
  render::RenderSettings settings = renderSettings(scene);
  settings.reuseStaticBackground = false;  // one frame: nothing to reuse
  render::Renderer renderer(settings);  // before the physics: bad render settings fail fast
  const MotionSurvey survey = surveyMotion(simulation);
  StillResult result;
  result.shownTime = std::min(request.time, survey.endTime);
  if (survey.stoppedBy && survey.endTime < request.time) result.stopDescription = describeStop(*survey.stoppedBy);

  std::vector<Query> queries;
  if (scene.render.trace) {
    const double dt = traceInterval(scene.duration);
    for (long k = 0; static_cast<double>(k) * dt < result.shownTime; ++k) queries.push_back({static_cast<double>(k) * dt, Use::Trace});
  }
  // A run that stopped early shows its end; the ghosts then span [ghostsFrom, end) if it is long enough.
  const double from = std::min(request.ghostsFrom, result.shownTime);
  for (int i = 0; i < request.ghosts; ++i) {
    queries.push_back({from + (result.shownTime - from) * i / request.ghosts, Use::Ghost});
  }
  queries.push_back({result.shownTime, Use::Shown});
  std::stable_sort(queries.begin(), queries.end(), [](const Query& a, const Query& b) { return a.t < b.t; });

  CoinRun trajectory(simulation);
  render::FrameSnapshot snapshot;
  physics::CoinState shown;
  for (const Query& q : queries) {
    const std::optional<physics::CoinState> y = trajectory.stateAt(q.t);
    if (!y) throw std::logic_error("still: the trajectory ended before the survey said it would");
    const physics::CoinState s = *y;
    switch (q.use) {
      case Use::Trace: {
        const Eigen::Vector2d c = contactOnFloor(simulation.model, s);
        snapshot.trace.emplace_back(static_cast<float>(c.x()), static_cast<float>(c.y()));
        break;
      }
      case Use::Ghost: snapshot.ghosts.push_back(coinPose(simulation.model, s)); break;
      case Use::Shown: shown = s; break;
    }
  }
  if (scene.render.trace) {
    const Eigen::Vector2d c = contactOnFloor(simulation.model, shown);
    snapshot.trace.emplace_back(static_cast<float>(c.x()), static_cast<float>(c.y()));
  }
  snapshot.showContact = scene.render.trace;
  snapshot.coin = coinPose(simulation.model, shown);
  const CameraRig rig(scene.render.camera, survey, simulation.model, scene.render.width, scene.render.height);
  snapshot.camera = rig.at(result.shownTime, shown);
  snapshot.traceWidth = traceWidthFor(snapshot.camera, scene.render.height, simulation.model.a);
  if (scene.render.hud) snapshot.hudLines = hudLines(simulation.model, shown, result.shownTime);

  image::writePng(renderer.draw(snapshot), request.output);
  return result;
}

}  // namespace coinroll::pipeline
