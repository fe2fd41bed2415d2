#include "render/gl_context.h"

#include <stdexcept>

#if COINROLL_HAVE_OSMESA
#include "render/osmesa_context.h"
#endif
#if COINROLL_HAVE_EGL
#include "render/egl_context.h"
#endif

namespace coinroll::render {

std::unique_ptr<GlContext> makeGlContext(GlBackend backend) {
  requireCompiledIn(backend);
  switch (backend) {
#if COINROLL_HAVE_OSMESA
    case GlBackend::OsMesa: return makeOsMesaContext();
#endif
#if COINROLL_HAVE_EGL
    case GlBackend::Egl: return makeEglSurfacelessContext();
    case GlBackend::EglDevice: return makeEglDeviceContext();
#endif
    default: break;
  }
  throw std::logic_error("makeGlContext: a compiled-in back end without a factory");
}

}  // namespace coinroll::render
