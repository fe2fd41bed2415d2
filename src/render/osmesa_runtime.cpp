// OSMesa's context functions, opened at the first call (io/runtime_library.h): OSMesa brings Mesa and
// its LLVM, which only a render needs. GL's own functions come through OSMesaGetProcAddress (gl.h).

#include <GL/osmesa.h>

#include "io/runtime_library.h"

namespace {

coinroll::io::RuntimeLibrary& osmesa() {
  static coinroll::io::RuntimeLibrary library(COINROLL_OSMESA_SONAME, COINROLL_OSMESA_PACKAGE);
  return library;
}

}  // namespace

COINROLL_FORWARD(osmesa(), OSMesaContext, OSMesaCreateContextAttribs, (const int* attributes, OSMesaContext shared),
                 (attributes, shared))
COINROLL_FORWARD(osmesa(), void, OSMesaDestroyContext, (OSMesaContext context), (context))
COINROLL_FORWARD(osmesa(), GLboolean, OSMesaMakeCurrent,
                 (OSMesaContext context, void* buffer, GLenum type, GLsizei width, GLsizei height),
                 (context, buffer, type, width, height))
COINROLL_FORWARD(osmesa(), OSMESAproc, OSMesaGetProcAddress, (const char* name), (name))
