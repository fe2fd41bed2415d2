#pragma once
// Move-only owners of OpenGL object names, so every buffer, vertex array, framebuffer,
// renderbuffer, shader and program is deleted exactly once, also on error paths. They must be
// destroyed while their context is current (Renderer's member order guarantees it).

#include <utility>

#include "render/gl.h"

namespace coinroll::render {

template <class Deleter>
class GlHandle {
 public:
  GlHandle() = default;
  explicit GlHandle(GLuint name) : name_(name) {}
  ~GlHandle() {
    if (name_ != 0) Deleter{}(name_);
  }
  GlHandle(GlHandle&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
  GlHandle& operator=(GlHandle&& other) noexcept {
    if (this != &other) {
      if (name_ != 0) Deleter{}(name_);
      name_ = std::exchange(other.name_, 0);
    }
    return *this;
  }
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;

  GLuint get() const { return name_; }

 private:
  GLuint name_ = 0;
};

struct BufferDeleter {
  void operator()(GLuint name) const { glDeleteBuffers(1, &name); }
};
struct VertexArrayDeleter {
  void operator()(GLuint name) const { glDeleteVertexArrays(1, &name); }
};
struct FramebufferDeleter {
  void operator()(GLuint name) const { glDeleteFramebuffers(1, &name); }
};
struct RenderbufferDeleter {
  void operator()(GLuint name) const { glDeleteRenderbuffers(1, &name); }
};
struct TextureDeleter {
  void operator()(GLuint name) const { glDeleteTextures(1, &name); }
};
struct ShaderDeleter {
  void operator()(GLuint name) const { glDeleteShader(name); }
};
struct ProgramDeleter {
  void operator()(GLuint name) const { glDeleteProgram(name); }
};

using Buffer = GlHandle<BufferDeleter>;
using VertexArray = GlHandle<VertexArrayDeleter>;
using Framebuffer = GlHandle<FramebufferDeleter>;
using Renderbuffer = GlHandle<RenderbufferDeleter>;
using Texture = GlHandle<TextureDeleter>;
using Shader = GlHandle<ShaderDeleter>;
using Program = GlHandle<ProgramDeleter>;

inline Buffer makeBuffer() {
  GLuint name = 0;
  glGenBuffers(1, &name);
  return Buffer(name);
}
inline VertexArray makeVertexArray() {
  GLuint name = 0;
  glGenVertexArrays(1, &name);
  return VertexArray(name);
}
inline Framebuffer makeFramebuffer() {
  GLuint name = 0;
  glGenFramebuffers(1, &name);
  return Framebuffer(name);
}
inline Texture makeTexture() {
  GLuint name = 0;
  glGenTextures(1, &name);
  return Texture(name);
}
inline Renderbuffer makeRenderbuffer() {
  GLuint name = 0;
  glGenRenderbuffers(1, &name);
  return Renderbuffer(name);
}

}  // namespace coinroll::render
