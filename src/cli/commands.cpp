#include "cli/commands.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cerrno>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <variant>

#include "cli/command_support.h"
#include "cli/exit_codes.h"
#include "cli/frame_times.h"
#include "cli/interrupts.h"
#include "io/destination.h"
#include "io/output_file.h"
#include "io/output_group.h"
#include "physics/observables.h"
#include "physics/steady.h"
#include "physics/validity.h"
#include "pipeline/scene_run.h"
#include "pipeline/simulation.h"
#include "pipeline/still.h"
#include "pipeline/trajectory_samples.h"
#include "pipeline/plan_report.h"
#include "pipeline/video_frames.h"
#include "render/camera.h"
#include "video/async_sink.h"
#include "video/make_sink.h"
#include "video/png_sequence_sink.h"
#include "video/scene_digest.h"
#include "video/video_kinds.h"
#include "cli/progress.h"
#include "pipeline/trajectory_csv.h"
#include "scene/render_output.h"
#include "scene/json_reader.h"
#include "scene/scene_loader.h"

namespace coinroll::cli {

namespace {

constexpr double kDegreesPerRadian = 180 / std::numbers::pi;

scene::SceneConfig loadScene(const SceneSource& source, const std::optional<nlohmann::json>& initial = std::nullopt) {
  const auto [document, sourceName] = loadSceneDocument(source, initial);
  return scene::parseScene(document, sourceName);
}

// A scene as a command that writes pictures resolves it (--set applied), with the provenance its
// outputs carry: the release, and a digest of the scene document as resolved (compact JSON, keys
// sorted), so the same release and scene give the same bytes (docs/outputs.md "Provenance").
struct ResolvedScene {
  scene::SceneConfig config;
  video::Provenance provenance;  // empty with render.provenance: false
  bool named = false;            // the document gives a name that is not empty
  std::string digest;            // of the resolved document, whether or not the outputs carry it
};

video::Provenance provenanceOf(const nlohmann::json& document) {
  return {.software = fmt::format("coinroll {}", COINROLL_VERSION), .sceneDigest = sceneDigestOf(document)};
}

ResolvedScene resolveScene(const SceneSource& source) {
  const auto [document, sourceName] = loadSceneDocument(source);
  ResolvedScene resolved{scene::parseScene(document, sourceName), {}, false, {}};
  if (resolved.config.render.provenance) resolved.provenance = provenanceOf(document);
  resolved.named = document.contains("name") && document.at("name") != "";
  resolved.digest = sceneDigestOf(document);
  return resolved;
}

// The CSV's sidecar (SimulateOptions::provenancePath).
nlohmann::json csvProvenance(const nlohmann::json& document, const SimulateOptions& options,
                             const pipeline::SceneTable& run) {
  const video::Provenance provenance = provenanceOf(document);
  return {{"program", "coinroll"},
          {"version", COINROLL_VERSION},
          {"scene_digest", provenance.sceneDigest},
          {"command", "simulate"},
          {"csv", options.csvPath},  // any bytes: dumped with invalid UTF-8 replaced (U+FFFD)
          {"sample_dt", options.sampleDt},
          {"rows", run.run.rows},
          {"end", run.end.event},
          {"end_time", run.end.time},
          {"scene", document}};
}

void reportSteadyStart(const scene::SceneConfig& scene, bool quiet) {
  if (quiet) return;
  if (const std::string note = pipeline::steadyStartNote(scene); !note.empty())
    std::cerr << "coinroll: note: " << note << '\n';
}

// Where a sidecar's name leads, for comparing it with its run's other outputs; nothing for a name
// that does not resolve, which the output layer then refuses with its reason when it opens it.
std::optional<io::Destination> destinationOf(const std::filesystem::path& name) {
  try {
    return io::resolveDestination(name);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// The scene with --size applied: after the --set ones, so the option names the size whatever the
// scene or a --set says.
SceneSource withPictureSize(const SceneSource& scene, const std::optional<std::string>& sizeName) {
  SceneSource source = scene;
  if (!sizeName) return source;
  const std::optional<scene::PictureSize> size = scene::pictureSizeNamed(*sizeName);
  if (!size) {
    throw UsageError(fmt::format("--size {}: unknown size; give {} (or set render.width and render.height with --set)",
                                 scene::printable(*sizeName), scene::pictureSizeNames()));
  }
  source.overrides.push_back(fmt::format("render.width={}", size->width));
  source.overrides.push_back(fmt::format("render.height={}", size->height));
  return source;
}

// render --frame-times: a file of its own, neither the video, nor a frame of its sequence (which
// would replace it, or remove it as a frame of an earlier, longer sequence), nor an input. Names
// are compared by the file they lead to, not by their spelling.
void refuseFrameTimesName(const std::string& path, const std::filesystem::path& video,
                          const std::vector<std::filesystem::path>& inputs) {
  const std::string example = video.stem().string() + "_frames.csv";
  refuseEmptyOutputName("--frame-times", path, example);
  if (path == "-") {
    throw UsageError(fmt::format("--frame-times -: give a file of its own beside the video, e.g. {}", example));
  }
  refuseOverwritingInput("--frame-times", path, inputs);
  const std::optional<io::Destination> sidecar = destinationOf(path);
  if (!sidecar) return;
  if (video::namesPngSequence(video)) {
    std::optional<video::SequencePattern> frames;
    try {
      frames = video::parseSequencePattern(video);
    } catch (const std::invalid_argument&) {
      return;  // the sink refuses the pattern, naming the rule it breaks
    }
    std::error_code error;
    const std::filesystem::path framesDirectory = video.parent_path().empty() ? "." : video.parent_path();
    if (!sidecar->path.empty() && std::filesystem::equivalent(sidecar->path.parent_path(), framesDirectory, error) &&
        frames->frameNumberOf(sidecar->path.filename().string())) {
      const std::string sequenceExample = frames->prefix + "frames.csv";
      throw UsageError(
          fmt::format("--frame-times {}: that is named like a frame of -o {}, which would replace it or "
                      "remove it; give a name the pattern cannot make, e.g. {}",
                      path, video.string(), sequenceExample));
    }
    return;
  }
  if (const std::optional<io::Destination> output = destinationOf(video); output && io::sameOutput(*sidecar, *output)) {
    throw UsageError(fmt::format(
        "--frame-times {}: that is the video's own name; give a file of its own beside it, e.g. {}", path, example));
  }
}

// simulate --provenance: a file of its own beside the CSV, whatever the spellings of the two.
void refuseProvenanceName(const SimulateOptions& options) {
  const std::string& path = *options.provenancePath;
  const std::string example = options.csvPath == "-" ? "run.json" : options.csvPath + ".json";
  refuseEmptyOutputName("--provenance", path, example);
  refuseOverwritingInput("--provenance", path, inputsOf(options.scene));
  const auto ownFile = [&] {
    return UsageError(fmt::format("--provenance {}: give a file of its own beside the CSV, e.g. {}", path, example));
  };
  if (path == "-" || path == options.csvPath) throw ownFile();
  const std::optional<io::Destination> sidecar = destinationOf(path);
  const std::optional<io::Destination> csv = destinationOf(options.csvPath == "-" ? "/dev/stdout" : options.csvPath);
  if (sidecar && csv && io::sameOutput(*sidecar, *csv)) throw ownFile();
}

// Bytes of CSV per value, comma included: 17 significant digits, sign, point and exponent come to
// 18 to 24, and the examples' rows average 14 to 20 bytes a column (spin_in_place to euler_disk).
constexpr double kCsvBytesPerValue = 20;

// "150 GB", "15.3 kB": a size estimate for a message, to three digits.
std::string approximateBytes(double bytes) {
  if (bytes >= 1e9) return fmt::format("{:.3g} GB", bytes / 1e9);
  if (bytes >= 1e6) return fmt::format("{:.3g} MB", bytes / 1e6);
  return fmt::format("{:.3g} kB", bytes / 1e3);
}

}  // namespace

void runSimulate(const SimulateOptions& options) {
  refuseEmptyOutputName("--csv", options.csvPath, "out.csv (or - for standard output)");
  if (options.csvPath != "-") refuseOverwritingInput("--csv", options.csvPath, inputsOf(options.scene));
  if (options.provenancePath) refuseProvenanceName(options);
  // Named, not a structured binding: the run's lambda captures the document, which clang 14 (the
  // sanitizer build's compiler) cannot do with a binding.
  const std::pair<nlohmann::json, std::string> loaded = loadSceneDocument(options.scene);
  const nlohmann::json& document = loaded.first;
  const scene::SceneConfig scene = scene::parseScene(document, loaded.second);
  const pipeline::SceneRunRequest request{
      .sampleDt = options.sampleDt,
      .sampleDtName = "--sample-dt",
      .maxRows = options.maxRows > 0 ? options.maxRows : pipeline::kDefaultMaxRows,
      .maxRowsOption = "--max-rows",
      .rowsCost =
          [](double rows, std::size_t columns) {
            return fmt::format("about {} of CSV",
                               approximateBytes(rows * static_cast<double>(columns) * kCsvBytesPerValue));
          },
      .cancel = &interruptRequested()};

  // The outputs open only once the run is accepted, so a refused run touches no file. With a
  // sidecar the CSV and it are published together or not at all: a failed or interrupted run leaves
  // both earlier files as they were.
  io::OutputGroup outputs;
  io::OutputGroup* const group = options.provenancePath ? &outputs : nullptr;
  std::optional<io::OutputFile> csv, provenance;
  std::ostream* out = &std::cout;
  pipeline::TrajectoryCsvLine csvLine;
  const auto begin = [&](const pipeline::RunStart& start) {
    if (!options.quiet) {
      for (const std::string& note : start.notes) std::cerr << note << '\n';
    }
    if (options.csvPath != "-") {
      out = &csv.emplace(options.csvPath, "CSV", io::OutputFile::Access::Sequential, group).stream();
    }
    if (options.provenancePath) {
      provenance.emplace(*options.provenancePath, "provenance JSON", io::OutputFile::Access::Sequential, group);
    }
    *out << pipeline::trajectoryCsvHeader(start.columns);
  };
  const auto row = [&](std::span<const double> values) {
    const std::string_view text = csvLine(values);
    out->write(text.data(), static_cast<std::streamsize>(text.size()));
  };
  ProgressLine noProgress(ProgressLine::Style::Off, "", "");
  const pipeline::SceneTable table = withProgress(noProgress, options.csvPath, [&] {
    pipeline::SceneTable run = pipeline::simulateScene(scene, request, {.begin = begin, .row = row});
    if (!csv) finishStandardOutput("CSV");
    if (provenance) {
      provenance->stream()
          << csvProvenance(document, options, run).dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
          << '\n';
    }
    if (csv) csv->commit();
    if (provenance) {
      provenance->commit();
      outputs.commit();
    }
    return run;
  });
  for (const std::string& line : table.report) {
    // Quiet keeps what changes the meaning of the CSV: a warning, and a run that ended early.
    if (options.quiet && !line.starts_with("coinroll: warning:") && !line.starts_with("coinroll: stopped early:"))
      continue;
    std::cerr << line << '\n';
  }
}

void runSteady(const SteadyOptions& options) {
  for (const auto& [name, value] :
       {std::pair{"--theta", options.thetaDegrees}, std::pair{"--omega-Z", options.omega_Z}}) {
    // JSON has no NaN or infinity: passed on, they would come back as a null the scene names.
    if (value && !std::isfinite(*value))
      throw UsageError(fmt::format("{}: must be a finite number, got {}", name, *value));
  }
  std::optional<nlohmann::json> initial;  // the steady state the options name, as the scene file would
  if (options.kind) {
    initial = nlohmann::json{{"steady", *options.kind}};
    if (options.thetaDegrees) (*initial)["theta"] = *options.thetaDegrees;
    if (options.omega_Z) (*initial)["omega_Z"] = *options.omega_Z;
    if (options.branch) (*initial)["branch"] = *options.branch;
  } else if (options.thetaDegrees || options.omega_Z || options.branch) {
    throw UsageError("--theta, --omega-Z and --branch describe a steady state: give --kind too");
  }
  const scene::SceneConfig scene = loadScene(options.scene, initial);
  if (!std::holds_alternative<scene::SteadyInitial>(scene.initial)) {
    throw UsageError(
        "steady: give --kind straight|circle|spin-in-place, or a scene whose initial names a steady state");
  }
  const pipeline::Simulation sim = pipeline::buildSimulation(scene);
  if (!scene.effects.empty() && !options.quiet) {
    std::cerr << "coinroll: note: the steady state and its stability below are those of the ideal model; the scene's "
                 "effects dissipate energy, so with them this state is only where a slowing motion starts\n";
  }
  const physics::CoinModel& m = sim.model;
  const physics::CoinState& s = sim.initial;
  const physics::SteadyReport report = physics::steadyReport(m, s);
  const double rateUnit = report.naturalRate;
  const double K = report.stiffness;

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
  if (!report.criticalSpin) {
    fmt::print(
        "natural rate sqrt(g/a) = {:.6g} rad/s; straight rolling is not a steady motion of a coin whose rim has "
        "corners (it switches corners at upright), so there is no critical spin (docs/rim.md eq. 5.4)\n\n",
        rateUnit);
  } else {
    const double omega_c = *report.criticalSpin;
    fmt::print(
        "natural rate sqrt(g/a) = {:.6g} rad/s; critical spin for straight rolling omega_c = {:.6g} rad/s "
        "({:.6f} sqrt(g/a){})\n\n",
        rateUnit, omega_c, omega_c / rateUnit, thick ? "; docs/rim.md eq. 5.9" : "");
  }
  fmt::print("initial conditions (scene units):\n");
  fmt::print(
      "  \"initial\": {{\"theta\": {:.12g}, \"phi\": {:.12g}, \"psi\": {:.12g}, \"omega_X\": {:.12g}, "
      "\"omega_Y\": {:.12g}, \"omega_Z\": {:.12g}, \"x\": {:.12g}, \"z\": {:.12g}}}\n",
      s.theta * kDegreesPerRadian, s.phi * kDegreesPerRadian, s.psi * kDegreesPerRadian, s.omega_X, s.omega_Y,
      s.omega_Z, s.x, s.z);
  fmt::print("  in units of sqrt(g/a): omega_Y = {:.9g}, omega_Z = {:.9g}\n", s.omega_Y / rateUnit,
             s.omega_Z / rateUnit);
  fmt::print("  phi-dot = {:.9g} rad/s, psi-dot = {:.9g} rad/s\n", report.precessionRate, report.spinRate);
  fmt::print("  circle radius: centre of mass R_G = {:.9g} m, contact point R_C = {:.9g} m\n",
             report.radii.centreOfMass, report.radii.contact);
  const physics::Reaction& r = report.reaction;
  fmt::print("  floor reaction: N = {:.6g} N, F = {:.6g} N (needs mu >= {:.4g})\n\n", r.N, r.F,
             r.N > 0 ? r.F / r.N : INFINITY);
  fmt::print("stability ({}): K = {:.9g} 1/s^2 ({:.9g} in units g/a)\n",
             thick ? "docs/rim.md eq. 5.8" : "docs/derivations.md eq. 3.6", K, K / (rateUnit * rateUnit));
  switch (const physics::TiltStability& stability = report.stability; stability.kind) {
    case physics::TiltStability::Kind::Stable:
      fmt::print("verdict: STABLE: a small tilt perturbation wobbles at {:.9g} rad/s (period {:.9g} s)\n",
                 stability.rate, stability.time);
      break;
    case physics::TiltStability::Kind::Unstable:
      fmt::print(
          "verdict: UNSTABLE: a small tilt perturbation grows like exp({:.9g} t / s) (e-folding time {:.9g} s)\n",
          stability.rate, stability.time);
      break;
    case physics::TiltStability::Kind::Marginal: fmt::print("verdict: MARGINAL (K = 0)\n"); break;
  }
}

void runStill(const StillOptions& options) {
  if (options.output) refuseEmptyOutputName("-o", *options.output, "still.png");
  // A device, FIFO or descriptor has no name to check: it gets the PNG.
  if (options.output && !video::namesExtension(*options.output, video::kPngExtension) &&
      !io::namesStream(*options.output)) {
    throw UsageError(
        fmt::format("-o: a still is written as PNG; give a name ending in .png, got \"{}\"", *options.output));
  }
  if (options.strobeFrom && options.strobe == 0) {
    throw UsageError("--strobe-from: places the first of the --strobe copies, and there are none; give --strobe N too");
  }
  if (options.panels && options.strobe == 0) {
    throw UsageError("--panels: lays out the --strobe copies side by side, and there are none; give --strobe N too");
  }
  const auto [scene, provenance, named, digest] = resolveScene(withPictureSize(options.scene, options.size));
  const std::filesystem::path output = options.output
                                           ? std::filesystem::path(*options.output)
                                           : defaultOutputName(named, scene.name, options.scene, video::kPngExtension);
  refuseOverwritingInput("-o", output, inputsOf(options.scene));
  if (!options.output && !options.force) refuseTakingOverDefaultName(output, digest, video::readSceneDigest);
  io::checkOutputName(output);  // the PNG is written after the rendering: a name that cannot work fails first
  reportSteadyStart(scene, options.quiet);
  pipeline::StillResult result;
  try {
    result = pipeline::renderStill(scene, {.time = options.time,
                                           .ghosts = options.strobe,
                                           .ghostsFrom = options.strobeFrom.value_or(0),
                                           .panels = options.panels,
                                           .output = output,
                                           .text = provenance.pngText(),
                                           .cancel = &interruptRequested()});
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  } catch (const pipeline::Cancelled&) {
    throw std::runtime_error(interruptionMessage(output.string()));
  }
  if (result.stopDescription) {
    std::cerr << fmt::format("coinroll: the run stopped early, so the still shows t = {:.6f} s: {}\n", result.shownTime,
                             *result.stopDescription);
  }
  if (!options.quiet) {
    std::cerr << fmt::format("coinroll: wrote {} ({}x{}, t = {:.6g} s)\n", scene::printable(output.string()),
                             result.width, result.height, result.shownTime);
  }
}

// The window of frames to write, on one clock: simulated seconds (--from/--to) or seconds of video
// (--from-video/--to-video, or --last). Options of both clocks, or both ways of giving the video
// window, are refused naming the two: which one was meant cannot be guessed.
pipeline::TimeWindow windowOf(const RenderOptions& options) {
  const std::array<std::pair<const char*, std::optional<double>>, 5> given = {
      std::pair{"--from", options.from}, std::pair{"--to", options.to}, std::pair{"--from-video", options.fromVideo},
      std::pair{"--to-video", options.toVideo}, std::pair{"--last", options.last}};
  for (std::size_t i = 0; i < given.size(); ++i) {
    const auto& [name, value] = given[i];
    const char* clock = i < 2 ? "simulated time" : "video time";
    // "--to-video inf" most likely means "to the end", which is what leaving the option out gives.
    if (value && !std::isfinite(*value)) {
      const char* bound = i == 1 || i == 3 ? "end" : i == 4 ? "whole length" : "start";
      throw UsageError(
          fmt::format("{} {}: must be a finite number of seconds ({} >= 0 s); leave {} out for the "
                      "clip's {}",
                      name, *value, clock, name, bound));
    }
    if (value && *value < 0) throw UsageError(fmt::format("{} {}: must be a {} >= 0 s", name, *value, clock));
  }
  if (options.last && !(*options.last > 0)) {
    throw UsageError(fmt::format("--last {}: give the seconds of video to keep, > 0", *options.last));
  }
  const auto firstGiven = [&](std::size_t begin, std::size_t end) -> const char* {
    for (std::size_t i = begin; i < end; ++i) {
      if (given[i].second) return given[i].first;
    }
    return nullptr;
  };
  const char* simulated = firstGiven(0, 2);
  const char* video = firstGiven(2, 5);
  if (simulated && video) {
    throw UsageError(
        fmt::format("{} and {} cannot be combined: {} counts simulated seconds, {} seconds of video "
                    "(frame k plays at k / fps); give the window on one clock (render --plan prints both)",
                    simulated, video, simulated, video));
  }
  if (options.last && (options.fromVideo || options.toVideo)) {
    throw UsageError(
        fmt::format("--last and {} cannot be combined: --last L is the window from L s of video before "
                    "the clip's end to its end; give --last, or --from-video and --to-video",
                    options.fromVideo ? "--from-video" : "--to-video"));
  }
  pipeline::TimeWindow window;
  if (options.last) {
    window.last = options.last;
    window.clock = pipeline::TimeWindow::Clock::Video;
    return window;
  }
  const std::optional<double> from = video ? options.fromVideo : options.from;
  const std::optional<double> to = video ? options.toVideo : options.to;
  if (video) window.clock = pipeline::TimeWindow::Clock::Video;
  if (from) window.from = *from;
  if (to) window.to = *to;
  if (window.from > window.to) {
    const char* fromName = video ? "--from-video" : "--from";
    const char* toName = video ? "--to-video" : "--to";
    throw UsageError(fmt::format("{} {} {} {}: the window ends before it starts; give {} <= {}", fromName, window.from,
                                 toName, window.to, fromName, toName));
  }
  return window;
}

namespace {

// The plan as data (render --plan --json): the clip's clock and, per frame, the camera and the overlay
// render draws it with, so a tool (the WebAssembly core's drift test) compares numbers, not a table.
nlohmann::json planJson(const pipeline::ClipViews& views, const pipeline::TimeWindow& window,
                        const std::string& output) {
  const pipeline::ClipPlan& plan = views.plan;
  const auto slowedBy = [](pipeline::SlowedBy by) -> nlohmann::json {
    switch (by) {
      case pipeline::SlowedBy::Rate: return "rate";
      case pipeline::SlowedBy::Flight: return "flight";
      case pipeline::SlowedBy::Impact: return "impact";
      case pipeline::SlowedBy::Nothing: break;
    }
    return nullptr;
  };
  // The floats' exact values as doubles: float's shortest text would read back as another double.
  const auto vector = [](const glm::vec3& v) {
    return nlohmann::json::array({static_cast<double>(v.x), static_cast<double>(v.y), static_cast<double>(v.z)});
  };
  const pipeline::FrameRange written = pipeline::framesIn(plan, window);
  nlohmann::json frames = nlohmann::json::array();
  for (std::size_t k = 0; k < views.frames.size(); ++k) {
    const render::CameraView& camera = views.frames[k].camera;
    frames.push_back({{"sim_time_s", plan.times[k]},
                      {"playback_rate", plan.playbackRates[k]},
                      {"slowed_by", slowedBy(plan.slowedBy[k])},
                      {"camera",
                       {{"eye", vector(camera.eye)},
                        {"target", vector(camera.target)},
                        {"up", vector(render::upOf(camera))},
                        {"fov_y_degrees", static_cast<double>(camera.fovYDegrees)}}},
                      {"overlay_lines", views.frames[k].overlayLines}});
  }
  return {{"output", output},
          {"fps", plan.fps},
          {"time_scale", plan.timeScale},
          {"end_time", plan.endTime},
          {"stopped_early", plan.stopDescription ? nlohmann::json(*plan.stopDescription) : nlohmann::json(nullptr)},
          {"simulated_frames", plan.simulatedFrames},
          {"landed", plan.landed},
          {"hold_seconds", plan.landed ? pipeline::kLandingHoldSeconds : 0.0},
          {"written", {{"first", written.first}, {"last", written.last}}},
          {"frames", std::move(frames)}};
}

}  // namespace

void runRender(const RenderOptions& options) {
  if (options.output) refuseEmptyOutputName("-o", *options.output, "clip.mp4");
  const SceneSource source = withPictureSize(options.scene, options.size);
  const pipeline::TimeWindow window = windowOf(options);
  if (options.plan && options.frameTimesPath) {
    throw UsageError(
        "--plan and --frame-times cannot be combined: a plan draws and writes nothing; drop --frame-times "
        "(the plan's table shows the playback rate; --frame-times lists it per frame of a render)");
  }
  if (options.json && !options.plan) {
    throw UsageError(
        "--json: prints the --plan as one JSON document, and there is no plan; give --plan too (a "
        "render's own frame times are --frame-times FILE.csv)");
  }
  const ResolvedScene resolved = resolveScene(source);  // named: clang 14 cannot capture a structured binding
  const scene::SceneConfig& scene = resolved.config;
  const video::Provenance& provenance = resolved.provenance;
  reportSteadyStart(scene, options.quiet);
  video::VideoOptions encoding = scene.render.mp4Options();
  encoding.provenance = provenance;
  const std::filesystem::path output = options.output ? std::filesystem::path(*options.output)
                                                      : defaultOutputName(resolved.named, scene.name, options.scene,
                                                                          video::videoKind(encoding.format).extension);
  if (const std::optional<video::VideoFormat> format = video::videoFormatOf(output)) {
    try {
      video::refuseOutputThatCannotCarry(encoding, *format);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  refuseOverwritingInput("-o", output, inputsOf(options.scene));
  if (!options.output && !options.force && !options.plan)
    refuseTakingOverDefaultName(output, resolved.digest, video::readSceneDigest);
  const long maxFrames = options.maxFrames > 0 ? options.maxFrames : pipeline::kDefaultMaxFrames;
  if (options.plan) {
    try {
      if (options.json) {
        const nlohmann::json plan =
            planJson(pipeline::planClipViews(scene, maxFrames, &interruptRequested()), window, output.string());
        // Doubles as the shortest text that reads back as the same double; a name that is not UTF-8 is kept readable.
        fmt::print("{}\n", plan.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
        return;
      }
      const pipeline::ClipPlan plan = pipeline::planClip(scene, maxFrames, &interruptRequested());
      fmt::print("plan of {} (nothing drawn, nothing written; frame k plays at video time k / fps)\n",
                 scene::printable(output.string()));
      for (const std::string& line : pipeline::planLines(plan, window)) fmt::print("{}\n", line);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    } catch (const pipeline::Cancelled&) {
      throw std::runtime_error(interruptionMessage(output.string()));
    }
    return;
  }
  if (options.frameTimesPath) refuseFrameTimesName(*options.frameTimesPath, output, inputsOf(options.scene));
  // Every file of the run (the video or its frames, the sidecar) is staged here and published by
  // one commit, all or none; declared first, it outlives their writers and removes what they staged
  // when the run fails or is interrupted.
  io::OutputGroup outputs;
  outputs.protect(inputsOf(options.scene));
  std::unique_ptr<video::FrameSink> sink;
  try {
    sink =
        std::make_unique<video::AsyncSink>(video::makeSinkForPath(output, encoding, inputsOf(options.scene), &outputs));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  // Staged before the first frame reaches the sink's thread, which stages frames in the same group.
  std::optional<FrameTimesSidecar> frameTimes;
  if (options.frameTimesPath) frameTimes.emplace(*options.frameTimesPath, scene.render.fps, outputs);
  // A render's log keeps to its summary line (its progress only on a terminal, as before).
  ProgressLine progress(ProgressLine::terminalStyleFor(options.quiet), "render", "frame");
  const auto start = std::chrono::steady_clock::now();
  const pipeline::VideoRunResult result = withProgress(
      progress, output.string(),
      [&] {
        const pipeline::VideoRunResult ran = pipeline::renderVideo(
            scene, *sink,
            {.onFrame = [&](const pipeline::FrameProgress& p) { progress.update(p.frame, p.total); },
             .onFrameTiming = frameTimes ? [&](const pipeline::FrameTiming& timing) { frameTimes->add(timing); }
                                         : std::function<void(const pipeline::FrameTiming&)>(),
             .cancel = &interruptRequested(),
             .maxFrames = maxFrames,
             .window = window,
             .inset = options.inset});
        if (frameTimes) frameTimes->finish();
        outputs.commit();
        return ran;
      },
      [&] { sink.reset(); });  // removes the partial output before we report
  if (result.stopDescription) {
    std::cerr << fmt::format("coinroll: the run stopped early, the clip ends at t = {:.6f} s: {}\n",
                             result.simulatedSeconds, *result.stopDescription);
  }
  if (!options.quiet) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << fmt::format("coinroll: wrote {} ({} frames, {}x{} at {} fps, {:.2f} s of video) in {:.1f} s\n",
                             scene::printable(output.string()), result.frames, scene.render.picture.width,
                             scene.render.picture.height, scene.render.fps,
                             static_cast<double>(result.frames) / scene.render.fps, seconds);
  }
}

}  // namespace coinroll::cli
