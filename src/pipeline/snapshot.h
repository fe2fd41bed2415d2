#pragma once
// From the physics to what the renderer reads (house style: the renderer never sees the physics):
// the FrameSnapshots of one run, built in one place for `still` and `render` alike.

#include <string>
#include <vector>

#include "physics/coin_model.h"
#include "physics/coin_state.h"
#include "pipeline/camera_rig.h"
#include "pipeline/coin_run.h"
#include "pipeline/motion_survey.h"
#include "pipeline/simulation.h"
#include "render/frame_snapshot.h"
#include "scene/scene_config.h"

namespace coinroll::pipeline {

// Snapshots of one run in time order, streaming its dense output once: the trace (the contact
// point every traceInterval up to the frame's time, then the contact point now), stroboscopic
// ghosts, the coin's pose, the camera from render.camera and the survey, the overlay.
class SnapshotMaker {
 public:
  // `survey` is surveyMotion(simulation). Times passed to the calls below never go back.
  SnapshotMaker(const scene::SceneConfig& scene, const Simulation& simulation, const MotionSurvey& survey);

  // Adds a semi-transparent copy of the coin as it is at `time` (s) to every later snapshot.
  void addGhost(double time);

  // The picture at simulated `time` (s), within the survey's end time; `extraHudLines` follow the
  // overlay's own lines (e.g. the slow-motion factor). Valid until the next call.
  const render::FrameSnapshot& makeSnapshot(double time, const std::vector<std::string>& extraHudLines = {});

  // The coin at the time of the last snapshot.
  const physics::CoinState& state() const { return sample_.state; }
  const physics::Forward& forward() const { return sample_.forward; }

 private:
  RunSample sampleAt(double time);
  // Appends the trace points strictly before `time`.
  void extendTraceTo(double time);

  physics::CoinModel model_;
  CoinRun run_;
  CameraRig rig_;
  double traceDt_;       // s, traceInterval(duration)
  long nextTracePoint_ = 0;
  bool traceEndsWithNow_ = false;  // the trace's last point is the last snapshot's contact point
  bool showTrace_, showHud_;
  int height_;           // pixels, for the trace's width on screen
  render::FrameSnapshot snapshot_;
  RunSample sample_;
};

}  // namespace coinroll::pipeline
