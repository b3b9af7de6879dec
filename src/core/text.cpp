// Plain-text helpers (core/text.hpp).
#include "pkm/core/text.hpp"

#include <cctype>

#include "pkm/core/error.hpp"

namespace pkm {

std::string_view trimBlanks(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> splitWords(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

std::vector<std::string_view> splitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    lines.push_back(text.substr(0, end));
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
  }
  return lines;
}

std::vector<IniEntry> parseIni(std::string_view text, const std::string& name) {
  std::vector<IniEntry> out;
  std::string section;
  const std::vector<std::string_view> lines = splitLines(text);
  for (std::size_t n = 0; n < lines.size(); ++n) {
    const std::string_view line = trimBlanks(lines[n]);
    if (line.empty() || line.front() == '#' || line.front() == ';') continue;
    if (line.front() == '[') {
      const auto close = line.find(']');
      if (close == std::string_view::npos)
        throw IoError(locate(name, n + 1, "unterminated section header"));
      section = std::string(line.substr(1, close - 1));
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string_view::npos) continue;
    out.push_back({section,
                   std::string(trimBlanks(line.substr(0, eq))),
                   std::string(trimBlanks(line.substr(eq + 1))),
                   n + 1});
  }
  return out;
}

}  // namespace pkm
