#include "render/osmesa_context.h"

#include <GL/osmesa.h>

#include <array>
#include <cstdint>
#include <stdexcept>

namespace coinroll::render {

namespace {

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext() : GlContext(GlBackend::OsMesa) {
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              0,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    context_ = OSMesaCreateContextAttribs(attributes, nullptr);
    if (context_ == nullptr) {
      throw std::runtime_error(
          "OSMesa: cannot create an OpenGL 3.3 core context (is Debian's libosmesa6 installed and Mesa >= 20?)");
    }
    try {
      makeCurrent();
      functions_ = loadGlFunctions(&OSMesaGetProcAddress, "osmesa");
    } catch (...) {
      OSMesaDestroyContext(context_);
      throw;
    }
  }
  ~OsMesaContext() override { OSMesaDestroyContext(context_); }

  // OSMesaMakeCurrent requires a colour buffer even though coinroll draws into framebuffer
  // objects only: a 1x1 placeholder.
  void makeCurrent() override {
    if (!OSMesaMakeCurrent(context_, placeholder_.data(), GL_UNSIGNED_BYTE, 1, 1)) {
      throw std::runtime_error("OSMesa: cannot make the context current");
    }
  }

 private:
  OSMesaContext context_ = nullptr;
  std::array<std::uint8_t, 4> placeholder_{};
};

}  // namespace

std::unique_ptr<GlContext> makeOsMesaContext() { return std::make_unique<OsMesaContext>(); }

}  // namespace coinroll::render
