/// @file
/// @brief Maps JSON pointers ("/struts/2/base") to the line where that value starts in the source
/// text, so that errors found after parsing can still name the line.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>

namespace pkm::io {

/// Line index of every value of a syntactically valid JSON text.
class JsonLocator {
 public:
  /// Scans `text` (already known to be valid JSON). Never throws on valid input; on invalid input
  /// some pointers are simply missing.
  explicit JsonLocator(std::string_view text);
  /// 1-based line of the value at `pointer` ("" is the root); 0 when unknown. A pointer that does
  /// not exist falls back to its nearest existing parent.
  [[nodiscard]] std::size_t line(std::string pointer) const;

 private:
  std::unordered_map<std::string, std::size_t> lines_;
};

}  // namespace pkm::io
