// The core's entry point for JavaScript (docs/web.md): `coinroll simulate` as one call. It makes the
// calls the command makes (cli/commands.cpp runSimulate, cli/command_support.cpp
// loadSceneDocument), in the command's order, so the CSV is the command's CSV and a refused scene
// the command's message. src/wasm/core_api.js wraps it in the module's documented functions.

#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <new>
#include <ostream>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <utility>
#include <vector>

#include "physics/validity.h"
#include "pipeline/cancelled.h"
#include "pipeline/simulation.h"
#include "pipeline/trajectory_csv.h"
#include "scene/json_reader.h"
#include "scene/scene_error.h"
#include "scene/scene_loader.h"

namespace coinroll::wasm {

namespace {

using emscripten::val;

// A refusal of the request (sample step, row limit, a bad request the run finds), as the command's
// UsageError: exit 2.
class BadRequest : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The CSV collected in memory, with the rows counted as they are written so that a page can show
// progress (and stop the run) from a callback: `progress(rowsWritten, rowsExpected)` after every
// `every` rows and after the last; returning false sets the run's cancel flag, which the run
// checks before its next sample.
class CsvCollector : public std::streambuf {
 public:
  CsvCollector(val progress, long expectedRows, std::atomic<bool>& cancel)
      : progress_(std::move(progress)), expected_(expectedRows), cancel_(cancel),
        every_(std::max(1L, expectedRows / kProgressCalls)) {}

  const std::string& text() const { return text_; }
  void finish() { report(); }

 protected:
  std::streamsize xsputn(const char* data, std::streamsize size) override {
    text_.append(data, static_cast<std::size_t>(size));
    for (const char* end = data + size; (data = static_cast<const char*>(std::memchr(data, '\n', end - data))); ++data) {
      newLine();
    }
    return size;
  }
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    text_.push_back(traits_type::to_char_type(c));
    if (c == '\n') newLine();
    return c;
  }

 private:
  // Often enough for a smooth bar, seldom enough that the calls into JavaScript cost nothing.
  static constexpr long kProgressCalls = 200;

  void newLine() {
    if (++lines_ > 1 && (lines_ - 1) % every_ == 0) report();
  }
  void report() {
    const long rows = std::max(0L, lines_ - 1);  // the header is no row
    if (progress_.isUndefined() || rows == reported_) return;
    reported_ = rows;
    if (progress_(static_cast<double>(rows), static_cast<double>(expected_)).strictlyEquals(val(false))) cancel_ = true;
  }

  val progress_;
  long expected_;
  std::atomic<bool>& cancel_;
  long every_;
  long lines_ = 0;
  long reported_ = -1;
  std::string text_;
};

// The lines `coinroll simulate` prints on stderr about a run (cli/commands.cpp reportStop and the
// summary after it), word for word; tests/web/wasm_core_test.js compares them with the command's.
std::vector<std::string> reportLines(const pipeline::TrajectoryReport& result) {
  std::vector<std::string> lines;
  for (const pipeline::ModeSwitch& w : result.switches) {
    lines.push_back(fmt::format("coinroll: {} at t = {:.9f} s", w.toSliding ? "slides" : "rolls", w.t));
  }
  for (const pipeline::RunEvent& warning : result.warnings) {
    lines.push_back("coinroll: warning: the ideal contact fails here (on_invalid: warn, going on): " +
                    pipeline::describeStop(warning));
  }
  if (result.stoppedBy) lines.push_back("coinroll: stopped early: " + pipeline::describeStop(*result.stoppedBy));
  if (result.singularTime) {
    const pipeline::SingularTimeEstimate& e = *result.singularTime;
    lines.push_back(fmt::format("coinroll: singular time t0 = {:.6f} s, {:.3g} s after the stop (E ~ (t0 - t)^{:.3f}, "
                                "fitted to E/P over t >= {:.6g} s, {} samples)",
                                e.t0, e.t0 - result.stoppedBy->t, e.gamma, e.fitFrom, e.samples));
  }
  lines.push_back(fmt::format("coinroll: {} rows, {} steps ({} rejected), {} right-hand-side evaluations", result.rows,
                              result.stats.acceptedSteps, result.stats.rejectedSteps, result.stats.rhsEvaluations));
  return lines;
}

val runEvent(std::string_view kind, std::string_view name, double t, const std::string& description) {
  val event = val::object();
  event.set("kind", std::string(kind));
  event.set("name", std::string(name));
  event.set("time", t);
  event.set("description", description);
  return event;
}

val stringArray(const std::vector<std::string>& strings) {
  val array = val::array();
  for (const std::string& s : strings) array.call<void>("push", s);
  return array;
}

val runResult(const std::string& csv, const pipeline::TrajectoryReport& result, double duration, const std::string& note) {
  val out = val::object();
  // As bytes, copied out of the module's memory (slice), for core_api.js to decode with TextDecoder:
  // embind's own std::string conversion walks the text a byte at a time in JavaScript, which took a
  // tenth of a long run.
  out.set("csvBytes", val(emscripten::typed_memory_view(csv.size(), reinterpret_cast<const std::uint8_t*>(csv.data())))
                          .call<val>("slice"));
  out.set("rows", static_cast<double>(result.rows));
  val end = val::object();
  if (result.stoppedBy) {
    end.set("event", std::string(physics::eventName(result.stoppedBy->event)));
    end.set("time", result.stoppedBy->t);
    end.set("description", pipeline::describeStop(*result.stoppedBy));
  } else {
    end.set("event", std::string("duration"));
    end.set("time", duration);
    end.set("description", std::string());
  }
  out.set("end", end);

  // The run's events in time order: a switch or a warning never follows the stop.
  std::vector<std::pair<double, val>> events;
  for (const pipeline::ModeSwitch& w : result.switches) {
    events.emplace_back(w.t, runEvent("switch", w.toSliding ? "slides" : "rolls", w.t, ""));
  }
  for (const pipeline::RunEvent& w : result.warnings) {
    events.emplace_back(w.t, runEvent("warning", physics::eventName(w.event), w.t, pipeline::describeStop(w)));
  }
  std::stable_sort(events.begin(), events.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (const auto& stop = result.stoppedBy) {
    events.emplace_back(stop->t, runEvent("stop", physics::eventName(stop->event), stop->t, pipeline::describeStop(*stop)));
  }
  val eventList = val::array();
  for (const auto& [t, event] : events) eventList.call<void>("push", event);
  out.set("events", eventList);

  if (const auto& e = result.singularTime) {
    val singular = val::object();
    singular.set("t0", e->t0);
    singular.set("gamma", e->gamma);
    singular.set("fitFrom", e->fitFrom);
    singular.set("samples", e->samples);
    out.set("singularTime", singular);
  } else {
    out.set("singularTime", val::null());
  }
  val stats = val::object();
  stats.set("acceptedSteps", static_cast<double>(result.stats.acceptedSteps));
  stats.set("rejectedSteps", static_cast<double>(result.stats.rejectedSteps));
  stats.set("rhsEvaluations", static_cast<double>(result.stats.rhsEvaluations));
  out.set("stats", stats);

  std::vector<std::string> report;
  if (!note.empty()) report.push_back("coinroll: note: " + note);
  for (std::string& line : reportLines(result)) report.push_back(std::move(line));
  out.set("report", stringArray(report));
  return out;
}

val failure(std::string_view kind, int exitCode, const std::string& message) {
  val error = val::object();
  error.set("kind", std::string(kind));
  error.set("exitCode", exitCode);
  // As the command prints it after "coinroll: error: ".
  error.set("message", scene::printable(message));
  val out = val::object();
  out.set("error", error);
  return out;
}

// `scene`: the scene file's bytes (a JavaScript string arrives as UTF-8); `hasScene` false: the
// built-in default scene, as the command without a scene file. The result holds `error` (kind,
// exitCode and message, as the command's exit code and message) instead of throwing, so no C++
// exception crosses into JavaScript; core_api.js throws it.
val simulateCsv(const std::string& scene, bool hasScene, val overrides, const std::string& sourceName, double sampleDt,
                double maxRows, val progress) {
  try {
    if (!(sampleDt > 0) || !std::isfinite(sampleDt)) {
      throw BadRequest(fmt::format("sampleDt: must be a finite number > 0 s, got {}", sampleDt));
    }
    nlohmann::json document = hasScene ? scene::parseSceneText(scene, sourceName) : scene::builtInDefaultScene();
    for (const std::string& assignment : emscripten::vecFromJSArray<std::string>(overrides)) {
      scene::applyOverride(document, assignment);
    }
    const scene::SceneConfig config = scene::parseScene(document, hasScene ? sourceName : "built-in default scene");
    if (const double rows = config.duration / sampleDt + 1; rows > maxRows) {
      throw BadRequest(fmt::format("sampleDt {}: duration {} s gives {:.4g} rows, more than the limit {}; raise sampleDt, "
                                   "or the limit with maxRows", sampleDt, config.duration, rows, maxRows));
    }
    pipeline::Simulation simulation = pipeline::buildSimulation(config);
    std::atomic<bool> cancel = false;
    simulation.cancel = &cancel;
    CsvCollector collector(progress, pipeline::sampleCount(config.duration, sampleDt), cancel);
    std::ostream out(&collector);
    pipeline::TrajectoryReport result;
    try {
      result = pipeline::writeTrajectoryCsv(simulation, sampleDt, out);
    } catch (const std::invalid_argument& e) {  // as the command's withProgress maps it
      throw BadRequest(e.what());
    }
    collector.finish();
    return runResult(collector.text(), result, config.duration, pipeline::steadyStartNote(config));
  } catch (const scene::SceneError& e) {
    return failure("scene", 2, e.what());
  } catch (const pipeline::Cancelled&) {
    return failure("cancelled", 1, "cancelled: the progress callback returned false");
  } catch (const BadRequest& e) {
    return failure("request", 2, e.what());
  } catch (const std::bad_alloc&) {
    return failure("failure", 1, "out of memory: the run's CSV does not fit in the module's memory; raise sampleDt");
  } catch (const std::exception& e) {
    return failure("failure", 1, e.what());
  }
}

std::string defaultSceneJson() { return scene::builtInDefaultScene().dump(2) + "\n"; }

}  // namespace

EMSCRIPTEN_BINDINGS(coinroll_core) {
  emscripten::function("coreSimulateCsv", &simulateCsv);
  emscripten::function("coreDefaultSceneJson", &defaultSceneJson);
  emscripten::constant("coreVersion", std::string(COINROLL_VERSION));
}

}  // namespace coinroll::wasm
