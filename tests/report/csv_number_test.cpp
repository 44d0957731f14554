// The CSV number text (report/csv_number.hpp): the same characters as std::to_chars, which the
// simulation files were written with before the short path for integers, and text that reads
// back to the same double.

#include "report/csv_number.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>

namespace vcontact::report {
namespace {

std::string written(double x) {
  char buf[kMaxNumberChars];
  return std::string(buf, writeNumber(buf, x));
}

// The format of the files so far: std::to_chars' shortest round-trip text.
std::string reference(double x) {
  char buf[64];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
}

double parsed(const std::string& s) {
  double x = 0.0;
  const auto [end, err] = std::from_chars(s.data(), s.data() + s.size(), x);
  EXPECT_EQ(err, std::errc()) << s;
  EXPECT_EQ(end, s.data() + s.size()) << s;
  return x;
}

std::uint64_t bits(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// Same text as before, and the text reads back bit for bit (so -0 stays -0).
void expectExact(double x) {
  const std::string s = written(x);
  EXPECT_EQ(s, reference(x)) << "bits " << bits(x);
  EXPECT_LE(s.size(), kMaxNumberChars);
  if (std::isnan(x)) {
    EXPECT_TRUE(std::isnan(parsed(s))) << s;
    return;
  }
  EXPECT_EQ(bits(parsed(s)), bits(x)) << s;
}

TEST(CsvNumber, EdgeValuesKeepTheOldText) {
  using L = std::numeric_limits<double>;
  const double cases[] = {0.0,
                          -0.0,
                          1.0,
                          -1.0,
                          0.2,
                          1e-300,
                          -1e-300,
                          1e300,
                          L::max(),
                          -L::max(),
                          L::min(),
                          L::denorm_min(),
                          -L::denorm_min(),
                          L::epsilon(),
                          99999.0,
                          -99999.0,
                          100000.0,
                          -100000.0,
                          99999.5,
                          10000.0,
                          12345.0,
                          1e5 - 1e-11,
                          1e16,
                          9007199254740993.0,
                          0.1,
                          1e-5,
                          1e-4,
                          123456.0,
                          -2.2250738585072014e-308,
                          6.279053237882563e-14,
                          0.3246270523986666};
  for (double x : cases) expectExact(x);
  EXPECT_EQ(written(-0.0), "-0");
  EXPECT_EQ(written(100000.0), "1e+05");  // beyond the short path: scientific is shorter
  EXPECT_EQ(written(-12345.0), "-12345");
}

TEST(CsvNumber, NonFiniteValuesKeepTheOldText) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double x : {inf, -inf, nan, -nan}) expectExact(x);
  EXPECT_EQ(written(-inf), "-inf");
}

// Every integer the short path takes, and its neighbours just off the integers.
TEST(CsvNumber, EveryShortIntegerKeepsTheOldText) {
  for (int i = -100001; i <= 100001; ++i) {
    const double x = i;
    ASSERT_EQ(written(x), reference(x)) << i;
    ASSERT_EQ(written(std::nextafter(x, 1e9)), reference(std::nextafter(x, 1e9))) << i;
  }
}

// Random bit patterns cover every exponent, subnormals and NaN payloads included; random
// values of the sizes a simulation writes cover the common case.
TEST(CsvNumber, RandomValuesRoundTripWithTheOldText) {
  std::mt19937_64 rng(20261126);
  for (int i = 0; i < 200000; ++i) {
    const std::uint64_t b = rng();
    double x = 0.0;
    std::memcpy(&x, &b, sizeof x);
    expectExact(x);
  }
  std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
  std::uniform_int_distribution<int> exponent(-20, 6);
  for (int i = 0; i < 200000; ++i) expectExact(std::ldexp(mantissa(rng), 3 * exponent(rng)));
}

TEST(CsvBuffer, BuildsRowsWithCommasAndKeepsItsCapacity) {
  CsvBuffer row;
  row.first(0.5);
  row.text("ball");
  row.number(-0.0);
  row.integer(-1);
  row.number(1e-300);
  row.endRow();
  row.first(1.0);
  row.endRow();
  EXPECT_EQ(row.view(), "0.5,ball,-0,-1,1e-300\n1\n");
  const char* before = row.view().data();
  row.clear();
  EXPECT_EQ(row.view(), "");
  row.first(0.25);
  row.number(2.0);
  EXPECT_EQ(row.view(), "0.25,2");
  EXPECT_EQ(row.view().data(), before);  // no new allocation for a shorter text
}

// first() keeps the text of the latest first field; a repeat is copied, anything else (even
// -0 after 0, which compare equal as doubles) is written anew.
TEST(CsvBuffer, FirstFieldsRepeatAndChange) {
  CsvBuffer row;
  for (double t : {0.0, -0.0, -0.0, 0.0, 0.0005, 0.0005, 0.001, 1e-300}) {
    row.first(t);
    row.endRow();
  }
  // 0.0005 is "5e-04" in std::to_chars' shortest form (5 characters against 6)
  EXPECT_EQ(row.view(), "0\n-0\n-0\n0\n5e-04\n5e-04\n0.001\n1e-300\n");
}

TEST(CsvBuffer, GrowsForLongRows) {
  CsvBuffer row;
  std::string expected = "0";
  row.first(0.0);
  for (int i = 0; i < 1000; ++i) {
    const double x = 1.0 / (i + 3);
    row.number(x);
    expected += ',' + reference(x);
  }
  EXPECT_EQ(row.view(), expected);
}

}  // namespace
}  // namespace vcontact::report
