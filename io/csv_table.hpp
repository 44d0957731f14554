#pragma once
// A numeric CSV table read in one pass: a header line of column names, then rows of decimal
// numbers separated by commas (blanks around a field and blank lines ignored). The file is
// read in large blocks and each row parsed where it lies in the block: std::from_chars from
// field to field, no string or row vector per line, the columns reserved from the size of the
// file, and each value checked against its column's limit as it is read. A table of ten
// million rows (4.5 GB) reads in seconds (benchmarks/README.md, "Reading a dataset"); progress
// is shown on a terminal (io/progress.hpp).

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace vcontact::io {

struct CsvTable {
  std::vector<std::string> names;            ///< the header, in file order
  std::vector<std::vector<double>> columns;  ///< columns[c][i]: row i of column names[c]
  std::vector<std::size_t> lineOf;           ///< file line (from 1) of each row, for messages
  std::size_t rowCount() const { return lineOf.size(); }
};

/// The largest magnitude a column's values may have, and its unit for the message.
struct ColumnLimit {
  double magnitude = std::numeric_limits<double>::max();  ///< the default: any finite value
  std::string unit;
};

/// A column's limit from its name (called once per column, after the header).
using ColumnLimits = std::function<ColumnLimit(const std::string& name)>;

/// @param limits each column's limit; none: every finite value
/// @throws InputError naming `path` and the line (and column) on: a file that cannot be read,
///         no header, an empty or repeated column name, a row with another number of fields
///         than the header, a field that is not a number or not finite, a value beyond its
///         column's limit ("line 7, column 'x': 2000 is beyond +-1000 m (io/input_ranges.hpp)")
CsvTable readCsvTable(const std::string& path, const ColumnLimits& limits = {});

}  // namespace vcontact::io
