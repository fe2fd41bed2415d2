// $COINROLL_GL from outside (docs/usage.md "OpenGL back ends"): every example's still and a short
// clip are the same bytes on osmesa and egl, a bad value is refused before anything is written, and
// egl-device on a machine without a GPU fails saying so instead of drawing on the CPU.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "cli/run_command.h"
#include "render/gl_backend.h"
#include "scratch_dir.h"

namespace {

namespace fs = std::filesystem;

using coinroll::render::defaultGlBackend;
using coinroll::render::GlBackend;
using coinroll::render::glBackendName;
using coinroll::render::isCompiledIn;
using coinroll::testing::runCoinroll;
using coinroll::testing::RunResult;

class GlBackendCliTest : public coinroll::testing::ScratchDirTest {
 protected:
  std::vector<std::string> leftovers() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename().string());
    return names;
  }
};

std::string bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// The built-in default scene ("") and every example.
std::vector<std::string> scenes() {
  std::set<std::string> examples;
  for (const auto& entry : fs::directory_iterator(fs::path(COINROLL_SOURCE_DIR) / "examples")) {
    if (entry.path().extension() == ".json") examples.insert(entry.path().string());
  }
  std::vector<std::string> all = {""};
  all.insert(all.end(), examples.begin(), examples.end());
  return all;
}

// One second of each scene at 160x90 and 10 fps keeps the clips cheap; the stills are at the
// goldens' size, overlay on.
TEST_F(GlBackendCliTest, EveryExampleStillAndClipIsTheSameBytesOnOsmesaAndEgl) {
  if (!isCompiledIn(GlBackend::OsMesa) || !isCompiledIn(GlBackend::Egl)) GTEST_SKIP() << "needs both osmesa and egl";
  for (const std::string& scene : scenes()) {
    const std::string name = scene.empty() ? "default" : fs::path(scene).stem().string();
    for (const char* kind : {"still", "clip"}) {
      std::string bytes[2];
      for (int i = 0; i < 2; ++i) {
        const char* backend = i == 0 ? "osmesa" : "egl";
        const fs::path out = dir_ / (name + "_" + backend + (std::string(kind) == "still" ? ".png" : ".mp4"));
        const std::string arguments =
            std::string(kind) == "still"
                ? "still " + scene + " --time 0.5 -o " + out.string() +
                      " --set render.width=320 --set render.height=180"
                : "render " + scene + " -q -o " + out.string() +
                      " --set duration=1 --set render.width=160 --set render.height=90 --set render.fps=10";
        const RunResult r = runCoinroll(arguments, std::string("COINROLL_GL=") + backend);
        ASSERT_EQ(r.exitCode, 0) << name << " " << kind << " on " << backend << ": " << r.output;
        bytes[i] = bytesOf(out);
        ASSERT_FALSE(bytes[i].empty()) << out;
      }
      EXPECT_TRUE(bytes[0] == bytes[1]) << name << ": the " << kind << " differs between osmesa and egl";
    }
  }
}

TEST_F(GlBackendCliTest, AnUnknownValueIsRefusedWithExitTwoBeforeAnythingIsWritten) {
  for (const std::string& command : {"still --time 0.5 -o " + (dir_ / "still.png").string(),
                                     "render -q -o " + (dir_ / "clip.mp4").string() + " --set duration=0.2"}) {
    const RunResult r = runCoinroll(command, "COINROLL_GL=bogus");
    EXPECT_EQ(r.exitCode, 2) << command << ": " << r.output;
    EXPECT_NE(r.output.find("COINROLL_GL=bogus: not an OpenGL back end; accepted values: "), std::string::npos)
        << r.output;
    for (const std::string_view name : coinroll::render::compiledBackends()) {
      EXPECT_NE(r.output.find(name), std::string::npos) << r.output;
    }
    EXPECT_TRUE(leftovers().empty()) << command << " left " << leftovers().front();
  }
}

TEST_F(GlBackendCliTest, EglDeviceWithoutAGpuExitsOneSayingSoAndWritesNothing) {
  if (!isCompiledIn(GlBackend::EglDevice)) GTEST_SKIP() << "built without EGL";
  const RunResult r = runCoinroll("still --time 0.5 -o " + (dir_ / "gpu.png").string(), "COINROLL_GL=egl-device");
  if (r.exitCode == 0) GTEST_SKIP() << "EGL lists a GPU here: egl-device drew on it";
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("COINROLL_GL=egl-device: no GPU"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("untested on GPU hardware"), std::string::npos) << r.output;
  EXPECT_TRUE(leftovers().empty()) << "left " << leftovers().front();
}

// docs/contract.md: `coinroll VERSION` (and the git revision from a checkout), then the back ends
// compiled in and the one COINROLL_GL selects, without opening a GL context: egl-device without a
// GPU, which fails any drawing here, still answers.
TEST_F(GlBackendCliTest, VersionNamesTheReleaseTheRevisionAndTheBackEndsWithoutAContext) {
  RunResult r = runCoinroll("--version");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::string firstLine = r.output.substr(0, r.output.find('\n'));
  EXPECT_TRUE(std::regex_match(firstLine, std::regex(R"(coinroll \d+\.\d+\.\d+( \(git [0-9a-f]{7,}(-dirty)?\))?)")))
      << firstLine;
  const auto listStart = r.output.find("OpenGL back ends: ");
  ASSERT_NE(listStart, std::string::npos) << r.output;
  const std::string list = r.output.substr(listStart + 18, r.output.find(';', listStart) - listStart - 18) + ",";
  for (const GlBackend backend : {GlBackend::OsMesa, GlBackend::Egl, GlBackend::EglDevice}) {
    const bool listed =
        ("," + list).find(std::string(" ") + std::string(glBackendName(backend)) + ",") != std::string::npos ||
        list.starts_with(std::string(glBackendName(backend)) + ",");
    EXPECT_EQ(listed, isCompiledIn(backend)) << glBackendName(backend) << ": " << r.output;
  }
  EXPECT_NE(r.output.find("; default " + std::string(glBackendName(defaultGlBackend()))), std::string::npos)
      << r.output;

  if (isCompiledIn(GlBackend::EglDevice)) {
    r = runCoinroll("--version", "COINROLL_GL=egl-device");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("COINROLL_GL selects egl-device"), std::string::npos) << r.output;
  }
  // A bad value is said, and the version still printed: only drawing refuses it (docs/usage.md
  // "OpenGL back ends").
  r = runCoinroll("--version", "COINROLL_GL=bogus");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(r.output.starts_with("coinroll ")) << r.output;
  EXPECT_NE(r.output.find("COINROLL_GL=bogus: not an OpenGL back end"), std::string::npos) << r.output;
}

}  // namespace
