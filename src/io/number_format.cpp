#include "pkm/io/number_format.hpp"

#include <fmt/format.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace pkm::io {

// The shortest round-trip digits come from fmt's Dragonbox (Jeon 2020; fmt's FMT_API entry
// fmt::detail::dragonbox::to_decimal), several times cheaper than libstdc++'s std::to_chars; the
// layout is std::to_chars's (plain format): fixed or scientific, whichever is shorter, fixed on
// a tie, two exponent digits at least. tests/io/number_format_test.cpp checks the output equals
// std::to_chars's on a million doubles.
namespace {

/// The digits buffer: 20 digit places and room for the fixed 24-byte copies read from any digit.
constexpr std::size_t kDigitsRoom = 48;

constexpr char kPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

/// The eight decimal digits of v < 10^8 (leading zeros included) at out[0..8).
inline void writeEightDigits(char* out, std::uint32_t v) {
  const std::uint32_t upper = v / 10000, lower = v % 10000;
  std::memcpy(out, kPairs + 2 * (upper / 100), 2);
  std::memcpy(out + 2, kPairs + 2 * (upper % 100), 2);
  std::memcpy(out + 4, kPairs + 2 * (lower / 100), 2);
  std::memcpy(out + 6, kPairs + 2 * (lower % 100), 2);
}

/// Number of decimal digits of s > 0: floor(log10(2^bits)) from the bit length (1233/4096 ≈
/// log10 2), corrected by one comparison.
inline int significandDigits(std::uint64_t s) {
  static constexpr std::uint64_t kPow10[] = {1ULL,
                                             10ULL,
                                             100ULL,
                                             1000ULL,
                                             10000ULL,
                                             100000ULL,
                                             1000000ULL,
                                             10000000ULL,
                                             100000000ULL,
                                             1000000000ULL,
                                             10000000000ULL,
                                             100000000000ULL,
                                             1000000000000ULL,
                                             10000000000000ULL,
                                             100000000000000ULL,
                                             1000000000000000ULL,
                                             10000000000000000ULL,
                                             100000000000000000ULL,
                                             1000000000000000000ULL,
                                             10000000000000000000ULL};
  const int t = (64 - std::countl_zero(s)) * 1233 >> 12;
  return t + 1 - (s < kPow10[t] ? 1 : 0);
}

}  // namespace

char* writeNumber(char* out, double value) {
  if (value == 0.0) {  // also drops the sign of -0
    *out = '0';
    return out + 1;
  }
  // Non-finite values, and integers of 2^53 and more, which std::to_chars writes in full in its
  // fixed layout (exact digits, not the shortest ones padded with zeros): its own text, which is
  // never longer than the scientific form (kMaxNumberChars).
  if (!std::isfinite(value) || std::abs(value) >= 9007199254740992.0)
    return std::to_chars(out, out + kMaxNumberChars, value).ptr;
  const auto dec = fmt::detail::dragonbox::to_decimal(value);
  // The significand has at most 17 digits: they are written right-aligned at digits[3..20), two
  // at a time, as three independent runs (8 + 8 + 1 digits), so that the divisions overlap.
  const std::uint64_t s = dec.significand;
  const int n = significandDigits(s);
  char digits[kDigitsRoom];
  const std::uint64_t high = s / 100000000;
  writeEightDigits(digits + 12, static_cast<std::uint32_t>(s - high * 100000000));
  writeEightDigits(digits + 4, static_cast<std::uint32_t>(high % 100000000));
  digits[3] = static_cast<char>('0' + high / 100000000);
  const char* const first = digits + 20 - n;
  // value = 0.d1...dn × 10^point.
  const int point = n + dec.exponent;
  const int sci_exp = point - 1;
  const int abs_exp = sci_exp < 0 ? -sci_exp : sci_exp;
  const int sci_len = n + (n > 1 ? 1 : 0) + 2 + (abs_exp >= 100 ? 3 : 2);
  const int fixed_len = point <= 0 ? 2 - point + n : point >= n ? point : n + 1;
  char* o = out;  // either layout is at most the scientific one's length, 23, with a sign: 24
  if (value < 0.0) *o++ = '-';
  const auto un = static_cast<std::size_t>(n);
  if (fixed_len <= sci_len) {
    if (point <= 0) {
      const auto zeros = static_cast<std::size_t>(-point);
      *o++ = '0';
      *o++ = '.';
      std::memset(o, '0', zeros);
      o += zeros;
      std::memcpy(o, first, un);
      o += un;
    } else if (point < n) {
      // Fixed-size copies (no library call): 24 bytes from `first`, then the fraction (at most
      // 16 digits) one place on, after the point; the bytes past the number are slack.
      const auto whole = static_cast<std::size_t>(point);
      std::memcpy(o, first, 24);
      std::memcpy(o + whole + 1, first + whole, 16);
      o[whole] = '.';
      o += un + 1;
    } else {
      std::memcpy(o, first, un);
      std::memset(o + un, '0', static_cast<std::size_t>(point - n));
      o += point;
    }
  } else {
    *o++ = first[0];
    if (n > 1) {
      *o++ = '.';
      std::memcpy(o, first + 1, un - 1);
      o += un - 1;
    }
    *o++ = 'e';
    *o++ = sci_exp < 0 ? '-' : '+';
    if (abs_exp >= 100) *o++ = static_cast<char>('0' + abs_exp / 100);
    *o++ = static_cast<char>('0' + abs_exp / 10 % 10);
    *o++ = static_cast<char>('0' + abs_exp % 10);
  }
  return o;
}

void appendNumber(std::string& out, double value) {
  char buf[kMaxNumberChars];
  out.append(buf, static_cast<std::size_t>(writeNumber(buf, value) - buf));
}

std::string formatNumber(double value) {
  std::string s;
  appendNumber(s, value);
  return s;
}

}  // namespace pkm::io
