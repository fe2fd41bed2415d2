#pragma once
// coinroll's C++ API: load a scene, simulate it to the trajectory CSV's columns, render a still
// into memory or a video into a file. The same scenes, numbers and pixels as the command line
// (`coinroll simulate`, `still`, `render`); the scene format is the README's "Scene format".
//
//   find_package(coinroll REQUIRED)            or   pkg-config --cflags --libs coinroll
//   target_link_libraries(app PRIVATE coinroll::coinroll)
//
// Errors are exceptions: std::invalid_argument for a bad scene or request (the message names the
// field and the fix, as the command line's exit 2), std::runtime_error for a run or an output that
// fails. A failed render leaves no file behind.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

// The library is built with hidden visibility; everything declared here is its exported API.
#pragma GCC visibility push(default)

namespace coinroll {

// "0.1.0": the release this library is.
std::string version();

// A validated scene. Cheap to copy (the scene is shared and never changes).
class Scene {
 public:
  // `overrides` are the command line's --set, KEY.PATH=VALUE ("initial.theta=12").
  static Scene fromFile(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
  static Scene fromJson(std::string_view json, const std::vector<std::string>& overrides = {});
  // The built-in default scene (what `coinroll render` draws without a scene file).
  static Scene builtInDefault(const std::vector<std::string>& overrides = {});

  std::string name() const;
  double duration() const;  // s of simulated time

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  explicit Scene(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  std::shared_ptr<const Impl> impl_;
};

// The trajectory CSV as columns: names[i] is the CSV's header field i, values[i] its column, one
// entry per sample t = k sampleDt (and the same doubles the CSV prints).
struct Columns {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;

  std::size_t rows() const { return values.empty() ? 0 : values.front().size(); }
  // The column named `name` ("t", "theta", "energy", ...); std::out_of_range naming it if absent.
  const std::vector<double>& operator[](std::string_view name) const;
};

// Integrates the scene and samples it every `sampleDt` seconds (the CSV's --sample-dt).
Columns simulate(const Scene& scene, double sampleDt = 0.01);

// An 8-bit RGBA picture, rows from the top, width * height * 4 bytes.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
};

// The picture `coinroll still --time` draws at `time` seconds (clamped to where the run stopped,
// if a validity event ended it first).
Image renderStill(const Scene& scene, double time);

// The clip `coinroll render -o output` writes; the kind follows the extension (.mp4, or a
// %d pattern for a PNG sequence). The file appears only once it is complete.
void renderVideo(const Scene& scene, const std::filesystem::path& output);

}  // namespace coinroll

#pragma GCC visibility pop
