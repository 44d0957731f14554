#include "report/csv_number.hpp"

#include <charconv>
#include <cmath>
#include <cstring>

namespace vcontact::report {
namespace {

// Below this magnitude an integer's fixed text ("99999", 5 characters) is never longer than
// its scientific one ("9.9999e+04"); from 10⁵ on a round one is shorter in scientific
// ("1e+05"), which std::to_chars then chooses.
constexpr double kShortIntegerBound = 1e5;

// The decimal digits of 0 <= v < 10⁵, most significant first; returns the end.
char* writeDigits(char* out, long v) {
  char digits[8];
  int n = 0;
  do {
    digits[n++] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v > 0);
  while (n > 0) *out++ = digits[--n];
  return out;
}

}  // namespace

char* writeNumber(char* out, double x) {
  const double magnitude = std::abs(x);
  if (magnitude < kShortIntegerBound && magnitude == std::floor(magnitude)) {
    if (std::signbit(x)) *out++ = '-';  // "-0" as well, as std::to_chars writes it
    return writeDigits(out, static_cast<long>(magnitude));
  }
  return std::to_chars(out, out + kMaxNumberChars, x).ptr;
}

char* CsvBuffer::reserve(std::size_t n) {
  if (size_ + n > buffer_.size()) buffer_.resize(2 * (size_ + n));
  return buffer_.data() + size_;
}

void CsvBuffer::append(std::string_view s) {
  std::memcpy(reserve(s.size()), s.data(), s.size());
  size_ += s.size();
}

void CsvBuffer::first(double x) {
  char* at = reserve(kMaxNumberChars);
  if (std::memcmp(&x, &first_, sizeof x) != 0) {
    first_ = x;
    first_size_ = static_cast<std::size_t>(writeNumber(first_text_, x) - first_text_);
  }
  std::memcpy(at, first_text_, first_size_);
  size_ += first_size_;
}

void CsvBuffer::number(double x) {
  char* at = reserve(kMaxNumberChars + 1);
  *at = ',';
  size_ = static_cast<std::size_t>(writeNumber(at + 1, x) - buffer_.data());
}

void CsvBuffer::text(std::string_view s) {
  append(",");
  append(s);
}

void CsvBuffer::integer(long i) {
  char* at = reserve(1 + 24);  // ',' and the 20 digits and sign of a 64-bit integer
  *at = ',';
  size_ = static_cast<std::size_t>(std::to_chars(at + 1, at + 25, i).ptr - buffer_.data());
}

}  // namespace vcontact::report
