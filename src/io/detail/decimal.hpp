/// @file
/// @brief Internal: the fast path of number reading. A decimal with at most 2^53 as its digits
/// and a power of ten within ±22 is exactly m·10^k with m and 10^k both exact doubles, so one
/// multiplication or division rounds it correctly (Clinger, "How to read floating point numbers
/// accurately", PLDI 1990): the same double std::from_chars gives, several times faster.
/// Decimals of 17 to 19 digits (the shortest round-trip text of most doubles) take the same step
/// in x87 extended precision, whose 64-bit significand holds any 19-digit m and 10^k for |k| ≤ 27
/// exactly; rounding that correctly rounded result once more to a double is only wrong when it
/// lies exactly halfway between two doubles, a case left to std::from_chars.
#pragma once

#include <bit>
#include <cfloat>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

namespace pkm::io::detail {

/// Whether long double arithmetic rounds to a 64-bit significand here (x87 extended precision:
/// true on x86-64 Linux; false where long double is another format, or under an emulator such
/// as valgrind that computes it in double precision).
inline bool extendedPrecisionWorks() {
  if constexpr (std::numeric_limits<long double>::digits != 64) {
    return false;
  } else {
    static const bool works = [] {
      volatile long double one = 1.0L;
      volatile long double tiny = LDBL_EPSILON;  // 2^-63
      return one + tiny != one;
    }();
    return works;
  }
}

/// m·10^exponent rounded correctly to a double through one extended-precision operation, for
/// m < 2^64 and |exponent| ≤ 27; false (value untouched) when the extended result is halfway
/// between two doubles or extended precision is not available.
inline bool extendedDecimal(std::uint64_t m, int exponent, double& value) {
  if constexpr (std::numeric_limits<long double>::digits != 64) {
    return false;
  } else {
    static constexpr long double kPow10[] = {1e0L,  1e1L,  1e2L,  1e3L,  1e4L,  1e5L,  1e6L,
                                             1e7L,  1e8L,  1e9L,  1e10L, 1e11L, 1e12L, 1e13L,
                                             1e14L, 1e15L, 1e16L, 1e17L, 1e18L, 1e19L, 1e20L,
                                             1e21L, 1e22L, 1e23L, 1e24L, 1e25L, 1e26L, 1e27L};
    if (exponent < -27 || exponent > 27 || !extendedPrecisionWorks()) return false;
    const long double x = exponent < 0 ? static_cast<long double>(m) / kPow10[-exponent]
                                       : static_cast<long double>(m) * kPow10[exponent];
    std::uint64_t significand = 0;  // the x87 format keeps it, explicit leading bit, first
    std::memcpy(&significand, &x, sizeof significand);
    // The 11 bits below a double's last are 100...0: x is a double's halfway point, where
    // the second rounding may go the wrong way.
    if ((significand & 0x7FF) == 0x400) return false;
    value = static_cast<double>(x);
    return true;
  }
}

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
  // At most 19 digits in all (leading zeros included) keeps m exact in 64 bits; longer numbers
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
  if (digits == 0 || digits > 19) return nullptr;
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
  double v = 0.0;
  if (m <= kMaxExact && exponent >= -22 && exponent <= 22) {
    v = static_cast<double>(m);
    v = exponent < 0 ? v / kPow10[-exponent] : v * kPow10[exponent];
  } else if (!extendedDecimal(m, exponent, v)) {
    return nullptr;
  }
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
