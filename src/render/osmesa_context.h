#pragma once
// An off-screen OpenGL 3.3 core context on Mesa's software rasteriser (llvmpipe): no display, no
// GPU. Rendering goes to framebuffer objects (the Renderer's, made with gl_handles.h's
// makeFramebuffer); the context's own buffer is a 1x1 placeholder that OSMesaMakeCurrent requires.

#include <array>
#include <cstdint>

#include "render/gl.h"

namespace coinroll::render {

class OsMesaContext {
 public:
  // Creates the context and makes it current on the calling thread. Throws std::runtime_error
  // if Mesa cannot provide a 3.3 core context.
  OsMesaContext();
  ~OsMesaContext();

  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  // Makes this context current on the calling thread (a context is current on one thread).
  void makeCurrent();

 private:
  OSMesaContext context_ = nullptr;
  std::array<std::uint8_t, 4> placeholder_{};
};

}  // namespace coinroll::render
