#include "io/csv_table.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>

#include "geometry/error.hpp"
#include "io/progress.hpp"

namespace vcontact::io {
namespace {

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
      throw InputError(path_, os.str());
    }
    table_.lineOf.push_back(lineNo_);
  }

  void field(std::size_t c, std::string_view f) {
    double x = 0.0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), x);
    if (f.empty() || ec != std::errc() || end != f.data() + f.size()) {
      throw InputError(path_, where(c) + ": '" + std::string(f) + "' is not a number");
    }
    if (!std::isfinite(x)) {
      throw InputError(path_, where(c) + ": '" + std::string(f) + "' is not finite");
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

}  // namespace

CsvTable readCsvTable(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot be read");
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  Progress progress("reading " + path, ec ? 0.0 : static_cast<double>(bytes) / 1e6, "MB");
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
    progress.update(read);
  }
  if (in.bad())
    throw InputError(path, "cannot be read (a read error after " + std::to_string(read) + " MB)");
  if (!buffer.empty()) builder.line(buffer);
  return builder.finish();
}

}  // namespace vcontact::io
