#include "render/shader_program.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/type_ptr.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "render/embedded_shaders.h"

namespace coinroll::render {

namespace {

// $COINROLL_SHADER_DIR is a developer's override: say which file, and why it cannot be read,
// rather than hand the compiler an empty source (a directory opens as a stream that reads nothing).
std::string readFile(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw std::runtime_error(
        fmt::format("shader: {} is a directory; $COINROLL_SHADER_DIR must hold the shader files "
                    "(e.g. the checkout's shaders/), or unset it for the built-in ones",
                    path.string()));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw std::runtime_error(
        fmt::format("shader: cannot read {}: {} ($COINROLL_SHADER_DIR names the directory it is "
                    "read from; unset it for the built-in shaders)",
                    path.string(), std::strerror(errno)));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad())
    throw std::runtime_error(fmt::format("shader: reading {} failed: {}", path.string(), std::strerror(errno)));
  return text.str();
}

// Mesa reports "0:12(7): error: ..." (source string 0, line 12, column 7). Rewrite each message
// to "origin:12:7: error: ..." so an editor jumps to it.
std::string withOrigin(const std::string& log, const std::string& origin) {
  static const std::regex mesaPosition(R"(^\d+:(\d+)\((\d+)\): )", std::regex::multiline);
  return std::regex_replace(log, mesaPosition, origin + ":$1:$2: ");
}

Shader compile(const GlFunctions& gl, GLenum stage, const ShaderSource& source) {
  Shader shader(gl, gl.CreateShader(stage));
  const char* text = source.text.c_str();
  gl.ShaderSource(shader.get(), 1, &text, nullptr);
  gl.CompileShader(shader.get());
  GLint ok = GL_FALSE;
  gl.GetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    gl.GetShaderiv(shader.get(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    gl.GetShaderInfoLog(shader.get(), length, nullptr, log.data());
    throw std::runtime_error(
        fmt::format("shader {} does not compile:\n{}", source.origin, withOrigin(log, source.origin)));
  }
  return shader;
}

}  // namespace

ShaderSource loadShaderSource(std::string_view name) {
  if (const char* dir = std::getenv("COINROLL_SHADER_DIR"); dir != nullptr && *dir != '\0') {
    const std::filesystem::path path = std::filesystem::path(dir) / name;
    return {readFile(path), path.string()};
  }
  const std::optional<std::string_view> embedded = embeddedShader(name);
  if (!embedded) throw std::runtime_error(fmt::format("shader: no shader named {}", name));
  return {std::string(*embedded), fmt::format("embedded:{}", name)};
}

ShaderProgram::ShaderProgram(const GlFunctions& gl, std::string_view vertexName, std::string_view fragmentName)
    : gl_(&gl) {
  const ShaderSource vertexSource = loadShaderSource(vertexName);
  const ShaderSource fragmentSource = loadShaderSource(fragmentName);
  const Shader vertex = compile(gl, GL_VERTEX_SHADER, vertexSource);
  const Shader fragment = compile(gl, GL_FRAGMENT_SHADER, fragmentSource);
  program_ = Program(gl, gl.CreateProgram());
  gl.AttachShader(program_.get(), vertex.get());
  gl.AttachShader(program_.get(), fragment.get());
  gl.LinkProgram(program_.get());
  GLint ok = GL_FALSE;
  gl.GetProgramiv(program_.get(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    gl.GetProgramiv(program_.get(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    gl.GetProgramInfoLog(program_.get(), length, nullptr, log.data());
    throw std::runtime_error(
        fmt::format("shaders {} + {} do not link:\n{}", vertexSource.origin, fragmentSource.origin, log));
  }
}

GLint ShaderProgram::location(const char* uniform) const {
  const GLint where = gl_->GetUniformLocation(program_.get(), uniform);
  // A uniform the compiler optimised away is not an error (e.g. while editing a shader).
  return where;
}

void ShaderProgram::set(const char* uniform, float value) const { gl_->Uniform1f(location(uniform), value); }
void ShaderProgram::set(const char* uniform, int value) const { gl_->Uniform1i(location(uniform), value); }
void ShaderProgram::set(const char* uniform, const glm::vec2& value) const {
  gl_->Uniform2fv(location(uniform), 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* uniform, const glm::vec3& value) const {
  gl_->Uniform3fv(location(uniform), 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* uniform, const glm::vec4& value) const {
  gl_->Uniform4fv(location(uniform), 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* uniform, const glm::mat3& value) const {
  gl_->UniformMatrix3fv(location(uniform), 1, GL_FALSE, glm::value_ptr(value));
}
void ShaderProgram::set(const char* uniform, const glm::mat4& value) const {
  gl_->UniformMatrix4fv(location(uniform), 1, GL_FALSE, glm::value_ptr(value));
}

}  // namespace coinroll::render
