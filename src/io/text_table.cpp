#include "pkm/io/text_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <sstream>

#include "io/detail/decimal.hpp"
#include "io/detail/table_preamble.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/parallel.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::io {
TextTable TextTable::read(const std::string& path) {
  NamedText in = readNamedText(path);
  return parse(std::move(in.text), in.name);
}

TextTable TextTable::parseData(std::string text, const std::string& source) {
  TextTable t = parse(std::move(text), source);
  if (t.rows() == 0) throw IoError(fmt::format("{}: no data rows (only a header)", source));
  return t;
}

namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/// The line [begin, end) of `all` without surrounding blanks.
std::string_view trimmedLine(std::string_view all, std::size_t begin, std::size_t end) {
  while (begin < end && isBlank(all[begin])) ++begin;
  while (end > begin && isBlank(all[end - 1])) --end;
  return all.substr(begin, end - begin);
}

}  // namespace

namespace {

/// The data rows of [begin, end) (whole lines): their offsets, their lines counted from 1 at
/// `begin`, and the first error, if any ("expected N fields" at a relative line).
struct RowChunk {
  std::vector<std::uint32_t> rows;
  LineNumbers lines;
  std::size_t line_count = 0;  ///< lines in [begin, end)
  std::size_t error_line = 0;  ///< relative line of the first bad row, 0 when none
  std::size_t error_fields = 0;
};

void scanRows(
    std::string_view all, std::size_t begin, std::size_t end, std::size_t fields, RowChunk& out) {
  std::size_t pos = begin;
  std::size_t line_no = 0;
  while (pos < end) {
    const void* nl = std::memchr(all.data() + pos, '\n', end - pos);
    const std::size_t stop =
        nl == nullptr ? end : static_cast<std::size_t>(static_cast<const char*>(nl) - all.data());
    const std::string_view line = trimmedLine(all, pos, stop);
    pos = stop + 1;
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    const std::size_t count =
        static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1;
    if (count != fields) {
      out.error_line = line_no;
      out.error_fields = count;
      break;
    }
    out.rows.push_back(static_cast<std::uint32_t>(line.data() - all.data()));
    out.lines.add(line_no);
  }
  out.line_count = line_no;
}

}  // namespace

TextTable TextTable::parse(std::string text, const std::string& source) {
  TextTable t;
  t.source_ = source;
  t.text_ = std::move(text);
  const std::string_view all(t.text_);
  // A row is kept as the 32-bit offset of its first character (4 bytes a row); its fields are
  // found again when read.
  if (all.size() >= std::numeric_limits<std::uint32_t>::max())
    throw IoError(locate(source, 0, "larger than 4 GiB; split the file"));
  detail::TablePreamble pre = detail::readTablePreamble(all, source, false);
  t.header_ = std::move(pre.header);
  t.metadata_ = std::move(pre.metadata);
  t.header_line_ = pre.header_line;
  const std::size_t pos = pre.data_begin;
  const std::size_t line_no = pre.header_line;

  // The data rows, in chunks of whole lines on the machine's cores (a large file), then joined.
  const std::size_t begin = std::min(pos, all.size());
  const std::size_t chunks = all.size() - begin < kParallelMinItems * 16 ? 1 : kParallelChunks;
  std::vector<std::size_t> bounds(chunks + 1, all.size());
  bounds[0] = begin;
  for (std::size_t c = 1; c < chunks; ++c) {
    const std::size_t guess = std::max(bounds[c - 1], begin + (all.size() - begin) / chunks * c);
    const void* nl = std::memchr(all.data() + guess, '\n', all.size() - guess);
    bounds[c] = nl == nullptr
                    ? all.size()
                    : static_cast<std::size_t>(static_cast<const char*>(nl) - all.data()) + 1;
  }
  std::vector<RowChunk> parts(chunks);
  forEachChunk(chunks, chunks, [&](std::size_t c, std::size_t, std::size_t) {
    scanRows(all, bounds[c], bounds[c + 1], t.header_.size(), parts[c]);
  });
  std::size_t rows = 0;
  for (const RowChunk& part : parts) rows += part.rows.size();
  t.rows_.reserve(rows);
  std::size_t lines_before = line_no;  // lines before the chunk
  for (const RowChunk& part : parts) {
    if (part.error_line != 0)
      throw IoError(
          locate(source,
                 lines_before + part.error_line,
                 fmt::format("expected {} fields, found {}", t.header_.size(), part.error_fields)));
    t.rows_.insert(t.rows_.end(), part.rows.begin(), part.rows.end());
    t.lines_.append(part.lines, lines_before);
    lines_before += part.line_count;
  }
  return t;
}

std::optional<std::string> TextTable::meta(std::string_view key) const {
  for (const auto& [k, v] : metadata_)
    if (k == key) return v;
  return std::nullopt;
}

std::optional<std::size_t> TextTable::findColumn(
    std::initializer_list<std::string_view> names) const {
  for (const std::string_view name : names)
    for (std::size_t i = 0; i < header_.size(); ++i)
      if (header_[i] == name) return i;
  return std::nullopt;
}

std::size_t TextTable::column(std::initializer_list<std::string_view> names) const {
  if (const auto found = findColumn(names)) return *found;
  std::string what;
  for (const std::string_view name : names)
    what +=
        what.empty() ? fmt::format("missing column '{}'", name) : fmt::format(" (or '{}')", name);
  failHeader(what);
}

std::string_view TextTable::text(std::size_t row, std::size_t col) const {
  assert(row < rows_.size() && col < header_.size());
  // The row has exactly header().size() fields before its line end (checked by parse).
  const char* p = text_.data() + rows_[row];
  const char* const end = text_.data() + text_.size();
  for (std::size_t i = 0; i < col; ++i)
    p = static_cast<const char*>(std::memchr(p, ',', end - p)) + 1;
  const char* e = p;
  while (e < end && *e != ',' && *e != '\n') ++e;
  while (p < e && isBlank(*p)) ++p;
  while (e > p && isBlank(e[-1])) --e;
  return {p, static_cast<std::size_t>(e - p)};
}

double TextTable::number(std::size_t row, std::size_t col) const {
  // Fast path: a plain decimal; parseFiniteDouble for the rest (a leading '+') and the error.
  const std::string_view field = text(row, col);
  double value = 0.0;
  if (detail::parseSimpleDecimal(field.data(), field.data() + field.size(), value)) return value;
  if (!parseFiniteDouble(field, value))
    fail(row, fmt::format("column '{}': '{}' is not a finite number", header_[col], field));
  return value;
}

void TextTable::numbers(std::size_t row,
                        std::span<const std::size_t> cols,
                        std::span<double> out) const {
  assert(row < rows_.size() && cols.size() == out.size());
  std::size_t last = 0;
  for (const std::size_t c : cols) last = std::max(last, c);
  assert(last < header_.size());
  const char* p = text_.data() + rows_[row];
  const char* const end = text_.data() + text_.size();
  for (std::size_t field = 0; field <= last; ++field) {
    bool wanted = false;
    for (const std::size_t c : cols) wanted = wanted || c == field;
    if (wanted) {
      // The number and blanks up to the field's end, or the slow path (from_chars, the error).
      while (p < end && isBlank(*p)) ++p;
      double value = 0.0;
      const char* after = detail::scanSimpleDecimal(p, end, value);
      if (after != nullptr)
        while (after < end && isBlank(*after)) ++after;
      if (after == nullptr || (after < end && *after != ',' && *after != '\n'))
        value = number(row, field);
      for (std::size_t k = 0; k < cols.size(); ++k)
        if (cols[k] == field) out[k] = value;
    }
    if (field < last)  // the row has header().size() fields (checked by parse)
      p = static_cast<const char*>(std::memchr(p, ',', static_cast<std::size_t>(end - p))) + 1;
  }
}

long long TextTable::integer(std::size_t row, std::size_t col) const {
  double value = 0.0;
  if (!parseFiniteDouble(text(row, col), value) || value != std::floor(value) ||
      std::fabs(value) >= 9007199254740992.0)
    fail(row, fmt::format("column '{}': '{}' is not an integer", header_[col], text(row, col)));
  return static_cast<long long>(value);
}

int TextTable::direction(std::size_t row, std::size_t col) const {
  const std::string_view d = text(row, col);
  std::string lower(d);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* plus : {"+", "+1", "1", "forward", "fwd", "f", "up", "positive", "pos"})
    if (lower == plus) return 1;
  for (const char* minus :
       {"-", "-1", "reverse", "rev", "r", "backward", "down", "negative", "neg"})
    if (lower == minus) return -1;
  fail(row,
       fmt::format("column '{}': direction '{}' is not one of +, -, Forward, Reverse, F, R, Up, "
                   "Down, 1, -1",
                   header_[col],
                   d));
}

void TextTable::fail(std::size_t row, const std::string& what) const {
  throw IoError(locate(source_, lines_[row], what));
}

void TextTable::failHeader(const std::string& what) const {
  throw IoError(locate(source_, header_line_, what));
}

}  // namespace pkm::io
