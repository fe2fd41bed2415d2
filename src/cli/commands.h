#pragma once
// One function per subcommand; each returns normally on success and throws scene::SceneError or
// cli::UsageError for bad input (exit 2) and anything else for failures (exit 1).

#include <optional>
#include <string>
#include <vector>

#include "cli/page_options.h"

namespace coinroll::cli {

struct SceneSource {
  std::optional<std::string> file;     // absent = the built-in default scene
  std::vector<std::string> overrides;  // --set KEY.PATH=VALUE, applied in order
};

struct SimulateOptions {
  SceneSource scene;
  std::string csvPath;     // "-" = stdout
  double sampleDt = 0.01;  // s
  long maxRows = 0;        // 0: pipeline::kDefaultMaxRows
  // A JSON file naming what made the CSV (the contract fixes the CSV's header, so its provenance
  // goes beside it): program, release, scene digest, the resolved scene, the sampling and how the
  // run ended. Unset: none.
  std::optional<std::string> provenancePath;
  bool quiet = false;  // only warnings and an early stop on stderr: no notes, mode switches or summary
};

void runSimulate(const SimulateOptions& options);

struct SteadyOptions {
  SceneSource scene;
  std::optional<std::string> kind;  // "straight" | "circle" | "spin-in-place"; default: the scene's steady initial
  std::optional<double> thetaDegrees;
  std::optional<double> omega_Z;      // rad/s
  std::optional<std::string> branch;  // "+" | "-"
  bool quiet = false;                 // no note on stderr (the report on stdout stays)
};
void runSteady(const SteadyOptions& options);

struct StillOptions {
  SceneSource scene;
  double time = 0;                    // s of simulated time
  std::optional<std::string> output;  // PNG path; default <scene name>.png
  int strobe = 0;                     // earlier copies of the coin overlaid, evenly spaced over [strobeFrom, time)
  std::optional<double> strobeFrom;   // s; 0 when absent, and only with strobe >= 1
  bool panels = false;                // the strobe's times as panels side by side; only with strobe >= 1
  std::optional<std::string> size;    // "480p" .. "2160p": render.width and render.height
  bool quiet = false;                 // no notes and no summary on stderr
  bool force = false;                 // replace a default-named output made from another scene
};
void runStill(const StillOptions& options);

struct RenderOptions {
  SceneSource scene;
  std::optional<std::string> output;  // a video kind's extension or a %d pattern of .png; default <scene name>.mp4
  std::optional<std::string> size;    // "480p" .. "2160p": render.width and render.height
  std::optional<double> from, to;     // s of simulated time: the frames to write
  std::optional<double> fromVideo, toVideo;  // s of video (frame k plays at k / fps): the frames to write
  std::optional<double> last;                // s of video: write the clip's last seconds
  bool plan = false;                         // print the clip's plan (pipeline::planLines); draw and write nothing
  bool json = false;   // with plan: the plan as one JSON document, each frame's camera and overlay
  bool inset = false;  // a plot of the contact rate and the tilt in each frame's corner
  bool quiet = false;  // no progress line, no notes, no summary
  bool force = false;  // replace a default-named output made from another scene
  long maxFrames = 0;  // 0: pipeline::kDefaultMaxFrames
  std::optional<std::string> frameTimesPath;  // --frame-times: the sidecar CSV of frame times (cli/frame_times.h)
};
void runRender(const RenderOptions& options);

struct SweepOptions {
  SceneSource scene;
  std::vector<std::string> grid;     // KEY.PATH=START:STOP:COUNT[:log] or KEY.PATH=V1,V2,...
  std::string output;                // CSV path
  std::optional<std::string> shard;  // "K/N" or "auto/N"
  int threads = 0;                   // 0: every hardware thread
  long maxPoints = 0;                // 0: pipeline::kDefaultMaxPoints
  bool quiet = false;
};
void runSweep(const SweepOptions& options);

struct SweepMergeOptions {
  std::vector<std::string> shards;
  std::string output;
  bool quiet = false;  // no summary on stderr
};
void runSweepMerge(const SweepMergeOptions& options);

// `coinroll compare A.png B.png`: the golden tests' rule (image/compare.h) for a user's CI.
struct CompareOptions {
  std::string a, b;                            // PNG paths; A is the reference the diff image is drawn from
  std::optional<long> maxDifferingPixels;      // absent and no fraction: 0 (exact)
  std::optional<double> maxDifferingFraction;  // [0, 1]
  int channelTolerance = 0;                    // 0..255
  std::optional<double> minPsnr;               // dB
  std::optional<std::string> diff;             // diff PNG to write, whatever the verdict
};
// Prints one line (PSNR, differing pixels, max channel difference, verdict) on stdout and returns
// the exit code: 0 within the thresholds, 1 outside. Any trouble (a missing or unreadable file,
// not a PNG, different sizes, a bad threshold, a diff that cannot be written) throws UsageError,
// exit 2, as cmp(1) does, so a CI can tell "differs" from "could not compare".
int runCompare(const CompareOptions& options);

// `coinroll export [SCENE] -o page.html`: the web page with the scene in it (docs/web.md).
struct ExportOptions {
  SceneSource scene;
  std::optional<std::string> output;  // HTML path; default <scene name>.html
  bool quiet = false;                 // no summary on stderr
  bool force = false;                 // replace a default-named page made from another scene
  PageOptions page;                   // title, caption, controls shown, researcher's details (page_options.h)
};
void runExport(const ExportOptions& options);

// `coinroll schema`: every key a scene file may hold (scene/scene_schema.h), as JSON for scripts
// and the web page's controls, or as docs/scene.md's or docs/contract.md's Markdown table.
struct SchemaOptions {
  bool markdown = false;
  bool contract = false;
};
void runSchema(const SchemaOptions& options);

}  // namespace coinroll::cli
