#include "pipeline/resources.h"

#include <fmt/format.h>

#include <malloc.h>
#include <pthread.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <thread>

namespace coinroll::pipeline {

namespace {

constexpr std::uint64_t kMiB = 1024 * 1024;

// What the renderer maps, measured with Mesa 22.3 (Debian 12) llvmpipe and one malloc arena
// (fitAllocatorToAddressSpaceLimit) as the smallest limit under which a still is written, less
// the process's size just before the renderer starts: 56.9, 62.1, 95.5 and 169 MiB for a 64x48
// picture with 1, 2, 4 and 8 llvmpipe threads (8 MiB thread stacks), and per pixel about 21 bytes
// plus 8.6 per MSAA sample (1280x720 with 1 and 4 samples: 88 and 111 MiB; 1920x1080 and
// 3840x2160 with 4: 162 and 432 MiB). The constants below are those rounded up, so the estimate
// stays above every measurement (118, 144, 594 MiB for the last three pictures).
constexpr std::uint64_t kGlContextBytes = 48 * kMiB;          // the context without its threads
constexpr std::uint64_t kPerLlvmpipeThreadBytes = 12 * kMiB;  // besides the thread's stack
constexpr std::uint64_t kBytesPerPixel = 24;                  // resolved picture, readback, image
constexpr std::uint64_t kBytesPerSample = 10;                 // colour and depth-stencil, per pixel

std::string mebibytes(std::uint64_t bytes) { return fmt::format("{} MiB", (bytes + kMiB - 1) / kMiB); }

// llvmpipe's rasterizer threads: LP_NUM_THREADS, else one per processor.
std::uint64_t llvmpipeThreads() {
  if (const char* text = std::getenv("LP_NUM_THREADS"); text != nullptr && *text != '\0') {
    char* end = nullptr;
    const unsigned long count = std::strtoul(text, &end, 10);
    if (*end == '\0') return count;
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

// The stack a new thread reserves (glibc takes it from RLIMIT_STACK).
std::uint64_t threadStackBytes() {
  pthread_attr_t attributes;
  std::size_t bytes = 8 * kMiB;
  if (::pthread_getattr_default_np(&attributes) == 0) {
    ::pthread_attr_getstacksize(&attributes, &bytes);
    ::pthread_attr_destroy(&attributes);
  }
  return bytes;
}

}  // namespace

std::optional<std::uint64_t> addressSpaceLimit() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  return static_cast<std::uint64_t>(limit.rlim_cur);
}

std::uint64_t addressSpaceInUse() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  statm >> pages;  // the first field: every page mapped
  return pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

std::string memoryLimitDescription() {
  const std::optional<std::uint64_t> limit = addressSpaceLimit();
  if (!limit) return "the machine's memory";
  return fmt::format("the address-space limit of {} (ulimit -v {})", mebibytes(*limit), *limit / 1024);
}

std::string outOfMemoryMessage() {
  if (addressSpaceLimit()) {
    return fmt::format(
        "out of memory: {} is used up; raise it, or ask for less (a smaller picture, fewer frames "
        "or threads)",
        memoryLimitDescription());
  }
  return "out of memory: the machine's memory is used up; ask for less (a smaller picture, fewer frames or threads), "
         "or free memory";
}

void requireAddressSpace(std::uint64_t bytes, std::string_view what, std::string_view remedy) {
  const std::optional<std::uint64_t> limit = addressSpaceLimit();
  if (!limit) return;
  const std::uint64_t used = addressSpaceInUse();
  const std::uint64_t left = used < *limit ? *limit - used : 0;
  if (left >= bytes) return;
  throw std::runtime_error(
      fmt::format("not enough memory for {}: it needs about {}, and {} of {} are left; raise the "
                  "limit, or {}",
                  what, mebibytes(bytes), mebibytes(left), memoryLimitDescription(), remedy));
}

std::uint64_t rendererAddressSpace(const render::RenderSettings& settings) {
  // Per picture pixel. FXAA: a second picture. SSAA: msaa samples at each of the drawn pixels, and
  // with MSAA those pixels resolved once more at the drawn size.
  const auto drawnPixels = static_cast<std::uint64_t>(render::drawScale(settings) * render::drawScale(settings));
  const std::uint64_t samples = settings.antialiasing == render::Antialiasing::Fxaa
                                    ? 2
                                    : drawnPixels * static_cast<std::uint64_t>(settings.msaa) +
                                          (render::isMultisampled(settings) && drawnPixels > 1 ? drawnPixels : 0);
  // A reused background keeps a second multisampled colour and depth buffer.
  const std::uint64_t perPixel = kBytesPerPixel + kBytesPerSample * samples * (settings.reuseStaticBackground ? 2 : 1);
  const std::uint64_t pixels = static_cast<std::uint64_t>(settings.width) * static_cast<std::uint64_t>(settings.height);
  return kGlContextBytes + llvmpipeThreads() * (threadStackBytes() + kPerLlvmpipeThreadBytes) + pixels * perPixel;
}

void requireRendererAddressSpace(const render::RenderSettings& settings, std::uint64_t encoderBytes) {
  const int samples = settings.antialiasing == render::Antialiasing::Fxaa
                          ? 1
                          : render::drawScale(settings) * render::drawScale(settings) * settings.msaa;
  requireAddressSpace(
      rendererAddressSpace(settings) + encoderBytes,
      fmt::format("{} {}x{} pictures with {} samples per pixel", encoderBytes > 0 ? "drawing and encoding" : "drawing",
                  settings.width, settings.height, samples),
      encoderBytes > 0 ? "draw smaller pictures (render.width, render.height, render.msaa), with fewer "
                         "llvmpipe threads (LP_NUM_THREADS=1) or with a faster render.video.preset"
                       : "draw smaller pictures (render.width, render.height, render.msaa) or with fewer "
                         "llvmpipe threads (LP_NUM_THREADS=1)");
}

void fitAllocatorToAddressSpaceLimit() {
  if (addressSpaceLimit()) ::mallopt(M_ARENA_MAX, 1);
}

}  // namespace coinroll::pipeline
