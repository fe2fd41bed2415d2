#include "pipeline/sweep.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <new>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "io/fnv1a.h"
#include "pipeline/cancelled.h"
#include "pipeline/coin_run.h"
#include "pipeline/resources.h"
#include "pipeline/simulation.h"
#include "pipeline/trajectory_csv.h"
#include "pipeline/video_frames.h"

namespace coinroll::pipeline {

namespace {

// s. theta_min and theta_max are taken over samples this far apart (simulate's default
// --sample-dt) and the end state; a wobble of period T is then resolved to (pi dt / T)^2 / 2 of
// its amplitude, 2e-3 for the toy coin's 0.2 s.
constexpr double kSummarySampleDt = 0.01;

// Points computed between two writes: large enough that the threads rarely wait for one another
// at a block's end, small enough that the block's rows are a few hundred kilobytes.
constexpr long kBlockSize = 512;

// RFC 4180: a field with a comma, a quote or a line break goes in quotes, quotes doubled.
std::string csvField(std::string_view text) {
  if (text.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(text);
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return quoted + '"';
}

struct PointSummary {
  std::string end;  // "duration" or the event's name
  double tEnd = 0, thetaMin = 0, thetaMax = 0, energyStart = 0, energyEnd = 0, thetaEnd = 0;
};

PointSummary summarize(const Simulation& simulation) {
  CoinRun run(simulation);
  PointSummary summary;
  summary.thetaMin = std::numeric_limits<double>::infinity();
  summary.thetaMax = -std::numeric_limits<double>::infinity();
  const auto include = [&summary](const physics::CoinState& s) {
    summary.thetaMin = std::min(summary.thetaMin, s.theta);
    summary.thetaMax = std::max(summary.thetaMax, s.theta);
  };
  const long samples = sampleCount(simulation.duration, kSummarySampleDt);
  std::optional<RunSample> first;
  for (long k = 0; k < samples; ++k) {
    const std::optional<RunSample> s = run.sampleAt(static_cast<double>(k) * kSummarySampleDt);
    if (!s) break;
    if (!first) first = s;
    include(s->state);
  }
  // The last state: the event's, or the duration's. Its theta's sign is a toss's face (heads < 0),
  // as simulate reports it at `decided`, `rest` or `face-down`.
  const auto ending = [&summary, &include](const physics::CoinState& last, double energy) {
    include(last);
    summary.thetaEnd = last.theta;
    summary.energyEnd = energy;
  };
  // The run goes on to its duration first: a stop after the last summary point is still its stop.
  const std::optional<RunSample> atDuration = run.sampleAt(simulation.duration);
  if (const auto hit = run.stoppedBy()) {
    summary.end = physics::eventName(hit->event);
    summary.tEnd = hit->t;
    ending(hit->state, hit->forward.energy);
  } else {
    const RunSample& last = *atDuration;
    summary.end = "duration";
    summary.tEnd = simulation.duration;
    ending(last.state, last.forward.energy);
  }
  summary.energyStart = first->forward.energy;  // t = 0 always has a sample: events are crossings after it
  return summary;
}

std::vector<double> pointValues(const std::vector<GridAxis>& axes, long point) {
  std::vector<double> values(axes.size());
  for (std::size_t i = axes.size(); i-- > 0;) {  // the last axis runs fastest
    values[i] = axes[i].valueAt(point % axes[i].count);
    point /= axes[i].count;
  }
  return values;
}

// Each point is the scene document with its grid values set as `--set KEY=VALUE` sets them, then
// parsed by the loader like any scene: the point is validated by exactly the loader's rules
// (ranges and cross-field checks alike, which read the file's units: degrees, JSON integers), a
// failed point's end quotes the loader's message, and a value typed as the --set text types it
// (5 an integer, 5.5 a float) gives the same row as the same --set would.
SweepPoint computePoint(const SweepSpec& spec, long point, const std::atomic<bool>* cancel) {
  SweepPoint result;
  result.point = point;
  result.values = pointValues(spec.axes, point);
  try {
    nlohmann::json document = spec.scene;
    for (std::size_t i = 0; i < result.values.size(); ++i) {
      scene::applyOverride(document, fmt::format("{}={}", spec.axes[i].key, result.values[i]));
    }
    Simulation simulation = buildSimulation(scene::parseScene(document, spec.sourceName));
    simulation.cancel = cancel;
    const PointSummary s = summarize(simulation);
    result.end = s.end;
    result.tEnd = s.tEnd, result.thetaMin = s.thetaMin, result.thetaMax = s.thetaMax;
    result.energyStart = s.energyStart, result.energyEnd = s.energyEnd, result.thetaEnd = s.thetaEnd;
  } catch (const Cancelled&) {
    throw;  // not the point's failure: the whole sweep stops
  } catch (const std::bad_alloc&) {
    throw;  // nor is memory running out, which would fail every point after it
  } catch (const std::exception& e) {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    result.end = std::string("error: ") + e.what();
    result.failed = true;
    result.tEnd = result.thetaMin = result.thetaMax = result.energyStart = result.energyEnd = result.thetaEnd = kNaN;
  }
  return result;
}

void refuseEmptyGrid(const SweepSpec& spec) {
  if (spec.axes.empty())
    throw std::invalid_argument("--grid: give at least one axis, e.g. --grid initial.theta=5:40:8");
}

}  // namespace

std::string sweepHeader(const std::vector<GridAxis>& axes) {
  std::string header = "point";
  for (const GridAxis& axis : axes) header.append(",").append(csvField(axis.key));
  header.append(kSweepSummaryColumns).append(kSweepIdentityColumns);
  return header;
}

void refuseMisnamedAxes(const SweepSpec& spec) {
  for (std::size_t i = 0; i < spec.axes.size(); ++i) {
    const GridAxis& axis = spec.axes[i];
    for (std::size_t j = 0; j < i; ++j) {
      if (spec.axes[j].key == axis.key) {
        throw std::invalid_argument(fmt::format("--grid {}: given twice; give each field one axis", axis.key));
      }
    }
    // One parse per axis, with that axis alone changed: a parse stops at its first error, so only
    // this way does a misnamed key get named by its own axis.
    nlohmann::json document = spec.scene;
    try {
      scene::applyOverride(document, fmt::format("{}={}", axis.key, axis.valueAt(0)));
      scene::parseScene(document, spec.sourceName);
    } catch (const scene::SceneError& e) {
      if (e.kind() == scene::SceneError::Kind::UnknownKey) {
        throw std::invalid_argument(fmt::format("--grid {}: not a scene field: {}", axis.key, e.what()));
      }
      // Every point would fail the same way: a grid varies numbers only.
      if (e.kind() == scene::SceneError::Kind::WrongType) {
        throw std::invalid_argument(
            fmt::format("--grid {}: not a number field, so a grid cannot vary it: {}", axis.key, e.what()));
      }
    }
  }
}

long gridPointCount(const SweepSpec& spec) {
  long points = 1;
  for (const GridAxis& axis : spec.axes) {
    if (axis.count > spec.maxPoints / points) {
      throw std::invalid_argument(fmt::format(
          "--grid: the grid has more than {} points (--max-points); raise it if you mean it", spec.maxPoints));
    }
    points *= axis.count;
  }
  return points;
}

SweepResult runSweep(const SweepSpec& spec, const std::function<void(const SweepPoint&)>& row,
                     const std::function<void(long, long)>& onPoint, const std::atomic<bool>* cancel) {
  refuseEmptyGrid(spec);
  const long total = gridPointCount(spec);
  // This shard's points are first + k step.
  const long first = spec.shard.index - 1, step = spec.shard.count;
  const long mine = total > first ? (total - first + step - 1) / step : 0;
  const int threads = std::max(1, spec.threads);

  SweepResult result;
  // Counted as points finish, not as blocks are written: a shard of fewer than kBlockSize points
  // would otherwise report nothing until its end.
  std::mutex progressMutex;
  long computed = 0;
  std::vector<SweepPoint> points;
  for (long blockStart = 0; blockStart < mine; blockStart += kBlockSize) {
    const long blockSize = std::min(kBlockSize, mine - blockStart);
    points.assign(static_cast<std::size_t>(blockSize), SweepPoint());
    std::atomic<long> next{0};
    // The first exception of any thread (Cancelled, out of memory), rethrown here once all have
    // stopped: one escaping a thread would end the process through std::terminate.
    std::mutex failureMutex;
    std::exception_ptr failure;
    const auto work = [&] {
      for (long i; (i = next.fetch_add(1)) < blockSize;) {
        try {
          throwIfCancelled(cancel);
          points[static_cast<std::size_t>(i)] = computePoint(spec, first + (blockStart + i) * step, cancel);
          if (onPoint) {
            const std::lock_guard lock(progressMutex);
            onPoint(++computed, mine);
          }
        } catch (...) {
          const std::lock_guard lock(failureMutex);
          if (!failure) failure = std::current_exception();
          next = blockSize;  // the other threads stop after their point
          return;
        }
      }
    };
    {
      std::vector<std::jthread> helpers;  // joined when the block ends, also when starting one throws
      for (int t = 1; t < threads; ++t) {
        try {
          helpers.emplace_back(work);
        } catch (const std::system_error& e) {
          next = blockSize;
          throw std::runtime_error(
              fmt::format("cannot start sweep thread {} of {}: {}: a thread needs memory for its "
                          "stack, within {}, and counts against the processes a user may run "
                          "(ulimit -u); give fewer --threads",
                          t + 1, threads, e.code().message(), memoryLimitDescription()));
        }
      }
      work();
    }
    if (failure) std::rethrow_exception(failure);
    for (const SweepPoint& point : points) {
      row(point);
      if (point.failed)
        ++result.failed;
      else
        ++result.ends[point.end];
      ++result.points;
    }
  }
  return result;
}

SweepResult writeSweepCsv(const SweepSpec& spec, std::ostream& out, const std::function<void(long, long)>& onPoint,
                          const std::atomic<bool>* cancel) {
  refuseEmptyGrid(spec);
  const SweepIdentity identity = sweepIdentity(spec);
  const std::string rowEnd = fmt::format(",{},{}\n", identity.gridPoints, identity.digest);
  out << sweepHeader(spec.axes) << '\n';
  std::string text;
  const SweepResult result = runSweep(
      spec,
      [&](const SweepPoint& point) {
        text = fmt::format("{}", point.point);
        for (const double v : point.values) text += fmt::format(",{}", v);
        if (point.failed)
          text += "," + csvField(point.end) + ",,,,,,";  // the six numbers empty
        else
          text += fmt::format(",{},{},{},{},{},{},{}", point.end, point.tEnd, point.thetaMin, point.thetaMax,
                              point.energyStart, point.energyEnd, point.thetaEnd);
        out << text << rowEnd;
        // Checked per row: a full disk is found before the rest of a long sweep is computed for nothing.
        if (!out) throw std::runtime_error("writing the sweep's rows failed");
      },
      onPoint, cancel);
  return result;
}

SweepIdentity sweepIdentity(const SweepSpec& spec) {
  std::string text = spec.scene.dump();  // nlohmann::json keeps keys sorted: one text per document
  for (const GridAxis& axis : spec.axes) {
    text += fmt::format("\n{}", axis.key);
    for (long i = 0; i < axis.count; ++i) text += fmt::format(" {}", axis.valueAt(i));
  }
  return {.gridPoints = gridPointCount(spec), .digest = fmt::format("{:016x}", io::fnv1a64(text))};
}

}  // namespace coinroll::pipeline
