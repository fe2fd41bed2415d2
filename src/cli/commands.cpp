#include "cli/commands.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <new>
#include <regex>
#include <iostream>
#include <numbers>
#include <thread>
#include <tuple>
#include <variant>

#include "cli/exit_codes.h"
#include "cli/interrupts.h"
#include "image/compare.h"
#include "image/image.h"
#include "integrate/solver_config.h"
#include "io/destination.h"
#include "io/fnv1a.h"
#include "io/output_file.h"
#include "physics/observables.h"
#include "physics/steady.h"
#include "render/render_settings.h"
#include "pipeline/resources.h"
#include "pipeline/simulation.h"
#include "pipeline/still.h"
#include "pipeline/sweep.h"
#include "pipeline/video_frames.h"
#include "video/async_sink.h"
#include "video/make_sink.h"
#include "cli/progress.h"
#include "cli/terminal_text.h"
#include "pipeline/trajectory_csv.h"
#include "scene/scene_loader.h"

namespace coinroll::cli {

namespace {

constexpr double kDegreesPerRadian = 180 / std::numbers::pi;

// The scene document with --set applied, and the name its messages use.
std::pair<nlohmann::json, std::string> loadSceneDocument(const SceneSource& source) {
  nlohmann::json document = source.file ? scene::readSceneDocument(*source.file) : scene::builtInDefaultScene();
  for (const std::string& assignment : source.overrides) scene::applyOverride(document, assignment);
  return {document, source.file ? *source.file : "built-in default scene"};
}

scene::SceneConfig loadScene(const SceneSource& source) {
  const scene::ParseOptions options{.solverMethods = integrate::methodNames()};
  if (source.file) return scene::loadScene(*source.file, source.overrides, options);
  nlohmann::json document = scene::builtInDefaultScene();
  for (const std::string& assignment : source.overrides) scene::applyOverride(document, assignment);
  return scene::parseScene(document, "built-in default scene", options);
}

// A scene as a command that writes pictures resolves it (--set applied), with the provenance its
// outputs carry: the release, and a digest of the scene document as resolved (compact JSON, keys
// sorted), so the same release and scene give the same bytes (docs/outputs.md "Provenance").
struct ResolvedScene {
  scene::SceneConfig config;
  video::Provenance provenance;  // empty with render.provenance: false
};

ResolvedScene resolveScene(const SceneSource& source) {
  const auto [document, sourceName] = loadSceneDocument(source);
  ResolvedScene resolved{scene::parseScene(document, sourceName, {.solverMethods = integrate::methodNames()}), {}};
  if (resolved.config.render.provenance) {
    const std::string canonical = document.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    resolved.provenance = {.software = fmt::format("coinroll {}", COINROLL_VERSION),
                           .sceneDigest = fmt::format("fnv1a64:{:016x}", io::fnv1a64(canonical))};
  }
  return resolved;
}

// --size's names: the usual video heights with 16:9 sides, even for 4:2:0 chroma (854 for 480p).
constexpr std::array<std::tuple<std::string_view, int, int>, 5> kSizes = {
    {{"480p", 854, 480}, {"720p", 1280, 720}, {"1080p", 1920, 1080}, {"1440p", 2560, 1440}, {"2160p", 3840, 2160}}};

void reportStop(const pipeline::CsvRunResult& result) {
  for (const pipeline::ModeSwitch& w : result.switches) {
    std::cerr << fmt::format("coinroll: {} at t = {:.9f} s\n", w.toSliding ? "slides" : "rolls", w.t);
  }
  for (const auto& warning : result.warnings) {
    std::cerr << "coinroll: warning: the ideal contact fails here (on_invalid: warn, going on): "
              << pipeline::describeStop(warning) << '\n';
  }
  if (result.stoppedBy) {
    std::cerr << "coinroll: stopped early: " << pipeline::describeStop(*result.stoppedBy) << '\n';
  }
  if (result.singularTime) {
    const pipeline::SingularTimeEstimate& e = *result.singularTime;
    std::cerr << fmt::format("coinroll: singular time t0 = {:.6f} s, {:.3g} s after the stop (E ~ (t0 - t)^{:.3f}, fitted "
                             "to E/P over t >= {:.6g} s, {} samples)\n",
                             e.t0, e.t0 - result.stoppedBy->t, e.gamma, e.fitFrom, e.samples);
  }
}

void reportSteadyStart(const scene::SceneConfig& scene) {
  if (const std::string note = pipeline::steadyStartNote(scene); !note.empty()) std::cerr << "coinroll: note: " << note << '\n';
}

// Runs a long command's work with its progress line, ending the line however the work ends, and
// maps the ways it fails alike for every command: Ctrl-C (after `discardOutput`, which removes
// a partial output the caller holds) to exit 1 saying nothing was written, a bad request to
// exit 2.
template <class Work>
auto withProgress(ProgressLine& progress, const std::string& output, Work work,
                  const std::function<void()>& discardOutput = {}) -> decltype(work()) {
  try {
    auto result = work();
    progress.finish();
    return result;
  } catch (const pipeline::Cancelled&) {
    progress.finish();
    if (discardOutput) discardOutput();
    throw std::runtime_error(interruptionMessage(output));
  } catch (const std::invalid_argument& e) {
    progress.finish();
    throw UsageError(e.what());
  } catch (...) {
    progress.finish();
    throw;
  }
}

// An output must never replace a file the command reads: refused before anything runs.
// Whether `name` is one of the file names a PNG sequence pattern ("f_%03d.png") produces.
bool isFrameOf(const std::string& pattern, const std::string& name) {
  std::string expression;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] == '%' && i + 1 < pattern.size() && pattern[i + 1] == '%') {
      expression += "%";
      ++i;
    } else if (pattern[i] == '%') {
      while (i < pattern.size() && pattern[i] != 'd') ++i;  // flags and width: any count of digits matches
      expression += "[0-9]+";
    } else {
      if (std::string_view("\\^$.|?*+()[]{}").find(pattern[i]) != std::string_view::npos) expression += '\\';
      expression += pattern[i];
    }
  }
  return std::regex_match(name, std::regex(expression));
}

void refuseOverwritingInput(const std::string& option, const std::filesystem::path& output,
                            const std::vector<std::filesystem::path>& inputs) {
  std::error_code error;
  const std::string outputName = output.filename().string();
  const bool isSequence = video::namesPngSequence(output);
  for (const std::filesystem::path& input : inputs) {
    const std::filesystem::path outputDirectory = output.parent_path().empty() ? "." : output.parent_path();
    const std::filesystem::path inputDirectory = input.parent_path().empty() ? "." : input.parent_path();
    if (isSequence && std::filesystem::equivalent(outputDirectory, inputDirectory, error) &&
        isFrameOf(outputName, input.filename().string())) {
      throw UsageError(fmt::format("{} {}: one of its frames would be the input {}; choose another output name", option,
                                   output.string(), input.string()));
    }
    if (std::filesystem::equivalent(output, input, error)) {
      throw UsageError(fmt::format("{} {}: that is the input {}; choose another output name", option, output.string(),
                                   input.string()));
    }
  }
}

// The files a command reads: its scene, and the files of $COINROLL_ASSET_DIR and
// $COINROLL_SHADER_DIR when set (a texture or a shader the output must not replace).
std::vector<std::filesystem::path> inputsOf(const SceneSource& source) {
  std::vector<std::filesystem::path> inputs;
  if (source.file) inputs.emplace_back(*source.file);
  for (const char* variable : {"COINROLL_ASSET_DIR", "COINROLL_SHADER_DIR"}) {
    const char* directory = std::getenv(variable);
    if (directory == nullptr || *directory == '\0') continue;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
      if (entry.is_regular_file(error)) inputs.push_back(entry.path());
    }
  }
  return inputs;
}

// A default output name made from the scene name (docs/outputs.md): a name of letters, digits,
// '-', '_' and '.' that does not start with a dot is used as it is; any other ("My scene: v2",
// ".hidden", a Cyrillic name) has each other byte and a leading dot replaced by '_', is cut to
// kMaxDerivedNameBytes, and gets '+' and 8 hex digits of a hash of the whole original name:
// "My_scene__v2+1c0e3f52". So different names never share a file ('+' never survives the
// replacement, so a hashed name cannot equal a kept one; two hashed ones clash only if both the
// replaced text and 32 bits of hash agree), no default name is a hidden file, and every one fits
// in a file name with its extension.
constexpr std::size_t kMaxDerivedNameBytes = 200;

std::string fileNameFrom(const std::string& sceneName) {
  if (sceneName.empty()) return "coinroll";
  std::string name = sceneName;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  }
  if (name[0] == '.') name[0] = '_';
  if (name == sceneName && name.size() <= kMaxDerivedNameBytes) return name;
  name.resize(std::min(name.size(), kMaxDerivedNameBytes));
  const std::uint64_t hash = io::fnv1a64(sceneName);
  return fmt::format("{}+{:08x}", name, static_cast<std::uint32_t>(hash ^ (hash >> 32)));
}

// An empty output name would be found only when the output is opened, which for some commands
// is after all the work: refused first, naming the option and what to give.
void refuseEmptyOutputName(const std::string& option, const std::string& name, const std::string& example) {
  if (name.empty()) {
    throw UsageError(fmt::format("{}: the output name is empty; give a file name, e.g. {} {}", option, option, example));
  }
}

// Runs `write` into `path`: standard output for "-", otherwise the output layer (a temporary file
// that takes the name only once `write` and the close have succeeded, or a device, FIFO or
// descriptor written directly; io/output_file.h). `what` names the content in errors ("CSV").
void writeTextOutput(const std::string& path, std::string_view what, const std::function<void(std::ostream&)>& write) {
  if (path == "-") {
    write(std::cout);
    std::cout.flush();
    // A full device, a closed stdout or a reader gone while SIGPIPE is ignored: the stream says so.
    if (!std::cout) throw std::runtime_error(fmt::format("writing the {} to stdout failed: {}", what, std::strerror(errno)));
    return;
  }
  io::OutputFile file(path, std::string(what));
  write(file.stream());
  file.commit();
}

}  // namespace

void runSimulate(const SimulateOptions& options) {
  if (!(options.sampleDt > 0) || !std::isfinite(options.sampleDt)) {
    throw UsageError(fmt::format("--sample-dt: must be a finite number > 0 s, got {}", options.sampleDt));
  }
  refuseEmptyOutputName("--csv", options.csvPath, "out.csv (or - for standard output)");
  if (options.csvPath != "-") refuseOverwritingInput("--csv", options.csvPath, inputsOf(options.scene));
  const scene::SceneConfig scene = loadScene(options.scene);
  const long maxRows = options.maxRows > 0 ? options.maxRows : kDefaultMaxRows;
  if (const double rows = scene.duration / options.sampleDt + 1; rows > static_cast<double>(maxRows)) {
    throw UsageError(fmt::format("--sample-dt {}: duration {} s gives {:.4g} rows, more than the limit {}; raise "
                                 "--sample-dt, or the limit with --max-rows", options.sampleDt, scene.duration, rows, maxRows));
  }
  pipeline::Simulation simulation = pipeline::buildSimulation(scene);
  simulation.cancel = &interruptRequested();
  reportSteadyStart(scene);

  ProgressLine noProgress(ProgressLine::Style::Off, "", "");
  const pipeline::CsvRunResult result = withProgress(noProgress, options.csvPath, [&] {
    pipeline::CsvRunResult r;
    writeTextOutput(options.csvPath, "CSV",
                    [&](std::ostream& out) { r = pipeline::writeTrajectoryCsv(simulation, options.sampleDt, out); });
    return r;
  });
  reportStop(result);
  std::cerr << fmt::format("coinroll: {} rows, {} steps ({} rejected), {} right-hand-side evaluations\n", result.rows,
                           result.stats.acceptedSteps, result.stats.rejectedSteps, result.stats.rhsEvaluations);
}

void runSteady(const SteadyOptions& options) {
  SceneSource source = options.scene;
  for (const auto& [name, value] : {std::pair{"--theta", options.thetaDegrees}, std::pair{"--omega-Z", options.omega_Z}}) {
    // JSON has no NaN or infinity: passed on, they would come back as a null the scene names.
    if (value && !std::isfinite(*value)) throw UsageError(fmt::format("{}: must be a finite number, got {}", name, *value));
  }
  if (options.kind) {
    nlohmann::json initial = {{"steady", *options.kind}};
    if (options.thetaDegrees) initial["theta"] = *options.thetaDegrees;
    if (options.omega_Z) initial["omega_Z"] = *options.omega_Z;
    if (options.branch) initial["branch"] = *options.branch;
    // The kind replaces the scene's initial block first, so that --set initial.phi=45 lands on it
    // instead of being replaced by it. Replacement characters keep argv that is not UTF-8 an input
    // error the parser names.
    source.overrides.insert(source.overrides.begin(),
                            "initial=" + initial.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
  } else if (options.thetaDegrees || options.omega_Z || options.branch) {
    throw UsageError("--theta, --omega-Z and --branch describe a steady state: give --kind too");
  }
  const scene::SceneConfig scene = loadScene(source);
  if (!std::holds_alternative<scene::SteadyInitial>(scene.initial)) {
    throw UsageError("steady: give --kind straight|circle|spin-in-place, or a scene whose initial names a steady state");
  }
  const pipeline::Simulation sim = pipeline::buildSimulation(scene);
  if (!scene.effects.empty()) {
    std::cerr << "coinroll: note: the steady state and its stability below are those of the ideal model; the scene's "
                 "effects dissipate energy, so with them this state is only where a slowing motion starts\n";
  }
  const physics::CoinModel& m = sim.model;
  const physics::CoinState& s = sim.initial;
  const double rateUnit = physics::naturalRate(m);
  const double K = physics::wobbleStiffness(m, s.theta, s.omega_Y, s.omega_Z);
  const physics::CircleRadii radii = physics::circleRadii(m, s);

  fmt::print("coin: M = {} kg, a = {} m, g = {} m/s^2, I_X = {:.6g} kg m^2, I_Z = {:.6g} kg m^2\n", m.M, m.a, m.g,
             m.I_X, m.I_Z);
  const bool thick = !m.rim.thin(), cornered = thick && !m.rim.fullyRounded();
  if (thick) {
    // The thin coin's lines stay byte for byte what they were; a thick one says which solid it is.
    fmt::print("rim: thickness h = {} m, edge radius rho = {} m ({})\n", m.rim.thickness, m.rim.edgeRadius,
               cornered ? fmt::format("rho < h/2: corners {:.6g} m either side of the mid-plane", m.rim.cornerOffset())
                        : std::string("rho = h/2: fully rounded, it rolls through upright"));
    fmt::print("inertia used: I_X, I_Z above, {}\n",
               scene.coin.shape == scene::Shape::Custom
                   ? "as the scene gives them (custom)"
                   : "those of the uniform solid of thickness h with this rim (docs/rim_inertia.md)");
  }
  if (cornered) {
    fmt::print("natural rate sqrt(g/a) = {:.6g} rad/s; straight rolling is not a steady motion of a coin whose rim has "
               "corners (it switches corners at upright), so there is no critical spin (docs/rim.md eq. 5.4)\n\n", rateUnit);
  } else {
    const double omega_c = physics::criticalSpin(m);
    fmt::print("natural rate sqrt(g/a) = {:.6g} rad/s; critical spin for straight rolling omega_c = {:.6g} rad/s "
               "({:.6f} sqrt(g/a){})\n\n", rateUnit, omega_c, omega_c / rateUnit, thick ? "; docs/rim.md eq. 5.9" : "");
  }
  fmt::print("initial conditions (scene units):\n");
  fmt::print("  \"initial\": {{\"theta\": {:.12g}, \"phi\": {:.12g}, \"psi\": {:.12g}, \"omega_X\": {:.12g}, "
             "\"omega_Y\": {:.12g}, \"omega_Z\": {:.12g}, \"x\": {:.12g}, \"z\": {:.12g}}}\n",
             s.theta * kDegreesPerRadian, s.phi * kDegreesPerRadian, s.psi * kDegreesPerRadian, s.omega_X, s.omega_Y,
             s.omega_Z, s.x, s.z);
  fmt::print("  in units of sqrt(g/a): omega_Y = {:.9g}, omega_Z = {:.9g}\n", s.omega_Y / rateUnit, s.omega_Z / rateUnit);
  fmt::print("  phi-dot = {:.9g} rad/s, psi-dot = {:.9g} rad/s\n", physics::precessionRate(s), physics::spinRate(s));
  fmt::print("  circle radius: centre of mass R_G = {:.9g} m, contact point R_C = {:.9g} m\n", radii.centreOfMass,
             radii.contact);
  const physics::Reaction r = physics::reaction(m, s);
  fmt::print("  floor reaction: N = {:.6g} N, F = {:.6g} N (needs mu >= {:.4g})\n\n", r.N, r.F, r.N > 0 ? r.F / r.N : INFINITY);
  fmt::print("stability ({}): K = {:.9g} 1/s^2 ({:.9g} in units g/a)\n",
             thick ? "docs/rim.md eq. 5.8" : "docs/derivations.md eq. 3.6", K, K / (rateUnit * rateUnit));
  if (K > 0) {
    fmt::print("verdict: STABLE: a small tilt perturbation wobbles at {:.9g} rad/s (period {:.9g} s)\n", std::sqrt(K),
               2 * std::numbers::pi / std::sqrt(K));
  } else if (K < 0) {
    fmt::print("verdict: UNSTABLE: a small tilt perturbation grows like exp({:.9g} t / s) (e-folding time {:.9g} s)\n",
               std::sqrt(-K), 1 / std::sqrt(-K));
  } else {
    fmt::print("verdict: MARGINAL (K = 0)\n");
  }
}

void runStill(const StillOptions& options) {
  const std::filesystem::path output(options.output);
  refuseEmptyOutputName("-o", options.output, "still.png");
  // A device, FIFO or descriptor has no name to check: it gets the PNG.
  if (output.extension() != ".png" && !io::namesStream(output)) {
    throw UsageError(fmt::format("-o: a still is written as PNG; give a name ending in .png, got \"{}\"", options.output));
  }
  if (options.strobeFrom && options.strobe == 0) {
    throw UsageError("--strobe-from: places the first of the --strobe copies, and there are none; give --strobe N too");
  }
  refuseOverwritingInput("-o", output, inputsOf(options.scene));
  io::checkOutputName(output);  // the PNG is written after the rendering: a name that cannot work fails first
  const auto [scene, provenance] = resolveScene(options.scene);
  reportSteadyStart(scene);
  pipeline::StillResult result;
  try {
    result = pipeline::renderStill(scene, {.time = options.time,
                                           .ghosts = options.strobe,
                                           .ghostsFrom = options.strobeFrom.value_or(0),
                                           .output = output,
                                           .text = provenance.pngText(),
                                           .cancel = &interruptRequested()});
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  } catch (const pipeline::Cancelled&) {
    throw std::runtime_error(interruptionMessage(options.output));
  }
  if (result.stopDescription) {
    std::cerr << fmt::format("coinroll: the run stopped early, so the still shows t = {:.6f} s: {}\n", result.shownTime,
                             *result.stopDescription);
  }
  std::cerr << fmt::format("coinroll: wrote {} ({}x{}, t = {:.6g} s)\n", printable(options.output), scene.render.picture.width, scene.render.picture.height,
                           result.shownTime);
}

void runRender(const RenderOptions& options) {
  if (options.output) refuseEmptyOutputName("-o", *options.output, "clip.mp4");
  SceneSource source = options.scene;
  if (options.size) {
    const auto size = std::find_if(kSizes.begin(), kSizes.end(), [&](const auto& s) { return std::get<0>(s) == *options.size; });
    if (size == kSizes.end()) {
      throw UsageError(fmt::format("--size {}: unknown size; give 480p, 720p, 1080p, 1440p or 2160p (or set render.width and "
                                   "render.height with --set)", printable(*options.size)));
    }
    // After the --set ones, so the option names the size whatever the scene or a --set says.
    source.overrides.push_back(fmt::format("render.width={}", std::get<1>(*size)));
    source.overrides.push_back(fmt::format("render.height={}", std::get<2>(*size)));
  }
  pipeline::TimeWindow window;
  for (const auto& [name, value] : {std::pair{"--from", options.from}, std::pair{"--to", options.to}}) {
    if (value && !(std::isfinite(*value) && *value >= 0)) {
      throw UsageError(fmt::format("{} {}: must be a simulated time >= 0 s", name, *value));
    }
  }
  if (options.from) window.from = *options.from;
  if (options.to) window.to = *options.to;
  if (window.from > window.to) {
    throw UsageError(fmt::format("--from {} --to {}: the window ends before it starts; give --from <= --to", window.from, window.to));
  }
  const auto [scene, provenance] = resolveScene(source);
  if (window.from > scene.duration) {
    throw UsageError(fmt::format("--from {}: beyond the run's end at {} s (the scene's duration); give a time in [0, {}]",
                                 window.from, scene.duration, scene.duration));
  }
  reportSteadyStart(scene);
  const std::filesystem::path output = options.output ? std::filesystem::path(*options.output)
                                                      : std::filesystem::path(fileNameFrom(scene.name) + ".mp4");
  const std::optional<video::VideoFormat> format = video::videoFormatOf(output);
  if (format == video::VideoFormat::Mp4 || format == video::VideoFormat::Gif) {
    const std::string kind = format == video::VideoFormat::Gif ? ".gif" : ".mp4";
    if (scene.render.picture.transparentBackground) {
      throw UsageError(fmt::format("render.background: \"transparent\" needs an output with alpha, and {} has none; write "
                                   "a .mov, a .webm or a PNG sequence (out_%05d.png), or set render.background to \"opaque\"",
                                   kind));
    }
  }
  if (scene.render.audio && (format == video::VideoFormat::Gif || format == video::VideoFormat::WebM)) {
    throw UsageError(fmt::format("render.audio: a {} gets no sound track; write a .mp4 or a .mov, or remove render.audio",
                                 format == video::VideoFormat::Gif ? ".gif" : ".webm"));
  }
  refuseOverwritingInput("-o", output, inputsOf(options.scene));
  video::VideoOptions encoding = scene.render.mp4Options();
  encoding.provenance = provenance;
  std::unique_ptr<video::FrameSink> sink;
  try {
    sink = std::make_unique<video::AsyncSink>(video::makeSinkForPath(output, encoding, inputsOf(options.scene)));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  // A render's log keeps to its summary line (its progress only on a terminal, as before).
  ProgressLine progress(options.quiet || isatty(STDERR_FILENO) != 1 ? ProgressLine::Style::Off : ProgressLine::Style::Terminal,
                        "render", "frame");
  const auto start = std::chrono::steady_clock::now();
  const pipeline::VideoRunResult result = withProgress(
      progress, output.string(),
      [&] {
        return pipeline::renderVideo(
            scene, *sink,
            {.onFrame = [&](const pipeline::FrameProgress& p) { progress.update(p.frame, p.total); },
             .cancel = &interruptRequested(),
             .maxFrames = options.maxFrames > 0 ? options.maxFrames : pipeline::kDefaultMaxFrames,
             .window = window});
      },
      [&] { sink.reset(); });  // removes the partial output before we report
  if (result.stopDescription) {
    std::cerr << fmt::format("coinroll: the run stopped early, the clip ends at t = {:.6f} s: {}\n", result.simulatedSeconds,
                             *result.stopDescription);
  }
  if (!options.quiet) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << fmt::format("coinroll: wrote {} ({} frames, {}x{} at {} fps, {:.2f} s of video) in {:.1f} s\n",
                             printable(output.string()), result.frames, scene.render.picture.width, scene.render.picture.height, scene.render.fps,
                             static_cast<double>(result.frames) / scene.render.fps, seconds);
  }
}

void runSweep(const SweepOptions& options) {
  refuseEmptyOutputName("-o", options.output, "sweep.csv (or - for standard output)");
  if (options.output != "-") refuseOverwritingInput("-o", options.output, inputsOf(options.scene));
  pipeline::SweepSpec spec;
  std::tie(spec.scene, spec.sourceName) = loadSceneDocument(options.scene);
  spec.parseOptions = {.solverMethods = integrate::methodNames()};
  // The scene must be valid as given: a grid then only varies fields of a scene that works.
  scene::parseScene(spec.scene, spec.sourceName, spec.parseOptions);
  try {
    for (const std::string& axis : options.grid) spec.axes.push_back(pipeline::parseGridAxis(axis));
    pipeline::refuseMisnamedAxes(spec);
    if (options.shard) {
      const char* arrayTaskId = std::getenv("SLURM_ARRAY_TASK_ID");
      spec.shard = pipeline::parseShard(*options.shard, arrayTaskId ? std::optional<std::string_view>(arrayTaskId) : std::nullopt);
    }
    if (options.maxPoints > 0) spec.maxPoints = options.maxPoints;
    if (options.threads < 0 || options.threads > 1024) {
      throw std::invalid_argument(fmt::format("--threads: must be 1 to 1024 (0: every hardware thread), got {}", options.threads));
    }
    pipeline::gridPointCount(spec);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  spec.threads = options.threads > 0 ? options.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  // In a batch job (Slurm, parallel) stderr is a log file: the progress comes as lines that name the shard.
  ProgressLine progress(ProgressLine::styleFor(options.quiet),
                        spec.shard.count > 1 ? fmt::format("sweep shard {}/{}", spec.shard.index, spec.shard.count) : "sweep",
                        "point");
  const auto start = std::chrono::steady_clock::now();
  const pipeline::SweepResult result = withProgress(progress, options.output, [&] {
    pipeline::SweepResult r;
    writeTextOutput(options.output, "sweep", [&](std::ostream& out) {
      r = pipeline::runSweep(spec, out, [&](long done, long total) { progress.update(done, total); }, &interruptRequested());
    });
    return r;
  });
  if (!options.quiet) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << fmt::format("coinroll: wrote {} ({} points{}, {} failed; {:.1f} s, {:.0f} points/s on {} threads)\n",
                             options.output == "-" ? "standard output" : printable(options.output), result.points,
                             spec.shard.count > 1 ? fmt::format(", shard {}/{}", spec.shard.index, spec.shard.count) : "",
                             result.failed, seconds, result.points / std::max(seconds, 1e-9), spec.threads);
  }
}

void runSweepMerge(const SweepMergeOptions& options) {
  const std::vector<std::filesystem::path> shards(options.shards.begin(), options.shards.end());
  // Checked before any file is opened: a closed descriptor 0 is the first one open() hands out, and
  // then reads as an empty shard (or as the output's temporary file).
  if (std::find(shards.begin(), shards.end(), "-") != shards.end() && ::fcntl(STDIN_FILENO, F_GETFD) == -1) {
    throw std::runtime_error("standard input: closed, so there is no shard to read from it; redirect the shard into it "
                             "(- < part.csv) or give its file name instead of -");
  }
  refuseEmptyOutputName("-o", options.output, "merged.csv (or - for standard output)");
  if (std::find(shards.begin(), shards.end(), "") != shards.end()) {
    throw UsageError("a shard name is empty; give the shard files (e.g. part_*.csv), or - for standard input");
  }
  if (options.output != "-") refuseOverwritingInput("-o", options.output, shards);
  ProgressLine noProgress(ProgressLine::Style::Off, "", "");
  withProgress(noProgress, options.output, [&] {
    writeTextOutput(options.output, "merged sweep",
                    [&](std::ostream& out) { pipeline::mergeSweepShards(shards, out, &interruptRequested()); });
    return 0;
  });
}

namespace {

// A picture to compare, checked as far as its header: its size, or a UsageError that names the
// file and says what to give instead.
image::PngSize checkComparedPng(const std::string& name) {
  const std::filesystem::path path(name);
  if (name.empty()) throw UsageError("a PNG name is empty; give the paths of the two PNGs to compare, e.g. golden.png new.png");
  std::error_code error;
  if (!std::filesystem::exists(path, error)) {
    throw UsageError(fmt::format("{}: no such file; give the path of a PNG to compare", name));
  }
  if (!std::filesystem::is_regular_file(path, error)) {
    throw UsageError(fmt::format("{}: not a regular file; give the path of a PNG to compare", name));
  }
  // stb would also decode JPEG, BMP, GIF, ...: a golden in another format is a mistake to name.
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UsageError(fmt::format("{}: cannot open: {}", name, std::strerror(errno)));
  constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  char head[8] = {};
  in.read(head, sizeof head);
  if (in.gcount() != sizeof head || std::memcmp(head, kSignature, sizeof head) != 0) {
    throw UsageError(fmt::format("{}: not a PNG file (no PNG signature); compare the PNGs coinroll still or render wrote",
                                 name));
  }
  image::PngSize size;
  try {
    size = image::readPngSize(path);
  } catch (const std::runtime_error& e) {
    throw UsageError(fmt::format("{} (a damaged or truncated PNG?)", e.what()));
  }
  // The decoder would read 16 bits per channel as 8, so two pictures that differ everywhere in
  // their low bytes would compare equal.
  if (size.bitDepth == 16) {
    throw UsageError(fmt::format("{}: 16 bits per channel; compare reads 8-bit PNGs (what coinroll writes): convert "
                                 "both, e.g. ffmpeg -i {} -pix_fmt rgba out8.png, or compare the 16-bit files with "
                                 "another tool", name, name));
  }
  return size;
}

// The decoder ignores CRCs, so the chunks are checked first: a damaged golden is no verdict.
image::Image decodeComparedPng(const std::string& name) {
  try {
    image::checkPngChunks(name);
  } catch (const std::runtime_error& e) {
    throw UsageError(e.what());
  }
  try {
    return image::readPng(name);
  } catch (const std::runtime_error& e) {
    throw UsageError(fmt::format("{} (a damaged or truncated PNG?)", e.what()));
  }
}

}  // namespace

int runCompare(const CompareOptions& options) {
  // Exit 1 means "the pictures differ" here, so every failure to compare is exit 2 (cmp(1)'s
  // convention), whatever its kind: a CI must never read a broken comparison as a verdict.
  try {
    if (options.channelTolerance < 0 || options.channelTolerance > 255) {
      throw UsageError(fmt::format("--channel-tolerance: must be a whole number 0..255, got {}", options.channelTolerance));
    }
    if (options.maxDifferingPixels && *options.maxDifferingPixels < 0) {
      throw UsageError(fmt::format("--max-differing-pixels: must be >= 0, got {}", *options.maxDifferingPixels));
    }
    if (options.maxDifferingFraction && !(*options.maxDifferingFraction >= 0 && *options.maxDifferingFraction <= 1)) {
      throw UsageError(fmt::format("--max-differing-fraction: must be in [0, 1] (0.01 is 1 % of the pixels), got {}",
                                   *options.maxDifferingFraction));
    }
    if (options.minPsnr && std::isnan(*options.minPsnr)) throw UsageError("--min-psnr: must be a number of dB, got nan");
    if (options.diff) {
      refuseEmptyOutputName("--diff", *options.diff, "diff.png");
      if (std::filesystem::path(*options.diff).extension() != ".png" && !io::namesStream(*options.diff)) {
        throw UsageError(fmt::format("--diff: the diff image is a PNG; give a name ending in .png, got \"{}\"", *options.diff));
      }
      refuseOverwritingInput("--diff", *options.diff, {options.a, options.b});
      io::checkOutputName(*options.diff);  // written after both pictures are read and compared
    }
    // Judged by the headers before anything is decoded: a small file may declare a huge picture.
    const image::PngSize sizeA = checkComparedPng(options.a), sizeB = checkComparedPng(options.b);
    if (sizeA.width != sizeB.width || sizeA.height != sizeB.height) {
      throw UsageError(fmt::format("{} is {}x{} but {} is {}x{}: compare pictures of the same size (render them with the same "
                                   "render.width and render.height)",
                                   options.a, sizeA.width, sizeA.height, options.b, sizeB.width, sizeB.height));
    }
    static_assert(image::kMaxComparedPixels == static_cast<long>(render::kMaxImageSide) * render::kMaxImageSide);
    const long pixels = static_cast<long>(sizeA.width) * sizeA.height;
    if (pixels > image::kMaxComparedPixels) {
      throw UsageError(fmt::format("{} and {} are {}x{}, more than the {} pixels compare decodes ({}x{}, the largest picture "
                                   "coinroll draws); compare smaller pictures", options.a, options.b, sizeA.width,
                                   sizeA.height, image::kMaxComparedPixels, render::kMaxImageSide, render::kMaxImageSide));
    }
    // RGBA pictures at the peak: A, B and B's decoder buffer; with --diff, A, B, the diff image and
    // the two buffers encoding it.
    pipeline::requireAddressSpace((options.diff ? 5 : 3) * 4 * static_cast<std::uint64_t>(pixels),
                                  fmt::format("comparing two {}x{} pictures", sizeA.width, sizeA.height),
                                  "compare smaller pictures");
    // Each step is bounded by the size limit above, so polling between them answers Ctrl-C quickly.
    const auto stopIfInterrupted = [&] {
      if (interruptRequested()) {
        throw UsageError(options.diff ? interruptionMessage(*options.diff) : interruption() + "; nothing was compared");
      }
    };
    const image::Image a = decodeComparedPng(options.a);
    stopIfInterrupted();
    const image::Image b = decodeComparedPng(options.b);
    stopIfInterrupted();
    const image::CompareThresholds thresholds{.maxDifferingPixels = options.maxDifferingPixels,
                                              .maxDifferingFraction = options.maxDifferingFraction,
                                              .channelTolerance = options.channelTolerance,
                                              .minPsnr = options.minPsnr};
    const image::ImageComparison result = image::compareImages(a, b, thresholds.channelTolerance);
    const bool pass = image::withinThresholds(result, thresholds);
    stopIfInterrupted();
    if (options.diff) image::writeDifferenceImage(a, b, thresholds.channelTolerance, *options.diff);

    // The verdict names the limits broken, or when a difference passes, the limits it was held to.
    const long maxPixels = options.maxDifferingPixels.value_or(options.maxDifferingFraction ? result.pixels : 0);
    std::string broken, heldTo;
    const auto add = [](std::string& list, const std::string& item) { list += (list.empty() ? "" : ", ") + item; };
    if (options.channelTolerance > 0) add(heldTo, fmt::format("--channel-tolerance {}", options.channelTolerance));
    if (options.maxDifferingPixels || !options.maxDifferingFraction) {
      add(heldTo, fmt::format("--max-differing-pixels {}", maxPixels));
      if (result.differingPixels > maxPixels) add(broken, fmt::format("{} > --max-differing-pixels {}", result.differingPixels, maxPixels));
    }
    if (options.maxDifferingFraction) {
      add(heldTo, fmt::format("--max-differing-fraction {}", *options.maxDifferingFraction));
      if (result.differingFraction() > *options.maxDifferingFraction) {
        add(broken, fmt::format("{:.6g} > --max-differing-fraction {}", result.differingFraction(), *options.maxDifferingFraction));
      }
    }
    if (options.minPsnr) {
      add(heldTo, fmt::format("--min-psnr {}", *options.minPsnr));
      if (!(result.psnr >= *options.minPsnr)) add(broken, fmt::format("{:.2f} dB < --min-psnr {}", result.psnr, *options.minPsnr));
    }
    const std::string verdict = !pass                              ? fmt::format("DIFFERENT ({})", broken)
                                : result.maxChannelDifference == 0 ? std::string("SAME (identical pixels)")
                                                                   : fmt::format("SAME within {}", heldTo);
    fmt::print("PSNR {:.2f} dB, {} of {} pixels differ ({:.4g} %, channel tolerance {}), max channel difference {}: {}\n",
               result.psnr, result.differingPixels, result.pixels, 100 * result.differingFraction(), options.channelTolerance,
               result.maxChannelDifference, verdict);
    errno = 0;
    std::fflush(stdout);
    if (std::ferror(stdout)) {
      throw std::runtime_error(fmt::format("writing to standard output failed: {}",
                                           errno != 0 ? std::strerror(errno) : "the stream reported an error"));
    }
    return pass ? kExitSuccess : kExitFailure;
  } catch (const UsageError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw UsageError(pipeline::outOfMemoryMessage());
  } catch (const std::exception& e) {
    throw UsageError(e.what());
  }
}

}  // namespace coinroll::cli
