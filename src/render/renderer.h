#pragma once
// Draws FrameSnapshots into RGBA images: floor with a metric grid, the contact trace, the coin's
// shadow, the coin (and stroboscopic ghosts), the overlay text. Owns its OSMesa context and every
// GL object; one Renderer per thread.

#include <memory>

#include "image/image.h"
#include "render/frame_snapshot.h"
#include "render/meshes.h"

namespace coinroll::render {

// Msaa: `msaa` samples per pixel, resolved by a blit. Fxaa: one sample per pixel and a fast
// approximate anti-aliasing pass over the picture (shaders/fxaa.frag); `msaa` is ignored.
enum class Antialiasing { Msaa, Fxaa };

struct RenderSettings {
  int width = 1280, height = 720;  // pixels
  Antialiasing antialiasing = Antialiasing::Msaa;
  int msaa = 4;                    // samples per pixel: 1 (none), 2, 4 or 8
  CoinShape coin;
  bool showShadow = true;
  // When a frame's camera equals the previous frame's, the sky and the floor are copied from the
  // first such frame instead of shaded again (the largest part of a frame on llvmpipe). The bytes
  // are the same either way; off only to measure or test the saving.
  bool reuseStaticBackground = true;
};

class Renderer {
 public:
  // Throws std::invalid_argument for bad settings (naming the field) and std::runtime_error if
  // OpenGL cannot be set up.
  explicit Renderer(const RenderSettings& settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders one frame. The same snapshot gives the same bytes, run after run.
  image::Image draw(const FrameSnapshot& snapshot);
  // The same, into `out` (resized if needed), so a frame loop reuses one allocation.
  void draw(const FrameSnapshot& snapshot, image::Image& out);

  const RenderSettings& settings() const { return settings_; }

 private:
  // Clears the draw target and shades the sky and the floor: everything a fixed camera sees the same.
  void drawBackground(const CameraView& camera, const glm::mat4& viewProjection);
  void allocateBackgroundCache();

  struct Gl;  // the context and GL objects, out of this header so callers need no GL
  RenderSettings settings_;
  std::unique_ptr<Gl> gl_;
};

}  // namespace coinroll::render
