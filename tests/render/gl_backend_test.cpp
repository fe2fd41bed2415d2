// The OpenGL back ends (render/gl_backend.h, docs/usage.md "OpenGL back ends"): $COINROLL_GL's
// values and refusals, the same bytes from osmesa and egl (both llvmpipe) with their contexts alive
// side by side, and egl-device refusing a machine without a GPU instead of falling back. The
// goldens themselves run once per back end (tests/CMakeLists.txt registers them again under
// COINROLL_GL=egl).

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <glm/gtc/quaternion.hpp>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "render/gl_backend.h"
#include "render/gl_context.h"
#include "image_compare.h"
#include "render/renderer.h"

namespace {

using namespace coinroll::render;
using coinroll::image::Image;

constexpr GlBackend kAllBackends[] = {GlBackend::OsMesa, GlBackend::Egl, GlBackend::EglDevice};

std::string refusal(std::string_view value) {
  try {
    parseGlBackend(value);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// Sets or unsets $COINROLL_GL until the end of the scope, then restores it: render_test may run as
// one process (CI's build without OSMesa does), where later tests read the variable.
class ScopedGlVariable {
 public:
  ScopedGlVariable() {
    if (const char* value = std::getenv("COINROLL_GL")) saved_ = value;
  }
  ~ScopedGlVariable() { set(saved_ ? saved_->c_str() : nullptr); }
  ScopedGlVariable(const ScopedGlVariable&) = delete;
  ScopedGlVariable& operator=(const ScopedGlVariable&) = delete;

  void set(const char* value) const {
    if (value == nullptr) {
      unsetenv("COINROLL_GL");
    } else {
      setenv("COINROLL_GL", value, 1);
    }
  }

 private:
  std::optional<std::string> saved_;
};

TEST(GlBackendNames, EachCompiledBackEndParsesFromItsName) {
  ASSERT_FALSE(compiledBackends().empty());
  for (const GlBackend backend : kAllBackends) {
    if (isCompiledIn(backend)) {
      EXPECT_EQ(parseGlBackend(glBackendName(backend)), backend) << glBackendName(backend);
    }
  }
  // egl and egl-device are one library: both or neither.
  EXPECT_EQ(isCompiledIn(GlBackend::Egl), isCompiledIn(GlBackend::EglDevice));
}

TEST(GlBackendNames, AnUnknownValueIsRefusedNamingTheVariableAndTheAcceptedValues) {
  for (const char* value : {"bogus", "EGL", "OSMesa", "egl ", "gpu"}) {
    const std::string message = refusal(value);
    EXPECT_NE(message.find(std::string("COINROLL_GL=") + value + ":"), std::string::npos) << message;
    EXPECT_NE(message.find("accepted values"), std::string::npos) << message;
    for (const std::string_view name : compiledBackends()) EXPECT_NE(message.find(name), std::string::npos) << message;
  }
}

// Vacuous where every back end is built; the CI's build without OSMesa runs it for real.
TEST(GlBackendNames, ABackEndThisBuildLacksIsRefusedNamingItsCMakeOption) {
  for (const GlBackend backend : kAllBackends) {
    if (isCompiledIn(backend)) continue;
    const std::string message = refusal(glBackendName(backend));
    EXPECT_NE(message.find("built without"), std::string::npos) << message;
    EXPECT_NE(message.find(backend == GlBackend::OsMesa ? "COINROLL_WITH_OSMESA" : "COINROLL_WITH_EGL"),
              std::string::npos)
        << message;
  }
}

TEST(GlBackendNames, TheDefaultIsOsmesaWhereCompiledInElseEglNeverAGpu) {
  EXPECT_EQ(defaultGlBackend(), isCompiledIn(GlBackend::OsMesa) ? GlBackend::OsMesa : GlBackend::Egl);
  const ScopedGlVariable variable;
  variable.set(nullptr);
  EXPECT_EQ(selectedGlBackend(), defaultGlBackend());
  variable.set("");  // set but empty, as `COINROLL_GL= coinroll ...` leaves it: the default
  EXPECT_EQ(selectedGlBackend(), defaultGlBackend());
}

TEST(GlBackendNames, TheVersionLineNamesTheCompiledBackEndsAndTheSelectedOne) {
  const ScopedGlVariable variable;
  variable.set(nullptr);
  const std::string compiled = "OpenGL back ends: " + std::string(compiledBackends().front());
  EXPECT_EQ(glBackendsLine().rfind(compiled, 0), 0u) << glBackendsLine();
  EXPECT_NE(glBackendsLine().find("; default " + std::string(glBackendName(defaultGlBackend()))), std::string::npos)
      << glBackendsLine();
  const std::string_view last = compiledBackends().back();
  variable.set(std::string(last).c_str());
  EXPECT_NE(glBackendsLine().find("; COINROLL_GL selects " + std::string(last)), std::string::npos) << glBackendsLine();
  variable.set("bogus");
  EXPECT_NE(glBackendsLine().find("; COINROLL_GL=bogus: not an OpenGL back end; accepted values: "), std::string::npos)
      << glBackendsLine();
  EXPECT_THROW({ const Renderer renderer{RenderSettings{}}; }, std::invalid_argument);
}

// A frame that takes every path of the renderer: floor, shadow with ghosts, trace, contact
// marker, the coin and its ghosts, the overlay.
FrameSnapshot busySnapshot(float time) {
  const auto attitude = [](float theta, float phi, float psi) {
    return glm::angleAxis(phi, glm::vec3(0, 1, 0)) * glm::angleAxis(theta, glm::vec3(1, 0, 0)) *
           glm::angleAxis(psi, glm::vec3(0, 0, 1));
  };
  FrameSnapshot s;
  s.camera = {{0.0f, 0.20f, 0.30f}, {0.0f, 0.0f, 0.0f}, 35.0f};
  for (int k = 0; k <= 120; ++k) {
    const float a = 1.5f * std::numbers::pi_v<float> * static_cast<float>(k) / 120 + time;
    s.trace.emplace_back(0.06f * std::cos(a), 0.06f * std::sin(a));
  }
  s.traceWidth = 0.002f;
  s.coin = {glm::vec3(s.trace.back().x, 0.034f, s.trace.back().y), attitude(0.45f, time, 5 * time)};
  for (int g = 0; g < 3; ++g) {
    const glm::vec2 at = s.trace[static_cast<std::size_t>(40 * g)];
    s.ghosts.push_back(
        {glm::vec3(at.x, 0.034f, at.y), attitude(0.45f, 0.5f * static_cast<float>(g), 0.3f * static_cast<float>(g))});
  }
  s.hudLines = {"t        1.000 s", "tilt     25.00 deg"};
  return s;
}

RenderSettings smallSettings(Antialiasing antialiasing) {
  RenderSettings s;
  s.width = 320;
  s.height = 180;
  s.antialiasing = antialiasing;
  return s;
}

// Both renderers alive at once and drawing in turn, so each draw follows the other context's.
// Their GL objects have the same names and contents, so a call reaching the other context (the
// hazard of OSMesa and EGL in one program: they share Mesa's current-context slot) would still
// draw the same picture; it shows once that context is gone, so each in turn is destroyed while
// the other draws on. Moving frames, then still ones (the background cache), MSAA, FXAA and SSAA.
TEST(GlBackends, OsmesaAndEglDrawTheSameBytesSideBySide) {
  if (!isCompiledIn(GlBackend::OsMesa) || !isCompiledIn(GlBackend::Egl)) GTEST_SKIP() << "needs both osmesa and egl";
  for (const Antialiasing antialiasing : {Antialiasing::Msaa, Antialiasing::Fxaa, Antialiasing::Ssaa}) {
    for (const GlBackend survivor : {GlBackend::Egl, GlBackend::OsMesa}) {
      std::optional<Renderer> osmesa(std::in_place, smallSettings(antialiasing), GlBackend::OsMesa);
      std::optional<Renderer> egl(std::in_place, smallSettings(antialiasing), GlBackend::Egl);
      EXPECT_EQ(osmesa->backend(), GlBackend::OsMesa);
      EXPECT_EQ(egl->backend(), GlBackend::Egl);
      for (const float time : {0.0f, 0.4f, 0.8f, 0.8f, 0.8f}) {
        const Image fromOsmesa = osmesa->draw(busySnapshot(time));
        const Image fromEgl = egl->draw(busySnapshot(time));
        ASSERT_EQ(fromOsmesa.rgba, fromEgl.rgba)
            << "t = " << time << ": checksums " << coinroll::testing::pixelChecksum(fromOsmesa) << " (osmesa), "
            << coinroll::testing::pixelChecksum(fromEgl) << " (egl)";
      }
      Renderer& kept = survivor == GlBackend::Egl ? *egl : *osmesa;
      const Image before = kept.draw(busySnapshot(1.2f));
      ASSERT_EQ(before.rgba[3], 255) << "an opaque picture";
      (survivor == GlBackend::Egl ? osmesa : egl).reset();
      EXPECT_EQ(kept.draw(busySnapshot(1.2f)).rgba, before.rgba)
          << glBackendName(survivor) << " after the other was destroyed";
    }
  }
}

// This machine has no GPU (CI's neither); with one, the test cannot check the refusal and says so.
TEST(GlBackends, EglDeviceWithoutAGpuFailsSayingSoAndNeverFallsBack) {
  if (!isCompiledIn(GlBackend::EglDevice)) GTEST_SKIP() << "built without EGL";
  std::string message;
  try {
    Renderer renderer(smallSettings(Antialiasing::Msaa), GlBackend::EglDevice);
    EXPECT_EQ(renderer.backend(), GlBackend::EglDevice);
    EXPECT_EQ(renderer.draw(busySnapshot(0)).width, 320);
    GTEST_SKIP() << "EGL lists a GPU here: egl-device drew on it (its bytes are not llvmpipe's; not compared)";
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("COINROLL_GL=egl-device: no GPU"), std::string::npos) << message;
  EXPECT_NE(message.find("never falls back"), std::string::npos) << message;
  EXPECT_NE(message.find("untested on GPU hardware"), std::string::npos) << message;
}

// A multiprocessing "fork" pool's child, forked after its parent drew, waited for ever on
// llvmpipe's threads, which stayed in the parent (docs/usage.md "Python"). It is refused now,
// within the child's alarm (on the old code the alarm kills it). Where the parent's Mesa draws on
// one thread there is nothing to refuse, and the child must draw; that case needs a process whose
// first draw is under LP_NUM_THREADS=0, so it lives in tests/python/test_doors.py.
TEST(GlBackends, AChildForkedAfterADrawIsRefusedNotLeftWaiting) {
  if (const char* threads = std::getenv("LP_NUM_THREADS"); threads != nullptr && std::string(threads) == "0") {
    GTEST_SKIP() << "LP_NUM_THREADS=0: llvmpipe starts no threads, so a forked child may draw";
  }
  Renderer parent(smallSettings(Antialiasing::Msaa), selectedGlBackend());
  ASSERT_EQ(parent.draw(busySnapshot(0)).width, 320);
  enum ChildEnd { Refused = 0, RefusedWithoutNamingTheFix = 1, OtherError = 2, Drew = 3 };
  const pid_t child = ::fork();
  ASSERT_GE(child, 0) << "fork failed";
  if (child == 0) {
    ::alarm(30);
    try {
      Renderer inChild(smallSettings(Antialiasing::Msaa), selectedGlBackend());
      inChild.draw(busySnapshot(0));
      ::_exit(Drew);
    } catch (const GlAfterForkError& e) {
      const std::string message = e.what();
      const bool namesTheFix =
          message.find("'spawn'") != std::string::npos && message.find("LP_NUM_THREADS=0") != std::string::npos;
      ::_exit(namesTheFix ? Refused : RefusedWithoutNamingTheFix);
    } catch (...) {
      ::_exit(OtherError);
    }
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  const bool alarmed = WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM;
  ASSERT_TRUE(WIFEXITED(status)) << "the child was killed by signal " << WTERMSIG(status)
                                 << (alarmed ? " (the alarm: it waited on its parent's threads)" : "");
  EXPECT_EQ(WEXITSTATUS(status), Refused) << "0 refused, 1 refused without naming the fix, 2 another error, 3 drew";
  EXPECT_EQ(parent.draw(busySnapshot(0)).width, 320) << "the parent draws on";
}

}  // namespace
