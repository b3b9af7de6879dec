// Active comments after the LinuxCNC 2.9 G-code overview ("Comments", "Messages", "Probe
// Logging", "Debug Messages", "Print Messages", "Abort"); the details (last comment wins, blanks
// before the keyword, no blank before the comma, 6 decimals, "######") were read off rs274.
#include "pkm/cnc/comment_message.hpp"

#include <fmt/format.h>

#include <array>
#include <cctype>
#include <utility>

#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace {

constexpr int kFirstParameter = 1;
constexpr int kLastParameter = 5601;
constexpr std::string_view kUndefined = "######";

/// True when `s` starts with `keyword` (lower case) in any case.
bool startsWithNoCase(std::string_view s, std::string_view keyword) {
  if (s.size() < keyword.size()) return false;
  for (std::size_t i = 0; i < keyword.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[i])) != keyword[i]) return false;
  return true;
}

constexpr std::array<std::pair<std::string_view, CommentKind>, 8> kKeywords{{
    {"msg", CommentKind::kMsg},
    {"debug", CommentKind::kDebug},
    {"print", CommentKind::kPrint},
    {"abort", CommentKind::kAbort},
    {"logopen", CommentKind::kLogOpen},
    {"logappend", CommentKind::kLogAppend},
    {"logclose", CommentKind::kLogClose},
    {"log", CommentKind::kLog},
}};

}  // namespace

std::string_view commentKeyword(CommentKind kind) {
  for (const auto& [name, k] : kKeywords)
    if (k == kind) return name;
  return "";
}

CommentKind classifyComment(std::string_view inner, std::string& text) {
  std::size_t i = 0;
  while (i < inner.size() && (inner[i] == ' ' || inner[i] == '\t')) ++i;
  const std::string_view s = inner.substr(i);
  if (startsWithNoCase(s, "py,")) throw GcodeError("embedded Python (PY, ...) is not supported");
  for (const auto& [name, kind] : kKeywords) {
    if (!startsWithNoCase(s, name)) continue;
    const std::string_view rest = s.substr(name.size());
    if (kind == CommentKind::kLogClose && rest.find_first_not_of(" \t") == std::string_view::npos) {
      text.clear();
      return kind;
    }
    if (rest.empty() || rest.front() != ',') continue;  // "log" is a prefix of "logopen"
    text.assign(rest.substr(1));
    return kind;
  }
  return CommentKind::kNone;
}

std::string substituteParameters(std::string_view text, ParameterSource& source) {
  std::string out;
  out.reserve(text.size() + 16);
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c != '#' || i + 1 >= text.size()) {
      out += c;
      ++i;
      continue;
    }
    if (text[i + 1] == '<') {
      const std::size_t close = text.find('>', i + 2);
      if (close == std::string_view::npos) {
        out += text.substr(i);
        break;
      }
      std::string name;
      for (const char n : text.substr(i + 2, close - i - 2))
        if (n != ' ' && n != '\t')
          name += static_cast<char>(std::tolower(static_cast<unsigned char>(n)));
      out +=
          source.exists(name) ? fmt::format("{:.6f}", source.named(name)) : std::string(kUndefined);
      i = close + 1;
      continue;
    }
    std::size_t j = i + 1;
    int index = 0;
    for (; j < text.size() && std::isdigit(static_cast<unsigned char>(text[j])) != 0; ++j)
      if (index <= kLastParameter) index = index * 10 + (text[j] - '0');  // no overflow
    if (j == i + 1) {
      out += c;
      ++i;
      continue;
    }
    out += index >= kFirstParameter && index <= kLastParameter
               ? fmt::format("{:.6f}", source.numbered(index))
               : std::string(kUndefined);
    i = j;
  }
  return out;
}

}  // namespace pkm::cnc
