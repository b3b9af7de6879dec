#include "io/detail/table_preamble.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "pkm/core/error.hpp"
#include "pkm/core/text.hpp"

namespace pkm::io::detail {
namespace {

/// The line [begin, end) of `all` without surrounding blanks.
std::string_view trimmedTableLine(std::string_view all, std::size_t begin, std::size_t end) {
  while (begin < end && isTableBlank(all[begin])) ++begin;
  while (end > begin && isTableBlank(all[end - 1])) --end;
  return all.substr(begin, end - begin);
}

/// The header's fields: split at commas, or at blanks for a blank-separated table.
std::vector<std::string> headerFields(std::string_view line, bool comma) {
  std::vector<std::string> out;
  if (!comma) {
    for (const std::string_view w : splitWords(line)) out.emplace_back(w);
    return out;
  }
  std::size_t start = 0;
  while (true) {
    const std::size_t at = line.find(',', start);
    out.emplace_back(trimBlanks(line.substr(start, at - start)));
    if (at == std::string_view::npos) return out;
    start = at + 1;
  }
}

}  // namespace

TablePreamble readTablePreamble(std::string_view all,
                                const std::string& source,
                                bool allow_blank_separated) {
  TablePreamble t;
  std::size_t pos = 0;
  std::size_t line_no = 0;
  while (pos < all.size()) {
    const void* nl = std::memchr(all.data() + pos, '\n', all.size() - pos);
    const std::size_t end =
        nl == nullptr ? all.size()
                      : static_cast<std::size_t>(static_cast<const char*>(nl) - all.data());
    std::string_view line = trimmedTableLine(all, pos, end);
    pos = std::min(end + 1, all.size());
    ++line_no;
    if (line_no == 1 && line.starts_with("\xEF\xBB\xBF")) line = trimBlanks(line.substr(3));
    if (line.empty()) continue;
    if (line.front() == '#') {
      const std::string_view body = trimBlanks(line.substr(1));
      const std::size_t colon = body.find(':');
      if (colon != std::string_view::npos)
        t.metadata.emplace_back(trimBlanks(body.substr(0, colon)),
                                trimBlanks(body.substr(colon + 1)));
      continue;
    }
    t.comma = !allow_blank_separated || line.find(',') != std::string_view::npos ||
              splitWords(line).size() < 2;
    t.header = headerFields(line, t.comma);
    for (std::size_t i = 0; i < t.header.size(); ++i) {
      if (t.header[i].empty())
        throw IoError(locate(source, line_no, fmt::format("header field {} is empty", i + 1)));
      for (std::size_t j = 0; j < i; ++j)
        if (t.header[j] == t.header[i])
          throw IoError(
              locate(source, line_no, fmt::format("column '{}' appears twice", t.header[i])));
    }
    t.header_line = line_no;
    t.data_begin = pos;
    return t;
  }
  throw IoError(locate(source, 0, "no header row"));
}

}  // namespace pkm::io::detail
