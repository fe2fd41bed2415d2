#pragma once
// The osmesa back end: an off-screen OpenGL 3.3 core context from Mesa's OSMesa library, drawn by
// llvmpipe on the CPU, with no display and no GPU. Compiled only with COINROLL_WITH_OSMESA (Mesa
// removed OSMesa in 25.1; the egl back end gives the same bytes on Mesa before that).

#include <memory>

#include "render/gl_context.h"

namespace coinroll::render {

// Creates the context and makes it current. Throws std::runtime_error if Mesa cannot provide a
// 3.3 core context.
std::unique_ptr<GlContext> makeOsMesaContext();

}  // namespace coinroll::render
