// The test-support CSV reader: the tests that read the program's CSVs trust it to refuse what the
// contract forbids rather than guess.

#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>
#include <string>

#include "csv_table.h"
#include "scratch_dir.h"

namespace {

using coinroll::testing::CsvTable;
using coinroll::testing::readCsvTable;

class CsvTableTest : public coinroll::testing::ScratchDirTest {
 protected:
  std::filesystem::path write(const std::string& text) {
    const std::filesystem::path file = dir_ / "table.csv";
    std::ofstream(file) << text;
    return file;
  }
};

std::string messageOf(const std::filesystem::path& file) {
  try {
    readCsvTable(file);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}

TEST_F(CsvTableTest, ReadsTheHeaderAndEveryRowAndColumnsByName) {
  const CsvTable table = readCsvTable(write("t,theta\n0,1.5\n0.01,-2e-3\n"));
  EXPECT_EQ(table.headerLine, "t,theta");
  EXPECT_EQ(table.columns, (std::vector<std::string>{"t", "theta"}));
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.column("theta"), (std::vector<double>{1.5, -2e-3}));
  EXPECT_THROW(table.column("phi"), std::out_of_range);
}

TEST_F(CsvTableTest, RefusesARaggedRowOrACellThatIsNoNumberNamingTheLine) {
  EXPECT_NE(messageOf(write("t,theta\n0,1\n0.01\n")).find("table.csv:3: 1 cells under a header of 2"),
            std::string::npos);
  EXPECT_NE(messageOf(write("t,theta\n0,1\n0.01,1,\n")).find("table.csv:3: 3 cells"), std::string::npos);
  EXPECT_NE(messageOf(write("t,theta\n0,1x\n")).find("table.csv:2: '1x' is no number"), std::string::npos);
  EXPECT_NE(messageOf(write("t,theta\n0,\n")).find("table.csv:2: '' is no number"), std::string::npos);
  EXPECT_NE(messageOf(dir_ / "missing.csv").find("cannot be opened"), std::string::npos);
}

}  // namespace
