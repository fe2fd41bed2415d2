#pragma once
// The egl and egl-device back ends: an OpenGL 3.3 core context made through EGL, with no surface
// (EGL_KHR_surfaceless_context). Compiled only with COINROLL_WITH_EGL.

#include <memory>

#include "render/gl_context.h"

namespace coinroll::render {

// On Mesa's surfaceless platform (EGL_PLATFORM_SURFACELESS_MESA), forced onto llvmpipe: the same
// rasteriser as OSMesa, so the same bytes on the same Mesa. Throws std::runtime_error naming
// COINROLL_GL=egl and what is missing if EGL cannot give that context.
std::unique_ptr<GlContext> makeEglSurfacelessContext();

// On the first GPU that EGL's device platform (EGL_PLATFORM_DEVICE_EXT) lists, skipping Mesa's
// software device. Throws std::runtime_error naming COINROLL_GL=egl-device when there is no GPU:
// it never falls back to the CPU. Built, but untested on GPU hardware.
std::unique_ptr<GlContext> makeEglDeviceContext();

}  // namespace coinroll::render
