#include "pipeline/sweep_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>

namespace coinroll::pipeline {

namespace {

double parseNumber(std::string_view text, std::string_view what, std::string_view whole) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw std::invalid_argument(fmt::format("--grid {}: {} must be a finite number, got \"{}\"", whole, what, text));
  }
  return value;
}

bool parseWholeNumber(std::string_view digits, long& value) {
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  return error == std::errc() && end == digits.data() + digits.size() && !digits.empty();
}

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  for (std::size_t from = 0;;) {
    const auto at = text.find(separator, from);
    parts.push_back(text.substr(from, at == std::string_view::npos ? std::string_view::npos : at - from));
    if (at == std::string_view::npos) return parts;
    from = at + 1;
  }
}

// Interpolates a and b by k of n: exactly a at 0 and b at n.
double between(double a, double b, long k, long n) {
  const double kd = static_cast<double>(k), nd = static_cast<double>(n);
  return (a * (nd - kd) + b * kd) / nd;
}

}  // namespace

double GridAxis::valueAt(long i) const {
  switch (spacing) {
    case Spacing::Listed: return listed[static_cast<std::size_t>(i)];
    case Spacing::Geometric:
      // Interpolated between the decimal logarithms, so decades come out as the numbers one would
      // type: 1e-3:1e-9:7:log gives 1e-4, not 9.999999999999999e-05 as start * ratio^k does.
      if (count == 1 || i == 0) return start;
      if (i == count - 1) return stop;
      return std::pow(10.0, between(std::log10(start), std::log10(stop), i, count - 1));
    case Spacing::Even: break;
  }
  return count == 1 ? start : between(start, stop, i, count - 1);
}

GridAxis parseGridAxis(std::string_view text) {
  const auto equals = text.find('=');
  const std::string_view key = text.substr(0, std::min(equals, text.size()));
  const std::string_view values = equals == std::string_view::npos ? std::string_view() : text.substr(equals + 1);
  const std::vector<std::string_view> fields = split(values, ':');
  const bool isRange = fields.size() == 3 || fields.size() == 4;
  if (key.empty() || values.empty() || (fields.size() > 1 && !isRange) ||
      (isRange && values.find(',') != values.npos)) {
    throw std::invalid_argument(
        fmt::format("--grid {}: expected KEY.PATH=START:STOP:COUNT, KEY.PATH=START:STOP:COUNT:log "
                    "or KEY.PATH=V1,V2,..., e.g. --grid initial.theta=5:40:8",
                    text));
  }
  GridAxis axis;
  axis.key = key;
  if (!isRange) {
    axis.spacing = GridAxis::Spacing::Listed;
    const std::vector<std::string_view> items = split(values, ',');
    for (std::size_t i = 0; i < items.size(); ++i) {
      const double value = parseNumber(items[i], fmt::format("value {}", i + 1), text);
      // A value twice would compute its points twice; it is a typo, not a request.
      if (std::find(axis.listed.begin(), axis.listed.end(), value) != axis.listed.end()) {
        throw std::invalid_argument(fmt::format("--grid {}: {} is listed twice; list each value once", text, items[i]));
      }
      axis.listed.push_back(value);
    }
    axis.count = static_cast<long>(axis.listed.size());
    axis.start = axis.listed.front();
    axis.stop = axis.listed.back();
    return axis;
  }
  axis.start = parseNumber(fields[0], "START", text);
  axis.stop = parseNumber(fields[1], "STOP", text);
  if (!parseWholeNumber(fields[2], axis.count) || axis.count < 1) {
    throw std::invalid_argument(
        fmt::format("--grid {}: COUNT must be a whole number >= 1, got \"{}\"", text, fields[2]));
  }
  if (fields.size() == 4) {
    if (fields[3] != "log") {
      throw std::invalid_argument(
          fmt::format("--grid {}: the field after COUNT must be log (geometric spacing), got \"{}\"", text, fields[3]));
    }
    if (!(axis.start > 0 && axis.stop > 0)) {
      throw std::invalid_argument(fmt::format("--grid {}: a log axis needs START > 0 and STOP > 0", text));
    }
    axis.spacing = GridAxis::Spacing::Geometric;
  }
  if (axis.count == 1 && axis.start != axis.stop) {
    throw std::invalid_argument(fmt::format("--grid {}: COUNT 1 takes one value; give START = STOP", text));
  }
  // The range's twin of a value listed twice: every point would be the same run.
  if (axis.count > 1 && axis.start == axis.stop) {
    throw std::invalid_argument(
        fmt::format("--grid {}: START and STOP are equal, so its {} points would all be {}; "
                    "give COUNT 1 for that one value, or a STOP other than START",
                    text, axis.count, fields[0]));
  }
  return axis;
}

Shard parseShard(std::string_view text, std::optional<std::string_view> slurmArrayTaskId) {
  Shard shard;
  const auto slash = text.find('/');
  const std::string_view index = text.substr(0, std::min(slash, text.size()));
  const bool countGiven =
      slash != std::string_view::npos && parseWholeNumber(text.substr(slash + 1), shard.count) && shard.count >= 1;
  if (index == "auto" && countGiven) {
    const long n = shard.count;
    if (!slurmArrayTaskId) {
      throw std::invalid_argument(fmt::format(
          "--shard {}: auto takes K from $SLURM_ARRAY_TASK_ID, which is not set: this is not a task of a Slurm job "
          "array; submit it with sbatch --array=1-{}, or give K, e.g. --shard 1/{}",
          text, n, n));
    }
    if (!parseWholeNumber(*slurmArrayTaskId, shard.index) || shard.index < 1 || shard.index > n) {
      throw std::invalid_argument(
          fmt::format("--shard {}: $SLURM_ARRAY_TASK_ID is \"{}\", not a shard number 1 to {}; "
                      "submit the array as --array=1-{} (task K computes shard K/{})",
                      text, *slurmArrayTaskId, n, n, n));
    }
    return shard;
  }
  if (!countGiven || !parseWholeNumber(index, shard.index) || shard.index < 1 || shard.index > shard.count) {
    throw std::invalid_argument(fmt::format(
        "--shard {}: expected K/N with 1 <= K <= N, e.g. --shard 2/8, or auto/N in a Slurm array task", text));
  }
  return shard;
}

}  // namespace coinroll::pipeline
