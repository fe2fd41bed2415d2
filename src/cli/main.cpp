// coinroll: command-line entry point. Parses arguments, runs one command, maps errors to the exit
// codes of docs/contract.md. All logic lives in the libraries; this file only wires them.

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <iostream>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "cli/commands.h"
#include "cli/exit_codes.h"
#include "cli/interrupts.h"
#include "cli/nearest_name.h"
#include "cli/version.h"
#include "pipeline/resources.h"
#include "pipeline/sweep.h"
#include "pipeline/trajectory_samples.h"
#include "pipeline/video_frames.h"
#include "scene/render_output.h"
#include "scene/json_reader.h"
#include "scene/scene_loader.h"
#include "video/video_kinds.h"

namespace {

using namespace coinroll::cli;

void addSceneOptions(CLI::App& command, SceneSource& scene, bool fileRequired) {
  CLI::Option* file = command.add_option(
      "scene", scene.file, "Scene file (JSON; its keys: docs/scene.md, or coinroll schema); - reads standard input");
  if (fileRequired) file->required();
  command
      .add_option("--set", scene.overrides,
                  "Override one scene field, KEY.PATH=VALUE (e.g. --set initial.theta=12 --set solver.rtol=1e-9); "
                  "repeatable")
      ->type_name("KEY=VALUE");
}

// -q, the same on every command that prints notes, progress or a summary on stderr.
void addQuietFlag(CLI::App& command, bool& quiet, const std::string& what) {
  command.add_flag("-q,--quiet", quiet, what + "; warnings, an early stop and errors are still printed");
}

// -o for the commands that write one picture, video or page: optional, the output then named after
// the scene (a default name that holds another scene's output is refused, --force replaces it).
void addOutputOptions(CLI::App& command, std::optional<std::string>& output, bool& force, const std::string& what) {
  command.add_option("-o,--output", output,
                     what +
                         "; default: the scene's name (or its file's, for a scene without one) + the extension, "
                         "coinroll + it for the built-in scene");
  command.add_flag("--force", force,
                   "Without -o: replace the file under the default name even when another scene made it (or it "
                   "names none); an -o name is always replaced");
}

// Limits a user raises: whole numbers from 1 (0 and negatives used to mean "the default" silently).
const CLI::Validator kAtLeastOne(
    [](std::string& text) -> std::string {
      long value = 0;
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
      if (error != std::errc() || end != text.data() + text.size() || value < 1) {
        return "must be a whole number >= 1, got " + text;
      }
      return {};
    },
    "INT>=1");

// Flushes stdout; false, with the reason on stderr, when what was printed did not all reach it.
// errno is the caller's to clear before the printing.
bool standardOutputWritten() {
  std::cout.flush();
  if (std::cout && std::fflush(stdout) == 0 && !std::ferror(stdout)) return true;
  std::cerr << "coinroll: error: writing to standard output failed: "
            << (errno != 0 ? std::strerror(errno) : "the stream reported an error") << '\n';
  return false;
}

// A subcommand as main() sees it: CLI11 fills its options while parsing, then run() acts on them
// and gives the exit code (compare's 1 means "the pictures differ"; the others succeed or throw).
struct Command {
  CLI::App* parsed = nullptr;
  std::function<int()> run;
};

// `add` declares the command's options on `app`; the options live as long as the Command.
template <class Options, class Run>
Command addCommand(CLI::App& app, CLI::App* (*add)(CLI::App&, Options&), Run run) {
  auto options = std::make_shared<Options>();
  CLI::App* parsed = add(app, *options);
  return {parsed, [options, run] {
            if constexpr (std::is_void_v<std::invoke_result_t<Run, const Options&>>) {
              run(*options);
              return kExitSuccess;
            } else {
              return run(*options);
            }
          }};
}

CLI::App* addSimulateCommand(CLI::App& app, SimulateOptions& options) {
  CLI::App* command = app.add_subcommand(
      "simulate", "Integrate a scene and write the trajectory CSV (t, angles, rates, positions, energy, N, F)");
  addSceneOptions(*command, options.scene, false);  // no file: the built-in default scene
  command->add_option("--csv", options.csvPath, "Output CSV path, or - for stdout")->required();
  command->add_option("--sample-dt", options.sampleDt, "Time between rows, s (rows at t = k S)")->capture_default_str();
  command
      ->add_option("--max-rows", options.maxRows,
                   fmt::format("Refuse runs whose duration / sample step exceeds this many rows (default {})",
                               coinroll::pipeline::kDefaultMaxRows))
      ->check(kAtLeastOne);
  command->add_option("--provenance", options.provenancePath,
                      "Also write FILE.json naming what made the CSV: coinroll's version, the scene's digest and the "
                      "resolved scene, the sample step and how the run ended (the CSV's header stays the contract's)");
  addQuietFlag(*command, options.quiet, "No notes, mode switches or summary on stderr");
  return command;
}

CLI::App* addSteadyCommand(CLI::App& app, SteadyOptions& options) {
  CLI::App* command = app.add_subcommand(
      "steady", "Steady motions (straight, circle, spin in place) of a coin: initial conditions and stability K");
  addSceneOptions(*command, options.scene, false);
  command->add_option("--kind", options.kind, "straight | circle | spin-in-place")
      ->check(CLI::IsMember({"straight", "circle", "spin-in-place"}));
  command->add_option("--theta", options.thetaDegrees, "Tilt from vertical, degrees (circle, spin-in-place)");
  command->add_option("--omega-Z", options.omega_Z, "Spin about the coin normal, rad/s (straight, circle)");
  command->add_option("--branch", options.branch, "Circle root: + (f+, default) or - (f-)")
      ->check(CLI::IsMember({"+", "-"}));
  addQuietFlag(*command, options.quiet, "No note on stderr (the report on stdout stays)");
  command->footer(
      "Without a scene file the built-in default coin is used. With coin.thickness (and coin.edge_radius) the coin\n"
      "is a solid with a rounded rim (docs/rim.md §5): its steady states and K follow the rim, e.g.\n"
      "  coinroll steady --kind straight --omega-Z 12 --set coin.thickness=0.013\n"
      "A rim with corners (edge_radius < thickness / 2) switches corners at upright, so it has no straight rolling.");
  return command;
}

// --size NAME, the same on every command that draws pictures (render, still).
void addSizeOption(CLI::App& command, std::optional<std::string>& size) {
  std::string sizes, sizeNames;
  for (const coinroll::scene::PictureSize& picture : coinroll::scene::kPictureSizes) {
    const bool last = &picture == &coinroll::scene::kPictureSizes.back();
    sizes += fmt::format("{}{} ({}x{})",
                         sizes.empty() ? ""
                         : last        ? " or "
                                       : ", ",
                         picture.name, picture.width, picture.height);
    sizeNames += fmt::format("{}{}", sizeNames.empty() ? "" : "|", picture.name);
  }
  command.add_option("--size", size, "Picture size, setting render.width x render.height: " + sizes)
      ->type_name(sizeNames);
}

CLI::App* addRenderCommand(CLI::App& app, RenderOptions& options) {
  // "an MP4 (H.264)" for the command, "NAME.mp4 (H.264)" for -o: the codec where the kind is not
  // named after it, and whether it loops.
  std::vector<std::string> kinds;
  std::string names;
  for (const coinroll::video::VideoKind& kind : coinroll::video::videoKinds()) {
    kinds.push_back(
        fmt::format("{} {}{}", kind.article, kind.label, kind.codec.empty() ? "" : fmt::format(" ({})", kind.codec)));
    std::vector<std::string_view> notes;
    if (!kind.codec.empty()) notes.push_back(kind.codec);
    if (kind.loops) notes.push_back("looping");
    names += fmt::format("NAME{} ({}), ", kind.extension, fmt::join(notes, ", "));
  }
  kinds.emplace_back("a PNG sequence");
  const std::string_view defaultExtension =
      coinroll::video::videoKind(coinroll::video::VideoOptions{}.format).extension;
  CLI::App* command = app.add_subcommand(
      "render",
      fmt::format("Render a scene to {}; without a scene, the built-in default", coinroll::video::joinedWithOr(kinds)));
  addSceneOptions(*command, options.scene, false);
  addOutputOptions(*command, options.output, options.force,
                   fmt::format("Output, its kind by the extension (any case): {}or a PNG sequence pattern like "
                               "frames_%05d.png (frames numbered from 0); the default extension is {}",
                               names, defaultExtension));
  addSizeOption(*command, options.size);
  command
      ->add_option("--from", options.from,
                   "Write only the frames whose simulated time is at least T0 s (default 0); the simulation still "
                   "runs from 0, so they are the full render's frames")
      ->type_name("T0");
  command
      ->add_option("--to", options.to, "Write only the frames whose simulated time is at most T1 s (default: the end)")
      ->type_name("T1");
  command
      ->add_option("--from-video", options.fromVideo,
                   "Write only the frames that play at video time V0 s or later in the full clip (frame k plays "
                   "at k / fps; render --plan lists both clocks); not with --from/--to")
      ->type_name("V0");
  command->add_option("--to-video", options.toVideo, "Write only the frames that play at video time V1 s or earlier")
      ->type_name("V1");
  command
      ->add_option("--last", options.last,
                   "Write only the frames that play in the full clip's last L s of video (e.g. the finale); not with "
                   "--from/--to or --from-video/--to-video")
      ->type_name("L");
  command->add_flag("--plan", options.plan,
                    "Print the clip's plan on stdout and stop, drawing and writing nothing: video length, frames, the "
                    "frames the window keeps on both clocks, the playback rate over the clip");
  command->add_flag("--json", options.json,
                    "With --plan: print the plan as one JSON document instead: fps, time_scale, end_time, "
                    "simulated_frames, landed, hold_seconds, the frames written (first, last) and per frame of the "
                    "clip sim_time_s, playback_rate, slowed_by (rate, flight, impact or null), the camera it is drawn "
                    "with (eye, target, up as [x, y, z] in m, fov_y_degrees) and its overlay_lines (none with "
                    "render.hud off); numbers read back as the same doubles");
  command->add_flag("--inset", options.inset,
                    "Draw a plot of the contact point's rate (log scale when it spans a factor 4) and the tilt above "
                    "the floor over the frames written in each frame's lower right corner, a marker at the frame: the "
                    "speed-up a time remap slows down, and a tilt of a degree, read off it");
  addQuietFlag(*command, options.quiet, "No progress line, notes or summary on stderr");
  command
      ->add_option("--frame-times", options.frameTimesPath,
                   "Also write the CSV FILE, one row per frame written: frame (index in the video), video_time_s "
                   "(frame / fps), clip_frame (index in the full render), sim_time_s (simulated time shown) and "
                   "playback_rate (simulated s per video s; 0 while a landing is held); published with the video, "
                   "never without it")
      ->type_name("FILE");
  command
      ->add_option("--max-frames", options.maxFrames,
                   fmt::format("Refuse clips of more frames than this (default {}; a duration alone giving {} times as "
                               "many is refused before any work)",
                               coinroll::pipeline::kDefaultMaxFrames, coinroll::pipeline::kUpFrontFrameFactor))
      ->check(kAtLeastOne);
  command->footer(
      "Frame k plays at video time k / fps and shows simulated time k * render.time_scale / render.fps (under\n"
      "render.time_remap, less as the coin speeds up, in the air and at each impact: render --plan prints where),\n"
      "from the dense output.\n"
      "Size, fps, anti-aliasing, camera, trace, overlay and encoder come from the scene's render block, e.g.\n"
      "  coinroll render                                    (built-in scene -> coinroll.mp4)\n"
      "  coinroll render examples/steady_circle.json -o circle.mp4\n"
      "  coinroll render examples/ring.json -o ring_%04d.png --set render.fps=10\n"
      "  coinroll render scene.json --set render.time_scale=0.25 --set render.camera.mode=follow\n"
      "  coinroll render scene.json -o loop.gif --size 480p --from 1 --to 3\n"
      "  coinroll render examples/euler_disk.json --last 20 --plan       (the finale's plan: frames, both clocks)\n"
      "  coinroll render examples/coin_toss.json --plan --json > plan.json   (per frame: time, rate, camera, overlay)\n"
      "  coinroll render examples/euler_disk.json --last 20 -o finale.mp4  (the last 20 s of the video)\n"
      "  coinroll render examples/euler_disk.json --last 20 --inset -o finale.mp4   (with the rate and tilt plotted)\n"
      "  coinroll render scene.json -o coin.mov --set render.background=\\\"transparent\\\"   (alpha for an editor)\n"
      "Outputs appear only when complete (written under a temporary name, then renamed); Ctrl-C leaves nothing.");
  return command;
}

CLI::App* addStillCommand(CLI::App& app, StillOptions& options) {
  CLI::App* command =
      app.add_subcommand("still", "Render one PNG of a scene at a simulated time (optionally a stroboscopic figure)");
  addSceneOptions(*command, options.scene, false);  // no file: the built-in default scene
  command->add_option("--time", options.time, "Simulated time to show, s (0 to the scene's duration)")->required();
  addOutputOptions(*command, options.output, options.force, "Output PNG path (written atomically)");
  command
      ->add_option("--strobe", options.strobe,
                   "Overlay N semi-transparent copies of the coin at evenly spaced earlier times (a figure); a "
                   "follow or orbit camera gives way to a fixed one that frames them all")
      ->capture_default_str();
  command->add_option("--strobe-from", options.strobeFrom,
                      "Simulated time of the first copy, s (default 0): e.g. the last second of a spin-down");
  command->add_flag("--panels", options.panels,
                    "With --strobe N: N + 1 panels side by side (the copies' times and --time, each the whole picture "
                    "labelled with its time, tilt and contact rate, or rim height in the air) instead of copies over "
                    "one picture, which pile up where the coin stays in place");
  addSizeOption(*command, options.size);
  addQuietFlag(*command, options.quiet, "No notes and no summary on stderr");
  command->footer(
      "Size, anti-aliasing, camera, trace and overlay come from the scene's render block, e.g.\n"
      "  coinroll still examples/steady_circle.json --time 1.5 -o circle.png --set render.width=640 --set "
      "render.height=360\n"
      "  coinroll still examples/perturbed_circle.json --time 2 --strobe 12 -o strobe.png --set render.hud=false\n"
      "  coinroll still examples/euler_disk.json --time 117.18 --strobe 5 --strobe-from 116.18 --panels \\\n"
      "      --set render.width=640 --set render.height=360 -o last_second.png   (the finale: 6 panels, 0.2 s apart)");
  return command;
}

CLI::App* addSweepCommand(CLI::App& app, SweepOptions& options) {
  CLI::App* command = app.add_subcommand(
      "sweep", "Simulate every point of a grid over scene fields; one summary row per point (all cores)");
  addSceneOptions(*command, options.scene, false);
  command
      ->add_option("--grid", options.grid,
                   "KEY.PATH=START:STOP:COUNT: COUNT evenly spaced values of a scene field, in the scene's units "
                   "(degrees for angles); START:STOP:COUNT:log: geometrically spaced (START, STOP > 0); "
                   "V1,V2,V3: the values listed; repeatable, the last axis runs fastest")
      ->required()
      ->type_name("KEY=START:STOP:COUNT[:log]|KEY=V1,V2,...");
  command->add_option("-o,--output", options.output, "Output CSV path (written atomically), or - for standard output")
      ->required();
  command
      ->add_option("--shard", options.shard,
                   "Compute only the points p with p mod N = K - 1 (K/N, 1 <= K <= N); auto/N: K from a Slurm "
                   "array task ($SLURM_ARRAY_TASK_ID, sbatch --array=1-N)")
      ->type_name("K/N|auto/N");
  command->add_option("--threads", options.threads, "Worker threads (default 0: every hardware thread)");
  command
      ->add_option("--max-points", options.maxPoints,
                   fmt::format("Refuse grids larger than this (default {})", coinroll::pipeline::kDefaultMaxPoints))
      ->check(kAtLeastOne);
  command->add_flag("-q,--quiet", options.quiet,
                    "No progress and no summary on stderr (progress is a line in place on a terminal, else a line "
                    "per tenth of the points and at least one every 30 s)");
  command->footer(
      "Rows: point, the grid values, end (duration, or the event that ended the run, or error: why), t_end, "
      "theta_min,\n"
      "theta_max (rad, over samples every 0.01 s and the end), energy_start, energy_end (J), theta_end (rad, at the "
      "end;\n"
      "a toss's face: heads < 0, tails > 0), grid_points, sweep. Same bytes for any --threads.\n"
      "  coinroll sweep examples/straight_stable.json --grid initial.omega_Z=2:20:10 --grid initial.theta=1:10:10 -o "
      "map.csv\n"
      "  coinroll sweep scene.json --grid coin.mass=0.01:1:5:log --grid initial.theta=5,10,20 -o mass.csv\n"
      "  coinroll sweep scene.json --grid coin.mass=0.1:1:10 --shard auto/8 -o part_${SLURM_ARRAY_TASK_ID}.csv\n"
      "      (one task of a Slurm array, sbatch --array=1-8)\n"
      "  coinroll sweep-merge -o all.csv part*.csv\n"
      "Clusters (Slurm job arrays, GNU parallel): docs/sweeps.md.");
  return command;
}

CLI::App* addSweepMergeCommand(CLI::App& app, SweepMergeOptions& options) {
  CLI::App* command =
      app.add_subcommand("sweep-merge", "Merge the shard files of one sweep into the file the unsharded sweep writes");
  command->add_option("-o,--output", options.output, "Output CSV path (written atomically), or - for standard output")
      ->required();
  command->add_option("shards", options.shards, "Shard CSV files (any order)")->required();
  addQuietFlag(*command, options.quiet, "No summary on stderr");
  command->footer(
      "Fails, naming the points, if a point is missing or repeated, or the file, row and column of a "
      "cell that is not of its column's type.");
  return command;
}

CLI::App* addCompareCommand(CLI::App& app, CompareOptions& options) {
  CLI::App* command = app.add_subcommand(
      "compare",
      "Compare two PNGs with the rule of coinroll's golden tests: PSNR, differing pixels, exit 0 same / 1 different");
  command->add_option("a", options.a, "Reference PNG (e.g. the committed golden); the diff image is drawn from it")
      ->required();
  command->add_option("b", options.b, "PNG to check against it")->required();
  command
      ->add_option("--max-differing-pixels", options.maxDifferingPixels,
                   "Pass with at most N differing pixels (default 0 unless --max-differing-fraction is given)")
      ->type_name("N");
  command
      ->add_option("--max-differing-fraction", options.maxDifferingFraction,
                   "Pass with at most this fraction of the pixels differing, 0..1 (0.01 = 1 %)")
      ->type_name("F");
  command
      ->add_option("--channel-tolerance", options.channelTolerance,
                   "A pixel differs only when a channel (R, G, B, A) differs by more than T levels, 0..255")
      ->type_name("T")
      ->capture_default_str();
  command->add_option("--min-psnr", options.minPsnr, "Pass only with a PSNR (over R, G, B) of at least DB decibels")
      ->type_name("DB");
  command
      ->add_option("--diff", options.diff,
                   "Write a diff PNG here (written atomically, whatever the verdict): equal pixels dim grey of A, "
                   "differing pixels red (brighter = larger), off by no more than --channel-tolerance amber")
      ->type_name("PATH.png");
  command->footer(
      "The default is an exact match; every limit given must hold. One line on stdout, e.g.\n"
      "  PSNR 47.31 dB, 12 of 57600 pixels differ (0.02083 %, channel tolerance 0), max channel difference 9: "
      "DIFFERENT (12 > --max-differing-pixels 0)\n"
      "PSNR is inf for identical pixels. Exit: 0 within the limits, 1 outside them, 2 could not compare (a missing "
      "file,\n"
      "not a PNG, different sizes, a bad limit, the diff not written).\n"
      "  coinroll compare golden.png new.png                (exact: the same Mesa and llvmpipe code path, or a pinned "
      "one)\n"
      "  coinroll compare golden.png new.png --max-differing-fraction 0.001 --min-psnr 60 --diff diff.png\n"
      "      (a CI runner with another x86-64 CPU and the same Mesa, where llvmpipe's shader code rounds a few pixels\n"
      "       differently: the rule of coinroll's own golden tests under COINROLL_GOLDEN_TOLERANT=1; measured in\n"
      "       docs/snapshot_testing.md, which also gives the environment that makes the bytes identical instead)");
  return command;
}

CLI::App* addExportCommand(CLI::App& app, ExportOptions& options) {
  CLI::App* command = app.add_subcommand(
      "export",
      "Write the scene as a web page: coinroll's own physics in WebAssembly, drawn with three.js, with sliders");
  addSceneOptions(*command, options.scene, false);
  addOutputOptions(*command, options.output, options.force, "The page to write (one HTML file that opens offline)");
  addQuietFlag(*command, options.quiet, "No summary on stderr");
  command->add_option("--title", options.page.title, "The page's title and heading; default: the scene's name")
      ->type_name("TEXT");
  command
      ->add_option("--caption", options.page.caption,
                   "A paragraph under the heading, shown as plain text (at most 1000 characters); default: none")
      ->type_name("TEXT");
  command
      ->add_option("--controls", options.page.controls,
                   "The controls a student sees, comma-separated: keys as the controls' tooltips name them "
                   "(initial.theta,initial.omega_Z,friction) or groups: all, coin, initial, floor, flight, effects, "
                   "run; the others keep the scene's values. Default: all")
      ->type_name("LIST");
  command
      ->add_option("--details", options.page.details,
                   "The researcher's details (scene file box, the run's log, the command): folded into one closed "
                   "section one click away, or shown")
      ->type_name("folded|shown")
      ->capture_default_str();
  command->footer(
      "The page opens from file:// with no network: the scene plays at once, and its sliders (from coinroll schema)\n"
      "re-run it in the browser. \"Download scene\" gives back a scene file that coinroll simulate runs exactly.\n"
      "  coinroll export examples/euler_disk.json -o euler.html\n"
      "  coinroll export examples/euler_disk.json -o euler.html --title \"Euler's disk\" \\\n"
      "      --caption \"Change the tilt and the spin.\" --controls initial.theta,initial.omega_Z,friction\n"
      "      (for a course site: only those three controls, the scene file and the log one click away)\n"
      "The page is built beside the program by tools/build_page.sh (docs/web.md \"The page\").");
  return command;
}

CLI::App* addSchemaCommand(CLI::App& app, SchemaOptions& options) {
  CLI::App* command = app.add_subcommand(
      "schema",
      "Print every key a scene file may hold: path, type, unit, default, range, presence rules, a line of doc");
  CLI::Option* markdown =
      command->add_flag("--markdown", options.markdown, "The table of docs/scene.md instead of JSON");
  command->add_flag("--contract", options.contract, "The key table of docs/contract.md instead of JSON")
      ->excludes(markdown);
  command->footer(
      "JSON by default, one object per key in \"keys\", for scripts and the web page's controls:\n"
      "  coinroll schema | jq '.keys[] | select(.path == \"coin.radius\")'\n"
      "`effects[air_drag].viscosity` is the key of an effects entry whose type is air_drag (--set "
      "effects.0.viscosity=...);\n"
      "`initial[steady].theta` is theta in an initial block that names a steady motion.");
  return command;
}

// CLI11 reports a misspelt command only as "a subcommand is required": the message naming it and
// the choices, when argv[1] is no command, and the command it is a slip of, if one is close.
std::optional<std::string> unknownCommandMessage(const CLI::App& app, int argc, char** argv) {
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands({})) names.push_back(command->get_name());
  if (argc < 2 || argv[1][0] == '-' || std::ranges::find(names, argv[1]) != names.end()) return std::nullopt;
  std::string given = argv[1];
  std::transform(given.begin(), given.end(), given.begin(), [](unsigned char c) { return std::tolower(c); });
  const std::optional<std::string> nearest = nearestName(given, names);
  return fmt::format("coinroll: error: unknown command '{}'; the commands are {} (coinroll --help){}\n",
                     coinroll::scene::printable(argv[1]), fmt::join(names, ", "),
                     nearest ? "; did you mean '" + *nearest + "'?" : "");
}

// CLI11 reads an empty value of a number as 0 (--time '' drew t = 0; --min-psnr '' dropped the
// limit): every numeric option refuses it, naming itself.
void refuseEmptyNumbers(CLI::App& app) {
  constexpr std::array<std::string_view, 19> kNumericOptions = {"--sample-dt",
                                                                "--max-rows",
                                                                "--theta",
                                                                "--omega-Z",
                                                                "--max-frames",
                                                                "--from",
                                                                "--to",
                                                                "--from-video",
                                                                "--to-video",
                                                                "--last",
                                                                "--time",
                                                                "--strobe",
                                                                "--strobe-from",
                                                                "--threads",
                                                                "--max-points",
                                                                "--max-differing-pixels",
                                                                "--max-differing-fraction",
                                                                "--channel-tolerance",
                                                                "--min-psnr"};
  for (CLI::App* command : app.get_subcommands({})) {
    for (CLI::Option* option : command->get_options()) {
      if (std::find(kNumericOptions.begin(), kNumericOptions.end(), option->get_name()) == kNumericOptions.end())
        continue;
      option->check(CLI::Validator(
          [](std::string& text) {
            return text.empty() ? std::string("the value is empty; give a number") : std::string();
          },
          ""));
    }
  }
}

// The top-level help's footer: examples of every command and the exit codes.
void addExamplesFooter(CLI::App& app) {
  app.footer(
      "Examples:\n"
      "  coinroll render                                (the built-in default scene -> coinroll.mp4)\n"
      "  coinroll render examples/steady_circle.json -o circle.mp4\n"
      "  coinroll simulate --csv default.csv            (the built-in default scene)\n"
      "  coinroll simulate examples/steady_circle.json --csv circle.csv\n"
      "  coinroll simulate scene.json --csv - --sample-dt 0.001 --set initial.theta=12 | head\n"
      "  coinroll still examples/steady_circle.json --time 1.5 -o circle.png\n"
      "  coinroll steady --kind circle --theta 20 --omega-Z 10\n"
      "  coinroll steady --kind straight --omega-Z 5 --set coin.shape=\\\"ring\\\"\n"
      "  coinroll sweep examples/straight_stable.json --grid initial.omega_Z=2:20:10 -o sweep.csv\n"
      "Exit codes: 0 success, 2 bad command line or scene (nothing written), 1 other failure.\n"
      "Run 'coinroll COMMAND --help' for a command's options.");
}

}  // namespace

int main(int argc, char** argv) {
  // Before anything allocates on a second thread (pipeline/resources.h says why).
  coinroll::pipeline::fitAllocatorToAddressSpaceLimit();
  CLI::App app{"coinroll: a coin rolling without slipping on a table, simulated, rendered headless to MP4 and PNG."};
  app.require_subcommand(1);
  app.set_version_flag(
      "--version", [] { return versionText(); },
      "Print the version, the git revision and the OpenGL back ends (COINROLL_GL), and exit");
  addExamplesFooter(app);

  // In the order --help lists them.
  const std::array commands = {
      addCommand(app, addSimulateCommand, runSimulate), addCommand(app, addSteadyCommand, runSteady),
      addCommand(app, addRenderCommand, runRender),     addCommand(app, addStillCommand, runStill),
      addCommand(app, addSweepCommand, runSweep),       addCommand(app, addSweepMergeCommand, runSweepMerge),
      addCommand(app, addCompareCommand, runCompare),   addCommand(app, addSchemaCommand, runSchema),
      addCommand(app, addExportCommand, runExport)};

  // `coinroll help [COMMAND]` is read as `coinroll [COMMAND] --help`, as git and cargo read it.
  std::vector<char*> arguments(argv, argv + argc);
  static char helpFlag[] = "--help";
  if (argc >= 2 && argc <= 3 && std::string_view(argv[1]) == "help") {
    arguments.erase(arguments.begin() + 1);
    arguments.push_back(helpFlag);
  }
  const int count = static_cast<int>(arguments.size());
  if (const std::optional<std::string> message = unknownCommandMessage(app, count, arguments.data())) {
    std::cerr << *message;
    return kExitBadInput;
  }
  refuseEmptyNumbers(app);
  try {
    app.parse(count, arguments.data());
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() != static_cast<int>(CLI::ExitCodes::Success)) {
      // In the style of every other refusal, naming where the command's options are listed,
      // instead of CLI11's own "Run with --help for more information."
      const std::vector<CLI::App*> parsed = app.get_subcommands();
      const std::string help =
          parsed.empty() ? "coinroll --help" : "coinroll " + parsed.front()->get_name() + " --help";
      std::cerr << "coinroll: error: " << coinroll::scene::printable(e.what()) << " (" << help << ")\n";
      return kExitBadInput;
    }
    errno = 0;
    const int code = app.exit(e);
    // --help and --version are output too: a full device or a closed stdout is no success.
    if (code == 0 && !standardOutputWritten()) return kExitFailure;
    return code == 0 ? kExitSuccess : kExitBadInput;
  }

  // Before any command can create an output (docs in cli/interrupts.h). compare's failure code is
  // 2: its 1 means "the pictures differ".
  const InterruptGuard interrupts(app.got_subcommand("compare") ? kExitBadInput : kExitFailure);
  int exitCode = kExitSuccess;  // compare's verdict: 1 when the pictures differ
  try {
    for (const Command& command : commands) {
      if (*command.parsed) exitCode = command.run();
    }
    // Reports printed to stdout (steady, summaries) are output too: a full device or a closed
    // stdout must not pass as success.
    errno = 0;
    return standardOutputWritten() ? exitCode : kExitFailure;
  } catch (const coinroll::scene::SceneError& e) {
    std::cerr << "coinroll: error: " << coinroll::scene::printable(e.what()) << '\n';
    return kExitBadInput;
  } catch (const UsageError& e) {
    std::cerr << "coinroll: error: " << coinroll::scene::printable(e.what()) << '\n';
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "coinroll: error: " << coinroll::pipeline::outOfMemoryMessage() << '\n';
    return kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "coinroll: error: " << coinroll::scene::printable(e.what()) << '\n';
    return kExitFailure;
  }
}
