#include "render/gl_backend.h"

#include <fmt/format.h>

#include <array>
#include <cstdlib>
#include <stdexcept>

namespace coinroll::render {

namespace {

constexpr std::array kAllBackends = {GlBackend::OsMesa, GlBackend::Egl, GlBackend::EglDevice};

std::string acceptedValues() { return fmt::format("{}", fmt::join(compiledBackends(), ", ")); }

}  // namespace

std::string_view glBackendName(GlBackend backend) {
  switch (backend) {
    case GlBackend::OsMesa: return "osmesa";
    case GlBackend::Egl: return "egl";
    case GlBackend::EglDevice: return "egl-device";
  }
  throw std::logic_error("glBackendName: not a GlBackend");
}

// COINROLL_HAVE_OSMESA and COINROLL_HAVE_EGL come from src/render/CMakeLists.txt: 1 when that
// back end's library was found and enabled.
bool isCompiledIn(GlBackend backend) {
  switch (backend) {
    case GlBackend::OsMesa: return COINROLL_HAVE_OSMESA == 1;
    case GlBackend::Egl:
    case GlBackend::EglDevice: return COINROLL_HAVE_EGL == 1;
  }
  throw std::logic_error("isCompiledIn: not a GlBackend");
}

std::vector<std::string_view> compiledBackends() {
  std::vector<std::string_view> names;
  for (const GlBackend backend : kAllBackends) {
    if (isCompiledIn(backend)) names.push_back(glBackendName(backend));
  }
  return names;
}

GlBackend defaultGlBackend() { return isCompiledIn(GlBackend::OsMesa) ? GlBackend::OsMesa : GlBackend::Egl; }

void requireCompiledIn(GlBackend backend) {
  if (isCompiledIn(backend)) return;
  const bool osmesa = backend == GlBackend::OsMesa;
  throw std::invalid_argument(
      fmt::format("{}={}: this coinroll was built without {} (CMake option {}); accepted values: {}",
                  kGlBackendVariable, glBackendName(backend), osmesa ? "OSMesa" : "EGL",
                  osmesa ? "COINROLL_WITH_OSMESA" : "COINROLL_WITH_EGL", acceptedValues()));
}

GlBackend parseGlBackend(std::string_view value) {
  for (const GlBackend backend : kAllBackends) {
    if (value == glBackendName(backend)) {
      requireCompiledIn(backend);
      return backend;
    }
  }
  throw std::invalid_argument(
      fmt::format("{}={}: not an OpenGL back end; accepted values: {}", kGlBackendVariable, value, acceptedValues()));
}

std::optional<GlBackend> glBackendFromEnvironment() {
  const char* value = std::getenv(std::string(kGlBackendVariable).c_str());
  if (value == nullptr || *value == '\0') return std::nullopt;
  return parseGlBackend(value);
}

GlBackend selectedGlBackend() { return glBackendFromEnvironment().value_or(defaultGlBackend()); }

std::string glBackendsLine() {
  const std::string compiled = fmt::format("OpenGL back ends: {}", acceptedValues());
  std::optional<GlBackend> chosen;
  try {
    chosen = glBackendFromEnvironment();
  } catch (const std::invalid_argument& e) {
    // Said, not thrown: the version is what someone asks for when something is wrong, and it
    // opens no context; the refusal belongs to drawing.
    return fmt::format("{}; {} (nothing is drawn until it names one of them)", compiled, e.what());
  }
  if (chosen) return fmt::format("{}; {} selects {}", compiled, kGlBackendVariable, glBackendName(*chosen));
  return fmt::format("{}; default {}", compiled, glBackendName(defaultGlBackend()));
}

}  // namespace coinroll::render
