#include "io/input_ranges.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace vcontact::io {
namespace {

// Length of the run of decimal digits at s[i...].
std::size_t digitsAt(const std::string& s, std::size_t i) {
  std::size_t n = 0;
  while (i + n < s.size() && std::isdigit(static_cast<unsigned char>(s[i + n]))) ++n;
  return n;
}

// [+-] digits [. digits] [e [+-] digits], at least one digit before the exponent.
bool isDecimal(const std::string& s) {
  std::size_t i = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
  std::size_t mantissa = digitsAt(s, i);
  i += mantissa;
  if (i < s.size() && s[i] == '.') {
    const std::size_t fraction = digitsAt(s, i + 1);
    mantissa += fraction;
    i += 1 + fraction;
  }
  if (mantissa == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    const std::size_t exponent = digitsAt(s, i);
    if (exponent == 0) return false;
    i += exponent;
  }
  return i == s.size();
}

}  // namespace

std::string outOfRange(double value, const Range& range, const std::string& name) {
  if (std::isfinite(value) && value >= range.lower && value <= range.upper) return "";
  std::ostringstream os;
  os << "expected " << name << " in [" << range.lower << ", " << range.upper << "] " << range.unit
     << ", got " << value;
  return os.str();
}

bool parseDecimal(const std::string& text, double& value, std::string& why) {
  if (!isDecimal(text)) {
    why = "not a number (expected a decimal such as 0.01 or 1e-3)";
    return false;
  }
  // from_chars takes no leading '+'; the sign was checked above.
  const std::size_t skip = text[0] == '+' ? 1 : 0;
  const auto [end, ec] = std::from_chars(text.data() + skip, text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range) {
    // from_chars reports an underflow so too; strtod gives the subnormal or zero it means
    // (the text is a plain decimal, so the locale's decimal point cannot differ from '.').
    const auto e = text.find_first_of("eE");
    const bool underflow = e != std::string::npos && text[e + 1] == '-';
    if (!underflow) {
      why = "beyond the range of a double";
      return false;
    }
    value = std::strtod(text.c_str(), nullptr);
    return true;
  }
  if (ec != std::errc() || end != text.data() + text.size()) {
    why = "not a number (expected a decimal such as 0.01 or 1e-3)";
    return false;
  }
  return true;
}

}  // namespace vcontact::io
