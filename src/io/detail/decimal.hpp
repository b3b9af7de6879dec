/// @file
/// @brief Internal: the fast path of number reading. A decimal with at most 2^53 as its digits
/// and a power of ten within ±22 is exactly m·10^k with m and 10^k both exact doubles, so one
/// multiplication or division rounds it correctly (Clinger, "How to read floating point numbers
/// accurately", PLDI 1990): the same double std::from_chars gives, several times faster.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace pkm::io::detail {

/// The run of decimal digits at p (at most 8, and none past `end`) as a number, and its length:
/// eight bytes at a time (SWAR, as fast_float does) when eight are there, else byte by byte.
inline int digitRun(const char* p, const char* end, std::uint64_t& value) {
  if (end - p >= 8) {
    std::uint64_t x = 0;
    std::memcpy(&x, p, 8);     // the first character in the lowest byte
    x ^= 0x3030303030303030u;  // digits become bytes 0..9
    // Bit 7 of a byte is set when it is not a digit; carries only reach later bytes, so the
    // first non-digit is found correctly.
    const std::uint64_t not_digit = ((x + 0x7676767676767676u) | x) & 0x8080808080808080u;
    const int n = not_digit == 0 ? 8 : std::countr_zero(not_digit) / 8;
    if (n == 0) {
      value = 0;
      return 0;
    }
    x <<= 8 * (8 - n);  // the n digits, led by zeros, as an eight-digit number
    x = x * 10 + (x >> 8);
    x = (((x & 0x000000FF000000FFu) * 0x000F424000000064u) +
         (((x >> 16) & 0x000000FF000000FFu) * 0x0000271000000001u)) >>
        32;
    value = static_cast<std::uint32_t>(x);
    return n;
  }
  std::uint64_t v = 0;
  int n = 0;
  while (p + n < end && n < 8 && static_cast<unsigned>(p[n] - '0') < 10)
    v = v * 10 + static_cast<unsigned>(p[n++] - '0');
  value = v;
  return n;
}

/// Appends the digit run at p to m (m·10^n + run); returns the run's length.
inline std::ptrdiff_t appendDigits(const char*& p, const char* end, std::uint64_t& m) {
  static constexpr std::uint64_t kPow10[] = {
      1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000};
  const char* const first = p;
  while (true) {
    std::uint64_t run = 0;
    const int n = digitRun(p, end, run);
    m = m * kPow10[n] + run;  // wraps for more than 19 digits: the caller refuses those
    p += n;
    if (n < 8) break;
  }
  return p - first;
}

/// Reads the number [-]digits[.digits][(e|E)[+|-]digits] at the start of [p, end) when it is
/// within the fast path's range and returns the end of it; returns nullptr (value untouched) for
/// anything else, which the caller then reads with std::from_chars.
inline const char* scanSimpleDecimal(const char* p, const char* end, double& value) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                      1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                      1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  constexpr std::uint64_t kMaxExact = std::uint64_t{1} << 53;
  const bool negative = p < end && *p == '-';
  if (negative) ++p;
  // At most 18 digits in all (leading zeros included) keeps m exact in 64 bits; longer numbers
  // are left to from_chars.
  std::uint64_t m = 0;
  std::ptrdiff_t digits = appendDigits(p, end, m);
  int exponent = 0;
  if (p < end && *p == '.') {
    ++p;
    const std::ptrdiff_t fraction = appendDigits(p, end, m);
    exponent = -static_cast<int>(fraction);
    digits += fraction;
  }
  if (digits == 0 || digits > 18) return nullptr;
  if (p < end && (*p == 'e' || *p == 'E')) {
    ++p;
    const bool negative_exponent = p < end && *p == '-';
    if (p < end && (*p == '-' || *p == '+')) ++p;
    int e = 0, e_digits = 0;
    while (p < end && static_cast<unsigned>(*p - '0') < 10 && e_digits < 4) {
      e = e * 10 + (*p++ - '0');
      ++e_digits;
    }
    if (e_digits == 0) return nullptr;
    exponent += negative_exponent ? -e : e;
  }
  if (m > kMaxExact || exponent < -22 || exponent > 22) return nullptr;
  double v = static_cast<double>(m);
  v = exponent < 0 ? v / kPow10[-exponent] : v * kPow10[exponent];
  value = negative ? -v : v;
  return p;
}

/// True when [p, end) is exactly one number that scanSimpleDecimal reads (value set).
inline bool parseSimpleDecimal(const char* p, const char* end, double& value) {
  double v = 0.0;
  if (scanSimpleDecimal(p, end, v) != end) return false;
  value = v;
  return true;
}

}  // namespace pkm::io::detail
