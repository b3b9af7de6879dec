/// @file
/// @brief Plain-text helpers the readers of several modules share: trimming, words, lines, and
/// the `[SECTION]` / `KEY = value` lines of an INI file (LinuxCNC's configuration format).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace pkm {

/// `s` without leading and trailing spaces, tabs and carriage returns.
[[nodiscard]] std::string_view trimBlanks(std::string_view s);

/// The whitespace-separated words of `line` (views into it), in order.
[[nodiscard]] std::vector<std::string_view> splitWords(std::string_view line);

/// The lines of `text` (views into it, without their '\n'), in order; a last line without a
/// '\n' counts, an empty text has none.
[[nodiscard]] std::vector<std::string_view> splitLines(std::string_view text);

/// One `KEY = value` line of an INI file.
struct IniEntry {
  std::string section;  ///< without the brackets, as written
  std::string key;      ///< as written, blanks trimmed
  std::string value;    ///< the rest of the line, blanks trimmed
  std::size_t line = 0;
};

/// The entries of INI `text` named `name` in order: `[SECTION]` headers, `KEY = value` lines;
/// blank lines, lines starting with '#' or ';' and lines without '=' are skipped. Throws
/// pkm::IoError "NAME:LINE: unterminated section header".
[[nodiscard]] std::vector<IniEntry> parseIni(std::string_view text, const std::string& name);

}  // namespace pkm
