// Anti-aliasing measured as quality per cost (docs/quality.md "Anti-aliasing"): for each picture
// the program makes, each method's error against a supersampled reference on the pixels where
// anti-aliasing matters, beside its cost per frame, on each llvmpipe back end this build has.
//
// Reference: the same snapshot drawn at 4x the width and height with the most MSAA samples the
// OpenGL allows and box-filtered down (64 samples per pixel on llvmpipe). Error: a pixel's RGB
// distance to the reference over sqrt(3) (the RMS over channels, 8-bit levels), its mean and 99th
// percentile over edge pixels (where the reference differs from a 4-neighbour by more than
// kEdgeContrast levels in a channel: the coin's silhouette, the rim's stripes, the trace, the grid
// lines), and its mean over every pixel. The overlay is left out of the error: it is drawn after
// anti-aliasing in every method, and at 4x the size its glyphs would be other glyphs.
//
// Cost: the median over `repeats` draws of the full snapshot (overlay included), the methods taken
// in turn round after round so that the load of a shared machine falls on all of them alike, as a
// ratio to 4x MSAA (today's default) on the same picture and back end. A fixed camera's video frame
// is drawn with the background reused, as `render` draws it; a still and a moving camera's frame
// shade it every time.
//
// Run: build/bench/antialias_quality [--repeats N] [--csv FILE]   (markdown table on stdout; FILE
// defaults to docs/data/antialias_quality.csv, run from the checkout)
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "image_compare.h"
#include "pipeline/run_record.h"
#include "pipeline/simulation.h"
#include "pipeline/snapshot.h"
#include "render/gl_backend.h"
#include "render/gl_context.h"
#include "render/gl_handles.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"

namespace {

using namespace coinroll;
using render::Antialiasing;

// 8-bit levels: a step between neighbours this large is an edge a viewer sees; flat floor and
// shading gradients stay below it.
constexpr double kEdgeContrast = 24;
constexpr int kReferenceScale = 4;  // the reference's width and height, times the picture's

struct Picture {
  std::string name;
  scene::SceneConfig scene;
  double time = 0;  // s of simulated time shown
  bool isVideoFrame = false;
};

struct Method {
  std::string name;
  Antialiasing antialiasing = Antialiasing::Msaa;
  int msaa = 1;
};

std::vector<Method> methods() {
  return {{"none", Antialiasing::Msaa, 1},
          {"msaa 2x", Antialiasing::Msaa, 2},
          {"msaa 4x", Antialiasing::Msaa, 4},
          {"msaa 8x", Antialiasing::Msaa, 8},
          {"fxaa", Antialiasing::Fxaa, 1},
          {"ssaa 2x2", Antialiasing::Ssaa, 1},
          {"ssaa 2x2 + msaa 4x", Antialiasing::Ssaa, 4}};
}

std::vector<Picture> pictures() {
  std::vector<Picture> list;
  const scene::SceneConfig defaultScene = scene::parseScene(scene::builtInDefaultScene(), "default");
  // Half-way through the default 12 s clip: the trace is half a circle, the coin tilted towards the camera.
  list.push_back({"default, video frame", defaultScene, 0.5 * defaultScene.duration, true});
  // The example's follow camera sits 6 mm above the floor: the finale seen edge-on, where the
  // silhouette is a thin sliver and every stair step shows.
  list.push_back({"euler_disk finale, grazing", scene::loadScene(COINROLL_SOURCE_DIR "/examples/euler_disk.json", {}),
                  98.0, true});
  list.push_back({"still with trace", defaultScene, defaultScene.duration, false});
  nlohmann::json paper = scene::builtInDefaultScene();
  scene::applyOverride(paper, "render.theme=paper");
  const scene::SceneConfig paperScene = scene::parseScene(paper, "paper");
  list.push_back({"still, paper theme", paperScene, paperScene.duration, false});
  return list;
}

render::FrameSnapshot snapshotOf(const Picture& picture) {
  const pipeline::Simulation simulation = pipeline::buildSimulation(picture.scene);
  pipeline::FixedFrameTimes times({picture.time});
  const pipeline::RunRecord record = pipeline::recordRun(simulation, times);
  if (record.frames.empty()) throw std::runtime_error(fmt::format("{}: no frame at {} s", picture.name, picture.time));
  pipeline::SnapshotMaker maker(picture.scene, simulation.model, record);
  return maker.makeSnapshot(record.frames.back());
}

std::vector<double> rgb(const image::Image& picture, int scale) { return testing::boxDownsample(picture, scale); }

struct ErrorFigures {
  double edgeMean = 0, edgeP99 = 0, allMean = 0, edgePsnr = 0;
  double edgeShare = 0;  // of all pixels
};

// Edge pixels: where the reference differs from a 4-neighbour by more than kEdgeContrast.
std::vector<bool> edgeMask(const std::vector<double>& reference, int width, int height) {
  std::vector<bool> mask(std::size_t(width) * height, false);
  const auto at = [&](int x, int y, int c) { return reference[(std::size_t(y) * width + x) * 3 + c]; };
  for (int y = 1; y + 1 < height; ++y) {
    for (int x = 1; x + 1 < width; ++x) {
      double contrast = 0;
      for (int c = 0; c < 3; ++c) {
        contrast = std::max({contrast, std::abs(at(x, y, c) - at(x + 1, y, c)), std::abs(at(x, y, c) - at(x - 1, y, c)),
                             std::abs(at(x, y, c) - at(x, y + 1, c)), std::abs(at(x, y, c) - at(x, y - 1, c))});
      }
      mask[std::size_t(y) * width + x] = contrast > kEdgeContrast;
    }
  }
  return mask;
}

ErrorFigures errorAgainst(const std::vector<double>& picture, const std::vector<double>& reference,
                          const std::vector<bool>& edges) {
  std::vector<double> edgeErrors;
  double all = 0, edgeSquared = 0;
  const std::size_t pixels = edges.size();
  for (std::size_t i = 0; i < pixels; ++i) {
    double squared = 0;
    for (int c = 0; c < 3; ++c) squared += std::pow(picture[i * 3 + c] - reference[i * 3 + c], 2) / 3;
    all += std::sqrt(squared);
    if (edges[i]) {
      edgeErrors.push_back(std::sqrt(squared));
      edgeSquared += squared;
    }
  }
  ErrorFigures figures;
  figures.allMean = all / static_cast<double>(pixels);
  figures.edgeShare = static_cast<double>(edgeErrors.size()) / static_cast<double>(pixels);
  if (edgeErrors.empty()) return figures;
  double sum = 0;
  for (double e : edgeErrors) sum += e;
  figures.edgeMean = sum / static_cast<double>(edgeErrors.size());
  const auto p99 = edgeErrors.begin() + static_cast<long>(0.99 * static_cast<double>(edgeErrors.size() - 1));
  std::nth_element(edgeErrors.begin(), p99, edgeErrors.end());
  figures.edgeP99 = *p99;
  figures.edgePsnr = 10 * std::log10(255.0 * 255.0 * static_cast<double>(edgeErrors.size()) / edgeSquared);
  return figures;
}

// The samples OpenGL really gives for a request of `asked` (a driver may round up): llvmpipe on
// Debian 12 knows only 1 and 4, so "msaa 2x" is 4x there.
int grantedSamples(render::GlBackend backend, int asked) {
  const std::unique_ptr<render::GlContext> context = render::makeGlContext(backend);
  const render::GlFunctions& gl = context->functions();
  GLint maxSamples = 0;
  gl.GetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  if (asked <= 1) return 1;  // a single-sample buffer, not a multisampled one with one sample
  if (asked > maxSamples) return 0;
  const render::Framebuffer framebuffer = render::makeFramebuffer(gl);
  const render::Renderbuffer colour = render::makeRenderbuffer(gl);
  gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.get());
  gl.BindRenderbuffer(GL_RENDERBUFFER, colour.get());
  gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, asked, GL_RGBA8, 64, 64);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour.get());
  GLint samples = 0;
  gl.GetIntegerv(GL_SAMPLES, &samples);
  return std::max(1, static_cast<int>(samples));
}

struct Row {
  std::string backend, picture, method;
  int samplesGranted = 0;  // per pixel, supersampling included; 0: not available
  ErrorFigures error;
  double milliseconds = 0, costRatio = 0;  // median per frame; ratio to msaa 4x
  std::string note;
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

std::vector<Row> measurePicture(render::GlBackend backend, const Picture& picture, int repeats) {
  const render::FrameSnapshot full = snapshotOf(picture);
  render::FrameSnapshot plain = full;
  plain.hudLines.clear();
  plain.inset.reset();
  render::RenderSettings base = picture.scene.render.picture;
  const bool reuse = picture.isVideoFrame && picture.scene.render.camera.mode == scene::CameraMode::Fixed;
  base.reuseStaticBackground = false;

  std::vector<double> reference;
  int maxSamples = 1;
  {
    render::RenderSettings settings = base;
    settings.width *= kReferenceScale;
    settings.height *= kReferenceScale;
    for (int samples : {8, 4, 2, 1}) {
      if (grantedSamples(backend, samples) == samples) {
        maxSamples = samples;
        break;
      }
    }
    settings.antialiasing = Antialiasing::Msaa;
    settings.msaa = maxSamples;
    reference = rgb(render::Renderer(settings, backend).draw(plain), kReferenceScale);
  }
  const std::vector<bool> edges = edgeMask(reference, base.width, base.height);

  struct Candidate {
    Row row;
    std::unique_ptr<render::Renderer> renderer;
    std::vector<double> times;
  };
  std::vector<Candidate> candidates;
  for (const Method& method : methods()) {
    Candidate candidate;
    candidate.row.backend = render::glBackendName(backend);
    candidate.row.picture = picture.name;
    candidate.row.method = method.name;
    render::RenderSettings settings = base;
    settings.antialiasing = method.antialiasing;
    settings.msaa = method.msaa;
    try {
      candidate.renderer = std::make_unique<render::Renderer>(settings, backend);
    } catch (const std::invalid_argument& refused) {
      candidate.row.note = refused.what();
      candidates.push_back(std::move(candidate));
      continue;
    }
    const int perPixel = method.antialiasing == Antialiasing::Fxaa ? 1 : grantedSamples(backend, method.msaa);
    candidate.row.samplesGranted = perPixel * render::drawScale(settings) * render::drawScale(settings);
    candidate.row.error = errorAgainst(rgb(candidate.renderer->draw(plain), 1), reference, edges);
    // The timed renderer draws the full snapshot; one with the background cache if `render` would use it.
    if (reuse) {
      settings.reuseStaticBackground = true;
      candidate.renderer = std::make_unique<render::Renderer>(settings, backend);
    }
    candidates.push_back(std::move(candidate));
  }
  image::Image frame;
  for (int round = -2; round < repeats; ++round) {  // two rounds of warm-up: shaders compile, the cache fills
    for (Candidate& candidate : candidates) {
      if (!candidate.renderer) continue;
      const auto start = std::chrono::steady_clock::now();
      candidate.renderer->draw(full, frame);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      if (round >= 0) candidate.times.push_back(ms);
    }
  }
  double baseline = 0;
  for (Candidate& candidate : candidates) {
    if (candidate.times.empty()) continue;
    candidate.row.milliseconds = median(candidate.times);
    if (candidate.row.method == "msaa 4x") baseline = candidate.row.milliseconds;
  }
  std::vector<Row> rows;
  for (Candidate& candidate : candidates) {
    if (baseline > 0 && candidate.row.milliseconds > 0) candidate.row.costRatio = candidate.row.milliseconds / baseline;
    rows.push_back(candidate.row);
  }
  return rows;
}

void printTable(const std::vector<Row>& rows) {
  fmt::print(
      "| back end | picture | method | samples | edge mean | edge p99 | edge PSNR dB | all mean | ms/frame "
      "| cost / msaa 4x |\n|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Row& r : rows) {
    if (r.samplesGranted == 0) {
      fmt::print("| {} | {} | {} | n/a | | | | | | |\n", r.backend, r.picture, r.method);
      continue;
    }
    fmt::print("| {} | {} | {} | {} | {:.2f} | {:.1f} | {:.2f} | {:.3f} | {:.1f} | {:.2f} |\n", r.backend, r.picture,
               r.method, r.samplesGranted, r.error.edgeMean, r.error.edgeP99, r.error.edgePsnr, r.error.allMean,
               r.milliseconds, r.costRatio);
  }
}

void writeCsv(const std::vector<Row>& rows, const std::string& path) {
  std::ofstream csv(path);
  csv << "backend,picture,method,samples,edge_share,edge_mean,edge_p99,edge_psnr_db,all_mean,ms_per_frame,"
         "cost_vs_msaa4,note\n";
  for (const Row& r : rows) {
    std::string note = r.note;
    std::replace(note.begin(), note.end(), '"', '\'');
    csv << fmt::format("{},\"{}\",{},{},{:.4f},{:.3f},{:.2f},{:.3f},{:.4f},{:.2f},{:.3f},\"{}\"\n", r.backend,
                       r.picture, r.method, r.samplesGranted, r.error.edgeShare, r.error.edgeMean, r.error.edgeP99,
                       r.error.edgePsnr, r.error.allMean, r.milliseconds, r.costRatio, note);
  }
  if (!csv) throw std::runtime_error(fmt::format("{}: cannot write", path));
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 9;
  std::string csvPath = "docs/data/antialias_quality.csv";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--repeats")
      repeats = std::atoi(argv[i + 1]);
    else if (flag == "--csv")
      csvPath = argv[i + 1];
    else {
      fmt::print(stderr, "usage: antialias_quality [--repeats N] [--csv file]\n");
      return 2;
    }
  }
  if (repeats < 1) {
    fmt::print(stderr, "--repeats: must be at least 1\n");
    return 2;
  }
  std::vector<Row> rows;
  for (const render::GlBackend backend : {render::GlBackend::OsMesa, render::GlBackend::Egl}) {
    if (!render::isCompiledIn(backend)) continue;
    try {
      render::makeGlContext(backend);
    } catch (const std::runtime_error& failed) {
      fmt::print(stderr, "{}: skipped, {}\n", render::glBackendName(backend), failed.what());
      continue;
    }
    for (const Picture& picture : pictures()) {
      fmt::print(stderr, "{}: {}\n", render::glBackendName(backend), picture.name);
      for (const Row& row : measurePicture(backend, picture, repeats)) rows.push_back(row);
    }
  }
  fmt::print(
      "antialias_quality: error in 8-bit levels against a {0}x{0}-size reference; edge pixels: reference "
      "contrast > {1} levels; cost: median of {2} draws\n\n",
      kReferenceScale, kEdgeContrast, repeats);
  printTable(rows);
  writeCsv(rows, csvPath);
  fmt::print("\nCSV: {}\n", csvPath);
  return 0;
}
