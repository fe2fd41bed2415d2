#pragma once
// From the physics to what the renderer reads (house style: the renderer never sees the physics):
// the FrameSnapshots of one recorded run, built in one place for `still` and `render` alike.

#include <string>
#include <utility>
#include <vector>

#include "physics/coin_model.h"
#include "pipeline/camera_rig.h"
#include "pipeline/run_record.h"
#include "render/frame_snapshot.h"
#include "scene/scene_config.h"

namespace coinroll::pipeline {

// Snapshots of one run in time order, read from its record (run_record.h): the trace (the contact
// point every traceInterval up to the frame's time, then the contact point now), stroboscopic
// ghosts, the coin's pose, the camera from render.camera and the survey, the overlay.
class SnapshotMaker {
 public:
  // `model` is the run's (buildSimulation(scene).model); `record` outlives the maker.
  SnapshotMaker(const scene::SceneConfig& scene, const physics::CoinModel& model, const RunRecord& record);

  // Adds a semi-transparent copy of the coin as it is at `frame` to every later snapshot.
  void addGhost(const FrameState& frame);

  // Replaces the scene's camera by a fixed one, looking the way it does (along its eye - target,
  // else from its elevation) with its field of view, that frames the coin at every one of `frames`
  // (the box of their centres widened by the coin's radius, from the floor up) below the overlay
  // the last of them will show with `extraHudLines`: a strobe seen by a camera that moves (follow,
  // orbit) would leave the copies it strobes out of the picture.
  void frameCopies(const std::vector<FrameState>& frames, const std::vector<std::string>& extraHudLines);

  // Draws `plot` (render --inset) in every later snapshot, its marker at `now` in [0, 1] and its
  // curves' labels as given; a later call moves the marker and changes the labels only.
  void setInset(render::InsetPlot plot) { snapshot_.inset = std::move(plot); }
  void markInset(float now, const std::vector<std::string>& labels);

  // The picture of `frame`, at or after the previous one's time; `extraHudLines` follow the
  // overlay's own lines (e.g. the slow-motion factor). Valid until the next call.
  const render::FrameSnapshot& makeSnapshot(const FrameState& frame,
                                            const std::vector<std::string>& extraHudLines = {});

 private:
  // Appends the recorded trace points strictly before `time`.
  void extendTraceTo(double time);

  physics::CoinModel model_;
  const RunRecord& record_;
  scene::CameraSpec camera_;  // the scene's, whose elevation and field of view frameCopies keeps
  CameraRig rig_;
  double traceDt_;  // s, traceInterval(duration)
  std::size_t nextTracePoint_ = 0;
  bool traceEndsWithNow_ = false;  // the trace's last point is the last snapshot's contact point
  bool showTrace_, showHud_;
  int width_, height_;  // pixels, of the picture: the framing's aspect, the trace's width on screen
  render::FrameSnapshot snapshot_;
};

}  // namespace coinroll::pipeline
