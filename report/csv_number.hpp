#pragma once
// The text of a number in the simulation's CSV files, and a row of them built in one reused
// buffer (report/simulation_csv.cpp).
//
// A number is written as std::to_chars(first, last, x) writes it: the shortest text that reads
// back to the same double, in fixed or scientific notation, whichever is shorter (fixed on a
// tie): "0", "-0", "0.2", "1e-05", "6.279053237882563e-14", "nan", "-inf". Integers of magnitude
// below 10⁵ (zeros included, which most contact columns hold out of contact) take a
// short path with the same text: they are ten times cheaper than the general algorithm.

#include <cstddef>
#include <string>
#include <string_view>

namespace vcontact::report {

/// The most characters writeNumber writes: "-2.2250738585072014e-308" is 24.
constexpr std::size_t kMaxNumberChars = 24;

/// Writes the text of `x` (above) at `out`, which has room for kMaxNumberChars; returns the
/// end of what was written.
char* writeNumber(char* out, double x);

/// Lines of a CSV file built in place before one write to the file: fields are appended with
/// their separating comma, and the buffer keeps its capacity from one output time to the
/// next, so that rows cost no allocation once the longest have been seen.
class CsvBuffer {
 public:
  /// Empties the buffer; keeps the capacity.
  void clear() { size_ = 0; }
  /// The first field of a row: the number without a comma. Every row of an output time starts
  /// with its time: the text of the latest first field is kept and copied when it repeats.
  void first(double x);
  /// ",x"
  void number(double x);
  /// ",text" (a name: the caller keeps commas and line breaks out of it)
  void text(std::string_view s);
  /// ",i" for a count or index
  void integer(long i);
  /// The end of the row.
  void endRow() { append("\n"); }

  std::string_view view() const { return std::string_view(buffer_.data(), size_); }

 private:
  /// Room for n more characters at data() + size_.
  char* reserve(std::size_t n);
  void append(std::string_view s);

  std::string buffer_;  ///< its size() is the capacity; the first size_ characters are the text
  std::size_t size_ = 0;
  double first_ = 0.0;                        ///< the latest first field (compared bit for bit) ...
  char first_text_[kMaxNumberChars] = {'0'};  ///< ... and its text
  std::size_t first_size_ = 1;
};

}  // namespace vcontact::report
