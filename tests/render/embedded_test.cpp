// The shaders compiled into the binary against shaders/: a binary draws with its embedded copies
// (wherever it runs, checkout or not), so those copies must be the files the source tree holds,
// and the golden tests, which run the embedded copies, then test the source.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "render/embedded_shaders.h"
#include "render/shader_program.h"
#include "scratch_dir.h"

namespace {

namespace fs = std::filesystem;
using coinroll::render::embeddedShader;
using coinroll::render::loadShaderSource;
using coinroll::render::ShaderSource;

const fs::path kShaderDir = fs::path(COINROLL_SOURCE_DIR) / "shaders";

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every stage file of shaders/, as cmake/embed_shaders.cmake globs them.
std::vector<fs::path> sourceShaders() {
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(kShaderDir)) {
    if (entry.path().extension() == ".vert" || entry.path().extension() == ".frag") files.push_back(entry.path());
  }
  return files;
}

TEST(EmbeddedShaders, EveryCopyIsTheSourceFile) {
  const std::vector<fs::path> files = sourceShaders();
  ASSERT_GE(files.size(), 2u) << kShaderDir;
  for (const fs::path& file : files) {
    const std::string name = file.filename().string();
    const std::optional<std::string_view> embedded = embeddedShader(name);
    ASSERT_TRUE(embedded.has_value()) << name << " is not embedded (rerun cmake?)";
    EXPECT_EQ(*embedded, readFile(file)) << name << ": the embedded copy differs from the source file";
  }
  EXPECT_FALSE(embeddedShader("no_such_shader.frag").has_value());
}

TEST(EmbeddedShaders, AreWhatTheRendererReadsByDefault) {
  unsetenv("COINROLL_SHADER_DIR");
  for (const fs::path& file : sourceShaders()) {
    const std::string name = file.filename().string();
    const ShaderSource source = loadShaderSource(name);
    EXPECT_EQ(source.origin, "embedded:" + name);
    EXPECT_EQ(source.text, readFile(file)) << name;
  }
}

TEST(EmbeddedShaders, ADirectoryNamedByTheEnvironmentComesFirst) {
  const coinroll::testing::ScratchDirectory scratch;
  const fs::path edited = scratch / "coin.frag";
  std::ofstream(edited, std::ios::binary) << "// edited\n";
  setenv("COINROLL_SHADER_DIR", scratch.path().c_str(), 1);
  const ShaderSource source = loadShaderSource("coin.frag");
  EXPECT_THROW(loadShaderSource("coin.vert"), std::runtime_error);  // named, so no silent fallback
  unsetenv("COINROLL_SHADER_DIR");
  EXPECT_EQ(source.text, "// edited\n");
  EXPECT_EQ(source.origin, edited.string());
}

}  // namespace
