#include "pipeline/sweep.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
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

// The header's last two columns: SweepIdentity, after the contract's columns.
constexpr std::string_view kIdentityColumns = ",grid_points,sweep";

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
  double tEnd = 0, thetaMin = 0, thetaMax = 0, energyStart = 0, energyEnd = 0;
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
  double energyEnd = 0;
  if (const auto hit = run.stoppedBy()) {
    summary.end = physics::eventName(hit->event);
    summary.tEnd = hit->t;
    include(hit->state);
    energyEnd = hit->forward.energy;
  } else {
    const RunSample last = *run.sampleAt(simulation.duration);
    summary.end = "duration";
    summary.tEnd = simulation.duration;
    include(last.state);
    energyEnd = last.forward.energy;
  }
  summary.energyStart = first->forward.energy;  // t = 0 always has a sample: events are crossings after it
  summary.energyEnd = energyEnd;
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

std::string pointRow(const SweepSpec& spec, long point, const std::atomic<bool>* cancel) {
  const std::vector<double> values = pointValues(spec.axes, point);
  std::string row = fmt::format("{}", point);
  for (const double v : values) row += fmt::format(",{}", v);
  try {
    nlohmann::json document = spec.scene;
    for (std::size_t i = 0; i < values.size(); ++i) scene::applyOverride(document, fmt::format("{}={}", spec.axes[i].key, values[i]));
    Simulation simulation = buildSimulation(scene::parseScene(document, spec.sourceName, spec.parseOptions));
    simulation.cancel = cancel;
    const PointSummary s = summarize(simulation);
    row += fmt::format(",{},{},{},{},{},{}", s.end, s.tEnd, s.thetaMin, s.thetaMax, s.energyStart, s.energyEnd);
  } catch (const Cancelled&) {
    throw;  // not the point's failure: the whole sweep stops
  } catch (const std::bad_alloc&) {
    throw;  // nor is memory running out, which would fail every point after it
  } catch (const std::exception& e) {
    row += "," + csvField(std::string("error: ") + e.what()) + ",,,,,";
  }
  return row;
}

}  // namespace

std::string sweepHeader(const std::vector<GridAxis>& axes) {
  std::string header = "point";
  for (const GridAxis& axis : axes) header.append(",").append(csvField(axis.key));
  header.append(",end,t_end,theta_min,theta_max,energy_start,energy_end").append(kIdentityColumns);
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
    nlohmann::json document = spec.scene;
    try {
      scene::applyOverride(document, fmt::format("{}={}", axis.key, axis.valueAt(0)));
      scene::parseScene(document, spec.sourceName, spec.parseOptions);
    } catch (const scene::SceneError& e) {
      if (e.kind() == scene::SceneError::Kind::UnknownKey) {
        throw std::invalid_argument(fmt::format("--grid {}: not a scene field: {}", axis.key, e.what()));
      }
      // Every point would fail the same way: a grid varies numbers only.
      if (e.kind() == scene::SceneError::Kind::WrongType) {
        throw std::invalid_argument(fmt::format("--grid {}: not a number field, so a grid cannot vary it: {}", axis.key, e.what()));
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

SweepResult runSweep(const SweepSpec& spec, std::ostream& out, const std::function<void(long, long)>& onPoint,
                     const std::atomic<bool>* cancel) {
  if (spec.axes.empty()) throw std::invalid_argument("--grid: give at least one axis, e.g. --grid initial.theta=5:40:8");
  const SweepIdentity identity = sweepIdentity(spec);
  const std::string rowEnd = fmt::format(",{},{}\n", identity.gridPoints, identity.digest);
  const long total = identity.gridPoints;
  // This shard's points are first + k step.
  const long first = spec.shard.index - 1, step = spec.shard.count;
  const long mine = total > first ? (total - first + step - 1) / step : 0;
  const int threads = std::max(1, spec.threads);

  out << sweepHeader(spec.axes) << '\n';
  SweepResult result;
  // Counted as points finish, not as blocks are written: a shard of fewer than kBlockSize points
  // would otherwise report nothing until its end.
  std::mutex progressMutex;
  long computed = 0;
  std::vector<std::string> rows;
  for (long blockStart = 0; blockStart < mine; blockStart += kBlockSize) {
    const long blockSize = std::min(kBlockSize, mine - blockStart);
    rows.assign(static_cast<std::size_t>(blockSize), std::string());
    std::atomic<long> next{0};
    // The first exception of any thread (Cancelled, out of memory), rethrown here once all have
    // stopped: one escaping a thread would end the process through std::terminate.
    std::mutex failureMutex;
    std::exception_ptr failure;
    const auto work = [&] {
      for (long i; (i = next.fetch_add(1)) < blockSize;) {
        try {
          throwIfCancelled(cancel);
          rows[static_cast<std::size_t>(i)] = pointRow(spec, first + (blockStart + i) * step, cancel);
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
          throw std::runtime_error(fmt::format("cannot start sweep thread {} of {}: {}: a thread needs memory for its "
                                               "stack, within {}, and counts against the processes a user may run "
                                               "(ulimit -u); give fewer --threads", t + 1, threads, e.code().message(),
                                               memoryLimitDescription()));
        }
      }
      work();
    }
    if (failure) std::rethrow_exception(failure);
    for (const std::string& row : rows) {
      out << row << rowEnd;
      if (row.find(",error: ") != std::string::npos || row.find(",\"error: ") != std::string::npos) ++result.failed;
      ++result.points;
    }
    if (!out) throw std::runtime_error("writing the sweep's rows failed");
  }
  return result;
}

namespace {

// Fields of one CSV row as csvField writes them (quoted fields may hold commas).
std::size_t csvFieldCount(std::string_view row) {
  std::size_t fields = 1;
  bool quoted = false;
  for (const char c : row) {
    if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) ++fields;
  }
  return fields;
}

// The row's last two fields, ",<grid points>,<digest>": never quoted, so found from the end.
std::string_view identityOf(std::string_view row) {
  const auto last = row.rfind(',');
  const auto beforeLast = last == std::string_view::npos || last == 0 ? std::string_view::npos : row.rfind(',', last - 1);
  return beforeLast == std::string_view::npos ? std::string_view() : row.substr(beforeLast);
}

// A list of point numbers for a message: the first 20, then how many more.
std::string pointList(const std::vector<long>& points) {
  const std::size_t shown = std::min<std::size_t>(points.size(), 20);
  return fmt::format("{}{}", fmt::join(points.begin(), points.begin() + static_cast<long>(shown), ", "),
                     points.size() > shown ? fmt::format(" and {} more", points.size() - shown) : "");
}

}  // namespace

SweepIdentity sweepIdentity(const SweepSpec& spec) {
  std::string text = spec.scene.dump();  // nlohmann::json keeps keys sorted: one text per document
  for (const GridAxis& axis : spec.axes) {
    text += fmt::format("\n{}", axis.key);
    for (long i = 0; i < axis.count; ++i) text += fmt::format(" {}", axis.valueAt(i));
  }
  return {.gridPoints = gridPointCount(spec), .digest = fmt::format("{:016x}", io::fnv1a64(text))};
}

void mergeSweepShards(const std::vector<std::filesystem::path>& shards, std::ostream& out, const std::atomic<bool>* cancel) {
  if (shards.empty()) throw std::invalid_argument("sweep-merge: give the shard files to merge");
  if (std::count(shards.begin(), shards.end(), "-") > 1) {
    throw std::invalid_argument("sweep-merge: - (standard input) is given more than once; it can be read only once");
  }
  std::string header, firstHeaderSource;
  std::string identity, identitySource;  // the first row's ",grid_points,sweep" and where it was read
  long gridPoints = 0;
  std::map<long, std::string> rows;  // point -> row
  std::vector<long> repeated;
  for (const std::filesystem::path& path : shards) {
    const bool standardInput = path == "-";
    const std::string name = standardInput ? "standard input" : path.string();
    std::ifstream file;
    if (!standardInput) {
      std::error_code ignored;
      if (std::filesystem::is_directory(path, ignored)) {
        throw std::invalid_argument(fmt::format("{}: is a directory; give the shard files (e.g. {}/*.csv)", name, name));
      }
      // A pipe or a FIFO reads as well as a file: the shard is read once, front to back.
      file.open(path, std::ios::binary);
      if (!file) throw std::runtime_error(fmt::format("{}: cannot open the shard: {}", name, std::strerror(errno)));
    }
    std::istream& in = standardInput ? std::cin : file;
    long lineNumber = 0;
    const auto readLine = [&](std::string& line) {
      if (!std::getline(in, line)) {
        if (in.bad()) throw std::runtime_error(fmt::format("{}: reading the shard failed: {}", name, std::strerror(errno)));
        return false;
      }
      ++lineNumber;
      return true;
    };
    // getline leaves eof set after a line that had no line break: the shard was cut inside it.
    const auto refuseCutLine = [&] {
      if (in.eof()) {
        throw std::runtime_error(fmt::format("{}:{}: cut short inside a row (no line break at its end): an unfinished "
                                             "or damaged shard, e.g. an interrupted `sweep -o - > part.csv`; run that "
                                             "shard again", name, lineNumber));
      }
    };
    std::string line;
    if (!readLine(line)) throw std::invalid_argument(fmt::format("{}: empty, not a sweep shard", name));
    if (!line.starts_with("point,")) {
      throw std::invalid_argument(fmt::format("{}: not a sweep shard (its first line does not start with \"point,\")", name));
    }
    refuseCutLine();
    if (!line.ends_with(kIdentityColumns)) {
      throw std::invalid_argument(fmt::format("{}: its header has no grid_points and sweep columns, which tell a merge "
                                              "which sweep a shard belongs to: written by an older coinroll, or "
                                              "edited; run the sweep again", name));
    }
    if (header.empty()) {
      header = line;
      firstHeaderSource = name;
    } else if (line != header) {
      throw std::runtime_error(fmt::format("{}: its header differs from {}'s: shards of sweeps over different axes; "
                                           "merge only the shards of one sweep", name, firstHeaderSource));
    }
    const std::size_t headerFields = csvFieldCount(header);
    while (readLine(line)) {
      throwIfCancelled(cancel);
      refuseCutLine();
      long point = -1;
      const auto comma = line.find(',');
      const auto [end, error] = std::from_chars(line.data(), line.data() + std::min(comma, line.size()), point);
      if (error != std::errc() || comma == std::string::npos || end != line.data() + comma || point < 0) {
        throw std::runtime_error(fmt::format("{}:{}: a row must start with its point number", name, lineNumber));
      }
      if (const std::size_t fields = csvFieldCount(line); fields != headerFields) {
        throw std::runtime_error(fmt::format("{}:{}: {} fields where the header has {}: a damaged shard; run it again",
                                             name, lineNumber, fields, headerFields));
      }
      const std::string_view rowIdentity = identityOf(line);
      if (identity.empty()) {
        const std::string_view count = rowIdentity.substr(1, rowIdentity.find(',', 1) - 1);
        const auto [countEnd, countError] = std::from_chars(count.data(), count.data() + count.size(), gridPoints);
        if (countError != std::errc() || countEnd != count.data() + count.size() || gridPoints < 1) {
          throw std::runtime_error(fmt::format("{}:{}: grid_points must be a whole number >= 1, got \"{}\": a damaged "
                                               "shard; run it again", name, lineNumber, count));
        }
        identity = rowIdentity;
        identitySource = fmt::format("{}:{}", name, lineNumber);
      } else if (rowIdentity != identity) {
        throw std::runtime_error(fmt::format(
            "{}:{}: from another sweep than {} (grid_points,sweep: {} here, {} there): the scene, its --set values or "
            "the grid differ; merge only the shards of one sweep", name, lineNumber, identitySource,
            rowIdentity.substr(1), std::string_view(identity).substr(1)));
      }
      if (point >= gridPoints) {
        throw std::runtime_error(fmt::format("{}:{}: point {} is outside the grid of {} points: a damaged shard; run it "
                                             "again", name, lineNumber, point, gridPoints));
      }
      if (!rows.emplace(point, line).second) repeated.push_back(point);
    }
  }
  if (!repeated.empty()) throw std::runtime_error(fmt::format("sweep-merge: points repeated: {}", pointList(repeated)));
  if (rows.empty()) {
    throw std::runtime_error("sweep-merge: no shard holds a point, but shard 1 of every sweep holds point 0: a shard is "
                             "missing or was cut short before its first row");
  }
  // Holes are found between the rows present and up to the grid's size, never by visiting every
  // number: a grid may have 1e7 points. The first holes are named, a run of three or more as a range.
  constexpr std::size_t kHolesNamed = 20;
  std::vector<std::string> holes;
  long missingPoints = 0, namedPoints = 0, expected = 0;
  const auto missing = [&](long from, long to) {  // points from .. to - 1
    if (to <= from) return;
    missingPoints += to - from;
    if (holes.size() < kHolesNamed) {
      holes.push_back(to - from == 1   ? fmt::format("{}", from)
                      : to - from == 2 ? fmt::format("{}, {}", from, from + 1)
                                       : fmt::format("{} to {}", from, to - 1));
      namedPoints += to - from;
    }
  };
  for (const auto& [point, row] : rows) {
    missing(expected, point);
    expected = point + 1;
  }
  missing(expected, gridPoints);
  if (missingPoints > 0) {
    throw std::runtime_error(fmt::format("sweep-merge: points missing (of {} in the grid): {}{}", gridPoints,
                                         fmt::join(holes, ", "),
                                         missingPoints > namedPoints ? fmt::format(" and {} more", missingPoints - namedPoints)
                                                                     : ""));
  }
  out << header << '\n';
  for (const auto& [point, row] : rows) out << row << '\n';
  if (!out) throw std::runtime_error("sweep-merge: writing the merged file failed");
}

}  // namespace coinroll::pipeline
