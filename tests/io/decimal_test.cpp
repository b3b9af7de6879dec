// io::detail::parseSimpleDecimal: bit-identical to std::from_chars wherever it answers.
#include "io/detail/decimal.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <string>

namespace pkm::io::detail {
namespace PKM_TEST_NS {

/// from_chars's reading of the whole of `s`, or nullopt.
std::optional<double> reference(const std::string& s) {
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

std::optional<double> fast(const std::string& s) {
  double v = 0.0;
  if (!parseSimpleDecimal(s.data(), s.data() + s.size(), v)) return std::nullopt;
  return v;
}

TEST(DecimalTest, AgreesBitForBitWithFromCharsOnRandomNumbers) {
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> scale(-12, 12);
  std::uniform_int_distribution<int> decimals(0, 17);
  int answered = 0;
  constexpr int kCases = 200000;
  for (int i = 0; i < kCases; ++i) {
    const double x = mantissa(rng) * std::pow(10.0, scale(rng));
    const int d = decimals(rng);
    for (const std::string& s : {fmt::format("{:.{}f}", x, d),
                                 fmt::format("{:.{}e}", x, d),
                                 fmt::format("{}", x),
                                 fmt::format("{:.{}g}", x, d + 1)}) {
      const std::optional<double> f = fast(s);
      if (!f) continue;
      ++answered;
      const std::optional<double> r = reference(s);
      ASSERT_TRUE(r.has_value()) << s;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(*f), std::bit_cast<std::uint64_t>(*r)) << s;
    }
  }
  EXPECT_GT(answered, 2 * kCases);  // the fast path takes most measurement-like numbers
}

TEST(DecimalTest, SeventeenToNineteenDigitsAgreeBitForBitWithFromChars) {
  // The shortest round-trip text of most doubles has 17 digits: the extended-precision step reads
  // them, and any 19-digit decimal with a power of ten within ±27, exactly as from_chars does.
  std::mt19937_64 rng(20261127);
  std::uniform_int_distribution<std::uint64_t> digits19(1'000'000'000'000'000'000u,
                                                        9'999'999'999'999'999'999u);
  std::uniform_int_distribution<int> exponent(-27, 27);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int answered = 0;
  constexpr int kCases = 200000;
  for (int i = 0; i < kCases; ++i) {
    const std::uint64_t m = digits19(rng) / (i % 2 == 0 ? 1 : 100);  // 19 and 17 digits
    const double x = unit(rng) * std::pow(10.0, exponent(rng) / 3);
    for (const std::string& s : {fmt::format("{}e{}", m, exponent(rng)),
                                 fmt::format("{}", x),
                                 fmt::format("{:.17g}", x),
                                 fmt::format("{:.19f}", x / 1e3)}) {
      const std::optional<double> f = fast(s);
      if (!f) continue;
      ++answered;
      const std::optional<double> r = reference(s);
      ASSERT_TRUE(r.has_value()) << s;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(*f), std::bit_cast<std::uint64_t>(*r)) << s;
    }
  }
  if (extendedPrecisionWorks()) EXPECT_GT(answered, 5 * kCases / 2);
}

TEST(DecimalTest, HalfwayCasesAreLeftToFromChars) {
  // Exactly halfway between two doubles: the extended result is the halfway point itself, whose
  // second rounding is not trusted.
  std::uint64_t m = 0;
  double v = 0.0;
  for (int shift = 54; shift <= 63; ++shift) {
    m = (std::uint64_t{1} << shift) + (std::uint64_t{1} << (shift - 53));
    EXPECT_FALSE(extendedDecimal(m, 0, v)) << m;
    EXPECT_FALSE(fast(std::to_string(m)).has_value()) << m;
    // One above halfway is read (rounded up), as from_chars does.
    if (extendedPrecisionWorks()) {
      const std::string above = std::to_string(m + 1);
      ASSERT_TRUE(fast(above).has_value()) << above;
      EXPECT_EQ(*fast(above), *reference(above)) << above;
    }
  }
}

TEST(DecimalTest, ScanStopsAtTheFieldEndInsideALongerBuffer) {
  // Eight bytes are read at a time where eight are there: the number's end must be found
  // whatever follows it.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1000.0, 1000.0);
  for (int i = 0; i < 20000; ++i) {
    const std::string number = fmt::format("{:.{}f}", u(rng), i % 12);
    for (const char* tail : {",12345678,9\n", "\n", " ,x", "e", ".5"}) {
      const std::string buffer = number + tail + "0123456789";
      double v = 0.0;
      const char* end = scanSimpleDecimal(buffer.data(), buffer.data() + buffer.size(), v);
      if (std::string_view(tail) == "e" || std::string_view(tail) == ".5") {
        // "1.5e0123..." and "1.5.5": scanned further or refused, never a wrong stop
        continue;
      }
      ASSERT_EQ(end, buffer.data() + number.size()) << buffer;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(v), std::bit_cast<std::uint64_t>(*reference(number)))
          << buffer;
    }
  }
}

TEST(DecimalTest, EdgeCases) {
  for (const char* s : {"0",
                        "-0",
                        "0.000",
                        "-0.0",
                        ".5",
                        "5.",
                        "-.25",
                        "1e22",
                        "1E-22",
                        "9007199254740992",
                        "0.00000000000000001",
                        "2.5e+3",
                        "-7e-0",
                        "00001.5000"}) {
    const std::optional<double> f = fast(s);
    ASSERT_TRUE(f.has_value()) << s;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(*f), std::bit_cast<std::uint64_t>(*reference(s))) << s;
  }
  // Outside the fast path or not numbers: no answer (the caller falls back to from_chars).
  for (const char* s : {"",
                        "-",
                        ".",
                        "e5",
                        "1e",
                        "1e+",
                        "--1",
                        "+1",
                        "1.2.3",
                        "1,5",
                        "1 ",
                        " 1",
                        "nan",
                        "inf",
                        "0x10",
                        "9007199254740993",     // 2^53 + 1: halfway between two doubles
                        "1152921504606847104",  // 2^60 + 2^7: halfway too
                        "12345678901234567890",
                        "1e-28",
                        "1e99999",
                        "12a"}) {
    EXPECT_FALSE(fast(s).has_value()) << s;
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io::detail
