#pragma once
// Which OpenGL back end draws. The build decides which are compiled in (CMake's
// COINROLL_WITH_OSMESA and COINROLL_WITH_EGL, by default whatever is installed); $COINROLL_GL picks
// one of them at run time. Nothing here opens a context, so `coinroll --version` can name the
// back ends on a machine with no working OpenGL at all.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace coinroll::render {

enum class GlBackend {
  OsMesa,     // "osmesa": Mesa's off-screen library, llvmpipe
  Egl,        // "egl": EGL's surfaceless platform on Mesa (EGL_PLATFORM_SURFACELESS_MESA), llvmpipe;
              // the same bytes as osmesa on the same Mesa
  EglDevice,  // "egl-device": EGL's device platform (EGL_PLATFORM_DEVICE_EXT) on the first GPU EGL
              // lists; other bytes than llvmpipe's. Built, but untested on GPU hardware
};

// The environment variable that picks the back end.
inline constexpr std::string_view kGlBackendVariable = "COINROLL_GL";

// "osmesa", "egl", "egl-device": the values of $COINROLL_GL.
std::string_view glBackendName(GlBackend backend);

bool isCompiledIn(GlBackend backend);

// Throws std::invalid_argument naming COINROLL_GL, the back end and the values this build accepts
// if this build lacks `backend`.
void requireCompiledIn(GlBackend backend);

// The names of the back ends this build has, in the order osmesa, egl, egl-device.
std::vector<std::string_view> compiledBackends();

// osmesa where compiled in, else egl: never a GPU unless asked for.
GlBackend defaultGlBackend();

// A value of $COINROLL_GL. Throws std::invalid_argument naming COINROLL_GL, the value and the
// values this build accepts, for an unknown name and for a back end this build lacks.
GlBackend parseGlBackend(std::string_view value);

// $COINROLL_GL parsed (parseGlBackend's errors), or nullopt when it is unset or empty.
std::optional<GlBackend> glBackendFromEnvironment();

// The back end a Renderer uses when not given one: $COINROLL_GL when set, else the default.
GlBackend selectedGlBackend();

// The line `coinroll --version` prints: the back ends compiled in, then the one $COINROLL_GL
// selects when it is set ("OpenGL back ends: osmesa, egl, egl-device; COINROLL_GL selects egl"),
// else the default ("...; default osmesa"). A bad $COINROLL_GL is named with parseGlBackend's
// refusal in the line, not thrown: only drawing refuses it.
std::string glBackendsLine();

}  // namespace coinroll::render
