#pragma once
// What a picture of a run shows besides the physics, for a back end that draws it itself: the page's
// WebGL view reads it from the WebAssembly core, so that its coin, its overlay and its clock are the
// renderer's own (docs/web.md "One visual track"), not a port of them.

#include <atomic>
#include <string>
#include <vector>

#include "physics/coin_model.h"
#include "pipeline/coin_run.h"
#include "pipeline/playback_clock.h"
#include "pipeline/run_record.h"
#include "render/frame_snapshot.h"
#include "render/meshes.h"
#include "scene/scene_config.h"

namespace coinroll::pipeline {

// Frames above this are refused in a visual track: its clock keeps a 112-byte state per frame while
// it is planned, and a page's memory is smaller than a renderer's (55 min of video at 30 fps).
inline constexpr long kVisualTrackMaxFrames = 100'000;

struct VisualTrack {
  // The coin's triangles in its body frame, as the renderer draws them (render/meshes.h).
  std::vector<render::CoinVertex> coin;
  // Per sample of the run, in time order: the overlay's lines joined by '\n', as `render` prints
  // them, and the same in the seed's units (overlay_lines.h OverlayUnits).
  std::vector<std::string> overlaySi, overlaySeed;
  // Per sample of the run: the camera `render` draws it with at that time (render.camera; a framed
  // camera fits render.width x render.height, the video's picture).
  std::vector<render::CameraView> cameras;
  // The clip `render` would make of the run (its frame times, playback rates and landing's hold):
  // a page plays frame k at k / fps as the video does.
  ClipPlan clock;
};

// Builds the track from the samples of a run, as sampleTrajectory hands them out.
class VisualTrackBuilder {
 public:
  VisualTrackBuilder(const scene::SceneConfig& scene, const physics::CoinModel& model);

  // A sample of the run: a row (`row`), or the one at the duration after the last row, which only
  // widens the box the camera frames, as render's survey takes it in.
  void add(double t, const RunSample& sample, bool row);
  // The track, once the run has ended: its clock is planned by a pass of its own, as `render --plan`
  // plans it (throws as planClip does: too many frames, Cancelled when `cancel` turns true).
  VisualTrack finish(const std::atomic<bool>* cancel) &&;

 private:
  const scene::SceneConfig& scene_;
  physics::CoinModel model_;
  RunRecord record_;  // its survey: the box round every centre and contact point
  std::vector<FrameState> rows_;
  VisualTrack track_;
};

}  // namespace coinroll::pipeline
