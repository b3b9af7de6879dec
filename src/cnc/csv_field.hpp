// Private to the cnc module: CSV number fields in shortest round-trip form, as the moves CSV of
// `pkm gcode moves` and the joint CSVs of `pkm gcode run` write them. The write* functions put
// the text at a raw pointer (the caller guarantees the room: kMaxShortest per number), the
// append* ones add it to a std::string.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

namespace pkm::cnc::detail {

/// The room writeShortest needs: std::to_chars's longest double is 24 characters, and the fast
/// path's fixed-size copies touch at most 19 bytes.
inline constexpr std::size_t kMaxShortest = 32;

/// "00" .. "99".
inline constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

/// Writes m·10⁻⁶ (m < 10^15, not a multiple of 10⁶) as "I.F": I without leading zeros ("0" for
/// none), F the six decimals without trailing zeros. Returns the end; touches up to 18 bytes
/// (fixed-size copies) whatever the length of the text.
inline char* writeMicros(char* out, std::uint64_t m) {
  char digits[32];                 // m's digits right-aligned at digits + 16, at least seven
  char* const stop = digits + 16;  // (zero-padded); fixed-size copies read up to digits + 32
  char* d = stop;
  while (m >= 100) {
    const auto pair = static_cast<std::size_t>(m % 100) * 2;
    m /= 100;
    d -= 2;
    std::memcpy(d, kDigitPairs + pair, 2);
  }
  if (m >= 10) {
    d -= 2;
    std::memcpy(d, kDigitPairs + m * 2, 2);
  } else {
    *--d = static_cast<char>('0' + m);
  }
  while (d > stop - 7) *--d = '0';
  const char* const point = stop - 6;
  std::memcpy(out, d, 16);  // the integer part (at most 9 digits) and more
  out += point - d;
  *out = '.';
  std::memcpy(out + 1, point, 8);  // the six decimals and two more bytes
  out += 7;
  while (out[-1] == '0') --out;  // stops at a decimal: m is no multiple of 10⁶
  return out;
}

/// Writes `value` (finite, non-zero) at `out` in shortest round-trip form and returns the end.
/// Integers below 1e15 are written as integers. Values of 0.001 <= |v| < 1e9 with at most six
/// decimals (the usual G-code coordinates) take a fast path: an n with n/10⁶ == v (one correctly
/// rounded division; n is v·10⁶ rounded, and if that rounding is off by one the test fails and
/// the general path runs) gives the shortest string that reads back as v: n's digits with the
/// point inserted and trailing zeros trimmed (distinct six-decimal numbers below 1e9 are distinct
/// doubles), the fixed form std::to_chars also chooses there. Everything else: std::to_chars.
inline char* writeShortest(char* out, double value) {
  const double a = std::abs(value);
  if (a < 1e15) {
    const auto i = static_cast<long long>(value);  // truncates; exact for |value| < 1e15
    if (static_cast<double>(i) == value) return std::to_chars(out, out + kMaxShortest, i).ptr;
    if (a >= 1e-3 && a < 1e9) {
      const double t = value * 1e6;  // |t| < 1e15: fits a long long
      const auto n = static_cast<long long>(t < 0.0 ? t - 0.5 : t + 0.5);
      if (static_cast<double>(n) / 1e6 == value) {
        if (n < 0) *out++ = '-';
        return writeMicros(out, static_cast<std::uint64_t>(n < 0 ? -n : n));
      }
    }
  }
  return std::to_chars(out, out + kMaxShortest, value).ptr;
}

/// Appends `value` (finite, non-zero) in shortest round-trip form (writeShortest).
inline void appendShortest(std::string& out, double value) {
  char buf[kMaxShortest];
  out.append(buf, writeShortest(buf, value));
}

/// Appends ",value" (shortest round-trip form; 0 for either zero, so no "-0").
inline void appendCsvField(std::string& out, double value) {
  out.push_back(',');
  if (value == 0.0) {
    out.push_back('0');
    return;
  }
  appendShortest(out, value);
}

/// Appends an unsigned integer without a separator.
inline void appendCsvIndex(std::string& out, std::size_t value) {
  char buf[24];
  const auto result = std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, result.ptr);
}

}  // namespace pkm::cnc::detail
