// Private to the cnc module: the reading of a plain decimal number "[+-]ddd.ddd", the common
// word value, shared by Expression::parseReal and parseLine's fast path so that both give the
// same value for the same text.
#pragma once

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <system_error>

namespace pkm::cnc::detail {

inline constexpr std::array<double, 16> kPow10{
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};

/// Reads a number "[+-]digits[.digits]" (at least one digit, at most one '.', either side of it
/// may be empty) starting at `p` (< `end`) into `v` and returns the end of it; nullptr when the
/// text there is no such number or its value is not finite (the caller then reads it as an
/// expression, which also reports the errors). Clinger's fast path: with at most 15 digits they
/// form an integer m < 2^53 and the fraction has k <= 15 digits, so m and 10^k are exact doubles
/// and m / 10^k, one IEEE division, is the correctly rounded value, the same as std::from_chars
/// gives; longer numbers go to std::from_chars.
inline const char* scanPlainNumber(const char* p, const char* end, double& v) {
  const bool negative = *p == '-';
  if (*p == '-' || *p == '+') ++p;
  const char* const digits_start = p;
  const char* dot = nullptr;
  std::uint64_t m = 0;
  unsigned digits = 0;
  for (; p < end; ++p) {
    const auto d = static_cast<unsigned>(static_cast<unsigned char>(*p)) - '0';
    if (d < 10u) {
      m = m * 10u + d;  // wraps harmlessly past 19 digits: std::from_chars is used then
      ++digits;
    } else if (*p == '.' && dot == nullptr) {
      dot = p;
    } else {
      break;
    }
  }
  if (digits == 0) return nullptr;  // empty, or a lone '.'
  if (digits <= 15) {
    const double x = static_cast<double>(m) / kPow10[dot == nullptr ? 0 : p - dot - 1];
    v = negative ? -x : x;
    return p;
  }
  double x = 0.0;
  const auto r = std::from_chars(digits_start, p, x);
  if (r.ec != std::errc() || r.ptr != p || !std::isfinite(x)) return nullptr;
  v = negative ? -x : x;
  return p;
}

}  // namespace pkm::cnc::detail
