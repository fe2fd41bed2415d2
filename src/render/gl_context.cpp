#include "render/gl_context.h"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <stdexcept>

#if COINROLL_HAVE_OSMESA
#include "render/osmesa_context.h"
#endif
#if COINROLL_HAVE_EGL
#include "render/egl_context.h"
#endif

namespace coinroll::render {

namespace {

// What the process's first context started (gl_context.h, GlAfterForkError): 0 before it, then the
// pid of the process whose first context started Mesa's threads, or kNoGlThreads where it started
// none (Mesa's screen keeps the count it was made with). A forked child reads its parent's value.
constexpr pid_t kNoGlThreads = -1;
std::atomic<pid_t> processThatStartedGlThreads{0};

// Mesa reads LP_NUM_THREADS as a C integer of any base; only 0 keeps llvmpipe on the calling thread.
bool llvmpipeStartsThreads() {
  const char* text = std::getenv("LP_NUM_THREADS");
  if (text == nullptr || *text == '\0') return true;
  char* end = nullptr;
  const long count = std::strtol(text, &end, 0);
  return end == text || count != 0;
}

void refuseAfterFork() {
  const pid_t parent = processThatStartedGlThreads.load();
  if (parent == 0 || parent == kNoGlThreads || parent == ::getpid()) return;
  throw GlAfterForkError(fmt::format(
      "cannot draw in this process (pid {}): it was forked from process {} after that process had drawn, and "
      "Mesa's rendering threads stay in the parent. Start worker processes before the first render or still, or "
      "with the 'spawn' or 'forkserver' start method (Python: multiprocessing.get_context('spawn')), or set "
      "LP_NUM_THREADS=0 in the parent before its first draw (llvmpipe then draws on the calling thread)",
      ::getpid(), parent));
}

std::unique_ptr<GlContext> makeContextOn(GlBackend backend) {
  switch (backend) {
#if COINROLL_HAVE_OSMESA
    case GlBackend::OsMesa: return makeOsMesaContext();
#endif
#if COINROLL_HAVE_EGL
    case GlBackend::Egl: return makeEglSurfacelessContext();
    case GlBackend::EglDevice: return makeEglDeviceContext();
#endif
    default: break;
  }
  throw std::logic_error("makeGlContext: a compiled-in back end without a factory");
}

}  // namespace

std::unique_ptr<GlContext> makeGlContext(GlBackend backend) {
  requireCompiledIn(backend);
  refuseAfterFork();
  std::unique_ptr<GlContext> context = makeContextOn(backend);
  pid_t beforeTheFirst = 0;
  processThatStartedGlThreads.compare_exchange_strong(beforeTheFirst,
                                                      llvmpipeStartsThreads() ? ::getpid() : kNoGlThreads);
  return context;
}

}  // namespace coinroll::render
