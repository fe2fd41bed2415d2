#include "pipeline/still.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/image.h"
#include "pipeline/cancelled.h"
#include "pipeline/run_record.h"
#include "pipeline/resources.h"
#include "pipeline/simulation.h"
#include "pipeline/overlay_lines.h"
#include "pipeline/snapshot.h"
#include "render/floor_tile.h"
#include "render/renderer.h"

namespace coinroll::pipeline {

StillResult renderStill(const scene::SceneConfig& scene, const StillRequest& request) {
  const StillPicture picture = drawStill(scene, request);
  // A draw cannot poll (a strobe's many copies take seconds): a request to stop made during it is
  // answered here, before the file exists, as render answers one before its next frame.
  throwIfCancelled(request.cancel);
  image::writePng(picture.image, request.output, request.text);
  return picture.result;
}

namespace {

// The ghosts' times, evenly spaced over [ghostsFrom, shown) (from `shown` when that is earlier),
// then `shown`, s.
std::vector<double> ghostAndStillTimes(const StillRequest& request, double shown) {
  const double from = std::min(request.ghostsFrom, shown);
  std::vector<double> times;
  for (int i = 0; i < request.ghosts; ++i) times.push_back(from + (shown - from) * i / request.ghosts);
  times.push_back(shown);
  return times;
}

// Panels per row of a strobe's grid: at most kMaxPanelColumns, rows as even as they can be (7
// panels: 4 + 3; 6: 3 + 3), so a figure of 16:9 panels stays about as wide as a page allows.
constexpr int kMaxPanelColumns = 4;

// `frames` (the ghosts' times, then the still's) drawn one by one and laid out in a grid, left to
// right, top to bottom, with a gutter of the background between them. Each panel's overlay is its
// panelLabel; render.hud: false leaves it out.
image::Image drawPanels(const scene::SceneConfig& scene, const physics::CoinModel& model, render::Renderer& renderer,
                        SnapshotMaker& snapshots, const std::vector<FrameState>& frames,
                        const std::atomic<bool>* cancel) {
  const int count = static_cast<int>(frames.size());
  const int rows = (count + kMaxPanelColumns - 1) / kMaxPanelColumns;
  const int columns = (count + rows - 1) / rows;
  const int width = scene.render.picture.width, height = scene.render.picture.height;
  const int gutter = std::max(2, width / 100);  // pixels
  image::Image figure(columns * width + (columns - 1) * gutter, rows * height + (rows - 1) * gutter);
  // The gutter and empty cells: white paper, or nothing on a transparent background.
  if (!scene.render.picture.transparentBackground) std::fill(figure.rgba.begin(), figure.rgba.end(), 255);
  image::Image panel;
  for (int i = 0; i < count; ++i) {
    throwIfCancelled(cancel);
    const FrameState& frame = frames[static_cast<std::size_t>(i)];
    render::FrameSnapshot snapshot = snapshots.makeSnapshot(frame);
    if (scene.render.hud) {
      snapshot.hudLines = panelLabel(model, frame);
      if (i == 0) snapshot.hudLines.push_back(fmt::format("grid {:g} mm", 1e3 * render::kFloorGridMetres));
    }
    renderer.draw(snapshot, panel);
    const int left = (i % columns) * (width + gutter), top = (i / columns) * (height + gutter);
    for (int y = 0; y < height; ++y) {
      std::copy_n(panel.pixel(0, y), 4 * width, figure.pixel(left, top + y));
    }
  }
  return figure;
}

}  // namespace

StillPicture drawStill(const scene::SceneConfig& scene, const StillRequest& request) {
  if (!std::isfinite(request.time) || request.time < 0 || request.time > scene.duration) {
    throw std::invalid_argument(fmt::format("{}: must be within the scene's duration, 0 to {} s, got {}",
                                            request.timeName, scene.duration, request.time));
  }
  if (request.ghosts < 0 || request.ghosts > 500) {
    throw std::invalid_argument(fmt::format("--strobe: must be 0 to 500 copies, got {}", request.ghosts));
  }
  if (!(request.ghostsFrom >= 0 && request.ghostsFrom < request.time) && request.ghostsFrom != 0) {
    throw std::invalid_argument(fmt::format("--strobe-from: must be at least 0 and before --time ({} s), got {}",
                                            request.time, request.ghostsFrom));
  }
  Simulation simulation = buildSimulation(scene);
  simulation.cancel = request.cancel;
  render::RenderSettings settings = scene.render.pictureFor(scene::RenderSpec::Output::Still);
  settings.reuseStaticBackground = false;  // one frame: nothing to reuse
  // llvmpipe does not check its allocations: short of memory, it crashes or hangs rather than
  // failing, so what it needs is checked first.
  requireRendererAddressSpace(settings);
  render::Renderer renderer(settings);  // before the physics: bad render settings fail fast
  FixedFrameTimes asked(ghostAndStillTimes(request, request.time));
  RunRecord record = recordRun(simulation, asked);
  StillResult result;
  result.shownTime = std::min(request.time, record.survey.endTime);
  if (record.survey.stoppedBy && record.survey.endTime < request.time)
    result.stopDescription = describeStop(*record.survey.stoppedBy);
  // A run that stopped early shows its end; the ghosts then span [ghostsFrom, end) if it is long
  // enough. Their times are known only once the end is, so this case alone integrates twice.
  if (request.ghosts > 0 && result.shownTime < request.time) {
    FixedFrameTimes toTheEnd(ghostAndStillTimes(request, result.shownTime));
    record = recordRun(simulation, toTheEnd);
  }
  const double from = std::min(request.ghostsFrom, result.shownTime);
  SnapshotMaker snapshots(scene, simulation.model, record);
  StillPicture picture;
  if (request.panels) {
    picture.image = drawPanels(scene, simulation.model, renderer, snapshots, record.frames, request.cancel);
  } else {
    for (int i = 0; i < request.ghosts; ++i) snapshots.addGhost(record.frames[static_cast<std::size_t>(i)]);
    // A strobe still is a figure: its overlay says how to read the copies and gives the scale.
    std::vector<std::string> legend;
    if (request.ghosts > 0) {
      legend = {fmt::format("copies   {:5d} every {:.4g} ms from t = {:.3f} s, blue first, yellow last", request.ghosts,
                            1e3 * (result.shownTime - from) / request.ghosts, from),
                fmt::format("grid     {:5g} mm squares", 1e3 * render::kFloorGridMetres)};
      // A camera that moves looks at one time: the figure is seen from one place that holds all of it.
      if (scene.render.camera.mode != scene::CameraMode::Fixed) snapshots.frameCopies(record.frames, legend);
    }
    picture.image = renderer.draw(snapshots.makeSnapshot(record.frames.back(), legend));
  }
  result.width = picture.image.width;
  result.height = picture.image.height;
  picture.result = result;
  return picture;
}

}  // namespace coinroll::pipeline
