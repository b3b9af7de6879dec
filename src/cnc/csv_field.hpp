// Private to the cnc module: CSV number fields in shortest round-trip form, as the joint CSVs of
// `pkm gcode run` write them.
#pragma once

#include <charconv>
#include <cstddef>
#include <string>

namespace pkm::cnc::detail {

/// Appends ",value" (shortest round-trip form; 0 for either zero, so no "-0").
inline void appendCsvField(std::string& out, double value) {
  out.push_back(',');
  if (value == 0.0) {
    out.push_back('0');
    return;
  }
  char buf[32];
  const auto result = std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, result.ptr);
}

/// Appends an unsigned integer without a separator.
inline void appendCsvIndex(std::string& out, std::size_t value) {
  char buf[24];
  const auto result = std::to_chars(buf, buf + sizeof buf, value);
  out.append(buf, result.ptr);
}

}  // namespace pkm::cnc::detail
