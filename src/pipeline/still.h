#pragma once
// `coinroll still`: one PNG of a scene at one simulated time, optionally stroboscopic.

#include <atomic>
#include <filesystem>
#include <optional>
#include <string>

#include "image/image.h"
#include "scene/scene_config.h"

namespace coinroll::pipeline {

struct StillRequest {
  double time = 0;                  // s of simulated time, in [0, duration]
  std::string timeName = "--time";  // names `time` in messages, as the caller's user gives it
  int ghosts = 0;                   // > 0: this many earlier poses, evenly spaced over [ghostsFrom, time)
  double ghostsFrom = 0;            // s, the first ghost's time, in [0, time)
  // The ghosts' times and `time` as panels side by side (a grid of ghosts + 1 pictures, each the
  // scene's full picture, labelled by panelLabel) instead of copies drawn over one picture, which
  // pile up where the coin stays in place.
  bool panels = false;
  std::filesystem::path output;               // .png, written atomically
  image::PngText text = {};                   // tEXt chunks of the PNG (its provenance)
  const std::atomic<bool>* cancel = nullptr;  // when set and true, stops with Cancelled
};

struct StillResult {
  double shownTime = 0;  // s; earlier than asked when a validity event ended the run first
  std::optional<std::string> stopDescription;
  // pixels, the picture's: a panels figure is wider (and taller) than render's width x height
  int width = 0, height = 0;
};

// Throws std::invalid_argument naming the option for a bad request, scene::SceneError for a bad
// scene, std::runtime_error for rendering or writing failures (nothing left under `output`).
StillResult renderStill(const scene::SceneConfig& scene, const StillRequest& request);

// renderStill's picture, kept in memory (request.output is not used): for callers that want the
// pixels, not a file. Throws as renderStill does.
struct StillPicture {
  image::Image image;
  StillResult result;
};
StillPicture drawStill(const scene::SceneConfig& scene, const StillRequest& request);

}  // namespace coinroll::pipeline
