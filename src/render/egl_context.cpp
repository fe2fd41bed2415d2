#include "render/egl_context.h"

// Without EGL_NO_X11, eglplatform.h includes Xlib.h for native window types coinroll never uses,
// and with it macros such as None, Bool and Status.
#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace coinroll::render {

namespace {

std::string eglErrorName(EGLint code) {
  constexpr std::pair<EGLint, const char*> kNames[] = {
      {EGL_NOT_INITIALIZED, "EGL_NOT_INITIALIZED"},
      {EGL_BAD_ACCESS, "EGL_BAD_ACCESS"},
      {EGL_BAD_ALLOC, "EGL_BAD_ALLOC"},
      {EGL_BAD_ATTRIBUTE, "EGL_BAD_ATTRIBUTE"},
      {EGL_BAD_CONFIG, "EGL_BAD_CONFIG"},
      {EGL_BAD_CONTEXT, "EGL_BAD_CONTEXT"},
      {EGL_BAD_DISPLAY, "EGL_BAD_DISPLAY"},
      {EGL_BAD_MATCH, "EGL_BAD_MATCH"},
      {EGL_BAD_PARAMETER, "EGL_BAD_PARAMETER"},
      {EGL_BAD_SURFACE, "EGL_BAD_SURFACE"},
      {EGL_CONTEXT_LOST, "EGL_CONTEXT_LOST"},
  };
  for (const auto& [value, name] : kNames) {
    if (value == code) return name;
  }
  return fmt::format("EGL error 0x{:04x}", code);
}

// What a failed EGL call reports: the back end, the call and EGL's error code.
std::runtime_error eglFailure(std::string_view backendLabel, std::string_view call) {
  return std::runtime_error(fmt::format("{}: {} failed ({})", backendLabel, call, eglErrorName(eglGetError())));
}

// EGL extension lists are names separated by single spaces.
bool hasExtension(const char* extensions, std::string_view name) {
  if (extensions == nullptr) return false;
  const std::string_view list(extensions);
  for (std::size_t start = 0; start < list.size();) {
    const std::size_t end = std::min(list.find(' ', start), list.size());
    if (list.substr(start, end - start) == name) return true;
    start = end + 1;
  }
  return false;
}

void requireClientExtension(std::string_view backendLabel, std::string_view name) {
  if (!hasExtension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), name)) {
    throw std::runtime_error(
        fmt::format("{}: this EGL lacks {} (Debian: libegl1 with Mesa's libegl-mesa0)", backendLabel, name));
  }
}

template <class Function>
Function extensionFunction(std::string_view backendLabel, const char* name) {
  const auto function = reinterpret_cast<Function>(eglGetProcAddress(name));
  if (function == nullptr) throw std::runtime_error(fmt::format("{}: this EGL has no {}", backendLabel, name));
  return function;
}

std::string backendLabel(GlBackend backend) { return fmt::format("{}={}", kGlBackendVariable, glBackendName(backend)); }

// Mesa's software device (llvmpipe) carries EGL_MESA_device_software; a GPU's does not.
bool isSoftwareDevice(EGLDeviceEXT device, std::string_view label) {
  const auto queryDeviceString = extensionFunction<PFNEGLQUERYDEVICESTRINGEXTPROC>(label, "eglQueryDeviceStringEXT");
  return hasExtension(queryDeviceString(device, EGL_EXTENSIONS), "EGL_MESA_device_software");
}

// Sets an environment variable until the end of the scope, then restores what was there (or its
// absence).
class ScopedEnvironmentVariable {
 public:
  ScopedEnvironmentVariable(const char* name, const char* value) : name_(name) {
    if (const char* previous = std::getenv(name)) previous_ = previous;
    setenv(name, value, 1);
  }
  ~ScopedEnvironmentVariable() {
    if (previous_) {
      setenv(name_, previous_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }
  ScopedEnvironmentVariable(const ScopedEnvironmentVariable&) = delete;
  ScopedEnvironmentVariable& operator=(const ScopedEnvironmentVariable&) = delete;

 private:
  const char* name_;
  std::optional<std::string> previous_;
};

class EglContext final : public GlContext {
 public:
  // Creates a 3.3 core context on `display` (initialised) and makes it current with no surface.
  EglContext(GlBackend backend, EGLDisplay display)
      : GlContext(backend), label_(backendLabel(backend)), display_(display) {
    if (!hasExtension(eglQueryString(display_, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
      throw std::runtime_error(fmt::format("{}: this EGL display lacks EGL_KHR_surfaceless_context", label_));
    }
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) throw eglFailure(label_, "eglBindAPI(EGL_OPENGL_API)");
    // Any configuration that can render OpenGL will do: its surface type is never used, and
    // pbuffer configurations are the ones both Mesa's platforms and GPU drivers offer.
    const EGLint configAttributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                       EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configCount = 0;
    if (eglChooseConfig(display_, configAttributes, &config, 1, &configCount) != EGL_TRUE) {
      throw eglFailure(label_, "eglChooseConfig");
    }
    if (configCount == 0) throw std::runtime_error(fmt::format("{}: no EGL configuration renders OpenGL", label_));
    const EGLint contextAttributes[] = {
        EGL_CONTEXT_MAJOR_VERSION,           3,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, contextAttributes);
    if (context_ == EGL_NO_CONTEXT) throw eglFailure(label_, "eglCreateContext (OpenGL 3.3 core)");
    try {
      makeCurrent();
      functions_ = loadGlFunctions(&eglGetProcAddress, label_.c_str());
    } catch (...) {
      destroy();
      throw;
    }
  }

  // The display stays initialised: EGL gives every caller in the process the same display for the
  // same platform and device, so eglTerminate would destroy other Renderers' contexts too.
  ~EglContext() override { destroy(); }

  // EGL skips making current a context it believes is current already, but OSMesa shares Mesa's
  // current-context slot with it (one libglapi) and may have taken it since: release first, so
  // the binding is made again whatever happened in between.
  void makeCurrent() override {
    if (eglGetCurrentContext() == context_ && !releaseCurrent())
      throw eglFailure(label_, "eglMakeCurrent(EGL_NO_CONTEXT)");
    if (eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) != EGL_TRUE)
      throw eglFailure(label_, "eglMakeCurrent");
  }

 private:
  // Leaves the calling thread without a current EGL context.
  bool releaseCurrent() const {
    return eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT) == EGL_TRUE;
  }

  void destroy() const {
    if (eglGetCurrentContext() == context_) releaseCurrent();
    eglDestroyContext(display_, context_);
  }

  std::string label_;  // "COINROLL_GL=egl", for messages
  EGLDisplay display_;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GlContext> makeEglSurfacelessContext() {
  const std::string label = backendLabel(GlBackend::Egl);
  requireClientExtension(label, "EGL_MESA_platform_surfaceless");
  requireClientExtension(label, "EGL_EXT_device_query");
  const EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) throw eglFailure(label, "eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA)");
  {
    // The surfaceless platform takes a GPU's render node when it finds one and has no attribute
    // to ask for the CPU; Mesa reads LIBGL_ALWAYS_SOFTWARE in eglInitialize, once per display, so
    // the variable is set for that call alone. (setenv is not safe against other threads reading
    // the environment: a Renderer is built before the frame loop it serves starts any.)
    const ScopedEnvironmentVariable software("LIBGL_ALWAYS_SOFTWARE", "1");
    if (eglInitialize(display, nullptr, nullptr) != EGL_TRUE)
      throw eglFailure(label, "eglInitialize (surfaceless, llvmpipe)");
  }
  // Never a GPU unless asked for: refuse a display that is not on Mesa's software device (another
  // EGL vendor, or a display initialised earlier in this process without the variable).
  const auto queryDisplayAttribute =
      extensionFunction<PFNEGLQUERYDISPLAYATTRIBEXTPROC>(label, "eglQueryDisplayAttribEXT");
  EGLAttrib device = 0;
  if (queryDisplayAttribute(display, EGL_DEVICE_EXT, &device) != EGL_TRUE)
    throw eglFailure(label, "eglQueryDisplayAttribEXT(EGL_DEVICE_EXT)");
  if (!isSoftwareDevice(reinterpret_cast<EGLDeviceEXT>(device), label)) {
    throw std::runtime_error(
        fmt::format("{}: Mesa's surfaceless platform chose a GPU, not llvmpipe; coinroll renders on a GPU "
                    "only with {}=egl-device",
                    label, kGlBackendVariable));
  }
  return std::make_unique<EglContext>(GlBackend::Egl, display);
}

std::unique_ptr<GlContext> makeEglDeviceContext() {
  const std::string label = backendLabel(GlBackend::EglDevice);
  requireClientExtension(label, "EGL_EXT_device_enumeration");
  requireClientExtension(label, "EGL_EXT_platform_device");
  const auto queryDevices = extensionFunction<PFNEGLQUERYDEVICESEXTPROC>(label, "eglQueryDevicesEXT");
  EGLint count = 0;
  if (queryDevices(0, nullptr, &count) != EGL_TRUE) throw eglFailure(label, "eglQueryDevicesEXT");
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  if (queryDevices(count, devices.data(), &count) != EGL_TRUE) throw eglFailure(label, "eglQueryDevicesEXT");
  devices.resize(static_cast<std::size_t>(count));
  for (const EGLDeviceEXT device : devices) {
    if (isSoftwareDevice(device, label)) continue;
    const EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    if (display == EGL_NO_DISPLAY) throw eglFailure(label, "eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT)");
    if (eglInitialize(display, nullptr, nullptr) != EGL_TRUE) throw eglFailure(label, "eglInitialize (GPU device)");
    return std::make_unique<EglContext>(GlBackend::EglDevice, display);
  }
  throw std::runtime_error(
      fmt::format("{}: no GPU: EGL lists {} device(s), none of them a GPU (Mesa's software rasteriser "
                  "is not one), and egl-device never falls back to the CPU; {}=egl renders on llvmpipe. "
                  "(egl-device is built but untested on GPU hardware.)",
                  label, count, kGlBackendVariable));
}

}  // namespace coinroll::render
