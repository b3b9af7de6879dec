/// @file
/// @brief Internal: what comes before a table's data rows — "# key: value" metadata, comments,
/// blank lines and the header row — read the same way by io::TextTable and io::NumberTable.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/io/text_table.hpp"

namespace pkm::io::detail {

/// The lines of a table up to and including its header.
struct TablePreamble {
  std::vector<std::string> header;  ///< the header's fields, trimmed
  Metadata metadata;                ///< "# key: value" lines before the header, in order
  std::size_t header_line = 0;      ///< 1-based line of the header
  std::size_t data_begin = 0;       ///< offset of the line after the header
  bool comma = true;                ///< fields separated by commas (false: by blanks)
};

/// A blank of a table line: space, tab, or the CR of a CRLF line end.
inline bool isTableBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/// Reads the preamble of `all`. With `allow_blank_separated`, a header line without a comma and
/// with more than one word makes a blank-separated table. Throws pkm::IoError "SOURCE:LINE:
/// header field N is empty", "column 'c' appears twice" or "SOURCE: no header row".
[[nodiscard]] TablePreamble readTablePreamble(std::string_view all,
                                              const std::string& source,
                                              bool allow_blank_separated);

}  // namespace pkm::io::detail
