#include "pipeline/visual_track.h"

#include <utility>

#include "pipeline/camera_rig.h"
#include "pipeline/overlay_lines.h"

namespace coinroll::pipeline {

VisualTrackBuilder::VisualTrackBuilder(const scene::SceneConfig& scene, const physics::CoinModel& model)
    : scene_(scene), model_(model) {
  track_.coin = render::coinTriangles(scene.render.picture.coin, render::kCoinSegments);
}

void VisualTrackBuilder::add(double t, const RunSample& sample, bool row) {
  addSurveySample(record_, sample, rows_.empty(), false);
  if (!row) return;
  const FrameState frame = frameStateOf(t, sample);
  rows_.push_back(frame);
  writeHud(track_.overlaySi.emplace_back(), model_, frame);
  writeHud(track_.overlaySeed.emplace_back(), model_, frame, OverlayUnits::seedOf(model_));
}

VisualTrack VisualTrackBuilder::finish(const std::atomic<bool>* cancel) && {
  const CameraRig rig(scene_.render.camera, record_.survey, model_, scene_.render.picture.width,
                      scene_.render.picture.height);
  for (const FrameState& row : rows_) track_.cameras.push_back(rig.at(row.time, row.centre));
  track_.clock = planClip(scene_, kVisualTrackMaxFrames, cancel);
  return std::move(track_);
}

}  // namespace coinroll::pipeline
