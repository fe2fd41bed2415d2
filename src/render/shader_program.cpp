#include "render/shader_program.h"

#include <fmt/format.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/gtc/type_ptr.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "render/embedded_shaders.h"

namespace coinroll::render {

namespace {

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("shader: cannot read {}", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Mesa reports "0:12(7): error: ..." (source string 0, line 12, column 7). Rewrite each message
// to "origin:12:7: error: ..." so an editor jumps to it.
std::string withOrigin(const std::string& log, const std::string& origin) {
  static const std::regex mesaPosition(R"(^\d+:(\d+)\((\d+)\): )", std::regex::multiline);
  return std::regex_replace(log, mesaPosition, origin + ":$1:$2: ");
}

Shader compile(GLenum stage, const ShaderSource& source) {
  Shader shader(glCreateShader(stage));
  const char* text = source.text.c_str();
  glShaderSource(shader.get(), 1, &text, nullptr);
  glCompileShader(shader.get());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetShaderiv(shader.get(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader.get(), length, nullptr, log.data());
    throw std::runtime_error(fmt::format("shader {} does not compile:\n{}", source.origin, withOrigin(log, source.origin)));
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

ShaderProgram::ShaderProgram(std::string_view vertexName, std::string_view fragmentName) {
  const ShaderSource vertexSource = loadShaderSource(vertexName);
  const ShaderSource fragmentSource = loadShaderSource(fragmentName);
  const Shader vertex = compile(GL_VERTEX_SHADER, vertexSource);
  const Shader fragment = compile(GL_FRAGMENT_SHADER, fragmentSource);
  program_ = Program(glCreateProgram());
  glAttachShader(program_.get(), vertex.get());
  glAttachShader(program_.get(), fragment.get());
  glLinkProgram(program_.get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program_.get(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(program_.get(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program_.get(), length, nullptr, log.data());
    throw std::runtime_error(fmt::format("shaders {} + {} do not link:\n{}", vertexSource.origin, fragmentSource.origin, log));
  }
}

GLint ShaderProgram::location(const char* uniform) const {
  const GLint where = glGetUniformLocation(program_.get(), uniform);
  // A uniform the compiler optimised away is not an error (e.g. while editing a shader).
  return where;
}

void ShaderProgram::set(const char* uniform, float value) const { glUniform1f(location(uniform), value); }
void ShaderProgram::set(const char* uniform, int value) const { glUniform1i(location(uniform), value); }
void ShaderProgram::set(const char* uniform, const glm::vec2& value) const {
  glUniform2fv(location(uniform), 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* uniform, const glm::vec3& value) const {
  glUniform3fv(location(uniform), 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* uniform, const glm::vec4& value) const {
  glUniform4fv(location(uniform), 1, glm::value_ptr(value));
}
void ShaderProgram::set(const char* uniform, const glm::mat3& value) const {
  glUniformMatrix3fv(location(uniform), 1, GL_FALSE, glm::value_ptr(value));
}
void ShaderProgram::set(const char* uniform, const glm::mat4& value) const {
  glUniformMatrix4fv(location(uniform), 1, GL_FALSE, glm::value_ptr(value));
}

}  // namespace coinroll::render
