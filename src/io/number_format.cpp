#include "pkm/io/number_format.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdint>

namespace pkm::io {

// The shortest round-trip digits come from fmt's Dragonbox (Jeon 2020; fmt's FMT_API entry
// fmt::detail::dragonbox::to_decimal), several times cheaper than libstdc++'s std::to_chars; the
// layout is std::to_chars's (plain format): fixed or scientific, whichever is shorter, fixed on
// a tie, two exponent digits at least. tests/io/number_format_test.cpp checks the output equals
// std::to_chars's on a million doubles.
void appendNumber(std::string& out, double value) {
  if (value == 0.0) {  // also drops the sign of -0
    out += '0';
    return;
  }
  // Non-finite values, and integers of 2^53 and more, which std::to_chars writes in full in its
  // fixed layout (exact digits, not the shortest ones padded with zeros): its own text.
  if (!std::isfinite(value) || std::abs(value) >= 9007199254740992.0) {
    char buf[400];
    out.append(buf, std::to_chars(buf, buf + sizeof buf, value).ptr);
    return;
  }
  const auto dec = fmt::detail::dragonbox::to_decimal(value);
  char digits[20];
  int n = 0;
  for (std::uint64_t s = dec.significand; s != 0; s /= 10)
    digits[n++] = static_cast<char>('0' + s % 10);
  // digits[n-1..0] are the significant digits, value = 0.d1...dn × 10^point.
  const int point = n + dec.exponent;
  const int sci_exp = point - 1;
  const int abs_exp = sci_exp < 0 ? -sci_exp : sci_exp;
  const int sci_len = n + (n > 1 ? 1 : 0) + 2 + (abs_exp >= 100 ? 3 : 2);
  const int fixed_len = point <= 0 ? 2 - point + n : point >= n ? point : n + 1;
  char buf[32];   // fixed layouts that reach here are at most 2 + 324 digits only for tiny
  char* o = buf;  // numbers, which take the scientific layout (shorter): 32 is enough
  if (value < 0.0) *o++ = '-';
  if (fixed_len <= sci_len) {
    if (point <= 0) {
      *o++ = '0';
      *o++ = '.';
      for (int i = 0; i < -point; ++i) *o++ = '0';
      for (int i = n - 1; i >= 0; --i) *o++ = digits[i];
    } else {
      for (int i = n - 1, k = 0; i >= 0; --i, ++k) {
        if (k == point) *o++ = '.';
        *o++ = digits[i];
      }
      for (int i = n; i < point; ++i) *o++ = '0';
    }
  } else {
    *o++ = digits[n - 1];
    if (n > 1) {
      *o++ = '.';
      for (int i = n - 2; i >= 0; --i) *o++ = digits[i];
    }
    *o++ = 'e';
    *o++ = sci_exp < 0 ? '-' : '+';
    if (abs_exp >= 100) *o++ = static_cast<char>('0' + abs_exp / 100);
    *o++ = static_cast<char>('0' + abs_exp / 10 % 10);
    *o++ = static_cast<char>('0' + abs_exp % 10);
  }
  out.append(buf, o);
}

std::string formatNumber(double value) {
  std::string s;
  appendNumber(s, value);
  return s;
}

}  // namespace pkm::io
