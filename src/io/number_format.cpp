#include "pkm/io/number_format.hpp"

#include <fmt/format.h>

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
  // The significant digits, two at a time from the last, end at digits + 20.
  static constexpr char kPairs[] =
      "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
      "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
      "8081828384858687888990919293949596979899";
  char digits[20];
  char* first = digits + sizeof digits;
  std::uint64_t s = dec.significand;
  while (s >= 100) {
    const std::uint64_t q = s / 100;
    first -= 2;
    std::memcpy(first, kPairs + 2 * (s - 100 * q), 2);
    s = q;
  }
  if (s >= 10) {
    first -= 2;
    std::memcpy(first, kPairs + 2 * s, 2);
  } else {
    *--first = static_cast<char>('0' + s);
  }
  const int n = static_cast<int>(digits + sizeof digits - first);
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
      const auto whole = static_cast<std::size_t>(point);
      std::memcpy(o, first, whole);
      o[whole] = '.';
      std::memcpy(o + whole + 1, first + whole, un - whole);
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
