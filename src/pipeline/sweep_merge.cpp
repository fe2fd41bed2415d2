#include "pipeline/sweep_merge.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <vector>

#include "pipeline/cancelled.h"
#include "pipeline/sweep.h"
#include "scene/json_reader.h"

namespace coinroll::pipeline {

namespace {

// The fields of one CSV row as csvField writes them (a quoted field may hold commas), quotes kept,
// into `fields` (reused from row to row: a merge may read ten million).
void splitCsvRow(std::string_view row, std::vector<std::string_view>& fields) {
  fields.clear();
  bool quoted = false;
  std::size_t start = 0;
  for (std::size_t i = 0; i < row.size(); ++i) {
    if (row[i] == '"')
      quoted = !quoted;
    else if (row[i] == ',' && !quoted) {
      fields.push_back(row.substr(start, i - start));
      start = i + 1;
    }
  }
  fields.push_back(row.substr(start));
}

bool isNumber(std::string_view cell) {
  double value = 0;
  const auto [end, error] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  return !cell.empty() && error == std::errc() && end == cell.data() + cell.size();
}

bool isDigest(std::string_view cell) {
  return cell.size() == 16 &&
         std::all_of(cell.begin(), cell.end(), [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

// Every cell of a row must be what the sweep writes in its column: a shard edited by hand or
// damaged on its way (a theta_end turned "abc") would otherwise be merged as if computed, and
// found, if ever, by whatever reads the table. Columns: point (read by the caller), the grid values,
// end, the six numbers (empty for a failed point, whose end is "error: why"), grid_points and sweep
// (the identity, compared by the caller).
void refuseDamagedCells(const std::vector<std::string_view>& cells, const std::vector<std::string_view>& columns,
                        const std::string& name, long lineNumber) {
  const auto refuse = [&](std::size_t column, std::string_view rule) {
    return std::runtime_error(
        fmt::format("{}:{}: {}: {}; a damaged or edited shard, run it again", name, lineNumber, columns[column], rule));
  };
  const auto quoted = [](std::string_view cell) { return fmt::format("\"{}\"", scene::printable(cell)); };
  const std::size_t end = columns.size() - 9;  // the column after the grid values
  for (std::size_t column = 1; column < end; ++column) {
    if (!isNumber(cells[column])) throw refuse(column, quoted(cells[column]) + " is not a number");
  }
  const std::string_view endCell = cells[end];
  if (endCell.empty()) throw refuse(end, "empty; it holds how the run ended (duration, an event, or error: why)");
  const bool failed = endCell.substr(endCell.starts_with('"') ? 1 : 0).starts_with("error: ");
  for (std::size_t column = end + 1; column < end + 7; ++column) {
    if (failed && !cells[column].empty()) {
      throw refuse(column, quoted(cells[column]) + " where a failed point (its end an error) has no number");
    }
    if (!failed && !isNumber(cells[column])) throw refuse(column, quoted(cells[column]) + " is not a number");
  }
  if (!isDigest(cells.back())) throw refuse(columns.size() - 1, quoted(cells.back()) + " is not 16 hexadecimal digits");
}

// The row's last two fields, ",<grid points>,<digest>": never quoted, so found from the end.
std::string_view identityOf(std::string_view row) {
  const auto last = row.rfind(',');
  const auto beforeLast =
      last == std::string_view::npos || last == 0 ? std::string_view::npos : row.rfind(',', last - 1);
  return beforeLast == std::string_view::npos ? std::string_view() : row.substr(beforeLast);
}

// The header's columns between the grid keys and the identity must be this coinroll's
// (kSweepSummaryColumns): a shard of another version has other columns, and its rows, merged with
// this version's, would make a file that no sweep writes. A shard written before theta_end existed
// is named as such, so its user knows to run it again rather than look for a wrong axis.
void refuseOtherSummaryColumns(std::string_view header, std::string_view name) {
  const std::string_view columns = header.substr(0, header.size() - kSweepIdentityColumns.size());
  if (columns.ends_with(kSweepSummaryColumns)) return;
  constexpr std::string_view kTheta = ",theta_end";
  static_assert(kSweepSummaryColumns.ends_with(kTheta));
  const std::string_view beforeTheta = kSweepSummaryColumns.substr(0, kSweepSummaryColumns.size() - kTheta.size());
  if (columns.ends_with(beforeTheta)) {
    throw std::invalid_argument(fmt::format(
        "{}: its header has no theta_end column (\"...,energy_end,grid_points,sweep\" where this coinroll writes "
        "\"...,energy_end,theta_end,grid_points,sweep\"): written by an older coinroll; run that shard again with "
        "this one",
        name));
  }
  // The keys end where the summary begins: a grid key is a scene field, never "end".
  const std::size_t summary = columns.find(",end,");
  throw std::invalid_argument(fmt::format(
      "{}: its header's columns after the grid keys are \"{}\" where this coinroll writes \"{}\": written by "
      "another coinroll, or edited; run that shard again with this one",
      name, summary == std::string_view::npos ? columns : columns.substr(summary + 1), kSweepSummaryColumns.substr(1)));
}

// A list of point numbers for a message: the first 20, then how many more.
std::string pointList(const std::vector<long>& points) {
  const std::size_t shown = std::min<std::size_t>(points.size(), 20);
  return fmt::format("{}{}", fmt::join(points.begin(), points.begin() + static_cast<long>(shown), ", "),
                     points.size() > shown ? fmt::format(" and {} more", points.size() - shown) : "");
}

}  // namespace

long mergeSweepShards(const std::vector<std::filesystem::path>& shards, std::ostream& out,
                      const std::atomic<bool>* cancel) {
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
        throw std::invalid_argument(
            fmt::format("{}: is a directory; give the shard files (e.g. {}/*.csv)", name, name));
      }
      // A pipe or a FIFO reads as well as a file: the shard is read once, front to back.
      file.open(path, std::ios::binary);
      if (!file) throw std::runtime_error(fmt::format("{}: cannot open the shard: {}", name, std::strerror(errno)));
    }
    std::istream& in = standardInput ? std::cin : file;
    long lineNumber = 0;
    const auto readLine = [&](std::string& line) {
      if (!std::getline(in, line)) {
        if (in.bad())
          throw std::runtime_error(fmt::format("{}: reading the shard failed: {}", name, std::strerror(errno)));
        return false;
      }
      ++lineNumber;
      return true;
    };
    // getline leaves eof set after a line that had no line break: the shard was cut inside it.
    const auto refuseCutLine = [&] {
      if (in.eof()) {
        throw std::runtime_error(
            fmt::format("{}:{}: cut short inside a row (no line break at its end): an unfinished "
                        "or damaged shard, e.g. an interrupted `sweep -o - > part.csv`; run that "
                        "shard again",
                        name, lineNumber));
      }
    };
    std::string line;
    if (!readLine(line)) throw std::invalid_argument(fmt::format("{}: empty, not a sweep shard", name));
    if (!line.starts_with("point,")) {
      throw std::invalid_argument(
          fmt::format("{}: not a sweep shard (its first line does not start with \"point,\")", name));
    }
    refuseCutLine();
    if (!line.ends_with(kSweepIdentityColumns)) {
      throw std::invalid_argument(
          fmt::format("{}: its header has no grid_points and sweep columns, which tell a merge "
                      "which sweep a shard belongs to: written by an older coinroll, or "
                      "edited; run the sweep again",
                      name));
    }
    refuseOtherSummaryColumns(line, name);
    if (header.empty()) {
      header = line;
      firstHeaderSource = name;
    } else if (line != header) {
      throw std::runtime_error(
          fmt::format("{}: its header differs from {}'s: shards of sweeps over different axes; "
                      "merge only the shards of one sweep",
                      name, firstHeaderSource));
    }
    std::vector<std::string_view> columns, cells;
    splitCsvRow(header, columns);
    while (readLine(line)) {
      throwIfCancelled(cancel);
      refuseCutLine();
      long point = -1;
      const auto comma = line.find(',');
      const auto [end, error] = std::from_chars(line.data(), line.data() + std::min(comma, line.size()), point);
      if (error != std::errc() || comma == std::string::npos || end != line.data() + comma || point < 0) {
        throw std::runtime_error(fmt::format("{}:{}: a row must start with its point number", name, lineNumber));
      }
      splitCsvRow(line, cells);
      if (cells.size() != columns.size()) {
        throw std::runtime_error(fmt::format("{}:{}: {} fields where the header has {}: a damaged shard; run it again",
                                             name, lineNumber, cells.size(), columns.size()));
      }
      refuseDamagedCells(cells, columns, name, lineNumber);
      const std::string_view rowIdentity = identityOf(line);
      if (identity.empty()) {
        const std::string_view count = rowIdentity.substr(1, rowIdentity.find(',', 1) - 1);
        const auto [countEnd, countError] = std::from_chars(count.data(), count.data() + count.size(), gridPoints);
        if (countError != std::errc() || countEnd != count.data() + count.size() || gridPoints < 1) {
          throw std::runtime_error(
              fmt::format("{}:{}: grid_points must be a whole number >= 1, got \"{}\": a damaged "
                          "shard; run it again",
                          name, lineNumber, count));
        }
        identity = rowIdentity;
        identitySource = fmt::format("{}:{}", name, lineNumber);
      } else if (rowIdentity != identity) {
        throw std::runtime_error(fmt::format(
            "{}:{}: from another sweep than {} (grid_points,sweep: {} here, {} there): the scene, its --set values or "
            "the grid differ; merge only the shards of one sweep",
            name, lineNumber, identitySource, rowIdentity.substr(1), std::string_view(identity).substr(1)));
      }
      if (point >= gridPoints) {
        throw std::runtime_error(
            fmt::format("{}:{}: point {} is outside the grid of {} points: a damaged shard; run it "
                        "again",
                        name, lineNumber, point, gridPoints));
      }
      if (!rows.emplace(point, line).second) repeated.push_back(point);
    }
  }
  if (!repeated.empty()) throw std::runtime_error(fmt::format("sweep-merge: points repeated: {}", pointList(repeated)));
  if (rows.empty()) {
    throw std::runtime_error(
        "sweep-merge: no shard holds a point, but shard 1 of every sweep holds point 0: a shard is "
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
    throw std::runtime_error(
        fmt::format("sweep-merge: points missing (of {} in the grid): {}{}", gridPoints, fmt::join(holes, ", "),
                    missingPoints > namedPoints ? fmt::format(" and {} more", missingPoints - namedPoints) : ""));
  }
  out << header << '\n';
  for (const auto& [point, row] : rows) out << row << '\n';
  if (!out) throw std::runtime_error("sweep-merge: writing the merged file failed");
  return static_cast<long>(rows.size());
}

}  // namespace coinroll::pipeline
