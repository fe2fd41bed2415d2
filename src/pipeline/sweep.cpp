#include "pipeline/sweep.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <new>
#include <stdexcept>
#include <system_error>
#include <thread>

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

double parseNumber(std::string_view text, std::string_view what, std::string_view whole) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw std::invalid_argument(fmt::format("--grid {}: {} must be a finite number, got \"{}\"", whole, what, text));
  }
  return value;
}

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

double GridAxis::valueAt(long i) const {
  if (count == 1) return start;
  const double n = static_cast<double>(count - 1), k = static_cast<double>(i);
  return (start * (n - k) + stop * k) / n;
}

GridAxis parseGridAxis(std::string_view text) {
  const auto equals = text.find('=');
  const std::string_view key = text.substr(0, std::min(equals, text.size()));
  const std::string_view range = equals == std::string_view::npos ? std::string_view() : text.substr(equals + 1);
  const auto colon1 = range.find(':');
  const auto colon2 = colon1 == std::string_view::npos ? colon1 : range.find(':', colon1 + 1);
  if (key.empty() || colon2 == std::string_view::npos || range.find(':', colon2 + 1) != std::string_view::npos) {
    throw std::invalid_argument(
        fmt::format("--grid {}: expected KEY.PATH=START:STOP:COUNT, e.g. --grid initial.theta=5:40:8", text));
  }
  GridAxis axis;
  axis.key = key;
  axis.start = parseNumber(range.substr(0, colon1), "START", text);
  axis.stop = parseNumber(range.substr(colon1 + 1, colon2 - colon1 - 1), "STOP", text);
  const std::string_view count = range.substr(colon2 + 1);
  const auto [end, error] = std::from_chars(count.data(), count.data() + count.size(), axis.count);
  if (error != std::errc() || end != count.data() + count.size() || axis.count < 1) {
    throw std::invalid_argument(fmt::format("--grid {}: COUNT must be a whole number >= 1, got \"{}\"", text, count));
  }
  if (axis.count == 1 && axis.start != axis.stop) {
    throw std::invalid_argument(fmt::format("--grid {}: COUNT 1 takes one value; give START = STOP", text));
  }
  return axis;
}

Shard parseShard(std::string_view text) {
  Shard shard;
  const auto slash = text.find('/');
  const auto number = [](std::string_view digits, long& value) {
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    return error == std::errc() && end == digits.data() + digits.size() && !digits.empty();
  };
  if (slash == std::string_view::npos || !number(text.substr(0, slash), shard.index) ||
      !number(text.substr(slash + 1), shard.count) || shard.count < 1 || shard.index < 1 || shard.index > shard.count) {
    throw std::invalid_argument(fmt::format("--shard {}: expected K/N with 1 <= K <= N, e.g. --shard 2/8", text));
  }
  return shard;
}

std::string sweepHeader(const std::vector<GridAxis>& axes) {
  std::string header = "point";
  for (const GridAxis& axis : axes) header.append(",").append(csvField(axis.key));
  header.append(",end,t_end,theta_min,theta_max,energy_start,energy_end");
  return header;
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
  const long total = gridPointCount(spec);
  // This shard's points are first + k step.
  const long first = spec.shard.index - 1, step = spec.shard.count;
  const long mine = total > first ? (total - first + step - 1) / step : 0;
  const int threads = std::max(1, spec.threads);

  out << sweepHeader(spec.axes) << '\n';
  SweepResult result;
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
      out << row << '\n';
      if (row.find(",error: ") != std::string::npos || row.find(",\"error: ") != std::string::npos) ++result.failed;
      ++result.points;
      if (onPoint) onPoint(result.points, mine);
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

// Rows end with a line break; a file that does not was cut short (a shard killed mid-write, or a
// copy that stopped). Leaves `in` where it was.
bool endsWithNewline(std::ifstream& in) {
  in.clear();  // a first line without a line break leaves the stream at its end
  const std::streampos position = in.tellg();
  in.seekg(-1, std::ios::end);
  const bool ends = in.get() == '\n';
  in.seekg(position);
  return ends;
}

}  // namespace

void mergeSweepShards(const std::vector<std::filesystem::path>& shards, std::ostream& out, const std::atomic<bool>* cancel) {
  if (shards.empty()) throw std::invalid_argument("sweep-merge: give the shard files to merge");
  std::string header;
  std::map<long, std::string> rows;  // point -> row
  std::vector<long> repeated;
  for (const std::filesystem::path& path : shards) {
    std::error_code ignored;
    if (std::filesystem::is_directory(path, ignored)) {
      throw std::invalid_argument(fmt::format("{}: is a directory; give the shard files (e.g. {}/*.csv)", path.string(),
                                              path.string()));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(fmt::format("{}: cannot open the shard", path.string()));
    std::string line;
    if (!std::getline(in, line)) throw std::invalid_argument(fmt::format("{}: empty, not a sweep shard", path.string()));
    if (!line.starts_with("point,")) {
      throw std::invalid_argument(fmt::format("{}: not a sweep shard (its first line does not start with \"point,\")",
                                              path.string()));
    }
    if (header.empty()) header = line;
    if (!endsWithNewline(in)) {
      throw std::runtime_error(fmt::format("{}: its last row is cut short (no final line break): an unfinished or "
                                           "damaged shard; run that shard again", path.string()));
    }
    if (line != header) {
      throw std::runtime_error(fmt::format("{}: its header differs from {}'s: shards of different sweeps", path.string(),
                                           shards.front().string()));
    }
    const std::size_t headerFields = csvFieldCount(header);
    for (long lineNumber = 2; std::getline(in, line); ++lineNumber) {
      throwIfCancelled(cancel);
      long point = -1;
      const auto comma = line.find(',');
      const auto [end, error] = std::from_chars(line.data(), line.data() + std::min(comma, line.size()), point);
      if (error != std::errc() || comma == std::string::npos || end != line.data() + comma || point < 0) {
        throw std::runtime_error(fmt::format("{}:{}: a row must start with its point number", path.string(), lineNumber));
      }
      if (const std::size_t fields = csvFieldCount(line); fields != headerFields) {
        throw std::runtime_error(fmt::format("{}:{}: {} fields where the header has {}: a damaged shard; run it again",
                                             path.string(), lineNumber, fields, headerFields));
      }
      if (!rows.emplace(point, line).second) repeated.push_back(point);
    }
  }
  const auto list = [](const std::vector<long>& points) {
    const std::size_t shown = std::min<std::size_t>(points.size(), 20);
    return fmt::format("{}{}", fmt::join(points.begin(), points.begin() + static_cast<long>(shown), ", "),
                       points.size() > shown ? fmt::format(" and {} more", points.size() - shown) : "");
  };
  if (!repeated.empty()) throw std::runtime_error(fmt::format("sweep-merge: points repeated: {}", list(repeated)));
  // Shards deal the points out in turn, so a lost shard leaves holes below the last point present
  // (only a shard holding nothing but the grid's top points could go unseen: grids smaller than
  // the number of shards). Holes are found between the rows present, never by counting up to the
  // last point: a damaged row numbered 9e18 must not make us count to it. The first holes are
  // named, a run of three or more points as a range.
  constexpr std::size_t kHolesNamed = 20;
  std::vector<std::string> holes;
  long missingPoints = 0, namedPoints = 0, expected = 0;
  for (const auto& [point, row] : rows) {
    if (point > expected) {
      const long count = point - expected;
      missingPoints += count;
      if (holes.size() < kHolesNamed) {
        holes.push_back(count == 1   ? fmt::format("{}", expected)
                        : count == 2 ? fmt::format("{}, {}", expected, expected + 1)
                                     : fmt::format("{} to {}", expected, point - 1));
        namedPoints += count;
      }
    }
    expected = point + 1;
  }
  if (missingPoints > 0) {
    throw std::runtime_error(fmt::format("sweep-merge: points missing: {}{}", fmt::join(holes, ", "),
                                         missingPoints > namedPoints ? fmt::format(" and {} more", missingPoints - namedPoints)
                                                                     : ""));
  }
  out << header << '\n';
  for (const auto& [point, row] : rows) out << row << '\n';
  if (!out) throw std::runtime_error("sweep-merge: writing the merged file failed");
}

}  // namespace coinroll::pipeline
