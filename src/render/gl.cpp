#include "render/gl.h"

#include <fmt/format.h>

#include <stdexcept>

namespace coinroll::render {

GlFunctions loadGlFunctions(GlProcedureLookup lookup, const char* backendName) {
  GlFunctions functions;
  const auto resolve = [&](const char* name) {
    const GlProcedure procedure = lookup(name);
    if (procedure == nullptr)
      throw std::runtime_error(fmt::format("OpenGL ({}): the function {} is missing", backendName, name));
    return procedure;
  };
#define COINROLL_GL_LOAD(type, name) functions.name = reinterpret_cast<type>(resolve("gl" #name));
  COINROLL_GL_FUNCTIONS(COINROLL_GL_LOAD)
#undef COINROLL_GL_LOAD
  return functions;
}

}  // namespace coinroll::render
