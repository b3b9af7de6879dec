// Private to the cnc module: CSV number fields in shortest round-trip form, as the moves CSV of
// `pkm gcode moves` and the joint CSVs of `pkm gcode run` write them.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

namespace pkm::cnc::detail {

/// Appends `value` (finite, non-zero) in shortest round-trip form. Integers below 1e15 are
/// written as integers. Values of 0.001 <= |v| < 1e9 with at most six decimals (the usual G-code
/// coordinates) take a fast path: n = round(v·10⁶) is exact when n/10⁶ == v (one correctly rounded
/// division), and then n's digits with the point inserted and trailing zeros trimmed are the
/// shortest string that reads back as v (distinct six-decimal numbers below 1e9 are distinct
/// doubles) and the fixed form std::to_chars also chooses there. Everything else: std::to_chars.
inline void appendShortest(std::string& out, double value) {
  char buf[32];
  const double a = std::abs(value);
  if (a < 1e15 && value == std::trunc(value)) {
    const auto r = std::to_chars(buf, buf + sizeof buf, static_cast<long long>(value));
    out.append(buf, r.ptr);
    return;
  }
  if (a >= 1e-3 && a < 1e9) {
    const long long n = std::llround(value * 1e6);
    if (static_cast<double>(n) / 1e6 == value) {
      const unsigned long long m = static_cast<unsigned long long>(n < 0 ? -n : n);
      if (n < 0) out.push_back('-');
      const auto r = std::to_chars(buf, buf + sizeof buf, m / 1000000u);
      out.append(buf, r.ptr);
      unsigned long long frac = m % 1000000u;  // not 0: value is not an integer
      char digits[6];
      int len = 6;
      for (int i = 5; i >= 0; --i, frac /= 10) digits[i] = static_cast<char>('0' + frac % 10);
      while (len > 0 && digits[len - 1] == '0') --len;
      out.push_back('.');
      out.append(digits, static_cast<std::size_t>(len));
      return;
    }
  }
  const auto r = std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, r.ptr);
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
