#include "render/osmesa_context.h"

#include <stdexcept>
#include <string>

namespace coinroll::render {

OsMesaContext::OsMesaContext() {
  const int attributes[] = {OSMESA_FORMAT,        OSMESA_RGBA,         OSMESA_DEPTH_BITS, 0,  OSMESA_STENCIL_BITS, 0,
                            OSMESA_PROFILE,       OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                            OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  context_ = OSMesaCreateContextAttribs(attributes, nullptr);
  if (context_ == nullptr) {
    throw std::runtime_error(
        "OSMesa: cannot create an OpenGL 3.3 core context (is Debian's libosmesa6 installed and Mesa >= 20?)");
  }
  makeCurrent();
}

OsMesaContext::~OsMesaContext() { OSMesaDestroyContext(context_); }

void OsMesaContext::makeCurrent() {
  if (!OSMesaMakeCurrent(context_, placeholder_.data(), GL_UNSIGNED_BYTE, 1, 1)) {
    throw std::runtime_error("OSMesa: cannot make the context current");
  }
}

}  // namespace coinroll::render
