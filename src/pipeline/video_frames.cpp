#include "pipeline/video_frames.h"

#include <fmt/format.h>

#include <cmath>

#include "pipeline/framing.h"
#include "pipeline/simulation.h"
#include "render/renderer.h"

namespace coinroll::pipeline {

long frameCount(double simulatedSeconds, double timeScale, int fps) {
  // The relative nudge makes 2 s at 30 fps give 61 frames despite 2 * 30 = 59.99999... in binary.
  return static_cast<long>(std::floor(simulatedSeconds / timeScale * fps * (1 + 1e-12) + 1e-9)) + 1;
}

VideoRunResult renderVideo(const scene::SceneConfig& scene, video::FrameSink& sink, const VideoRunOptions& options) {
  const Simulation simulation = buildSimulation(scene);
  render::Renderer renderer(renderSettings(scene));
  const MotionSurvey survey = surveyMotion(simulation);
  const CameraRig rig(scene.render.camera, survey, simulation.model, scene.render.width, scene.render.height);
  const physics::CoinModel& model = simulation.model;

  VideoRunResult result;
  result.simulatedSeconds = survey.endTime;
  if (survey.stoppedBy) result.stopDescription = describeStop(*survey.stoppedBy);
  const long total = frameCount(survey.endTime, scene.render.timeScale, scene.render.fps);
  const double simulatedPerFrame = scene.render.timeScale / scene.render.fps;
  const double traceDt = traceInterval(scene.duration);
  std::vector<std::string> extraHud;
  if (scene.render.timeScale != 1.0) extraHud.push_back(fmt::format("slow  x{:.3g}", 1 / scene.render.timeScale));

  CoinTrajectory trajectory = startTrajectory(simulation);
  render::FrameSnapshot snapshot;
  snapshot.showContact = scene.render.trace;
  image::Image frame;
  long nextTracePoint = 0;
  for (long k = 0; k < total; ++k) {
    if (options.cancel != nullptr && options.cancel->load()) throw Cancelled();
    const double t = std::min(static_cast<double>(k) * simulatedPerFrame, survey.endTime);
    if (scene.render.trace) {
      // Trace points strictly before t; the current contact point is appended per frame below.
      if (!snapshot.trace.empty()) snapshot.trace.pop_back();
      for (; static_cast<double>(nextTracePoint) * traceDt < t; ++nextTracePoint) {
        const std::optional<physics::StateVec> y = trajectory.stateAt(static_cast<double>(nextTracePoint) * traceDt);
        if (!y) break;
        const Eigen::Vector2d c = contactOnFloor(model, physics::toState(*y));
        snapshot.trace.emplace_back(static_cast<float>(c.x()), static_cast<float>(c.y()));
      }
    }
    const std::optional<physics::StateVec> y = trajectory.stateAt(t);
    if (!y) throw std::logic_error("render: the trajectory ended before the survey said it would");
    const physics::CoinState state = physics::toState(*y);
    if (scene.render.trace) {
      const Eigen::Vector2d c = contactOnFloor(model, state);
      snapshot.trace.emplace_back(static_cast<float>(c.x()), static_cast<float>(c.y()));
    }
    snapshot.coin = coinPose(model, state);
    snapshot.camera = rig.at(t, state);
    snapshot.traceWidth = traceWidthFor(snapshot.camera, scene.render.height, model.a);
    if (scene.render.hud) snapshot.hudLines = hudLines(model, state, t, extraHud);
    renderer.draw(snapshot, frame);
    sink.push(frame);
    result.frames = k + 1;
    if (options.onFrame) options.onFrame({k + 1, total});
  }
  sink.finish();
  return result;
}

}  // namespace coinroll::pipeline
