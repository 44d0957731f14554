// csv/<reader>/<rows>: reading a dataset-shaped CSV table (14 kinematic columns and 6 wrench
// columns, numbers in round-trip form) with io::readCsvTable against the two readers before it
// in the same run: the line-by-line reader of before issue 20 (std::getline, a stringstream
// split and a row vector per line) and the previous block reader (a split and trim per line,
// unreserved columns, the range check as a second pass). Issue 20: a 10-million-row dataset is
// read in seconds.

#include <benchmark/benchmark.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "io/csv_table.hpp"

namespace {

namespace fs = std::filesystem;

// A table of `rows` rows in the temporary folder, written once per size.
fs::path table(long rows) {
  const fs::path path =
      fs::temp_directory_path() / ("vcontact_csv_bench_" + std::to_string(rows) + ".csv");
  if (fs::exists(path)) return path;
  std::ofstream out(path);
  out.precision(std::numeric_limits<double>::max_digits10);
  out << "t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,fx,fy,fz,tx,ty,tz\n";
  for (long i = 0; i < rows; ++i) {
    const double t = 1e-4 * static_cast<double>(i);
    out << t;
    for (int c = 1; c < 20; ++c) out << ',' << std::sin(t * c + c) * (c == 4 ? 0.0 : 1e-3);
    out << '\n';
  }
  return path;
}

// Limits like the dataset reader's (formats/dataset_file.cpp): position and time bounded, the
// rest finite.
vcontact::io::ColumnLimit datasetLimits(const std::string& name) {
  if (name == "t") return {1e6, "s"};
  if (name == "x" || name == "y" || name == "z") return {1e3, "m"};
  return {};
}

// The block reader of io/csv_table.cpp before the one-pass parser (a string_view split per
// line, every field trimmed, columns grown without reserve, ranges checked in a second pass by
// the dataset reader), kept to measure the change in the same run (errors as runtime_error).
namespace previous {

using vcontact::io::CsvTable;

// Its errors as the project's: the file, then the message.
struct InputError : std::runtime_error {
  InputError(const std::string& path, const std::string& what)
      : std::runtime_error(path + ": " + what) {}
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

constexpr std::size_t kBlockBytes = std::size_t{1} << 20;  // read size; lines may span blocks

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

bool isBlank(std::string_view line) { return line.find_first_not_of(" \t\r") == line.npos; }

class TableBuilder {
 public:
  explicit TableBuilder(const std::string& path) : path_(path) {}

  void line(std::string_view text) {
    ++lineNo_;
    if (isBlank(text)) return;
    if (table_.names.empty()) {
      header(text);
    } else {
      row(text);
    }
  }

  CsvTable finish() {
    if (table_.names.empty()) {
      throw InputError("empty file: expected a header line of column names");
    }
    return std::move(table_);
  }

 private:
  // A header that a spreadsheet in a decimal-comma locale or a UTF-8 editor wrote is named as
  // such, since the generic "missing column" would not say why.
  void header(std::string_view text) {
    if (text.substr(0, 3) == "\xEF\xBB\xBF") {
      throw InputError(path_,
                       "line 1: starts with a UTF-8 byte order mark; expected plain text (save "
                       "the CSV as UTF-8 without BOM)");
    }
    if (text.find(';') != text.npos && text.find(',') == text.npos) {
      throw InputError(path_,
                       "line 1: columns are separated by ';'; expected ',' and numbers with a "
                       "decimal point (a CSV written with decimal commas is not read)");
    }
    std::set<std::string> seen;
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = text.find(',', start);
      const std::string name(trim(text.substr(start, comma - start)));
      if (name.empty()) throw InputError("line 1: empty column name");
      if (!seen.insert(name).second) {
        throw InputError("line 1: column '" + name + "' appears twice");
      }
      table_.names.push_back(name);
      if (comma == text.npos) break;
      start = comma + 1;
    }
    table_.columns.resize(table_.names.size());
  }

  void row(std::string_view text) {
    const std::size_t n = table_.names.size();
    std::size_t c = 0, start = 0;
    while (true) {
      const std::size_t comma = text.find(',', start);
      if (c < n) field(c, trim(text.substr(start, comma - start)));
      ++c;
      if (comma == text.npos) break;
      start = comma + 1;
    }
    if (c != n) {
      std::ostringstream os;
      os << "line " << lineNo_ << ": " << c << " fields, but the header names " << n << " columns";
      throw InputError(os.str());
    }
    table_.lineOf.push_back(lineNo_);
  }

  void field(std::size_t c, std::string_view f) {
    double x = 0.0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), x);
    if (f.empty() || ec != std::errc() || end != f.data() + f.size()) {
      throw InputError(where(c) + ": '" + std::string(f) + "' is not a number");
    }
    if (!std::isfinite(x)) {
      throw InputError(where(c) + ": '" + std::string(f) + "' is not finite");
    }
    table_.columns[c].push_back(x);
  }

  std::string where(std::size_t c) const {
    return "line " + std::to_string(lineNo_) + ", column '" + table_.names[c] + "'";
  }

  const std::string& path_;
  CsvTable table_;
  std::size_t lineNo_ = 0;
};

CsvTable readBlockReader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot be read");
  TableBuilder builder(path);
  std::string buffer;  // the unfinished line of the previous block, then this block
  std::vector<char> block(kBlockBytes);
  double read = 0.0;
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got == 0) break;
    buffer.append(block.data(), got);
    std::string_view rest(buffer);
    for (auto nl = rest.find('\n'); nl != rest.npos; nl = rest.find('\n')) {
      builder.line(rest.substr(0, nl));
      rest.remove_prefix(nl + 1);
    }
    buffer.erase(0, buffer.size() - rest.size());
    read += static_cast<double>(got) / 1e6;
  }
  if (in.bad())
    throw InputError("cannot be read (a read error after " + std::to_string(read) + " MB)");
  if (!buffer.empty()) builder.line(buffer);
  return builder.finish();
}

// The dataset reader's second pass over the table: every value against its column's limit.
void checkRanges(const CsvTable& t, const vcontact::io::ColumnLimits& limits) {
  for (std::size_t c = 0; c < t.names.size(); ++c) {
    const double limit = limits(t.names[c]).magnitude;
    for (double x : t.columns[c]) {
      if (std::abs(x) > limit) throw InputError("beyond the limit");
    }
  }
}

}  // namespace previous

// The reader before issue 20, as it was in formats/dataset_file.cpp (errors left out).
std::vector<std::vector<double>> referenceRead(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::vector<double>> rows;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::string field;
    std::stringstream ss(line);
    while (std::getline(ss, field, ',')) fields.push_back(field);
    std::vector<double> row(fields.size());
    for (std::size_t c = 0; c < fields.size(); ++c) {
      std::from_chars(fields[c].data(), fields[c].data() + fields[c].size(), row[c]);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

void BM_ReferenceReader(benchmark::State& state) {
  const fs::path path = table(state.range(0));
  std::size_t rows = 0;
  for (auto _ : state) {
    const auto r = referenceRead(path.string());
    rows = r.size();
    benchmark::DoNotOptimize(r.data());
  }
  state.counters["rows"] = static_cast<double>(rows);
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_PreviousBlockReader(benchmark::State& state) {
  const fs::path path = table(state.range(0));
  std::size_t rows = 0;
  for (auto _ : state) {
    const vcontact::io::CsvTable t = previous::readBlockReader(path.string());
    previous::checkRanges(t, datasetLimits);
    rows = t.rowCount();
    benchmark::DoNotOptimize(t.columns.data());
  }
  state.counters["rows"] = static_cast<double>(rows);
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_CsvTable(benchmark::State& state) {
  const fs::path path = table(state.range(0));
  std::size_t rows = 0;
  for (auto _ : state) {
    const vcontact::io::CsvTable t = vcontact::io::readCsvTable(path.string(), datasetLimits);
    rows = t.rowCount();
    benchmark::DoNotOptimize(t.columns.data());
  }
  state.counters["rows"] = static_cast<double>(rows);
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

BENCHMARK(BM_ReferenceReader)
    ->Name("csv/reference")
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PreviousBlockReader)
    ->Name("csv/previous_block_reader")
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CsvTable)
    ->Name("csv/csv_table")
    ->Arg(100000)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond);
// Ten million rows (4.5 GB, written once to the temporary folder): one read of each.
BENCHMARK(BM_PreviousBlockReader)
    ->Name("csv/previous_block_reader")
    ->Arg(10000000)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CsvTable)
    ->Name("csv/csv_table")
    ->Arg(10000000)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
