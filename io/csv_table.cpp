#include "io/csv_table.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>

#include "geometry/error.hpp"
#include "io/progress.hpp"

namespace vcontact::io {
namespace {

constexpr std::size_t kBlockBytes = std::size_t{4} << 20;  // read size; lines may span blocks
// Rows parsed before the rest of the table's rows are estimated from the file size.
constexpr std::size_t kRowsForEstimate = 1000;

bool isBlankChar(char c) { return c == ' ' || c == '\t' || c == '\r'; }

const char* skipBlanks(const char* p, const char* end) {
  while (p != end && isBlankChar(*p)) ++p;
  return p;
}

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

class TableBuilder {
 public:
  TableBuilder(const std::string& path, const ColumnLimits& limits, double fileBytes)
      : path_(path), limits_(limits), fileBytes_(fileBytes) {}

  // One line, without its '\n'.
  void line(const char* begin, const char* end) {
    ++lineNo_;
    const char* p = skipBlanks(begin, end);
    if (p == end) return;
    if (table_.names.empty()) {
      header(std::string_view(begin, static_cast<std::size_t>(end - begin)));
      return;
    }
    rowBegin_ = begin;
    row(p, end);
    bytesParsed_ += static_cast<double>(end - begin) + 1.0;
    if (table_.lineOf.size() == kRowsForEstimate) reserveRest();
  }

  CsvTable finish() {
    if (table_.names.empty()) {
      throw InputError(path_, "empty file: expected a header line of column names");
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
      if (name.empty()) throw InputError(path_, "line 1: empty column name");
      if (!seen.insert(name).second) {
        throw InputError(path_, "line 1: column '" + name + "' appears twice");
      }
      table_.names.push_back(name);
      limit_.push_back(limits_ ? limits_(name) : ColumnLimit{});
      if (comma == text.npos) break;
      start = comma + 1;
    }
    table_.columns.resize(table_.names.size());
  }

  // The rows still to come, from the bytes per row so far, reserved in every column: no
  // column is copied as it grows (10 million rows are 80 MB a column).
  void reserveRest() {
    const double perRow = bytesParsed_ / static_cast<double>(kRowsForEstimate);
    const auto rows = static_cast<std::size_t>(1.02 * fileBytes_ / perRow) + kRowsForEstimate;
    for (auto& c : table_.columns) c.reserve(rows);
    table_.lineOf.reserve(rows);
  }

  // Field by field: blanks, a number std::from_chars reads, blanks, then ',' (or the line's
  // end after the last column).
  void row(const char* p, const char* end) {
    const std::size_t n = table_.names.size();
    for (std::size_t c = 0; c < n; ++c) {
      const char* field = skipBlanks(p, end);
      double x = 0.0;
      const auto [stop, ec] = std::from_chars(field, end, x);
      p = skipBlanks(stop, end);
      const bool last = c + 1 == n;
      if (ec != std::errc() || (p != end && *p != ',')) notANumber(c, field, end);
      if (last ? p != end : p == end) fieldCount(end);
      if (!(std::abs(x) <= limit_[c].magnitude)) outOfRange(c, field, end, x);
      table_.columns[c].push_back(x);
      ++p;  // past the ','
    }
    table_.lineOf.push_back(lineNo_);
  }

  // A line with more or fewer fields than the header: how many it has.
  [[noreturn]] void fieldCount(const char* end) const {
    const std::size_t fields = 1 + static_cast<std::size_t>(std::count(rowBegin_, end, ','));
    std::ostringstream os;
    os << "line " << lineNo_ << ": " << fields << " fields, but the header names "
       << table_.names.size() << " columns";
    throw InputError(path_, os.str());
  }

  [[noreturn]] void notANumber(std::size_t c, const char* field, const char* end) const {
    const std::string text(trim(fieldText(field, end)));
    throw InputError(path_, where(c) + ": '" + text + "' is not a number");
  }

  [[noreturn]] void outOfRange(std::size_t c, const char* field, const char* end, double x) const {
    if (!std::isfinite(x)) {
      throw InputError(
          path_, where(c) + ": '" + std::string(trim(fieldText(field, end))) + "' is not finite");
    }
    std::ostringstream os;
    os << where(c) << ": " << x << " is beyond +-" << limit_[c].magnitude << " " << limit_[c].unit
       << " (io/input_ranges.hpp)";
    throw InputError(path_, os.str());
  }

  static std::string_view fieldText(const char* field, const char* end) {
    const char* comma =
        static_cast<const char*>(std::memchr(field, ',', static_cast<std::size_t>(end - field)));
    return std::string_view(field, static_cast<std::size_t>((comma ? comma : end) - field));
  }

  std::string where(std::size_t c) const {
    return "line " + std::to_string(lineNo_) + ", column '" + table_.names[c] + "'";
  }

  const std::string& path_;
  const ColumnLimits& limits_;
  double fileBytes_;
  CsvTable table_;
  std::vector<ColumnLimit> limit_;  ///< per column
  std::size_t lineNo_ = 0;
  double bytesParsed_ = 0.0;
  const char* rowBegin_ = nullptr;  ///< the line being parsed
};

}  // namespace

CsvTable readCsvTable(const std::string& path, const ColumnLimits& limits) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot be read");
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  const double fileBytes = ec ? 0.0 : static_cast<double>(bytes);
  Progress progress("reading " + path, fileBytes / 1e6, "MB");
  TableBuilder builder(path, limits, fileBytes);
  // buffer[0, kept) holds the unfinished line of the previous block, then a block is read
  // after it; complete lines are parsed where they lie.
  std::vector<char> buffer(kBlockBytes);
  std::size_t kept = 0;
  double read = 0.0;
  while (in) {
    if (buffer.size() - kept < kBlockBytes / 2) buffer.resize(2 * buffer.size());  // long line
    in.read(buffer.data() + kept, static_cast<std::streamsize>(buffer.size() - kept));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got == 0) break;
    const char* p = buffer.data();
    const char* end = buffer.data() + kept + got;
    while (const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end - p))) {
      const char* eol = static_cast<const char*>(nl);
      builder.line(p, eol);
      p = eol + 1;
    }
    kept = static_cast<std::size_t>(end - p);
    std::memmove(buffer.data(), p, kept);
    read += static_cast<double>(got) / 1e6;
    progress.update(read);
  }
  if (in.bad())
    throw InputError(path, "cannot be read (a read error after " + std::to_string(read) + " MB)");
  if (kept > 0) builder.line(buffer.data(), buffer.data() + kept);
  return builder.finish();
}

}  // namespace vcontact::io
