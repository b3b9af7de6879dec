// Number formatting shared by the table writers (internal to pkm::compensation).
#pragma once

#include <fmt/format.h>

#include <string>

namespace pkm::compensation::detail {

/// The shortest decimal text that parses back to the same double (fmt's default, std::to_chars
/// semantics; docs/conventions.md "Number output"); −0 as "0". May use an exponent (1e-05).
inline std::string shortestText(double v) {
  if (v == 0.0) return "0";
  return fmt::format("{}", v);
}

/// Fixed-point text with at most 9 decimals (1 nm for mm), trailing zeros removed, −0 as "0":
/// for controllers whose syntax has no 'e' exponent (SINUMERIK part programs write 1EX-5).
inline std::string fixedText(double v) {
  const std::string s = fmt::format("{:.9f}", v);
  std::size_t n = s.size();
  while (n > 0 && s[n - 1] == '0') --n;
  if (n > 0 && s[n - 1] == '.') --n;
  if (n == 0 || (n == 2 && s[0] == '-' && s[1] == '0')) return std::string(1, '0');
  return s.substr(0, n);
}

}  // namespace pkm::compensation::detail
