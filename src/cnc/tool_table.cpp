// LinuxCNC tool table: one tool per line, words T (tool), P (pocket), X Y Z A B C U V W
// (offsets), D (diameter), I J Q (lathe), anything after ';' a comment.
#include "pkm/cnc/tool_table.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "pkm/core/error.hpp"

namespace pkm::cnc {

namespace {

/// `v` (in the table's unit) in mm; throws pkm::IoError "FILE:LINE: ..." when the product
/// overflows (a finite value near the largest double read as inch).
double toMm(double v,
            double mm_per_unit,
            char letter,
            std::string_view num,
            const std::string& file,
            std::size_t line) {
  const double mm = v * mm_per_unit;
  if (!std::isfinite(mm))
    throw IoError(locate(file, line, fmt::format("{}{} is too large", letter, num)));
  return mm;
}

/// Cuts the comment (after ';') off `line` and returns it trimmed ("" without one).
std::string splitComment(std::string_view& line) {
  const std::size_t semi = line.find(';');
  if (semi == std::string_view::npos) return {};
  std::string_view c = line.substr(semi + 1);
  line = line.substr(0, semi);
  const std::size_t first = c.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  c = c.substr(first);
  return std::string(c.substr(0, c.find_last_not_of(" \t\r") + 1));
}

}  // namespace

const ToolEntry* ToolTable::find(int t) const {
  const auto it = tools.find(t);
  return it == tools.end() ? nullptr : &it->second;
}

ToolTable ToolTable::parse(std::string_view text, double mm_per_unit, const std::string& file) {
  ToolTable table;
  std::size_t pos = 0;
  std::size_t line = 0;
  while (pos < text.size()) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view l = text.substr(pos, eol - pos);
    pos = eol + 1;
    ++line;
    ToolEntry e;
    e.comment = splitComment(l);
    bool have_t = false;
    std::size_t i = 0;
    while (i < l.size()) {
      if (l[i] == ' ' || l[i] == '\t' || l[i] == '\r') {
        ++i;
        continue;
      }
      const char letter = static_cast<char>(l[i] >= 'a' && l[i] <= 'z' ? l[i] - 'a' + 'A' : l[i]);
      const std::size_t start = ++i;
      while (i < l.size() && l[i] != ' ' && l[i] != '\t' && l[i] != '\r') ++i;
      const std::string_view num = l.substr(start, i - start);
      double v = 0.0;
      const char* first = num.data();
      if (!num.empty() && num[0] == '+') ++first;
      const auto r = std::from_chars(first, num.data() + num.size(), v);
      if (num.empty() || r.ec != std::errc() || r.ptr != num.data() + num.size() ||
          !std::isfinite(v))
        throw IoError(locate(file, line, fmt::format("bad number '{}' after {}", num, letter)));
      if ((letter == 'T' || letter == 'P') && !(v >= 0.0 && v < 1e9 && v == std::floor(v)))
        throw IoError(locate(file, line, fmt::format("bad {} number '{}'", letter, num)));
      switch (letter) {
        case 'T':
          e.number = static_cast<int>(v);
          have_t = true;
          break;
        case 'P':
          e.pocket = static_cast<int>(v);
          break;
        case 'X':
        case 'Y':
        case 'Z':
          e.offset[static_cast<std::size_t>(letter - 'X')] =
              toMm(v, mm_per_unit, letter, num, file, line);
          break;
        case 'A':
        case 'B':
        case 'C':
          e.offset[static_cast<std::size_t>(3 + letter - 'A')] = v;
          break;
        case 'D':
          e.diameter = toMm(v, mm_per_unit, letter, num, file, line);
          break;
        case 'U':
        case 'V':
        case 'W':
        case 'I':
        case 'J':
        case 'Q':
          break;  // U V W offsets and lathe data: not used by a 6-axis PKM
        default:
          throw IoError(locate(file, line, fmt::format("unknown tool table word '{}'", letter)));
      }
    }
    if (!have_t) {
      if (i > 0 && l.find_first_not_of(" \t\r") != std::string_view::npos)
        throw IoError(locate(file, line, "tool table line without T"));
      continue;
    }
    if (!table.tools.emplace(e.number, e).second)
      throw IoError(locate(file, line, fmt::format("tool T{} listed twice", e.number)));
  }
  return table;
}

ToolTable ToolTable::load(const std::string& path, double mm_per_unit) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(fmt::format("{}: cannot open tool table", path));
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), mm_per_unit, path);
}

}  // namespace pkm::cnc
