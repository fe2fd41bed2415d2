#pragma once
// Draws FrameSnapshots into RGBA images: floor with a metric grid, the contact trace, the coin's
// shadow, the coin (and stroboscopic ghosts), the overlay text. Owns its OpenGL context (on the
// back end of gl_backend.h) and every GL object; one Renderer per thread.

#include <memory>
#include <optional>

#include "image/image.h"
#include "render/frame_snapshot.h"
#include "render/gl_backend.h"
#include "render/meshes.h"
#include "render/render_settings.h"
#include "render/scale_bar.h"

namespace coinroll::render {

class Renderer {
 public:
  // On the back end $COINROLL_GL selects (selectedGlBackend()). Throws std::invalid_argument for
  // bad settings (naming the field) or a bad $COINROLL_GL, and std::runtime_error if OpenGL
  // cannot be set up.
  explicit Renderer(const RenderSettings& settings);
  // On `backend`, whatever $COINROLL_GL says; never on another one (a back end that cannot start
  // is an error, not a fallback).
  Renderer(const RenderSettings& settings, GlBackend backend);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders one frame. The same snapshot gives the same bytes, run after run.
  image::Image draw(const FrameSnapshot& snapshot);
  // The same, into `out` (resized if needed), so a frame loop reuses one allocation.
  void draw(const FrameSnapshot& snapshot, image::Image& out);

  const RenderSettings& settings() const { return settings_; }
  GlBackend backend() const;

 private:
  // One frame's passes, in the order draw() runs them (renderer_passes.cpp).
  void bindDrawTarget();
  // A camera that has not moved gets the floor it saw last frame back by a blit, not redrawn.
  void drawOrRestoreBackground(const CameraView& camera, const glm::mat4& viewProjection);
  // Clears the draw target and shades the sky and the floor: everything a fixed camera sees the same.
  void drawBackground(const CameraView& camera, const glm::mat4& viewProjection);
  void allocateBackgroundCache();
  // The shadows, trace, contact marker and scale bar; returns where the bar lies (its label is overlay).
  std::optional<ScaleBarPlacement> drawFloorDecals(const FrameSnapshot& snapshot, const glm::mat4& viewProjection);
  void drawShadows(const FrameSnapshot& snapshot, const glm::mat4& viewProjection);
  void drawTrace(const FrameSnapshot& snapshot, const glm::mat4& viewProjection);
  void drawContactMarker(const FrameSnapshot& snapshot, const glm::mat4& viewProjection);
  ScaleBarPlacement drawScaleBar(const FrameSnapshot& snapshot, const glm::mat4& viewProjection);
  void drawCoins(const FrameSnapshot& snapshot, const glm::mat4& viewProjection);
  void applyFxaa();
  void downsampleSupersampled();
  void drawOverlay(const FrameSnapshot& snapshot, const std::optional<ScaleBarPlacement>& scaleBar);
  void readBack(image::Image& out);

  struct GlState;  // the context and GL objects, out of this header so callers need no GL
  RenderSettings settings_;
  std::unique_ptr<GlState> state_;
};

}  // namespace coinroll::render
