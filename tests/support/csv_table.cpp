#include "csv_table.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace coinroll::testing {

namespace {

std::vector<std::string> splitCells(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();  // getline drops a trailing empty cell
  return cells;
}

double parseCell(const std::string& cell, const std::filesystem::path& csv, long lineNumber) {
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(cell.c_str(), &end);
  if (cell.empty() || end != cell.c_str() + cell.size() || errno == ERANGE) {
    throw std::runtime_error(csv.string() + ":" + std::to_string(lineNumber) + ": '" + cell + "' is no number");
  }
  return value;
}

}  // namespace

std::vector<double> CsvTable::column(std::string_view name) const {
  const auto found = std::find(columns.begin(), columns.end(), name);
  if (found == columns.end()) throw std::out_of_range("no column '" + std::string(name) + "' in " + headerLine);
  const auto index = static_cast<std::size_t>(found - columns.begin());
  std::vector<double> values;
  values.reserve(rows.size());
  for (const std::vector<double>& row : rows) values.push_back(row[index]);
  return values;
}

CsvTable readCsvTable(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(csv.string() + ": cannot be opened");
  CsvTable table;
  if (!std::getline(in, table.headerLine)) throw std::runtime_error(csv.string() + ": empty, no header");
  table.columns = splitCells(table.headerLine);
  long lineNumber = 1;
  for (std::string line; std::getline(in, line);) {
    ++lineNumber;
    const std::vector<std::string> cells = splitCells(line);
    if (cells.size() != table.columns.size()) {
      throw std::runtime_error(csv.string() + ":" + std::to_string(lineNumber) + ": " + std::to_string(cells.size()) +
                               " cells under a header of " + std::to_string(table.columns.size()));
    }
    std::vector<double>& row = table.rows.emplace_back();
    row.reserve(cells.size());
    for (const std::string& cell : cells) row.push_back(parseCell(cell, csv, lineNumber));
  }
  return table;
}

}  // namespace coinroll::testing
