#pragma once
// Test support: a numeric CSV as the program writes it (a header line of column names, then rows
// of numbers), read one way for every test instead of a hand-rolled loop per file.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace coinroll::testing {

struct CsvTable {
  std::string headerLine;                 // the first line as written, for comparing the contract's header
  std::vector<std::string> columns;       // the header's names, in order
  std::vector<std::vector<double>> rows;  // every later line, one number per column

  // The values of the column named `name`, one per row. Throws std::out_of_range naming the column
  // and listing the header when there is no such column.
  std::vector<double> column(std::string_view name) const;
};

// Reads `csv`. Throws std::runtime_error naming the file (and the line) when it cannot be opened,
// has no header, or has a row whose cell count differs from the header's or a cell that is no number.
CsvTable readCsvTable(const std::filesystem::path& csv);

}  // namespace coinroll::testing
