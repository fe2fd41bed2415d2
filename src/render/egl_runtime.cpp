// EGL's functions, opened at the first call (io/runtime_library.h): the EGL back end's libraries
// (libglvnd, Mesa, its LLVM) are only a render's. GL's functions come through eglGetProcAddress.

#define EGL_NO_X11  // as in egl_context.cpp: no Xlib.h and its macros
#include <EGL/egl.h>

#include "io/runtime_library.h"

namespace {

coinroll::io::RuntimeLibrary& egl() {
  static coinroll::io::RuntimeLibrary library(COINROLL_EGL_SONAME, COINROLL_EGL_PACKAGE);
  return library;
}

}  // namespace

COINROLL_FORWARD(egl(), EGLBoolean, eglBindAPI, (EGLenum api), (api))
COINROLL_FORWARD(egl(), EGLBoolean, eglChooseConfig,
                 (EGLDisplay display, const EGLint* attributes, EGLConfig* configs, EGLint size, EGLint* count),
                 (display, attributes, configs, size, count))
COINROLL_FORWARD(egl(), EGLContext, eglCreateContext,
                 (EGLDisplay display, EGLConfig config, EGLContext shared, const EGLint* attributes),
                 (display, config, shared, attributes))
COINROLL_FORWARD(egl(), EGLBoolean, eglDestroyContext, (EGLDisplay display, EGLContext context), (display, context))
COINROLL_FORWARD(egl(), EGLContext, eglGetCurrentContext, (void), ())
COINROLL_FORWARD(egl(), EGLint, eglGetError, (void), ())
COINROLL_FORWARD(egl(), EGLDisplay, eglGetPlatformDisplay,
                 (EGLenum platform, void* native_display, const EGLAttrib* attributes),
                 (platform, native_display, attributes))
COINROLL_FORWARD(egl(), __eglMustCastToProperFunctionPointerType, eglGetProcAddress, (const char* name), (name))
COINROLL_FORWARD(egl(), EGLBoolean, eglInitialize, (EGLDisplay display, EGLint* major, EGLint* minor),
                 (display, major, minor))
COINROLL_FORWARD(egl(), EGLBoolean, eglMakeCurrent,
                 (EGLDisplay display, EGLSurface draw, EGLSurface read, EGLContext context),
                 (display, draw, read, context))
COINROLL_FORWARD(egl(), const char*, eglQueryString, (EGLDisplay display, EGLint name), (display, name))
