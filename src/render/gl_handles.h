#pragma once
// Move-only owners of OpenGL object names, so every buffer, vertex array, framebuffer,
// renderbuffer, shader and program is deleted exactly once, also on error paths. Each keeps the
// function table it was made with, and must be destroyed while that table's context is current
// (Renderer's member order and destructor guarantee it).

#include <utility>

#include "render/gl.h"

namespace coinroll::render {

template <class Deleter>
class GlHandle {
 public:
  GlHandle() = default;
  GlHandle(const GlFunctions& gl, GLuint name) : gl_(&gl), name_(name) {}
  ~GlHandle() { release(); }
  GlHandle(GlHandle&& other) noexcept : gl_(other.gl_), name_(std::exchange(other.name_, 0)) {}
  GlHandle& operator=(GlHandle&& other) noexcept {
    if (this != &other) {
      release();
      gl_ = other.gl_;
      name_ = std::exchange(other.name_, 0);
    }
    return *this;
  }
  GlHandle(const GlHandle&) = delete;
  GlHandle& operator=(const GlHandle&) = delete;

  GLuint get() const { return name_; }

 private:
  void release() {
    if (name_ != 0) Deleter{}(*gl_, name_);
  }
  const GlFunctions* gl_ = nullptr;
  GLuint name_ = 0;
};

struct BufferDeleter {
  void operator()(const GlFunctions& gl, GLuint name) const { gl.DeleteBuffers(1, &name); }
};
struct VertexArrayDeleter {
  void operator()(const GlFunctions& gl, GLuint name) const { gl.DeleteVertexArrays(1, &name); }
};
struct FramebufferDeleter {
  void operator()(const GlFunctions& gl, GLuint name) const { gl.DeleteFramebuffers(1, &name); }
};
struct RenderbufferDeleter {
  void operator()(const GlFunctions& gl, GLuint name) const { gl.DeleteRenderbuffers(1, &name); }
};
struct TextureDeleter {
  void operator()(const GlFunctions& gl, GLuint name) const { gl.DeleteTextures(1, &name); }
};
struct ShaderDeleter {
  void operator()(const GlFunctions& gl, GLuint name) const { gl.DeleteShader(name); }
};
struct ProgramDeleter {
  void operator()(const GlFunctions& gl, GLuint name) const { gl.DeleteProgram(name); }
};

using Buffer = GlHandle<BufferDeleter>;
using VertexArray = GlHandle<VertexArrayDeleter>;
using Framebuffer = GlHandle<FramebufferDeleter>;
using Renderbuffer = GlHandle<RenderbufferDeleter>;
using Texture = GlHandle<TextureDeleter>;
using Shader = GlHandle<ShaderDeleter>;
using Program = GlHandle<ProgramDeleter>;

inline Buffer makeBuffer(const GlFunctions& gl) {
  GLuint name = 0;
  gl.GenBuffers(1, &name);
  return Buffer(gl, name);
}
inline VertexArray makeVertexArray(const GlFunctions& gl) {
  GLuint name = 0;
  gl.GenVertexArrays(1, &name);
  return VertexArray(gl, name);
}
inline Framebuffer makeFramebuffer(const GlFunctions& gl) {
  GLuint name = 0;
  gl.GenFramebuffers(1, &name);
  return Framebuffer(gl, name);
}
inline Texture makeTexture(const GlFunctions& gl) {
  GLuint name = 0;
  gl.GenTextures(1, &name);
  return Texture(gl, name);
}
inline Renderbuffer makeRenderbuffer(const GlFunctions& gl) {
  GLuint name = 0;
  gl.GenRenderbuffers(1, &name);
  return Renderbuffer(gl, name);
}

}  // namespace coinroll::render
