// Tests of pkm::io::appendNumber / formatNumber: shortest decimal output that round-trips exactly.
#include "pkm/io/number_format.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using pkm::io::appendNumber;
using pkm::io::formatNumber;

/// Parses the whole of `text` with std::from_chars; fails the test on leftovers or errors.
double parseBack(const std::string& text) {
  double v = std::numeric_limits<double>::quiet_NaN();
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  EXPECT_EQ(ec, std::errc()) << text;
  EXPECT_EQ(ptr, text.data() + text.size()) << text;
  return v;
}

/// Bit-exact equality (distinguishes nothing that == would not, except for -0, which is handled
/// apart).
void expectRoundTrip(double x) {
  std::string s;
  appendNumber(s, x);
  const double back = parseBack(s);
  ASSERT_EQ(std::bit_cast<std::uint64_t>(back), std::bit_cast<std::uint64_t>(x)) << s;
}

TEST(NumberFormat, RandomDoublesOfEveryMagnitudeRoundTrip) {
  std::mt19937_64 rng(pkm::test::kSeed);
  int tested = 0;
  for (int i = 0; i < 200000; ++i) {
    const double x = std::bit_cast<double>(rng());  // every exponent, subnormals included
    if (!std::isfinite(x) || x == 0.0) continue;
    expectRoundTrip(x);
    ++tested;
  }
  EXPECT_GT(tested, 190000);
}

TEST(NumberFormat, RandomMachineSizedValuesRoundTrip) {
  std::mt19937 rng(pkm::test::kSeed);
  std::uniform_real_distribution<double> u(-2000.0, 2000.0);
  std::uniform_real_distribution<double> small(-1e-6, 1e-6);
  for (int i = 0; i < 100000; ++i) {
    expectRoundTrip(u(rng));
    expectRoundTrip(small(rng));
    expectRoundTrip(std::round(u(rng) * 1000.0) / 1000.0);  // values typed with 3 decimals
  }
}

TEST(NumberFormat, ExtremesRoundTrip) {
  for (const double x : {std::numeric_limits<double>::max(),
                         std::numeric_limits<double>::lowest(),
                         std::numeric_limits<double>::min(),
                         std::numeric_limits<double>::denorm_min(),
                         -std::numeric_limits<double>::denorm_min(),
                         std::numeric_limits<double>::epsilon(),
                         1.0 + std::numeric_limits<double>::epsilon(),
                         0.1,
                         0.2,
                         0.30000000000000004,
                         1e23,
                         9007199254740993.0,
                         29.746680487072839})
    expectRoundTrip(x);
}

TEST(NumberFormat, NegativeZeroIsWrittenAsZero) {
  EXPECT_EQ(formatNumber(-0.0), "0");
  EXPECT_EQ(formatNumber(0.0), "0");
  std::string s = "x=";
  appendNumber(s, -0.0);
  EXPECT_EQ(s, "x=0");
  EXPECT_FALSE(std::signbit(parseBack(formatNumber(-0.0))));
}

TEST(NumberFormat, ShortestForm) {
  EXPECT_EQ(formatNumber(1.0), "1");
  EXPECT_EQ(formatNumber(-22.95), "-22.95");
  EXPECT_EQ(formatNumber(0.1), "0.1");
  EXPECT_EQ(formatNumber(1e-9), "1e-09");
  EXPECT_EQ(formatNumber(120.0), "120");
  EXPECT_EQ(formatNumber(0.1 + 0.2), "0.30000000000000004");
}

TEST(NumberFormat, AppendsWithoutClearing) {
  std::string s = "a,";
  appendNumber(s, 1.5);
  s += ',';
  appendNumber(s, -2.0);
  EXPECT_EQ(s, "a,1.5,-2");
}

TEST(NumberFormat, WriteNumberStaysWithinItsRoom) {
  // writeNumber's text is appendNumber's and never longer than 24 bytes (kMaxNumberChars is the
  // room callers give it), at every exponent and for large integers (std::to_chars's own text).
  std::mt19937_64 rng(20261128);
  std::size_t longest = 0;
  for (int i = 0; i < 200000; ++i) {
    for (const double v : {std::bit_cast<double>(rng()),
                           static_cast<double>(rng()),
                           -static_cast<double>(rng() >> 3)}) {
      char buf[pkm::io::kMaxNumberChars];
      const char* end = pkm::io::writeNumber(buf, v);
      const auto n = static_cast<std::size_t>(end - buf);
      longest = std::max(longest, n);
      ASSERT_EQ(std::string(buf, n), formatNumber(v));
    }
  }
  EXPECT_LE(longest, 24u);
  EXPECT_GE(longest, 23u);  // "-1.2345678901234567e-123" lengths were met
}

TEST(NumberFormat, NonFinite) {
  EXPECT_EQ(formatNumber(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(formatNumber(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(formatNumber(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(NumberFormat, SameTextAsStdToCharsOnAMillionDoubles) {
  // appendNumber's own layout of Dragonbox digits against libstdc++'s std::to_chars: random bit
  // patterns (every exponent), measurement-like values, integers and short decimals.
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> e(-30, 30);
  auto expect = [](double v) {
    if (v == 0.0 || !std::isfinite(v)) return;
    char buf[64];
    const std::string ref(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
    ASSERT_EQ(formatNumber(v), ref) << std::hexfloat << v;
  };
  for (int i = 0; i < 250000; ++i) {  // a million values
    expect(std::bit_cast<double>(rng()));
    expect(u(rng) * std::pow(10.0, e(rng)));
    expect(std::round(u(rng) * 1e6) / 1e3);
    expect(static_cast<double>(static_cast<long long>(rng() >> (rng() % 64))));
  }
  for (const double v : {1e22,
                         1e23,
                         123456.0,
                         1234567.0,
                         1e16,
                         1.5e15,
                         0.0001,
                         0.00012,
                         1e-5,
                         5e-324,
                         1.7976931348623157e308,
                         100.0,
                         1e21,
                         12e20})
    expect(v);
}

}  // namespace PKM_TEST_NS
