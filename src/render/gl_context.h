#pragma once
// An OpenGL 3.3 core context with no window, on one of the back ends of gl_backend.h, with the GL
// functions that reach it. coinroll draws into framebuffer objects only, so no back end needs a
// drawable surface.

#include <memory>
#include <stdexcept>

#include "render/gl.h"
#include "render/gl_backend.h"

namespace coinroll::render {

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes this context current on the calling thread (a context is current on one thread at a
  // time). GL calls go to the current context, so call this before drawing whenever another
  // context may have been made current since. Throws std::runtime_error if the back end refuses.
  virtual void makeCurrent() = 0;

  // The functions, resolved through this context's back end; valid while the context lives.
  const GlFunctions& functions() const { return functions_; }
  GlBackend backend() const { return backend_; }

 protected:
  explicit GlContext(GlBackend backend) : backend_(backend) {}
  GlFunctions functions_;  // loaded by the back end once its context is current

 private:
  GlBackend backend_;
};

// Creates a context on `backend` and makes it current. Throws std::invalid_argument if this build
// lacks the back end, std::runtime_error if this machine cannot give the context (naming the back
// end and why), and GlAfterForkError in a child forked after its parent drew. Never substitutes
// another back end.
std::unique_ptr<GlContext> makeGlContext(GlBackend backend);

// Mesa starts llvmpipe's rasterizer threads with the first context and keeps them, with the rest
// of its screen, for the life of the process; no back end lets coinroll make a new screen. A child
// forked after that inherits the screen but not its threads, so its first draw would wait on them
// for ever (a multiprocessing "fork" pool after a render in the parent). The child is refused
// instead. Not when LP_NUM_THREADS=0 held at the parent's first context: then llvmpipe draws on the
// calling thread and a child draws too.
class GlAfterForkError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace coinroll::render
