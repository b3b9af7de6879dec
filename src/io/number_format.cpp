#include "pkm/io/number_format.hpp"

#include <charconv>

namespace pkm::io {

void appendNumber(std::string& out, double value) {
  if (value == 0.0) value = 0.0;  // drop the sign of -0
  char buf[32];
  const auto result = std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, result.ptr);
}

std::string formatNumber(double value) {
  std::string s;
  appendNumber(s, value);
  return s;
}

}  // namespace pkm::io
