#pragma once
// GLSL programs built from the files in shaders/ (one file per stage). Sources are the copies
// embedded at build time, so a binary draws the same pixels wherever it runs and whether or not
// its checkout still exists; $COINROLL_SHADER_DIR, when set, names a directory to read them from
// instead (edit and rerun, no rebuild).

#include <glm/glm.hpp>
#include <string>
#include <string_view>

#include "render/gl_handles.h"

namespace coinroll::render {

// The text of shaders/<name> and where it came from (for error messages).
struct ShaderSource {
  std::string text;
  std::string origin;  // a path, or "embedded:<name>"
};

// Throws std::runtime_error if $COINROLL_SHADER_DIR is set and the file there is unreadable, or
// if `name` is not embedded.
ShaderSource loadShaderSource(std::string_view name);

class ShaderProgram {
 public:
  // Compiles shaders/<vertexName> and shaders/<fragmentName> and links them, in the context `gl`
  // reaches (current, and outliving the program). Compile and link errors throw
  // std::runtime_error with the file and line of each message ("coin.frag:12: ...").
  ShaderProgram(const GlFunctions& gl, std::string_view vertexName, std::string_view fragmentName);

  void use() const { gl_->UseProgram(program_.get()); }
  void set(const char* uniform, float value) const;
  void set(const char* uniform, int value) const;
  void set(const char* uniform, const glm::vec2& value) const;
  void set(const char* uniform, const glm::vec3& value) const;
  void set(const char* uniform, const glm::vec4& value) const;
  void set(const char* uniform, const glm::mat3& value) const;
  void set(const char* uniform, const glm::mat4& value) const;

 private:
  GLint location(const char* uniform) const;
  const GlFunctions* gl_;
  Program program_;
};

}  // namespace coinroll::render
