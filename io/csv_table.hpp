#pragma once
// A numeric CSV table read in one pass: a header line of column names, then rows of decimal
// numbers separated by commas (blanks around a field and blank lines ignored). The file is
// read in blocks and each field parsed in place with std::from_chars, without a string or a
// row vector per line, so a table of ten million rows reads in seconds; progress is shown on a
// terminal (io/progress.hpp).

#include <cstddef>
#include <string>
#include <vector>

namespace vcontact::io {

struct CsvTable {
  std::vector<std::string> names;            ///< the header, in file order
  std::vector<std::vector<double>> columns;  ///< columns[c][i]: row i of column names[c]
  std::vector<std::size_t> lineOf;           ///< file line (from 1) of each row, for messages
  std::size_t rowCount() const { return lineOf.size(); }
};

/// @throws InputError naming `path` and the line (and column) on: a file that cannot be read,
///         no header, an empty or repeated column name, a row with another number of fields
///         than the header, a field that is not a number or not finite
CsvTable readCsvTable(const std::string& path);

}  // namespace vcontact::io
