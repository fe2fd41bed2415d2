// Frames per second of the renderer against a minimal probe built here and run in the same
// process: floor, 128-segment coin, 10,000-point trace, MSAA resolve and readback, flat colour,
// nothing else. The ratio (ours / probe) is comparable across machines; absolute fps are not.
// Then the frames users render: the built-in default scene and every example at its own framing
// (floor filling the frame, trace, shadow, overlay), through the pipeline's frame loop into a
// sink that discards them, with the static background reused and shaded every frame.
// Run: build/bench/render_bench [frames]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <numbers>
#include <vector>

#include "render/camera.h"
#include "render/gl_context.h"
#include "render/gl_handles.h"
#include "render/meshes.h"
#include "image_compare.h"
#include "render/renderer.h"
#include "pipeline/video_frames.h"
#include "scene/scene_loader.h"
#include "scene/scene_schema.h"
#include "video/frame_sink.h"

namespace {

using namespace coinroll::render;

std::vector<glm::vec2> circleTrace(int points) {
  std::vector<glm::vec2> trace;
  for (int i = 0; i < points; ++i) {
    const double a = 8 * std::numbers::pi * i / points;
    trace.emplace_back(0.08 * std::cos(a) + 0.0005 * i / 100.0, 0.08 * std::sin(a));
  }
  return trace;
}

FrameSnapshot benchSnapshot(double time) {
  FrameSnapshot s;
  s.camera = {{0.12f, 0.17f, 0.36f}, {0.0f, 0.02f, 0.0f}, 35.0f};
  s.trace = circleTrace(10000);
  s.traceWidth = 0.0015f;
  const float theta = 0.35f, phi = static_cast<float>(time), psi = static_cast<float>(5 * time);
  s.coin.attitude = glm::angleAxis(phi, glm::vec3(0, 1, 0)) * glm::angleAxis(theta, glm::vec3(1, 0, 0)) *
                    glm::angleAxis(psi, glm::vec3(0, 0, 1));
  s.coin.centre = glm::vec3(0.08f * std::cos(phi), 0.0375f * std::cos(theta), 0.08f * std::sin(phi));
  s.hudLines = {"t        1.000 s", "tilt     20.00 deg", "spin     15.00 rad/s", "E      0.22160 J"};
  return s;
}

// The probe: the same geometry drawn with one flat-colour program into a multisampled
// framebuffer, resolved and read back, as a plain OpenGL program would.
class Probe {
 public:
  Probe(const GlFunctions& gl, int width, int height, int samples)
      : gl_(gl), width_(width), height_(height), pixels_(std::size_t(width) * height * 4) {
    const char* vertexSource =
        "#version 330 core\nlayout(location=0) in vec3 p; uniform mat4 m; void main(){ gl_Position = m * vec4(p, 1.0); "
        "}\n";
    const char* fragmentSource = "#version 330 core\nuniform vec4 c; out vec4 o; void main(){ o = c; }\n";
    const Shader vs(gl, gl.CreateShader(GL_VERTEX_SHADER)), fs(gl, gl.CreateShader(GL_FRAGMENT_SHADER));
    gl.ShaderSource(vs.get(), 1, &vertexSource, nullptr);
    gl.ShaderSource(fs.get(), 1, &fragmentSource, nullptr);
    gl.CompileShader(vs.get());
    gl.CompileShader(fs.get());
    program_ = Program(gl, gl.CreateProgram());
    gl.AttachShader(program_.get(), vs.get());
    gl.AttachShader(program_.get(), fs.get());
    gl.LinkProgram(program_.get());

    std::vector<glm::vec3> vertices = {{-5, 0, -5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}};
    for (const CoinVertex& v : coinTriangles({0.0375f, 0.0f, 0.00225f}, 128)) vertices.push_back(v.position);
    coinFirst_ = 6;
    coinCount_ = static_cast<GLsizei>(vertices.size()) - 6;
    traceFirst_ = static_cast<GLsizei>(vertices.size());
    for (const RibbonVertex& v : ribbonStrip(circleTrace(10000), 0.0015f))
      vertices.emplace_back(v.position.x, 0.0f, v.position.y);
    traceCount_ = static_cast<GLsizei>(vertices.size()) - traceFirst_;
    gl.BindVertexArray(array_.get());
    gl.BindBuffer(GL_ARRAY_BUFFER, buffer_.get());
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(glm::vec3)), vertices.data(),
                  GL_STATIC_DRAW);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);

    gl.BindFramebuffer(GL_FRAMEBUFFER, msaa_.get());
    gl.BindRenderbuffer(GL_RENDERBUFFER, msaaColour_.get());
    gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaaColour_.get());
    gl.BindRenderbuffer(GL_RENDERBUFFER, msaaDepth_.get());
    gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, width, height);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, msaaDepth_.get());
    gl.BindFramebuffer(GL_FRAMEBUFFER, resolve_.get());
    gl.BindRenderbuffer(GL_RENDERBUFFER, resolveColour_.get());
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolveColour_.get());
  }

  void draw(const FrameSnapshot& s) {
    const CameraMatrices m = cameraMatrices(s.camera, width_, height_);
    const glm::mat4 viewProjection = m.projection * m.view;
    gl_.BindFramebuffer(GL_FRAMEBUFFER, msaa_.get());
    gl_.Viewport(0, 0, width_, height_);
    gl_.ClearColor(0.8f, 0.8f, 0.8f, 1.0f);
    gl_.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.UseProgram(program_.get());
    gl_.BindVertexArray(array_.get());
    const GLint mLocation = gl_.GetUniformLocation(program_.get(), "m"),
                cLocation = gl_.GetUniformLocation(program_.get(), "c");
    gl_.UniformMatrix4fv(mLocation, 1, GL_FALSE, glm::value_ptr(viewProjection));
    gl_.Uniform4f(cLocation, 0.5f, 0.5f, 0.5f, 1.0f);
    gl_.DrawArrays(GL_TRIANGLES, 0, 6);
    gl_.Uniform4f(cLocation, 0.9f, 0.4f, 0.1f, 1.0f);
    gl_.DrawArrays(GL_TRIANGLE_STRIP, traceFirst_, traceCount_);
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), s.coin.centre) * glm::mat4_cast(s.coin.attitude);
    gl_.UniformMatrix4fv(mLocation, 1, GL_FALSE, glm::value_ptr(viewProjection * model));
    gl_.Uniform4f(cLocation, 0.8f, 0.6f, 0.2f, 1.0f);
    gl_.DrawArrays(GL_TRIANGLES, coinFirst_, coinCount_);
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, msaa_.get());
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_.get());
    gl_.BlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, resolve_.get());
    gl_.ReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, pixels_.data());
  }

 private:
  const GlFunctions& gl_;
  int width_, height_;
  std::vector<std::uint8_t> pixels_;
  Program program_;
  VertexArray array_ = makeVertexArray(gl_);
  Buffer buffer_ = makeBuffer(gl_);
  Framebuffer msaa_ = makeFramebuffer(gl_), resolve_ = makeFramebuffer(gl_);
  Renderbuffer msaaColour_ = makeRenderbuffer(gl_), msaaDepth_ = makeRenderbuffer(gl_),
               resolveColour_ = makeRenderbuffer(gl_);
  GLsizei coinFirst_ = 0, coinCount_ = 0, traceFirst_ = 0, traceCount_ = 0;
};

// Anti-aliasing quality (llvmpipe offers at most 4 samples): each mode at 320x180 against a
// reference drawn at 8x the size with one sample per pixel and box-averaged down (64 samples per
// pixel), as PSNR over edge pixels (tests/support/image_compare.h).
void antialiasingQuality() {
  constexpr int kWidth = 320, kHeight = 180, kFactor = 8;
  FrameSnapshot snapshot = benchSnapshot(1.0);
  snapshot.hudLines.clear();  // the overlay's font scales with the picture; leave it out
  snapshot.camera = {{0.10f, 0.07f, 0.16f}, {0.0f, 0.02f, 0.0f}, 35.0f};  // the coin fills a good part
  RenderSettings big;
  big.width = kWidth * kFactor;
  big.height = kHeight * kFactor;
  big.msaa = 1;
  const std::vector<double> reference = coinroll::testing::boxDownsample(Renderer(big).draw(snapshot), kFactor);
  fmt::print("\nanti-aliasing quality at {}x{} against a 64-sample reference:\n{:>10} {:>14}\n", kWidth, kHeight,
             "mode", "PSNR edges dB");
  struct Mode {
    const char* name;
    Antialiasing antialiasing;
    int msaa;
  };
  for (const Mode& mode : {Mode{"none", Antialiasing::Msaa, 1}, Mode{"msaa 2", Antialiasing::Msaa, 2},
                           Mode{"msaa 4", Antialiasing::Msaa, 4}, Mode{"fxaa", Antialiasing::Fxaa, 1}}) {
    RenderSettings small;
    small.width = kWidth;
    small.height = kHeight;
    small.antialiasing = mode.antialiasing;
    small.msaa = mode.msaa;
    fmt::print("{:>10} {:>14.2f}\n", mode.name, coinroll::testing::edgePsnr(Renderer(small).draw(snapshot), reference));
  }
}

// Best of three runs of `frames` frames, in frames per second.
double framesPerSecond(int frames, const std::function<void(int)>& drawFrame) {
  for (int i = 0; i < 3; ++i) drawFrame(i);  // warm up: shader variants compile on first use
  double best = 0;
  for (int run = 0; run < 3; ++run) {
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < frames; ++i) drawFrame(i);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::max(best, frames / seconds);
  }
  return best;
}

class DiscardingSink : public coinroll::video::FrameSink {
 public:
  void push(const coinroll::image::Image&) override {}
  void finish() override {}
};

struct NamedScene {
  std::string name;
  coinroll::scene::SceneConfig scene;
};

std::vector<NamedScene> usersScenes() {
  namespace scene = coinroll::scene;
  std::vector<NamedScene> scenes;
  scenes.push_back({"default", scene::parseScene(scene::builtInDefaultScene(), "default")});
  nlohmann::json orbit = scene::builtInDefaultScene();
  scene::applyOverride(orbit, "render.camera.mode=orbit");
  scenes.push_back({"default, orbit", scene::parseScene(orbit, "default, orbit")});
  std::set<std::filesystem::path> examples;
  for (const auto& entry : std::filesystem::directory_iterator(COINROLL_SOURCE_DIR "/examples")) {
    if (entry.path().extension() == ".json") examples.insert(entry.path());
  }
  for (const std::filesystem::path& file : examples) {
    scenes.push_back({file.stem().string(), scene::loadScene(file, {})});
  }
  return scenes;
}

// Frames per second of the pipeline's own frame loop over the first `frames` frames of `scene`
// (sampling, snapshot, draw, readback; no encoding), best of three, set-up excluded.
double sceneFramesPerSecond(const coinroll::scene::SceneConfig& scene, int frames, bool reuseBackground) {
  double best = 0;
  for (int run = 0; run < 3; ++run) {
    DiscardingSink sink;
    std::atomic<bool> enough = false;
    std::chrono::steady_clock::time_point first;
    double seconds = 0;
    int timedFrames = 0;
    try {
      coinroll::pipeline::renderVideo(scene, sink,
                                      {.onFrame =
                                           [&](const coinroll::pipeline::FrameProgress& progress) {
                                             const auto now = std::chrono::steady_clock::now();
                                             if (progress.frame == 1) first = now;  // after the first frame's warm-up
                                             seconds = std::chrono::duration<double>(now - first).count();
                                             timedFrames = static_cast<int>(progress.frame - 1);
                                             if (progress.frame >= frames + 1) enough = true;
                                           },
                                       .cancel = &enough,
                                       .reuseStaticBackground = reuseBackground});
    } catch (const coinroll::pipeline::Cancelled&) {
    }
    if (timedFrames > 0) best = std::max(best, timedFrames / seconds);
  }
  return best;
}

// Where a 1280x720 4x-MSAA frame's time goes, by difference: the bench frame (floor filling the
// picture, coin, shadow, 10,000-point trace, overlay) against the same frame with one part left
// out, each best of three in the same run. What remains with everything left out and the
// background reused is the per-frame floor of the renderer: the background blit, the MSAA
// resolve, the readback and the row flip.
void frameSplit(int frames) {
  RenderSettings shadedSettings;
  shadedSettings.reuseStaticBackground = false;
  RenderSettings reusedSettings;
  RenderSettings noShadowSettings;
  noShadowSettings.showShadow = false;
  const auto millisecondsPerFrame = [&](const RenderSettings& settings, auto&& edit) {
    Renderer renderer(settings);
    coinroll::image::Image frame;
    return 1000.0 / framesPerSecond(frames, [&](int i) {
             FrameSnapshot s = benchSnapshot(i / 30.0);
             edit(s);
             renderer.draw(s, frame);
           });
  };
  const auto unchanged = [](FrameSnapshot&) {};
  const auto noTrace = [](FrameSnapshot& s) { s.trace.clear(); };
  const auto noHud = [](FrameSnapshot& s) { s.hudLines.clear(); };
  const auto noCoin = [](FrameSnapshot& s) {
    s.coin.centre = s.camera.eye + (s.camera.eye - s.camera.target);
  };  // behind the camera
  const auto nothing = [&](FrameSnapshot& s) { noTrace(s), noHud(s), noCoin(s); };
  const double shaded = millisecondsPerFrame(shadedSettings, unchanged);
  const double reused = millisecondsPerFrame(reusedSettings, unchanged);
  const double withoutTrace = millisecondsPerFrame(reusedSettings, noTrace);
  const double withoutHud = millisecondsPerFrame(reusedSettings, noHud);
  const double withoutCoin = millisecondsPerFrame(noShadowSettings, noCoin);
  const double withoutShadow = millisecondsPerFrame(noShadowSettings, unchanged);
  const double bare = millisecondsPerFrame(noShadowSettings, nothing);
  fmt::print("\nwhere a 1280x720 4x-MSAA frame\'s time goes (by difference, ms per frame):\n");
  fmt::print("{:>44} {:>8.2f}\n", "whole frame, background shaded", shaded);
  fmt::print("{:>44} {:>8.2f}\n", "whole frame, background reused", reused);
  fmt::print("{:>44} {:>8.2f}\n", "  floor and sky shaded, minus the blit", shaded - reused);
  fmt::print("{:>44} {:>8.2f}\n", "  trace ribbon (10,000 points)", reused - withoutTrace);
  fmt::print("{:>44} {:>8.2f}\n", "  overlay text", reused - withoutHud);
  fmt::print("{:>44} {:>8.2f}\n", "  shadow", reused - withoutShadow);
  fmt::print("{:>44} {:>8.2f}\n", "  coin", withoutShadow - withoutCoin);
  fmt::print("{:>44} {:>8.2f}\n", "  blit, resolve, readback, flip (the rest)", bare);
}

void usersFrames(int frames, double probeFps) {
  fmt::print("\nframes users render (1280x720, 4x MSAA unless the scene says otherwise), {} frames, best of 3:\n",
             frames);
  fmt::print("{:>22} {:>8} {:>14} {:>14} {:>9} {:>14}\n", "scene", "camera", "shaded fps", "reused fps", "speed-up",
             "reused / probe");
  for (const NamedScene& named : usersScenes()) {
    const double shaded = sceneFramesPerSecond(named.scene, frames, false);
    const double reused = sceneFramesPerSecond(named.scene, frames, true);
    const std::string_view camera =
        coinroll::scene::schema::kCameraModeNames.at(static_cast<std::size_t>(named.scene.render.camera.mode));
    fmt::print("{:>22} {:>8} {:>14.1f} {:>14.1f} {:>9.2f} {:>14.2f}\n", named.name, camera, shaded, reused,
               reused / shaded, reused / probeFps);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::atoi(argv[1]) : 40;
  const char* threads = std::getenv("LP_NUM_THREADS");
  fmt::print("render_bench: {} frames per run, best of 3; llvmpipe threads: {}\n\n", frames,
             threads ? threads : "default");
  fmt::print("{:>10} {:>6} {:>12} {:>12} {:>14}\n", "size", "AA", "probe fps", "ours fps", "ours / probe");
  double probeFps720 = 0;
  for (auto [width, height] : {std::pair{1280, 720}, std::pair{1920, 1080}}) {
    double probeFps = 0;
    {
      const std::unique_ptr<GlContext> context = makeGlContext(selectedGlBackend());
      Probe probe(context->functions(), width, height, 4);
      probeFps = framesPerSecond(frames, [&](int i) { probe.draw(benchSnapshot(i / 30.0)); });
    }
    if (width == 1280) probeFps720 = probeFps;
    for (int msaa : {4, 2, 1, 0}) {  // 0: FXAA
      RenderSettings settings;
      settings.width = width;
      settings.height = height;
      settings.msaa = std::max(msaa, 1);
      settings.antialiasing = msaa == 0 ? Antialiasing::Fxaa : Antialiasing::Msaa;
      Renderer renderer(settings);
      coinroll::image::Image frame;
      const double ours = framesPerSecond(frames, [&](int i) { renderer.draw(benchSnapshot(i / 30.0), frame); });
      fmt::print("{:>10} {:>6} {:>12.1f} {:>12.1f} {:>14.2f}\n", fmt::format("{}x{}", width, height),
                 msaa == 0 ? "fxaa" : std::to_string(msaa), probeFps, ours, ours / probeFps);
    }
  }
  frameSplit(frames);
  usersFrames(frames, probeFps720);
  antialiasingQuality();
  return 0;
}
