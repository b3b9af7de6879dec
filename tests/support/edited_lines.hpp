// Test inputs made by editing a sample file line by line, and the messages their readers give
// (the JSON reader tests of tests/io).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"

namespace pkm::test {

/// `lines` joined with newlines, line n (1-based) replaced by `edits[n]`; an empty replacement
/// drops the line.
inline std::string editedLines(const std::vector<std::string>& lines,
                               const std::map<int, std::string>& edits) {
  std::string out;
  for (int n = 1; n <= static_cast<int>(lines.size()); ++n) {
    const auto it = edits.find(n);
    if (it == edits.end())
      out += lines[static_cast<std::size_t>(n - 1)] + "\n";
    else if (!it->second.empty())
      out += it->second + "\n";
  }
  return out;
}

/// The message of the pkm::IoError that `parse()` throws ("" when it does not throw).
template <typename Parse>
std::string ioErrorOf(Parse&& parse) {
  try {
    (void)parse();
  } catch (const IoError& e) {
    return e.what();
  }
  return {};
}

}  // namespace pkm::test
