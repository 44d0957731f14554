// io::readCsvTable: the table read, and each kind of bad table refused with file and line.

#include "io/csv_table.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "geometry/error.hpp"

namespace {

namespace fs = std::filesystem;
using vcontact::io::readCsvTable;

fs::path writeTable(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() /
                     ("vcontact_csv_" + name + "_" + std::to_string(::getpid()) + ".csv");
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

std::string errorOf(const std::string& name, const std::string& text) {
  const fs::path p = writeTable(name, text);
  std::string message;
  try {
    readCsvTable(p.string());
    ADD_FAILURE() << name << ": accepted";
  } catch (const vcontact::InputError& e) {
    message = e.what();
  }
  fs::remove(p);
  // The message starts with the file; the rest is compared by the caller.
  EXPECT_EQ(message.rfind(p.string() + ": ", 0), 0u) << message;
  return message.substr(std::min(message.size(), p.string().size() + 2));
}

TEST(CsvTable, ReadsColumnsAndLinesAcrossBlanksAndCrlf) {
  // No final newline, CRLF line ends, blanks around fields and a blank line between rows.
  const fs::path p = writeTable("ok", " t , x\r\n0, 1.5\r\n\r\n1e-3,-2\r\n0.25,3");
  const auto t = readCsvTable(p.string());
  fs::remove(p);
  ASSERT_EQ(t.names, (std::vector<std::string>{"t", "x"}));
  ASSERT_EQ(t.rowCount(), 3u);
  EXPECT_EQ(t.columns[0], (std::vector<double>{0.0, 1e-3, 0.25}));
  EXPECT_EQ(t.columns[1], (std::vector<double>{1.5, -2.0, 3.0}));
  EXPECT_EQ(t.lineOf, (std::vector<std::size_t>{2, 4, 5}));
}

// Rows that straddle the boundary of the 1 MiB read blocks are put together whole: 60000
// columns of ~360 KB a line, past 1 MiB in all.
TEST(CsvTable, LineSpanningReadBlocksIsWhole) {
  std::string header, row;
  for (int c = 0; c < 60000; ++c) {
    header += (c ? ",c" : "c") + std::to_string(c);
    row += (c ? ",0.125" : "0.125");
  }
  const fs::path p = writeTable("long", header + "\n" + row + "\n" + row + "\n");
  ASSERT_GT(fs::file_size(p), std::size_t{1} << 20);
  const auto t = readCsvTable(p.string());
  fs::remove(p);
  ASSERT_EQ(t.names.size(), 60000u);
  EXPECT_EQ(t.rowCount(), 2u);
  EXPECT_EQ(t.columns[59999], (std::vector<double>{0.125, 0.125}));
}

TEST(CsvTable, BadTablesNameTheLineAndWhatWasExpected) {
  EXPECT_EQ(errorOf("empty", "\n  \n"), "empty file: expected a header line of column names");
  EXPECT_EQ(errorOf("noname", "t,,x\n"), "line 1: empty column name");
  EXPECT_EQ(errorOf("twice", "t,x,t\n"), "line 1: column 't' appears twice");
  EXPECT_EQ(errorOf("fields", "t,x\n0,1\n1,2,3\n"),
            "line 3: 3 fields, but the header names 2 columns");
  EXPECT_EQ(errorOf("few", "t,x\n0\n"), "line 2: 1 fields, but the header names 2 columns");
  EXPECT_EQ(errorOf("trailing", "t,x\n0,1,\n"), "line 2: 3 fields, but the header names 2 columns");
  EXPECT_EQ(errorOf("word", "t,x\n0,abc\n"), "line 2, column 'x': 'abc' is not a number");
  EXPECT_EQ(errorOf("comma", "t,x\n0,1;5\n"), "line 2, column 'x': '1;5' is not a number");
  EXPECT_EQ(errorOf("blank", "t,x\n0, \n"), "line 2, column 'x': '' is not a number");
  EXPECT_EQ(errorOf("inf", "t,x\n0,inf\n"), "line 2, column 'x': 'inf' is not finite");
  EXPECT_EQ(errorOf("nan", "t,x\nnan,0\n"), "line 2, column 't': 'nan' is not finite");
}

TEST(CsvTable, MissingFileCannotBeRead) {
  const std::string p = (fs::temp_directory_path() / "vcontact_csv_no_such.csv").string();
  try {
    readCsvTable(p);
    ADD_FAILURE() << "accepted";
  } catch (const vcontact::InputError& e) {
    EXPECT_EQ(std::string(e.what()), p + ": cannot be read");
  }
}

}  // namespace
